"""Seed 003 Table 3 with the flexible chock (femcheck.bem.mill_chock, scene trb-mill-4row): the row shares' mesh
convergence and their sensitivity to every assumed input (chock radius, support pad, seat, load line, axial load,
neck length), against the measured shares and the rigid-ring model with the same load line.

Run: flock /tmp/femcheck-cpu.lock python benchmarks/mill_chock.py
(Refining every direction at once, m = 2, needs more than 24 GB: the load matrix and the solutions are dense over
some 800k DOFs; the mesh study refines one direction at a time instead.)
Writes benchmarks/results/mill_chock.json and .md (times on this machine, 2 cores).
"""
from __future__ import annotations

import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from femcheck.bem import mill_chock as mc
from femcheck.problems._bearing_chock import parts, seat_of
from femcheck.scene import load_scene

OUT = Path(__file__).parent / "results"


def run(overrides: dict, cones_cache: dict, mesh_kw: dict | None = None) -> dict:
    sc = load_scene("trb-mill-4row", overrides)
    p = sc.params
    bearing, chock, neck, mesh = parts(p)
    mesh = dataclasses.replace(mesh, **(mesh_kw or {}))
    t0 = time.perf_counter()
    cc = mc.chock_compliance(bearing, chock, mesh)
    t_chock = time.perf_counter() - t0
    key = (mesh, bearing.slices)
    if key not in cones_cache:
        cones_cache[key] = mc.cone_compliance(bearing, chock.material, mesh)
    ci = cones_cache[key]
    cn = mc.roll_compliance(bearing, neck)
    seat = seat_of(p)
    sol = mc.solve(bearing, cc.C + ci.C + cn, p["load.radial"], p["load.axial"], seat=seat)
    rigid = mc.solve(bearing, None, p["load.radial"], p["load.axial"], seat=seat)
    meas = np.asarray(p["paper.row_shares_measured"], float)
    return {"overrides": {**overrides, **{f"mesh.{k}": v for k, v in (mesh_kw or {}).items()}}, "shares": sol.row_shares.tolist(), "rigid_shares": rigid.row_shares.tolist(),
            "errors_pct": (100 * (sol.row_shares - meas) / meas).tolist(), "q_max_N": float(sol.roller_loads.max()),
            "chock_dofs": cc.n_dofs, "cone_dofs": ci.n_dofs, "chock_time_s": t_chock,
            "newton_iterations": sol.iterations, "residual": sol.residual}


def main() -> None:
    cones: dict = {}
    # one direction at a time: through the thickness, along the axis (and the ISO slices with it), around
    mesh = [({}, None), ({"numerics.chock_radial": 4}, None), ({"numerics.chock_slices": 12}, None),
            ({}, {"between": 3, "gaps": 4, "ends": 2, "radial_cones": 2})]
    sens = [{"chock.outer_radius": 0.11}, {"chock.outer_radius": 0.16},
            {"chock.support_length": 0.03}, {"chock.support_length": 0.12},
            {"chock.support_half_angle": 3 * np.pi / 20},
            {"load.offset": 0.0225}, {"load.offset": 0.030}, {"load.axial": 0.0},
            {"chock.seat": "clamped"}, {"chock.seat": "clamped", "roll.neck_length": 0.13}]
    out = {"mesh": [], "sensitivity": []}
    for group, cases in (("mesh", mesh), ("sensitivity", [(ov, None) for ov in sens])):
        for ov, kw in cases:
            r = run(ov, cones, kw)
            print(group, ov, np.round(r["shares"], 2), np.round(r["errors_pct"], 1), r["chock_dofs"],
                  f"{r['chock_time_s']:.1f} s", flush=True)
            out[group].append(r)
    OUT.mkdir(exist_ok=True)
    (OUT / "mill_chock.json").write_text(json.dumps(out, indent=1, default=float))
    lines = ["# Seed 003 Table 3, flexible chock: mesh and assumptions", "",
             "Measured shares 10.05 / 16.49 / 40.79 / 32.67 %. Defaults: scene trb-mill-4row.", "",
             "| case | shares (%) | error vs measured (%) | rigid rings, same load line (%) | chock DOFs | chock FE (s) |",
             "|---|---|---|---|---|---|"]
    for group in ("mesh", "sensitivity"):
        for r in out[group]:
            ov = ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in r["overrides"].items())
            lines.append(f"| {group}: {ov or 'defaults'} | {' / '.join(f'{v:.2f}' for v in r['shares'])} | "
                         f"{' / '.join(f'{v:+.1f}' for v in r['errors_pct'])} | "
                         f"{' / '.join(f'{v:.2f}' for v in r['rigid_shares'])} | {r['chock_dofs']} | "
                         f"{r['chock_time_s']:.1f} |")
    (OUT / "mill_chock.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
