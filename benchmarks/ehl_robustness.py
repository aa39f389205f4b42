"""Robustness of the EHL solver over the thesis range (issue 14): steady and centred-indent transient at Moes
(M, L) corners, each either converged or a ConvergenceError with its iterations and residual.

    flock /work/heavy.lock python benchmarks/ehl_robustness.py [--grid 257] [--scene-grid 129]
        [--fine-cases 0,6,7 --coarse-grid 129] [--steady-only] [--name ehl_robustness] [--out benchmarks/results]

Contact: ehl-indent's steel ball (Rx = Ry = 10 mm, E = 210 GPa, nu = 0.3), Roelands + Dowson-Higginson
(eta0 = 0.04 Pa s, alpha = 2.2e-8 1/Pa), pure rolling, domain [-2.5, 1.5] x [-2, 2] b, tolerances 1e-7 (mean
scaled residual and load error, every solve and every time step). Cases (M, L): (100, 3), (100, 19), (1200, 3),
(1200, 19), (347, 17.2) (seed 004 §4.3.1), (1000, 2), (50, 8), (100, 8). Per case:

- ``steady``: the smooth contact on ``--grid``;
- ``phi1``: the indent Phi = 1, D/Phi = 1/4, K = 4 (the one that made the 257^2 transient relaxation diverge at
  M = 50 and 100 before the transient under-relaxation of ``femcheck/ehl/relax.py``) marched from the inlet
  through the centre and out through the exit (the full crossing, every step's film checked) on ``--grid`` (with ``--fine-cases``: only for those cases, the others on ``--coarse-grid``, to keep
  the lock time down);
- ``scene``: ehl-indent's indent (Phi = 0.5, D/Phi = 0.5, K = 4) on ``--scene-grid`` (cheaper).

Reported: status (converged / ConvergenceError with iterations and residual), wall time, steps and cycles per
step, max load error over the steps, h_central, h_min, p_max (smooth), and at X_D = 0 the shoulder amplitude
(``outputs.additional_pressure``, Pa and / p_H). Results are written after every case (a cut-off run keeps what
it has).
"""
from __future__ import annotations

import argparse
import json
import re
import time
from pathlib import Path

import numpy as np

from femcheck.errors import ConvergenceError
from femcheck.ehl import groups, model

CASES = [(100.0, 3.0), (100.0, 19.0), (1200.0, 3.0), (1200.0, 19.0), (347.0, 17.2), (1000.0, 2.0), (50.0, 8.0),
         (100.0, 8.0)]
RX, E, NU, ETA0, ALPHA = 0.010, 210e9, 0.3, 0.04, 2.2e-8
E_PRIME = E / (1.0 - NU**2)
X_START, X_END, TOL = -2.5, 1.5, 1e-7
INDENTS = {"phi1": {"diameter": 1.0, "slope": 0.25, "decay": 4.0},
           "scene": {"diameter": 0.5, "slope": 0.5, "decay": 4.0}}


def setup(M: float, L: float, grid: int) -> model.Setup:
    g = groups.from_moes(M, L, RX, RX, E_PRIME, ETA0, ALPHA)
    return model.make_setup(g, "roelands", "dowson_higginson", grid, None, X_START, X_END)


def failed(e: ConvergenceError, t0: float, grid: int) -> dict:
    return {"status": "ConvergenceError", "grid": grid, "message": str(e), "iterations": getattr(e, "iterations", None),
            "residual": getattr(e, "residual", None), "time_s": time.perf_counter() - t0}


def run_steady(M: float, L: float, grid: int) -> dict:
    s = setup(M, L, grid)
    t0 = time.perf_counter()
    try:
        sol, _ = model.solve_smooth(s, TOL, TOL)
    except ConvergenceError as e:
        return failed(e, t0, grid)
    q = model.film_quantities(s, sol)
    return {"status": "converged", "time_s": time.perf_counter() - t0, "cycles": sol.cycles,
            "residual": sol.residual, "load_error": sol.load_error, "h_central": q["h_central"],
            "h_min": q["h_min"], "p_max": q["p_max"], "H_min_moes": q["H_min_moes"], "p_hertz": s.g.p_hertz}


def run_transient(M: float, L: float, grid: int, indent: dict) -> dict:
    s = setup(M, L, grid)
    t0 = time.perf_counter()
    try:
        c = model.crossing(s, indent, 0.0, TOL, TOL)
    except ConvergenceError as e:
        return failed(e, t0, grid)
    hist, sm = c["history"], c["smooth"]
    q = model.film_quantities(s, sm)
    amp = c["amplitudes"]["amplitude"][c["centre_step"] - 1]
    return {"status": "converged", "grid": grid, "time_s": time.perf_counter() - t0, "steps": c["steps"],
            "levels": s.levels, "cycles_per_step": float(np.mean(hist.cycles)), "max_cycles": int(max(hist.cycles)),
            "residual_max": float(max(hist.residual)), "load_error_max": float(max(hist.load_error)),
            "h_central": q["h_central"], "h_min": q["h_min"], "p_max": q["p_max"],
            "shoulder_amplitude": amp * s.g.p_hertz, "shoulder_amplitude_pH": amp, "p_hertz": s.g.p_hertz}


def cell(r: dict, transient: bool) -> str:
    g = f"{r['grid']}^2: " if transient else ""
    if r["status"] != "converged" and "negative film" in r["message"]:
        # the steps converged; the film of one of them is negative in the contact: refused as under-resolved
        hmin = r["message"].split("H_min = ")[1].split(" ")[0]
        at = re.search(r"step (\d+) of (\d+) \(T = [^,]*, indent centre X_D = (\S+) b\)", r["message"])
        where = f"step {at[1]} of {at[2]}, X_D = {at[3]} b" if at else "in the steady solution"
        return g + f"refused at {where}: negative film H_min = {hmin} (grid too coarse), {r['time_s']:.0f} s"
    if r["status"] != "converged":
        return g + f"ConvergenceError ({r['iterations']} it, res {r['residual']:.2g}), {r['time_s']:.0f} s"
    if not transient:
        return (f"{r['cycles']} cyc, {r['time_s']:.1f} s, load {r['load_error']:.1e}, h_c {r['h_central'] * 1e9:.1f} "
                f"nm, h_min {r['h_min'] * 1e9:.1f} nm, p_max {r['p_max'] / 1e9:.3f} GPa")
    return g + (f"{r['steps']} steps, {r['cycles_per_step']:.1f} cyc/step (max {r['max_cycles']}), {r['time_s']:.0f} s, "
            f"load <= {r['load_error_max']:.1e}, dP {r['shoulder_amplitude'] / 1e6:.0f} MPa "
            f"({r['shoulder_amplitude_pH']:.4f} p_H)")


def write(out: Path, res: dict, name: str = "ehl_robustness") -> None:
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{name}.json").write_text(json.dumps(res, indent=1))
    a = res["args"]
    what = (f"steady on {a['grid']}^2, Phi = 1 (D/Phi = 1/4, K = 4) transient on the grid given in the cell, "
            f"ehl-indent's indent (Phi = 0.5, D/Phi = 0.5, K = 4) on {a['scene_grid']}^2"
            if any("phi1" in c for c in res["cases"]) else f"steady on {a['grid']}^2 only (`--steady-only`)")
    lines = ["# EHL robustness over the thesis range (issue 14)", "",
             f"`benchmarks/ehl_robustness.py`; {what}; tolerances 1e-7; timings indicative (shared 2-core machine).",
             "",
             "| M | L | steady | transient Phi = 1 | transient scene indent |", "|---|---|---|---|---|"]
    for c in res["cases"]:
        row = [f"{c['M']:g}", f"{c['L']:g}"]
        for k, tr in (("steady", False), ("phi1", True), ("scene", True)):
            row.append(cell(c[k], tr) if k in c else "not run")
        lines.append("| " + " | ".join(row) + " |")
    (out / f"{name}.md").write_text("\n".join(lines) + "\n")


def rewrite_table(out: Path, name: str = "ehl_robustness") -> None:
    """Rewrite the .md from the stored .json (after a change of the table format)."""
    write(out, json.loads((out / f"{name}.json").read_text()), name)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", type=int, default=257)
    ap.add_argument("--scene-grid", type=int, default=129)
    ap.add_argument("--fine-cases", default="", help="case indices whose Phi = 1 transient runs on --grid")
    ap.add_argument("--coarse-grid", type=int, default=129)
    ap.add_argument("--only", default="", help="comma-separated case indices (0-based) to run")
    ap.add_argument("--steady-only", action="store_true", help="only the smooth steady solution of each case")
    ap.add_argument("--name", default="ehl_robustness", help="stem of the .json / .md written under --out")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results"))
    args = ap.parse_args()
    out = Path(args.out)
    idx = [int(i) for i in args.only.split(",")] if args.only else range(len(CASES))
    fine = {int(i) for i in args.fine_cases.split(",")} if args.fine_cases else set(range(len(CASES)))
    res = {"args": {"grid": args.grid, "scene_grid": args.scene_grid, "coarse_grid": args.coarse_grid,
                    "fine_cases": sorted(fine)}, "cases": []}
    for i in idx:
        M, L = CASES[i]
        case = {"M": M, "L": L}
        res["cases"].append(case)
        case["steady"] = run_steady(M, L, args.grid)
        print(f"M {M:g} L {L:g} steady: {cell(case['steady'], False)}", flush=True)
        write(out, res, args.name)
        if args.steady_only:
            continue
        case["phi1"] = run_transient(M, L, args.grid if i in fine else args.coarse_grid, INDENTS["phi1"])
        print(f"M {M:g} L {L:g} phi1: {cell(case['phi1'], True)}", flush=True)
        write(out, res, args.name)
        case["scene"] = run_transient(M, L, args.scene_grid, INDENTS["scene"])
        print(f"M {M:g} L {L:g} scene: {cell(case['scene'], True)}", flush=True)
        write(out, res, args.name)


if __name__ == "__main__":
    main()
