"""Scaling of femcheck's half-space BEM, and its two convolution back-ends side by side.

    python benchmarks/bem_scaling.py [--sizes 256,512,1024] [--mlmi-sizes 65,129,257,513,1025] [--out benchmarks/results]

Case: hertz-point (steel ball R = 10 mm on a steel flat, 1 kN; E* = 115.4 GPa, a = 0.402 mm), n x n cells over
+/- 1.25 a, tolerance 1e-10 on the relative gap residual, wall-clock time on this machine (threads as the
library chooses them: one below 1024^2 padded points, all cores above), best of repeats, operators built
before the clock starts (their set-up time is listed separately).

1. Solver scaling (issue 3: time at 1024^2 at most 20x the time at 256^2): plain Polonsky-Keer CG, with the
   circulant preconditioner, and preconditioned with a coarse-to-fine warm start. Per grid: iterations per
   level, time, time per finest-level iteration against its floor (two DC-FFT convolutions and one
   preconditioner application), and p_max against Hertz.
2. Convolution back-ends (issue 3 item 2): DC-FFT (exact) against MLMI at several interpolation orders and
   correction widths -- max relative error on a Hertz pressure field and on a random field, time per
   application, set-up time.
3. Contact solves with each back-end: iterations, time, p_max against DC-FFT and Hertz.
"""
from __future__ import annotations

import argparse
import json
import time
from functools import partial
from pathlib import Path

import numpy as np

from femcheck.analytic.hertz import point_contact
from femcheck.bem.convolution import DCFFT
from femcheck.bem.halfspace import grid, half_space_operator, half_space_preconditioner, operation_times, solve
from femcheck.bem.influence import love_rectangle
from femcheck.bem.mlmi import MLMI, error_against

R, P, E_STAR = 0.010, 1000.0, 210e9 / (2 * (1 - 0.3**2))
HERTZ = point_contact(P, R, E_STAR)
A = HERTZ.semi_axis_x


def gap(x, y):
    return (x * x + y * y) / (2 * R)


def best_of(f, repeats):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def solver_scaling(sizes):
    rows = []
    for n in sizes:
        g = grid(1.25 * A, 1.25 * A, n, n)
        t0 = time.perf_counter()
        half_space_operator(g, E_STAR), half_space_preconditioner(g, E_STAR)
        setup = time.perf_counter() - t0
        ops = operation_times(g, E_STAR)
        floor = 2 * ops["convolution_s"] + ops["preconditioner_s"]
        repeats = 3 if n <= 512 else 2
        for name, kw in (("plain", {"precondition": False}), ("preconditioned", {}),
                         ("preconditioned+warm", {"warm_levels": 8, "min_cells": 32})):
            if name == "plain" and n > 512:
                kw["max_iter"] = 5000
            for lv in range(9):                      # warm-start levels' operators built before timing too
                gk = g
                for _ in range(lv):
                    gk = gk.coarser()
                if min(gk.nx, gk.ny) >= 32:
                    half_space_operator(gk, E_STAR), half_space_preconditioner(gk, E_STAR)
            t, sol = best_of(lambda: solve(g, gap, E_STAR, P, tol=1e-10, **kw), repeats)
            fine = sol.stats["levels"][-1]
            rows.append({"n": n, "solver": name, "time_s": t, "setup_s": setup,
                         "iterations": [lv["iterations"] for lv in sol.stats["levels"]],
                         "level_cells": [lv["nx"] for lv in sol.stats["levels"]],
                         "finest_time_per_iteration_s": fine["time_s"] / fine["iterations"],
                         "convolution_s": ops["convolution_s"], "preconditioner_s": ops["preconditioner_s"],
                         "iteration_over_floor": fine["time_s"] / fine["iterations"] / floor,
                         "err_p_max": sol.result.pressure.max() / HERTZ.p_max - 1})
            print(f"{n:5d} {name:20s} {t:8.3f} s  its {rows[-1]['iterations']}  "
                  f"t/it {rows[-1]['finest_time_per_iteration_s'] * 1e3:7.1f} ms = "
                  f"{rows[-1]['iteration_over_floor']:.2f} x floor  p_max {rows[-1]['err_p_max']:+.1e}", flush=True)
    ratios = {}
    for name in ("plain", "preconditioned", "preconditioned+warm"):
        t = {r["n"]: r["time_s"] for r in rows if r["solver"] == name}
        if 256 in t and 1024 in t:
            ratios[name] = t[1024] / t[256]
    return rows, ratios


def backends(sizes, settings=((4, 4), (6, 6), (6, 10), (8, 12))):
    rows = []
    for n in sizes:
        g = grid(1.25 * A, 1.25 * A, n, n)
        kernel = partial(love_rectangle, dx=g.dx, dy=g.dy, modulus=E_STAR)
        X, Y = g.mesh()
        fields = {"hertz": HERTZ.pressure(X, Y), "random": np.random.default_rng(0).random((n, n))}
        t0 = time.perf_counter()
        ref = DCFFT(kernel, (n, n), (g.dx, g.dy))
        setup = time.perf_counter() - t0
        t_fft, _ = best_of(lambda: ref(fields["hertz"]), 5)
        rows.append({"n": n, "backend": "dcfft", "time_s": t_fft, "setup_s": setup, "err_hertz": 0.0,
                     "err_random": 0.0})
        print(f"{n:5d} dcfft            {t_fft * 1e3:9.2f} ms  (exact)", flush=True)
        for order, m in settings:
            t0 = time.perf_counter()
            op = MLMI(kernel, (n, n), (g.dx, g.dy), order=order, correction=m)
            setup = time.perf_counter() - t0
            t, _ = best_of(lambda: op(fields["hertz"]), 3)
            row = {"n": n, "backend": f"mlmi(order={order},m={m})", "time_s": t, "setup_s": setup,
                   "levels": len(op.levels), "time_over_dcfft": t / t_fft,
                   **{f"err_{k}": error_against(ref, op, f) for k, f in fields.items()}}
            rows.append(row)
            print(f"{n:5d} {row['backend']:17s}{t * 1e3:9.2f} ms = {t / t_fft:5.1f} x dcfft  err hertz "
                  f"{row['err_hertz']:.1e} random {row['err_random']:.1e}", flush=True)
    return rows


def contact_solves(sizes):
    rows = []
    for n in sizes:
        g = grid(1.25 * A, 1.25 * A, n, n)
        ref = None
        for conv in ("dcfft", "mlmi"):
            half_space_operator(g, E_STAR, -1, conv)
            t, sol = best_of(lambda: solve(g, gap, E_STAR, P, tol=1e-10, convolution=conv), 2)
            pm = float(sol.result.pressure.max())
            ref = ref or pm
            rows.append({"n": n, "convolution": conv, "time_s": t, "iterations": sol.result.iterations,
                         "err_p_max_vs_hertz": pm / HERTZ.p_max - 1, "diff_p_max_vs_dcfft": pm / ref - 1})
            print(f"{n:5d} {conv:6s} {t:8.3f} s its {sol.result.iterations:3d}  p_max vs Hertz "
                  f"{pm / HERTZ.p_max - 1:+.1e}  vs dcfft {pm / ref - 1:+.1e}", flush=True)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="256,512,1024")
    ap.add_argument("--mlmi-sizes", default="65,129,257,513,1025")
    ap.add_argument("--solve-sizes", default="65,129,257")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results"))
    args = ap.parse_args()
    ints = lambda s: [int(v) for v in s.split(",") if v]     # noqa: E731
    print("== solver scaling")
    scaling, ratios = solver_scaling(ints(args.sizes))
    for name, r in ratios.items():
        print(f"time(1024^2) / time(256^2), {name}: {r:.1f}x (N log N of the padded FFT: 19.6x)")
    print("== convolution back-ends")
    conv = backends(ints(args.mlmi_sizes))
    print("== contact solves per back-end")
    solves = contact_solves(ints(args.solve_sizes))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    doc = {"case": {"R_m": R, "load_N": P, "E_star_Pa": E_STAR, "a_m": A, "domain": "+/-1.25 a", "tol": 1e-10},
           "solver_scaling": scaling, "time_ratio_1024_over_256": ratios, "convolution_backends": conv,
           "contact_solves": solves}
    (out / "bem_scaling.json").write_text(json.dumps(doc, indent=1))
    print(f"wrote {out / 'bem_scaling.json'}")


if __name__ == "__main__":
    main()
