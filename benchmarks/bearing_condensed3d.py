"""Cost and mesh convergence of the 3D condensed bearing model (issue 28 item 1; femcheck.fem.ring3d_compliance,
femcheck.bem.bearing_condensed3d): the 209-type cylindrical roller bearing (Z = 14, D = 10 mm, L = 9.6 mm, outer
raceway 75.032 mm, outer ring 85 mm x 19 mm, steel), ISO crown, inner ring misaligned by 0.5 mrad, F_r = 8900 N,
outer ring elastic on a housing arc of +-60 deg about the load line (and, for contrast, a full rigid housing).

Per mesh level m (nested: every cell split in m^3): DOFs, cells, the compliance build (mesh, assembly,
factorisation, Z n_s solves), the coupled solve reused for several load cases (time, Newton iterations), and
Q_max, the roller loads and the rigid-ring contrast. Goal of the issue: < 60 s with the compliance, < 5 s reused.
The timing is wall time on the shared 2-core machine (not a test assertion).

Run: flock /tmp/femcheck-cpu.lock python benchmarks/bearing_condensed3d.py [--slices 10] [--levels 1 2]
Writes benchmarks/results/bearing_condensed3d.json and .md.
"""
from __future__ import annotations

import argparse
import json
import resource
import time
import warnings
from pathlib import Path

import numpy as np

from femcheck.bem import bearing_condensed3d as bc
from femcheck.fem import ring3d_compliance as rc
from femcheck.materials import Elastic
from femcheck.meshes.ring3d import RingMeshSpec
from femcheck.solvers.convergence import richardson

STEEL = Elastic(210e9, 0.3)
Z, D, L = 14, 10e-3, 9.6e-3
R_RACE, R_OUT, WIDTH = 37.516e-3, 42.5e-3, 19e-3
CASES = ((8900.0, 5e-4), (2000.0, 5e-4), (20000.0, 5e-4), (8900.0, 0.0), (8900.0, 1e-3))
OUT = Path(__file__).parent / "results"


def level(m: int, slices: int, housing: float) -> dict:
    spec = RingMeshSpec(R_RACE, R_OUT, WIDTH, L, Z, slices, 1.0e-3 / R_RACE, refine=m, between=3, ends=2, radial=1)
    t0 = time.perf_counter()
    comp = rc.ring_compliance(rc.RingFE(spec, STEEL, "housing", housing))
    build = time.perf_counter() - t0
    runs = []
    for load, tilt in CASES:
        row = bc.SlicedRow(Z, L, D, slices=slices, crown="iso", misalignment=tilt)
        sol = bc.solve(row, comp.C, load)
        rigid = bc.solve(row, None, load)
        runs.append({"load": load, "misalignment": tilt, "time_s": sol.time_s, "iterations": sol.iterations,
                     "residual": sol.residual, "q_max": sol.q_max, "roller_loads": sol.roller_loads.tolist(),
                     "rigid_q_max": rigid.q_max, "rigid_roller_loads": rigid.roller_loads.tolist(),
                     "max_slice": float(sol.slice_loads.max()), "rigid_max_slice": float(rigid.slice_loads.max()),
                     "delta_x": float(sol.u[0])})
    return {"refine": m, "slices": slices, "housing_half_angle": housing, "dofs": int(comp.n_dofs), "cells": int(comp.cells),
            "build_s": build, "times": comp.times, "backend": comp.backend, "asymmetry": comp.asymmetry,
            "peak_rss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6, "runs": runs,
            "c_self": float(comp.C[slices // 2, slices // 2]),
            "c_roller": float(comp.C[:slices, :slices].mean())}


def main() -> dict:
    ap = argparse.ArgumentParser()
    ap.add_argument("--slices", type=int, default=10)
    ap.add_argument("--levels", type=int, nargs="+", default=[1, 2])
    args = ap.parse_args()
    warnings.simplefilter("ignore", DeprecationWarning)
    out = {"arc": [], "full": []}
    for m in args.levels:
        out["arc"].append(level(m, args.slices, np.pi / 3))
        r = out["arc"][-1]
        print(f"arc m={m}: {r['dofs']} DOFs, build {r['build_s']:.1f} s {r['times']}, solve "
              f"{max(x['time_s'] for x in r['runs']):.3f} s, Q_max {r['runs'][0]['q_max']:.2f} N "
              f"(rigid {r['runs'][0]['rigid_q_max']:.2f}), peak {r['peak_rss_gb']:.2f} GB", flush=True)
    out["full"].append(level(args.levels[0], args.slices, np.pi))
    if len(args.levels) >= 3:
        h = [1.0 / m for m in args.levels]
        out["richardson"] = {k: richardson(h, [lv[k] if k != "q_max" else lv["runs"][0]["q_max"]
                                               for lv in out["arc"]]).as_dict()
                             for k in ("c_self", "c_roller", "q_max")}
    OUT.mkdir(exist_ok=True)
    (OUT / "bearing_condensed3d.json").write_text(json.dumps(out, indent=1, default=float))
    lines = ["| housing | m | DOFs | cells | compliance build (s) | reused solve (s) | Newton it. | Q_max (N) | "
             "rigid Q_max (N) | max slice (N) | rigid max slice (N) |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for key, name in (("arc", "+-60 deg arc"), ("full", "full")):
        for lv in out[key]:
            r0 = lv["runs"][0]
            lines.append(f"| {name} | {lv['refine']} | {lv['dofs']} | {lv['cells']} | {lv['build_s']:.1f} | "
                         f"{max(x['time_s'] for x in lv['runs']):.3f} | {r0['iterations']} | {r0['q_max']:.1f} | "
                         f"{r0['rigid_q_max']:.1f} | {r0['max_slice']:.1f} | {r0['rigid_max_slice']:.1f} |")
    (OUT / "bearing_condensed3d.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return out


if __name__ == "__main__":
    main()
