"""srb-rolling on fine contact grids with finite-body coefficients: the CECT roller equilibrium (61 x 121 cells per
contact by default) with the FE finite-body correction (:mod:`femcheck.fem.srb_finite_body`), beside the
half-space CECT, at Table 2's cases.

The correction comes from the FE tables on a correction grid spanning the roller's length (nx x ns cells, the
roller, both ring segments; :mod:`femcheck.fem.compliance_split`, near-field fill ``--near`` cells).

    python benchmarks/srb_finite_body.py [--mu 0.1] [--cells 61 121] [--correction 13 25] [--out DIR]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

from femcheck.cect.influence import combined_constants
from femcheck.fem import compliance_split as cs
from femcheck.fem import srb_rolling as fe
from femcheck.fem.rolling_compliance import MeshSettings
from femcheck.fem.srb_finite_body import finite_body_equilibrium
from femcheck.problems import _srb_rolling_out as out_q
from femcheck.problems import srb_rolling as kind
from femcheck.scene import elastic, load_scene

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from srb_split_compliance import ROOT, _key, load_tables, log, save_tables  # noqa: E402

QUANTITIES = ("f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "f_lat_sum", "d_y", "tilt", "skew",
              "omega_m_deviation", "omega_R_deviation")


def correction_tables(p: dict, nx: int, ns: int, mesh: MeshSettings, out: pathlib.Path):
    grids = fe.grids(p, nx, ns, float(p["load.normal"]), half_x=1.35, half_s=3.0)
    key = _key("roller-span", nx, ns, mesh, {k: v for k, v in p.items() if k.startswith(("geometry.", "materials."))},
               float(p["load.normal"]))
    path = out / f"correction_{nx}x{ns}_{key}.npz"
    if (stored := load_tables(path, grids)) is not None:     # None: missing or damaged
        return stored
    log(f"FE compliance on the correction grid {nx} x {ns} (roller span)")
    t = fe.compliance(p, grids, mesh, progress=log)
    save_tables(path, t)
    return t


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mu", type=float, default=0.1)
    ap.add_argument("--cells", type=int, nargs=2, default=(61, 121))
    ap.add_argument("--correction", type=int, nargs=2, default=(13, 25))
    ap.add_argument("--h-contact", type=float, default=0.7)
    ap.add_argument("--layers", type=int, default=1)
    ap.add_argument("--near", type=int, default=2)
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "out" / "srb_split"))
    a = ap.parse_args(argv)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    scene = load_scene(ROOT / "femcheck" / "scenes" / "srb-rolling.toml",
                       overrides={"friction.mu": a.mu, "numerics.conformal_cells_x": a.cells[0],
                                  "numerics.conformal_cells_s": a.cells[1]})
    p = scene.params
    constants = combined_constants(elastic(p, "roller"), elastic(p, "ring"))
    mesh = MeshSettings(a.h_contact, 0.4 / 1.4142135623730951, 2e-3, a.layers, 2)
    t0 = time.perf_counter()
    tables = correction_tables(p, *a.correction, mesh, out)
    corr = cs.correction(tables, constants, a.near)
    t_corr = time.perf_counter() - t0
    pr, num = kind.problem_of(p), kind.numerics_of(p)
    t0 = time.perf_counter()
    log(f"half-space CECT equilibrium {a.cells[0]} x {a.cells[1]}")
    start = kind.solved(p)
    t_hs = time.perf_counter() - t0
    fb = finite_body_equilibrium(pr, num, corr, start, progress=log)
    q_hs, q_fb = out_q.quantities(pr, start), out_q.quantities(pr, fb.result)
    res = {"mu": a.mu, "cells": list(a.cells), "correction": list(a.correction), "near": a.near,
           "mesh": str(mesh), "n_dofs": tables.stats.get("n_dofs"), "correction_s": t_corr,
           "halfspace_s": t_hs, "finite_body_s": fb.time_s, "outer_iterations": fb.iterations,
           "history": fb.history, "halfspace": {k: q_hs.get(k) for k in QUANTITIES},
           "finite_body": {k: q_fb.get(k) for k in QUANTITIES}}
    for k in QUANTITIES:
        log(f"{k:20s} half-space {q_hs.get(k): .6e}   finite body {q_fb.get(k): .6e}")
    path = out / f"finite_body_mu{a.mu:g}_{a.cells[0]}x{a.cells[1]}_c{a.correction[0]}x{a.correction[1]}_near{a.near}" \
                 f"_h{a.h_contact:g}_l{a.layers}.json"
    path.write_text(json.dumps(res, indent=1, default=str))
    log(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
