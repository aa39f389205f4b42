"""Seed 004 Figs 3.17-3.21: the nabla_Phi master curves of a shallow indent in a pure-rolling EHL point contact.

    flock /tmp/femcheck-cpu.lock python benchmarks/ehl_master_curves.py [--workers 2] [--scheduler ADDR|local-dask]
        [--dask-workers 2] [--grid 65] [--cache DIR] [--out benchmarks/results] [--label NAME] [--retry-failed]
        [--case M:L:Phi:K ...]
    python benchmarks/ehl_master_curves.py --resolution 129 [--grid 65] --out benchmarks/results   # grid error
    python benchmarks/ehl_master_curves.py --report --out benchmarks/results       # md + png from the JSON

Grid (54 EHL cases + 6 dry): M 100, 400, 1200; L 3, 8, 19; Phi 0.25, 0.5, 1; K 3, 8 (seed 004's range, §3.3.3).
65^2 nodes keep one sweep at about 10 min of CPU (measured: 567 s of case time); the 65^2 -> 129^2 change of
the ratios is measured by ``--resolution`` (benchmarks/results/ehl_master_curves.md).

For every case (M, L, Phi, K) of the grid below, the relative initial slopes S dP^EHL / S dP^DRY of the additional
pressure over the rear and front shoulders and in the hole (seed 004 eq 3.9: S dP = d dP / d(D/Phi) at
D/Phi -> 0) against nabla_Phi = Phi sqrt(M/L) (eq 3.8; the thesis gives only the proportionality, so the
constant is 1 here, spec ehl-life §A.6), and the fit of eq 3.7, S dP^EHL / S dP^DRY = 1 - 1/(1 + f), with
f = (nabla_Phi / c)^q.

EHL case: circular contact (steel E' = 226 GPa, Rx = Ry = 10 mm, Roelands and Dowson-Higginson, eta0 = 0.04 Pa s,
alpha = 22 GPa^-1, M and L by the load and the speed, femcheck.ehl.groups.from_moes), domain [-2.5, 1.5] b along
X and +-2 b across, GRID^2 nodes. One steady smooth solution; then per indent slope D/Phi (0.05 and 0.1) the
indent enters at the inlet and is marched (NU2, time step = mesh size) to the centre X_D = 0, where the amplitudes
are read (femcheck.ehl.outputs.additional_pressure: the same routine as ``femcheck run ehl-indent``). The initial
slope is Richardson's 2 dP(0.05)/0.05 - dP(0.1)/0.1 (spec §A.6).
Dry case (per Phi, K): femcheck's BEM (femcheck.bem.halfspace) on the Hertz contact of the same dimensionless
scaling, the same two slopes and the same Richardson step; dry rear = front = the axisymmetric amplitude
max dP, dry centre = min dP in the hole.

Cases run through femcheck.executor.map_cases: local worker processes (default) or a dask.distributed cluster
(``--scheduler tcp://host:8786``, or ``local-dask`` to start a LocalCluster of ``--dask-workers`` processes on
this machine). Every finished case is written at once to the case cache (one JSON file per case, keyed on its
inputs and on the source of the code it runs), so an interrupted sweep resumes where it stopped; a case that fails
is recorded with its status and message, and the others go on.
"""
from __future__ import annotations

import argparse
import copy
import dataclasses
import hashlib
import inspect
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from femcheck import provenance
from femcheck.cache import cache_dir
from femcheck.executor import Interrupted, map_cases, stop_on_signals

E_PRIME, ETA0, ALPHA, RX = 226e9, 0.04, 2.2e-8, 0.01
X_START, X_END = -2.5, 1.5
SLOPES = (0.05, 0.1)
TOL = 1e-7
M_VALUES = (100.0, 400.0, 1200.0)
L_VALUES = (3.0, 8.0, 19.0)
PHI_VALUES = (0.25, 0.5, 1.0)
K_VALUES = (3.0, 8.0)
DRY_CELLS_PER_PHI = 32          # BEM cells per indent diameter (dry reference)
DRY_HALF = 1.6                  # BEM domain +-1.6 b
CODE_MODULES = ("femcheck.ehl.model", "femcheck.ehl.outputs", "femcheck.ehl.transient", "femcheck.bem.halfspace",
                "femcheck.geometry.profiles")


# ---------------------------------------------------------------------------------------------------- cases
def ehl_case(M: float, L: float, phi: float, K: float, grid: int) -> dict:
    return {"kind": "ehl", "M": float(M), "L": float(L), "phi": float(phi), "K": float(K), "grid": int(grid),
            "slopes": list(SLOPES)}


def dry_case(phi: float, K: float) -> dict:
    return {"kind": "dry", "phi": float(phi), "K": float(K), "cells_per_phi": DRY_CELLS_PER_PHI,
            "slopes": list(SLOPES)}


def default_cases(grid: int) -> list[dict]:
    cases = [dry_case(p, K) for K in K_VALUES for p in PHI_VALUES]
    cases += [ehl_case(M, L, p, K, grid) for K in K_VALUES for M in M_VALUES for L in L_VALUES for p in PHI_VALUES]
    return cases


def richardson(s: list[float], amps: list[float]) -> float:
    """Initial slope from two slopes s1 < s2: the secants a/s extrapolated linearly in s to s = 0."""
    (s1, s2), (a1, a2) = s, amps
    return (s2 * a1 / s1 - s1 * a2 / s2) / (s2 - s1)


def _ehl(case: dict) -> dict:
    from femcheck.ehl import groups, model, outputs, transient
    from femcheck.ehl.film import Indent

    M, L, phi, K, grid = case["M"], case["L"], case["phi"], case["K"], case["grid"]
    if not (M > 0 and L > 0 and phi > 0 and K > 0):
        raise ValueError(f"M, L, Phi, K must be > 0 (got M={M}, L={L}, Phi={phi}, K={K})")
    if grid < 33 or (grid - 1) & (grid - 2):
        raise ValueError(f"grid must be 2^k + 1 >= 33 nodes (got {grid})")
    g = groups.from_moes(M, L, RX, RX, E_PRIME, ETA0, ALPHA)
    s = model.make_setup(g, "roelands", "dowson_higginson", grid, None, X_START, X_END)
    smooth, mg0 = model.solve_smooth(s, TOL, TOL)
    film = outputs.film_measures(smooth.x, smooth.y, smooth.P, smooth.H)
    h = mg0.fine.h
    centre, _ = model.crossing_steps(phi, X_START, h, 1.0)
    amps = {k: [] for k in ("rear", "front", "lateral", "centre")}
    cycles = []
    for slope in case["slopes"]:
        mg = copy.deepcopy(mg0)
        ind = Indent(phi, slope * phi, K, x0=-centre * h, speed_ratio=1.0)
        mg.prob = dataclasses.replace(s.prob, indent=ind)
        mg.set_time(0.0)
        transient.start(mg)
        hist = transient.march(mg, centre, tol=TOL, load_tol=TOL, keep=lambda k, T: k == centre, base=smooth.P)
        sol = hist.snapshots[-1]
        a = outputs.additional_pressure(sol.x, sol.y, sol.P - smooth.P, ind.centre(mg.T), 0.0, phi)
        for k in amps:
            amps[k].append(a[k])
        cycles.append(float(np.mean(hist.cycles)))
    return {"amplitudes": amps, "steps": centre, "mean_cycles": cycles, "H_central": film["H_central"],
            "H_min": film["H_min"], "nabla_phi": phi * np.sqrt(M / L)}


def _dry(case: dict) -> dict:
    from femcheck.bem import halfspace
    from femcheck.geometry.profiles import indented, paraboloid

    phi, K = case["phi"], case["K"]
    if not (phi > 0 and K > 0):
        raise ValueError(f"Phi, K must be > 0 (got Phi={phi}, K={K})")
    # dimensionless Hertz scaling (b = 1, Rx = 1, p_H = 1): E* with a = 1 at unit Rx needs W = 4 a^3 E*/(3 R)
    n = int(2 ** np.ceil(np.log2(2 * DRY_HALF * case["cells_per_phi"] / phi))) + 1
    e_star = np.pi / 2.0                       # p_H = 2 a E*/(pi R) = 1 with a = R = 1
    load = 4.0 * e_star / 3.0
    gr = halfspace.grid(DRY_HALF, DRY_HALF, n, n)
    smooth = halfspace.solve(gr, paraboloid(1.0, 1.0), e_star, load).result.pressure
    X, Y = gr.mesh()
    r = np.hypot(X, Y)
    amps = {"amplitude": [], "centre": []}
    for slope in case["slopes"]:
        p = halfspace.solve(gr, indented(paraboloid(1.0, 1.0), phi, slope * phi, K), e_star, load).result.pressure
        dP = p - smooth
        amps["amplitude"].append(float(dP.max()))
        amps["centre"].append(float(dP[r <= 0.5 * phi].min()))
    return {"amplitudes": amps, "cells": n, "p_max_smooth": float(smooth.max())}


def run_case(case: dict) -> dict:
    """One case -> {"case", "status": "ok"|"failed", "time_s", ...}; never raises for a bad case (the message is
    kept), so that one failure does not stop a sweep."""
    t0 = time.perf_counter()
    try:
        out = _ehl(case) if case.get("kind") == "ehl" else _dry(case) if case.get("kind") == "dry" else None
        if out is None:
            raise ValueError(f"unknown case kind {case.get('kind')!r} (allowed: ehl, dry)")
        out["slope"] = {k: richardson(case["slopes"], v) for k, v in out["amplitudes"].items()}
        out["status"] = "ok"
    except Exception as err:            # noqa: BLE001 - recorded in the result; the other cases go on
        out = {"status": "failed", "error": f"{type(err).__name__}: {str(err)[:400]}"}
    out.update({"case": case, "time_s": time.perf_counter() - t0, "pid": os.getpid()})
    return out


# ---------------------------------------------------------------------------------------------------- cache
def code_digest() -> str:
    """The source of the femcheck modules the cases run (and everything they import) and of this script's case
    functions and constants (not its reporting, so that a new plot does not invalidate the cached cases)."""
    own = "".join(inspect.getsource(f) for f in (run_case, _ehl, _dry, richardson))
    own += repr((E_PRIME, ETA0, ALPHA, RX, X_START, X_END, TOL, DRY_HALF))
    return hashlib.sha256((provenance.code_digest(CODE_MODULES) + own).encode()).hexdigest()[:16]


def case_key(case: dict, code: str) -> str:
    return hashlib.sha256(json.dumps({"case": case, "code": code}, sort_keys=True).encode()).hexdigest()[:24]


def _write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def sweep(cases: list[dict], cache: Path, workers: int = 2, scheduler: str | None = None,
          retry_failed: bool = False, log=print) -> dict:
    """Run the cases not in the cache; returns {"results" (in case order), "computed", "cached", "wall_s"}."""
    code = code_digest()
    keys = [case_key(c, code) for c in cases]
    results: list[dict | None] = [None] * len(cases)
    todo = []
    for i, k in enumerate(keys):
        path = cache / f"{k}.json"
        if path.is_file():
            r = json.loads(path.read_text())
            if r["status"] == "ok" or not retry_failed:
                results[i] = r
                continue
        todo.append(i)
    n_cached = len(cases) - len(todo)
    log(f"{len(cases)} cases: {n_cached} from the cache, {len(todo)} to run"
        + (f" on {scheduler}" if scheduler else f" in {workers} local processes"))
    t0 = time.perf_counter()
    done = [0]

    def on_done(j: int, r: dict) -> None:
        i = todo[j]
        results[i] = r
        _write_atomic(cache / f"{keys[i]}.json", json.dumps(r))
        done[0] += 1
        c = r["case"]
        what = " ".join(f"{k}={c[k]:g}" for k in ("M", "L", "phi", "K") if k in c)
        msg = "ok" if r["status"] == "ok" else f"FAILED {r['error']}"
        log(f"[{done[0]}/{len(todo)}] {c['kind']} {what}: {msg} ({r['time_s']:.1f} s, "
            f"elapsed {time.perf_counter() - t0:.0f} s)")

    if todo:
        map_cases(run_case, [cases[i] for i in todo], workers=workers, on_done=on_done, scheduler=scheduler)
    return {"results": results, "computed": len(todo), "cached": n_cached, "wall_s": time.perf_counter() - t0,
            "code": code, "case_time_s": sum(results[i]["time_s"] for i in todo)}


# ---------------------------------------------------------------------------------------------------- analysis
SERIES = (("rear", "amplitude"), ("front", "amplitude"), ("centre", "centre"), ("lateral", "amplitude"))


def master(x: np.ndarray, c: float, q: float) -> np.ndarray:
    """Eq 3.7 with f = (nabla_Phi / c)^q: 1 - 1/(1 + f) (0 at nabla_Phi = 0, 1 for nabla_Phi -> inf)."""
    f = (np.asarray(x, float) / c) ** q
    return f / (1.0 + f)


def fit_master(x: np.ndarray, y: np.ndarray) -> dict:
    """Least-squares fit of :func:`master` (c, q > 0) and its scatter: rms and max |residual| (absolute, in the
    ratio), rms of the residual relative to the curve, R^2 of the curve against the scatter about the mean."""
    from scipy.optimize import least_squares

    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = np.isfinite(x) & np.isfinite(y)          # a case without that shoulder (NaN amplitude) is left out
    x, y = x[keep], y[keep]
    sol = least_squares(lambda v: master(x, np.exp(v[0]), np.exp(v[1])) - y, [0.0, 0.0])
    c, q = np.exp(sol.x)
    res = master(x, c, q) - y
    return {"c": float(c), "q": float(q), "n": int(x.size), "rms": float(np.sqrt(np.mean(res ** 2))),
            "max_abs": float(np.abs(res).max()), "rms_rel": float(np.sqrt(np.mean((res / master(x, c, q)) ** 2))),
            "R2": float(1.0 - np.sum(res ** 2) / np.sum((y - y.mean()) ** 2)),
            "at": {f"{v:g}": float(master(v, c, q)) for v in (0.5, 1.0, 2.0, 5.0, 10.0, 20.0)}}


def analyse(results: list[dict]) -> dict:
    """Ratios S dP^EHL / S dP^DRY of every finished EHL case, the fits per series (rear, front, centre, lateral)
    and K, and the failed cases."""
    dry = {(r["case"]["phi"], r["case"]["K"]): r["slope"] for r in results
           if r["case"]["kind"] == "dry" and r["status"] == "ok"}
    rows, failed = [], []
    for r in results:
        c = r["case"]
        if r["status"] != "ok":
            failed.append({"case": c, "error": r["error"]})
            continue
        if c["kind"] != "ehl":
            continue
        d = dry.get((c["phi"], c["K"]))
        if d is None:
            failed.append({"case": c, "error": "no dry slope for this (Phi, K)"})
            continue
        row = {k: c[k] for k in ("M", "L", "phi", "K", "grid")}
        row["nabla_phi"] = c["phi"] * np.sqrt(c["M"] / c["L"])
        row["slope"] = r["slope"]
        row["ratio"] = {name: r["slope"][name] / d[ref] for name, ref in SERIES}
        row["H_min"], row["time_s"] = r["H_min"], r["time_s"]
        rows.append(row)
    fits = {}
    for name, _ in SERIES:
        for K in sorted({r["K"] for r in rows}):
            sel = [r for r in rows if r["K"] == K]
            if sum(np.isfinite(r["ratio"][name]) for r in sel) >= 3:
                x = np.array([r["nabla_phi"] for r in sel])
                y = np.array([r["ratio"][name] for r in sel])
                f = fit_master(x, y)
                # is one curve enough? the mean residual per Phi (a systematic Phi trend is not scatter)
                f["mean_residual_by_phi"] = {f"{p:g}": float(np.nanmean([master(r["nabla_phi"], f["c"], f["q"])
                                                                          - r["ratio"][name] for r in sel
                                                                          if r["phi"] == p]))
                                             for p in sorted({r["phi"] for r in sel})}
                fits[f"{name}_K{K:g}"] = f
    k3 = [r for r in rows if r["K"] == 3.0]
    if k3:
        x = np.array([r["nabla_phi"] for r in k3] * 3)
        y = np.array([r["ratio"][n] for n in ("rear", "front", "centre") for r in k3])
        fits["all3_K3"] = fit_master(x, y)
    above = [{"case": {k: r[k] for k in ("M", "L", "phi", "K")}, "series": n, "ratio": r["ratio"][n]}
             for r in rows for n in ("rear", "front", "centre") if r["ratio"][n] > 1.0]
    return {"dry": [{"phi": p, "K": K, **v} for (p, K), v in sorted(dry.items())], "cases": rows, "fits": fits,
            "failed": failed, "above_dry": above}


def plot(a: dict, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharey=True)
    xs = np.geomspace(0.3, 40.0, 200)
    marks = {0.25: "o", 0.5: "s", 1.0: "^"}
    colours = {3.0: "tab:blue", 8.0: "tab:red"}
    for ax, name, fig_no in zip(axes, ("rear", "front", "centre"), ("3.17", "3.18", "3.19")):
        for r in a["cases"]:
            ax.plot(r["nabla_phi"], r["ratio"][name], marks.get(r["phi"], "x"), color=colours.get(r["K"], "k"),
                    mfc="none", ms=6)
        for K, col in colours.items():
            f = a["fits"].get(f"{name}_K{K:g}")
            if f:
                ax.plot(xs, master(xs, f["c"], f["q"]), "-", color=col,
                        label=f"K = {K:g}: c = {f['c']:.2f}, q = {f['q']:.2f}, rms {f['rms']:.3f}")
        ax.set_xscale("log")
        ax.set_xlabel(r"$\nabla_\Phi = \Phi\sqrt{M/L}$")
        ax.set_title(f"{name} (thesis Fig {fig_no})")
        ax.axhline(1.0, color="0.6", lw=0.8, ls="--")
        ax.legend(fontsize=7, loc="upper left")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel(r"$S\Delta P^{EHL} / S\Delta P^{DRY}$")
    for p, mk in marks.items():
        axes[2].plot([], [], mk, color="k", mfc="none", label=f"Phi = {p:g}")
    axes[2].legend(fontsize=7, loc="upper left")
    fig.suptitle("femcheck: relative initial slopes of the additional pressure against nabla_Phi "
                 "(M 100-1200, L 3-19, Phi 0.25-1, K 3 and 8)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_outputs(out: Path, results: list[dict], run: dict, label: str, grid: int) -> dict:
    """benchmarks/results/ehl_master_curves.{json,png} (the md is written by hand around these numbers). The
    run record of ``label`` (wall time, scheduler, counts) is merged into the existing file's ``runs``."""
    path = out / "ehl_master_curves.json"
    old = json.loads(path.read_text()) if path.is_file() else {}
    a = analyse(results)
    # the same cases run before (e.g. on local processes, now on dask): how far apart are the slopes?
    before = {json.dumps(r["case"], sort_keys=True): r for r in old.get("results", []) if r["status"] == "ok"}
    diffs = [abs(r["slope"][k] / b["slope"][k] - 1.0) for r in results if r["status"] == "ok"
             for b in [before.get(json.dumps(r["case"], sort_keys=True))] if b for k in r["slope"]]
    if diffs:
        run["max_rel_difference_to_previous_run"] = float(max(diffs))
        run["compared_slopes"] = len(diffs)
    runs = old.get("runs", {})
    runs[label] = run
    doc = {"grid": grid, "domain_b": [X_START, X_END, -2.0, 2.0], "slopes": list(SLOPES),
           "nabla_phi": "Phi sqrt(M/L)", "fit": "1 - 1/(1 + (nabla_Phi/c)^q)", "runs": runs,
           "resolution": old.get("resolution"), **a, "results": results}
    _write_atomic(path, json.dumps(doc, indent=1))
    plot(a, out / "ehl_master_curves.png")
    write_md(doc, out / "ehl_master_curves.md")
    return doc


THESIS = [
    "Figs 3.17 (rear), 3.18 (front): 'a single curve can be clearly observed'; the ratio increases with nabla_Phi "
    "between two asymptotes, 0 (small deformation, small perturbation) and 1 (indent flattened, dry amplitude)",
    "Fig 3.19 (centre): 'as the behavior of the pressure in the indent hole is very non-linear, results are less "
    "satisfying' (more scatter than rear and front)",
    "Fig 3.20: rear, front and centre 'are very similar and no clear difference can be extracted when accounting "
    "for the numerical accuracy'",
    "Fig 3.21: 'the additional pressure amplitude initial slope is lower when the shoulders are flatter' (K = 8 "
    "below K = 3), similar trends",
    "§3.3: for pure rolling 'the dry contact pressure is an upper limit' (ratio <= 1)",
    "eq 3.7-3.8: ratio = 1 - 1/(1 + f(nabla_Phi)), f(0) = 0, f increasing, nabla_Phi proportional to Phi sqrt(M/L); "
    "the constant, f and every plotted value are figure-only (not printed)",
]


def write_md(doc: dict, path: Path) -> None:
    L = ["# nabla_Phi master curves (seed 004 Figs 3.17-3.21)", "",
         f"Relative initial slopes S dP^EHL / S dP^DRY against nabla_Phi = Phi sqrt(M/L), circular pure-rolling "
         f"EHL contact on {doc['grid']}^2 nodes over [-2.5, 1.5] x [-2, 2] b, indent slopes D/Phi = "
         f"{', '.join(f'{v:g}' for v in doc['slopes'])} with Richardson (seed 004 eq 3.9); dry slopes from the BEM "
         f"({DRY_CELLS_PER_PHI} cells per indent diameter). Fit (eq 3.7): {doc['fit']}.", "",
         "| run | scheduler | workers | cases | computed | failed | wall time (s) | sum of case times (s) | "
         "max rel. difference to the previous run |", "|---|---|---|---|---|---|---|---|---|"]
    for name, r in doc["runs"].items():
        d = r.get("max_rel_difference_to_previous_run")
        L.append(f"| {name} | {r['scheduler']} | {r['workers']} | {r['cases']} | {r['computed']} | {r['failed']} | "
                 f"{r['wall_s']:.0f} | {r.get('case_time_s', float('nan')):.0f} | "
                 + (f"{d:.1e} ({r['compared_slopes']} slopes)" if d is not None else "") + " |")
    L += ["", "Fits (c, q of f = (nabla_Phi/c)^q; scatter = residuals of the cases about the curve):", "",
          "| series | n | c | q | rms | max abs | rms rel. | R^2 | at nabla_Phi = 1 | 2 | 5 | 10 | "
          "mean residual by Phi (0.25 / 0.5 / 1) |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, f in doc["fits"].items():
        by = " / ".join(f"{v:+.3f}" for v in f.get("mean_residual_by_phi", {}).values())
        L.append(f"| {name} | {f['n']} | {f['c']:.3f} | {f['q']:.3f} | {f['rms']:.3f} | {f['max_abs']:.3f} | "
                 f"{f['rms_rel']:.1%} | {f['R2']:.3f} | {f['at']['1']:.3f} | {f['at']['2']:.3f} | "
                 f"{f['at']['5']:.3f} | {f['at']['10']:.3f} | {by} |")
    L += ["", "(mean residual = curve - cases: positive where the cases of that Phi lie below the curve.)", "",
          "Dry reference slopes (BEM, Richardson of D/Phi 0.05 and 0.1):", "", "| Phi | K | S dP^DRY (max) | "
          "S dP_CENT^DRY (hole) |", "|---|---|---|---|"]
    for d in doc["dry"]:
        L.append(f"| {d['phi']:g} | {d['K']:g} | {d['amplitude']:.4f} | {d['centre']:.4f} |")
    chk = doc.get("dask_case_time_check")
    if chk:
        L += ["", f"Why the dask cases run slower: {chk['what']}", "", "| run | wall (s) | case times (s) |",
              "|---|---|---|"]
        L += [f"| {r['run']} | {r['wall_s']:.1f} | {', '.join(f'{t:.1f}' for t in r['case_times'])} |"
              for r in chk["runs"]]
    res = doc.get("resolution")
    if res and res.get("cases"):
        L += ["", "Discretisation error of the sweep's grid (same case on two grids; relative difference of the "
              "ratio, coarse / fine - 1):", "", "| M | L | Phi | K | grids | rear | front | centre | lateral | "
              "case time coarse / fine (s) |", "|---|---|---|---|---|---|---|---|---|---|"]
        for c in res["cases"]:
            rd = c["rel_difference"]
            L.append(f"| {c['M']:g} | {c['L']:g} | {c['phi']:g} | {c['K']:g} | {c['coarse']}^2 / {c['fine']}^2 | "
                     f"{rd['rear']:+.1%} | {rd['front']:+.1%} | {rd['centre']:+.1%} | {rd['lateral']:+.1%} | "
                     f"{c['time_s'][str(c['coarse'])]:.0f} / {c['time_s'][str(c['fine'])]:.0f} |")
    if doc["failed"]:
        L += ["", "Failed cases (reported, the others finished):", ""]
        for f in doc["failed"]:
            c = f["case"]
            what = " ".join(f"{k} = {c[k]:g}" for k in ("M", "L", "phi", "K") if k in c)
            L.append(f"- {c['kind']} {what}, {c.get('grid', '')}^2: {f['error'][:170]}...")
    if doc.get("above_dry"):
        L += ["", f"Ratios above 1 (above the dry upper bound): {len(doc['above_dry'])}: "
              + ", ".join(f"{a['series']} {a['case']} {a['ratio']:.3f}" for a in doc["above_dry"])]
    L += ["", "Per case (ratios rear / front / centre / lateral):", "",
          "| M | L | Phi | K | nabla_Phi | rear | front | centre | lateral | H_min smooth | time (s) |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in sorted(doc["cases"], key=lambda c: (c["K"], c["nabla_phi"])):
        r = c["ratio"]
        L.append(f"| {c['M']:g} | {c['L']:g} | {c['phi']:g} | {c['K']:g} | {c['nabla_phi']:.3f} | {r['rear']:.3f} | "
                 f"{r['front']:.3f} | {r['centre']:.3f} | {r['lateral']:.3f} | {c['H_min']:.4f} | {c['time_s']:.1f} |")
    L += ["", "What the thesis states (its values are figure-only):", ""] + [f"- {t}" for t in THESIS]
    _write_atomic(path, "\n".join(L) + "\n")


def report(out: Path) -> dict:
    """Rewrite the md and png from benchmarks/results/ehl_master_curves.json (no case runs)."""
    doc = json.loads((out / "ehl_master_curves.json").read_text())
    write_md(doc, out / "ehl_master_curves.md")
    plot(doc, out / "ehl_master_curves.png")
    return doc


RESOLUTION_CASES = ((400.0, 8.0, 0.5, 3.0), (400.0, 8.0, 0.25, 3.0))


def resolution(cache: Path, coarse: int, fine: int, workers: int, scheduler: str | None) -> dict:
    """The discretisation error of the sweep's grid: the same cases at ``coarse`` and ``fine`` nodes, the
    relative difference of each slope ratio (the dry slope is the same for both)."""
    cases = [dry_case(p, K) for _, _, p, K in RESOLUTION_CASES]
    cases += [ehl_case(M, L, p, K, n) for M, L, p, K in RESOLUTION_CASES for n in (coarse, fine)]
    a = analyse(sweep(cases, cache, workers, scheduler)["results"])
    out = []
    for M, L, p, K in RESOLUTION_CASES:
        at = {r["grid"]: r for r in a["cases"] if (r["M"], r["L"], r["phi"], r["K"]) == (M, L, p, K)}
        if coarse in at and fine in at:
            out.append({"M": M, "L": L, "phi": p, "K": K, "coarse": coarse, "fine": fine,
                        "ratio_coarse": at[coarse]["ratio"], "ratio_fine": at[fine]["ratio"],
                        "rel_difference": {n: at[coarse]["ratio"][n] / at[fine]["ratio"][n] - 1.0
                                           for n in at[fine]["ratio"]},
                        "time_s": {str(coarse): at[coarse]["time_s"], str(fine): at[fine]["time_s"]}})
    return {"cases": out, "failed": a["failed"]}


# ---------------------------------------------------------------------------------------------------- main
def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=65)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", default=None)
    ap.add_argument("--dask-workers", type=int, default=2)
    ap.add_argument("--cache", type=Path, default=cache_dir() / "ehl_master_curves",
                    help="case cache folder (default: $FEMCHECK_CACHE/ehl_master_curves)")
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--case", action="append", default=[], help="M:L:Phi:K (EHL) instead of the default grid")
    ap.add_argument("--retry-failed", action="store_true")
    ap.add_argument("--label", default=None, help="name of this run's timing record in the JSON (default: "
                    "local or dask)")
    ap.add_argument("--report", action="store_true", help="only rewrite the md and png from the JSON in --out")
    ap.add_argument("--resolution", type=int, default=None, metavar="FINE",
                    help="instead of the sweep: the discretisation error of --grid against FINE nodes")
    a = ap.parse_args(argv)
    if a.report:
        report(a.out or Path("benchmarks/results"))
        return 0
    if a.case:
        cases = []
        for spec in a.case:
            M, L, phi, K = (float(v) for v in spec.split(":"))
            cases += [c for c in (dry_case(phi, K), ehl_case(M, L, phi, K, a.grid)) if c not in cases]
    else:
        cases = default_cases(a.grid)
    cluster = None
    scheduler = a.scheduler
    if scheduler == "local-dask":
        from distributed import LocalCluster
        cluster = LocalCluster(n_workers=a.dask_workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        scheduler = cluster.scheduler_address
    try:
        with stop_on_signals():
            if a.resolution:
                res = resolution(a.cache, a.grid, a.resolution, a.workers, scheduler)
                print(json.dumps(res, indent=1))
                if a.out:
                    path = a.out / "ehl_master_curves.json"
                    doc = json.loads(path.read_text()) if path.is_file() else {}
                    doc["resolution"] = res
                    _write_atomic(path, json.dumps(doc, indent=1))
                    if "runs" in doc:
                        report(a.out)
                return 0
            out = sweep(cases, a.cache, a.workers, scheduler, a.retry_failed)
    except (Interrupted, KeyboardInterrupt):
        print("interrupted: finished cases are in the cache; run again to resume", file=sys.stderr)
        return 130
    finally:
        if cluster is not None:
            cluster.close()
    run = {"computed": out["computed"], "cached": out["cached"], "wall_s": out["wall_s"], "cases": len(cases),
           "failed": sum(r["status"] != "ok" for r in out["results"]),
           "case_time_s": out["case_time_s"], "scheduler": a.scheduler or "local processes",
           "workers": a.dask_workers if a.scheduler else a.workers, "code": out["code"]}
    print(json.dumps(run))
    if a.out:
        label = a.label or ("dask" if a.scheduler else "local")
        doc = write_outputs(a.out, out["results"], run, label, a.grid)
        for name, f in doc["fits"].items():
            print(f"{name}: c = {f['c']:.3f}, q = {f['q']:.3f}, rms {f['rms']:.3f}, max {f['max_abs']:.3f}, "
                  f"R2 {f['R2']:.3f} (n = {f['n']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
