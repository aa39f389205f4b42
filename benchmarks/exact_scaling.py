"""Time vs error of Kalker's exact solver against grid size on the creep-curve scene (issue 6, item 5): the dense
Newton solver (LU of the 2C x 2C Newton matrix) and the matrix-free one (Newton-FGMRES with DC-FFT products,
femcheck.cect.tangential_fft).

The scene (steel on steel, Rx = 5 mm, Ry = 20 mm, 1 kN, mu = 0.3, xi = 0.005, eta = 0.002, phi = 10 1/m; partial
slip) is solved on n x n grids over +/- 1.1 Hertz semi-axes, n = 16 ... 256 (dense up to 48). The error of each grid is
measured against a Richardson-extrapolated value from the three finest matrix-free grids (64, 128, 256) (observed order,
femcheck.cect.creep.richardson); the two solvers give the same discrete solution to solver tolerance, so one
reference serves both. Timings are wall-clock on the machine the script runs on (one thread, shared cores): a
picture of the scaling, not a benchmark.

Run: OMP_NUM_THREADS=1 python benchmarks/exact_scaling.py
Writes benchmarks/results/exact_scaling.json.
"""
from __future__ import annotations

import json
import os
import tempfile
import time
from pathlib import Path

import femcheck
from femcheck.cect.creep import richardson

QUANTITIES = ("creep_force_x", "creep_force_y", "spin_moment", "adhesion_fraction")
FFT_GRIDS = (16, 32, 48, 64, 128, 256)
RICHARDSON_GRIDS = (64, 128, 256)     # doubling: the Richardson triple
DENSE_GRIDS = (16, 32, 48)


def solve(n: int, solver: str) -> dict:
    t0 = time.perf_counter()
    res = femcheck.run("creep-curve", overrides={"numerics.exact_cells": n, "numerics.exact_levels": 1, "numerics.exact_solver": solver,
                                                 "models.run": ["exact"], "models.references": ["exact"]})
    wall = time.perf_counter() - t0
    m = res.models["exact"]
    if m.status != "ok":
        raise RuntimeError(f"exact solver failed on {n}^2 ({solver}): {m.error}")
    s = m.stats
    return {"n": n, "solver": solver, "time_s": m.time_s if m.time_s is not None else wall,
            "contact_elements": s["contact_elements"], "newton_iterations": s["newton_iterations"],
            "gmres_iterations": s["gmres_iterations"], "normal_iterations": s["normal_iterations"],
            "tangential_residual": s["tangential_residual"],
            **{q: float(m.quantities[q]) for q in QUANTITIES}}


def main() -> dict:
    rows = []
    for n in FFT_GRIDS:
        rows.append(solve(n, "fft"))
        print({k: rows[-1][k] for k in ("n", "solver", "time_s", "newton_iterations", "gmres_iterations")},
              flush=True)
    for n in DENSE_GRIDS:
        rows.append(solve(n, "dense"))
        print({k: rows[-1][k] for k in ("n", "solver", "time_s", "newton_iterations")}, flush=True)
    finest = [next(r for r in rows if r["solver"] == "fft" and r["n"] == n) for n in RICHARDSON_GRIDS]
    reference, estimate, order = {}, {}, {}
    for q in QUANTITIES:
        reference[q], estimate[q], order[q] = richardson([r[q] for r in finest[-3:]])
    for r in rows:
        for q in QUANTITIES:
            r[f"{q}_rel_error"] = r[q] / reference[q] - 1.0
    # same grid, both solvers: the difference must be solver tolerance, not discretisation
    agreement = {}
    for n in DENSE_GRIDS:
        pair = [r for r in rows if r["n"] == n]
        if len(pair) == 2:
            agreement[n] = {q: abs(pair[0][q] - pair[1][q]) / abs(reference[q]) for q in QUANTITIES}
    out = {"scene": "creep-curve", "reference": "Richardson over the three finest fft grids "
           f"{list(RICHARDSON_GRIDS)}", "reference_values": reference, "reference_error_estimate": estimate,
           "observed_order": order, "rows": rows, "dense_vs_fft_same_grid": agreement,
           "note": "wall-clock seconds on a shared 2-core machine, one thread; scaling picture, not a benchmark"}
    path = Path(__file__).parent / "results" / "exact_scaling.json"
    path.parent.mkdir(exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, delete=False, suffix=".tmp") as f:
        json.dump(out, f, indent=1)
    os.replace(f.name, path)
    print(f"{'n':>4} {'solver':>6} {'C':>6} {'time s':>8} {'Newton':>6} {'GMRES':>6} " +
          " ".join(f"{q[:14]:>15}" for q in QUANTITIES))
    for r in rows:
        print(f"{r['n']:>4} {r['solver']:>6} {r['contact_elements']:>6} {r['time_s']:>8.2f} "
              f"{r['newton_iterations']:>6} {r['gmres_iterations']:>6} " +
              " ".join(f"{100 * r[q + '_rel_error']:>+14.3f}%" for q in QUANTITIES))
    print("reference:", {q: f"{reference[q]:.6g} +/- {estimate[q]:.2g} (order {order[q]})" for q in QUANTITIES})
    print("dense vs fft on the same grid (relative):", agreement)
    print(f"-> {path}")
    return out


if __name__ == "__main__":
    main()
