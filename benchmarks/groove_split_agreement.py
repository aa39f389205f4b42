"""The groove-rolling finite-body split against the pure FE at equal cell counts: on each of fem's levels (11 x 21,
17 x 31, 23 x 43 cells; grid and mesh exactly fem's), the exact theory's free rolling with the half-space
coefficients plus the FE correction of that level, without the near-field fill (near = 0: A_HS + (A_FE - A_HS)
= A_FE on the FE's own cells) and with the reference's fill (near = 2), against fem's own solution on the same
tables. Without the fill the two solve the same contact problem with two solvers; what remains is the kinematic
datum (the exact theory's rigid velocities at the approached pose, the FE's at the nominal one: delta / r0).
Writes benchmarks/results/groove_split_agreement.{json,md}.

    python benchmarks/groove_split_agreement.py [--levels 3]
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from femcheck.cect.groove_contact import GridSpec, solve_groove_cect
from femcheck.fem import compliance_split as cs
from femcheck.fem import groove_rolling as fg
from femcheck.fem.groove_finite_body import finite_body_rolling
from femcheck.problems import groove_rolling as kind
from femcheck.scene import load_scene

PAIRS = (("approach", "body_approach"), ("p_max", "p_max"), ("half_length_s", "contact_half_length_s"),
         ("adhesion_fraction", "adhesion_fraction"), ("creepage_x", "creepage_x"), ("friction_power", "friction_power"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--out", default="benchmarks/results/groove_split_agreement")
    a = ap.parse_args()
    p = {**fg.FEM_DEFAULTS, **load_scene("groove-rolling").params}
    geom, const = kind.geometry(p), kind._constants(p)
    rows = []
    for level in range(a.levels):
        t0 = time.perf_counter()
        grid = fg._grid(fg.setup(p), p, level)
        comp = fg.compliance(p, grid, level)
        fe = fg.solve_level(p, level, comp=comp)["quantities"]
        # the FE level's window in Hertz units (odd counts widen it by the rounding)
        hz = fg.setup(p)["hertz"]
        spec = GridSpec(grid.nx, grid.ns, 0.5 * grid.nx * grid.dx / hz.semi_axis_x,
                        0.5 * grid.ns * grid.ds / hz.semi_axis_y)
        for near in (0, 2):
            def solve(extra, omega0, spec=spec):
                return solve_groove_cect(geom, p["load.normal"], p["friction.mu"], const, p["kinematics.speed"],
                                         spec, extra_displacement=extra, omega0=omega0)

            fb = finite_body_rolling(solve, cs.correction(comp, const, near=near), tol=1e-7)
            q = fb.solution.quantities
            grid_ok = abs(fb.solution.grid.x[0] - grid.x[0]) < 1e-12 and abs(fb.solution.grid.s[0] - grid.s[0]) < 1e-12
            rows.append({"level": level, "cells": [grid.nx, grid.ns], "near": near, "same_cells": bool(grid_ok),
                         **{f"{k}_rel": (q[k] - fe[f]) / abs(fe[f]) for k, f in PAIRS if fe[f]},
                         "time_s": time.perf_counter() - t0})
            print(rows[-1], flush=True)
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".json").write_text(json.dumps(rows, indent=1))
    lines = ["| cells | fill | " + " | ".join(k for k, _ in PAIRS) + " |", "|---|---|" + "---|" * len(PAIRS)]
    for r in rows:
        lines.append(f"| {r['cells'][0]} x {r['cells'][1]} | {r['near']} | "
                     + " | ".join(f"{100 * r.get(k + '_rel', 0.0):+.3f} %" for k, _ in PAIRS) + " |")
    out.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
