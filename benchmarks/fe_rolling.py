"""Benchmark of the 3D frictional FE rolling reference (issue 11 item 6): time and peak memory of the FE
compliances (mesh, assembly, factorisations, unit-load solves) and of the rolling solve per level, against the
budget of the whole reference (<= 10 min, <= 8 GB on 2 cores). Run under the shared lock:

    flock /work/heavy.lock python benchmarks/fe_rolling.py [--levels 3] [--case srb|groove] [--out FILE]

``srb``: both contacts of the seed-000 roller (whole roller + two ring segments) at 5.5 kN, mu = 0.3, the
frictionless-pose rolling problem with the nominal speeds (spec §1.2) under load control of each contact;
``groove``: the groove-rolling fem model (free rolling). Writes a JSON line per level (quantities, sizes,
times, peak RSS) and a markdown table to benchmarks/results/fe_rolling.md.
"""
from __future__ import annotations

import argparse
import json
import resource
import time
from pathlib import Path

import numpy as np

from femcheck.fem import srb_rolling
from femcheck.fem.contact_grid import ContactInput
from femcheck.fem.rolling_compliance import MeshSettings
from femcheck.fem.rolling_contact import approach_unknown
from femcheck.fem.rolling_geometry import Crowned, Grooved, gap, kinematics

SRB = {"geometry.roller_diameter": 0.0198, "geometry.crown_radius": 0.1003, "geometry.groove_radius_inner": 0.103,
       "geometry.groove_radius_outer": 0.1024, "geometry.contact_angle": float(np.deg2rad(11.5)),
       "materials.roller.E": 207e9, "materials.roller.nu": 0.3, "materials.ring.E": 207e9, "materials.ring.nu": 0.3}


def peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2


def srb_level(level: int, mu: float = 0.3, ratio: float = 2**0.5) -> dict:
    N = 5500.0
    nx, ns = (int(round(11 * ratio**level)) | 1), (int(round(21 * ratio**level)) | 1)
    t0 = time.perf_counter()
    grids = srb_rolling.grids(SRB, nx, ns, N)
    tables = srb_rolling.compliance(SRB, grids, MeshSettings(0.7, 0.4 / ratio**level, 2e-3, 1, 2))
    t_comp = time.perf_counter() - t0
    geo = srb_rolling.geometry(SRB)
    roller = Crowned(np.zeros(3), np.array([0, 1.0, 0]), geo["r"], geo["R"])
    # nominal speeds (seed 000 eqs 2-3) in the bearing frame rotating with the cage: ring j turns at
    # omega_j - omega_m about the bearing axis, the roller at omega_R about its axis
    # eqs 2-3 with the rolling radii r_roll,I/E = r_m -/+ (D/2) cos(alpha) (spec §1.2: 22.2652, -225.675 rad/s)
    D, al = SRB["geometry.roller_diameter"], SRB["geometry.contact_angle"]
    r_m = (SRB["geometry.groove_radius_outer"] - 0.5 * D) * np.cos(al)
    rI, rE = r_m - 0.5 * D * np.cos(al), r_m + 0.5 * D * np.cos(al)
    wI, wE = 476.2 * 2 * np.pi / 60, 0.0
    wm = (rI * wI + rE * wE) / (rI + rE)
    wR = -2 * rI * rE * (wI - wE) / (D * (rI + rE))
    rates = {"inner": wI - wm, "outer": wE - wm}
    inputs, extras = {}, []
    hz = srb_rolling.hertz_estimates(SRB, N)
    for c, g in grids.items():
        ring = Grooved(geo[c]["G"], geo[c]["rg"], geo["O"], geo["Y"])
        kin = kinematics(g, roller, wR, ring, rates[c])
        inputs[c] = ContactInput(g, gap(g, roller, ring), kin.slip, kin.speed, kin.kappa)
        extras.append(approach_unknown(c, c, g, g.normal(0.0), N, hz[c].approach))
    t1 = time.perf_counter()
    sol = srb_rolling.solve_contacts(tables, inputs, mu, extras)
    t_solve = time.perf_counter() - t1
    out = {"case": "srb", "level": level, "nx": nx, "ns": ns, "n_dofs": tables.stats["n_dofs"],
           "time_compliance_s": t_comp, "time_solve_s": t_solve, "iterations": sol.iterations,
           "residual": sol.residual, "peak_rss_gb": peak_rss_gb()}
    for c, r in sol.contacts.items():
        out[f"f_x_{c}"] = float(r.creep_force_x / (mu * N))
        out[f"f_lat_{c}"] = float(r.creep_force_s / (mu * N))
        out[f"friction_power_{c}"] = r.friction_power
        out[f"adhesion_fraction_{c}"] = r.adhesion_fraction
        out[f"p_max_{c}"] = r.p_max
    out["bodies"] = {k: {"dofs": v["n_dofs"], "times": v["times"], "factorisations": v["factorisations"]}
                     for k, v in tables.stats.items() if isinstance(v, dict) and "n_dofs" in v}
    return out


def groove_level(level: int) -> dict:
    from femcheck.fem.groove_rolling import solve_level, FEM_DEFAULTS

    p = {**FEM_DEFAULTS, "geometry.rolling_radius": 0.0099, "geometry.crown_radius": 0.1003,
         "geometry.groove_radius": 0.103, "geometry.ring_curvature": 1 / 0.0826, "load.normal": 5500.0,
         "friction.mu": 0.3, "materials.body1.E": 207e9, "materials.body1.nu": 0.3, "materials.body2.E": 207e9,
         "materials.body2.nu": 0.3, "kinematics.speed": 2.234}
    r = solve_level(p, level)
    return {"case": "groove", **{k: v for k, v in r["stats"].items() if k != "bodies"}, "peak_rss_gb": peak_rss_gb()}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--case", choices=("srb", "groove"), default="srb")
    ap.add_argument("--out", default="benchmarks/results/fe_rolling.jsonl")
    a = ap.parse_args()
    rows = []
    t0 = time.perf_counter()
    for k in range(a.levels):
        row = srb_level(k) if a.case == "srb" else groove_level(k)
        row["elapsed_total_s"] = time.perf_counter() - t0
        rows.append(row)
        print(json.dumps({k_: v for k_, v in row.items() if k_ != "bodies"}), flush=True)
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    with open(a.out, "a") as fh:
        for row in rows:
            fh.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main()
