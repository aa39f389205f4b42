"""Time-vs-error sweeps: each model over its discretisation, errors against the scene's reference model.

Timings are wall-clock of the model alone (no cache), the minimum over repeats for runs shorter than 0.5 s
(interference from the machine only ever adds time), single process so runs do not compete.
"""
from __future__ import annotations

import time
from typing import Any, Callable

import numpy as np

from .compare import profile_errors
from .executor import map_cases
from .problems import problem
from .runner import run_model
from .scene import Scene

SKIP = ("total_force",)   # exact by construction in every model; no discretisation error to show


def _timed(scene: Scene, model: str) -> tuple[Any, float, int]:
    best, repeats, res = np.inf, 0, None
    start = time.perf_counter()
    while True:
        res = run_model(scene, model, use_cache=False)
        best = min(best, res.time_s)
        repeats += 1
        if res.status != "ok" or time.perf_counter() - start > 0.5 or repeats >= 20:
            return res, best, repeats


def _bench_case(args: tuple[Scene, str, dict[str, Any], Any]) -> dict[str, Any]:
    """Time one (model, discretisation) case and measure its errors against ``ref`` (a ModelResult)."""
    scene, label, overrides, ref = args
    model = label.split(":")[0]          # "bem:mlmi": the bem model with another back-end, its own rows
    sc = scene.with_overrides(overrides)
    res, t, repeats = _timed(sc, model)
    row: dict[str, Any] = {"model": label, "setting": overrides, "status": res.status, "time_s": t,
                           "repeats": repeats}
    if res.status != "ok":
        row["error"] = res.error
        return row
    for q in quantities(res, ref):
        row[f"{q}_value"] = res.quantities[q]
        if ref.quantities[q] != 0.0:
            row[f"err_{q}"] = abs(res.quantities[q] / ref.quantities[q] - 1.0)
    if "pressure" in res.fields and "pressure" in ref.fields:
        errs = profile_errors(res.fields["x"], res.fields["pressure"], ref.fields["x"], ref.fields["pressure"],
                              problem(scene.kind).profile_scale(scene))
        row["err_pressure_profile_l2"] = errs["pressure_profile_l2"]
    st = res.stats
    row["size"] = (st.get("n_elements") or (st["nx"] * st["ny"] if "nx" in st else None)
                   or (st["levels"][-1].get("n_dofs") if "levels" in st else None))
    row["iterations"] = st.get("iterations") or (st["levels"][-1]["iterations"] if "levels" in st else None)
    return row


def bench(scene: Scene, models: list[str] | None = None, on_step: Callable[[str], None] | None = None,
          workers: int = 1, scheduler: str | None = None) -> list[dict[str, Any]]:
    """One row per (model, discretisation): time_s, errors err_<q> against the scene's first reference model
    (stored FE references are used as they are), and the model's stats. Cases run one at a time by default
    so that timings do not compete; ``scheduler`` sends them to a dask cluster (each case is then timed on
    the worker that runs it)."""
    prob = problem(scene.kind)
    ref_name = scene["models.references"][0]
    ref = run_model(scene, ref_name, use_cache=True)
    if ref.status != "ok":
        raise RuntimeError(f"bench: the reference model {ref_name} failed: {ref.error}")
    cases = [(scene, label, overrides, ref) for label, sweep in prob.bench_sweeps(scene).items()
             if not models or label.split(":")[0] in models for overrides in sweep]
    done = (lambda i, row: on_step(f"{row['model']} {row['setting']}")) if on_step else None
    rows = map_cases(_bench_case, cases, workers, done, scheduler)
    _self_convergence(rows)
    return rows


def quantities(res, ref) -> list[str]:
    """The scalar quantities a model shares with the analytic reference (bench error columns)."""
    return [q for q in res.quantities if q in ref.quantities and q not in SKIP]


def _self_convergence(rows: list[dict[str, Any]]) -> None:
    """Add err_self_<q>: the change against the model's own finest setting. Errors against the analytic
    solution level off at the model's physical floor (BEM: exact circle vs Hertz's parabola; FEM: finite
    clamped block); the self-convergence shows the discretisation error beneath that floor."""
    for model in {r["model"] for r in rows}:
        ok = [r for r in rows if r["model"] == model and r["status"] == "ok"]
        if len(ok) < 2 or "p_max_value" not in ok[-1]:
            continue
        finest = ok[-1]
        names = [k[: -len("_value")] for k in finest if k.endswith("_value")]
        for r in ok[:-1]:
            for q in names:
                r[f"err_self_{q}"] = abs(r[f"{q}_value"] / finest[f"{q}_value"] - 1.0)


def scaling_exponent(rows: list[dict[str, Any]], model: str) -> float | None:
    """Least-squares slope of log(time) against log(size) for one model (e.g. ~1 for N log N)."""
    pts = [(r["size"], r["time_s"]) for r in rows if r["model"] == model and r.get("size")]
    if len(pts) < 3:
        return None
    n, t = np.log(np.array(pts, dtype=float)).T
    return float(np.polyfit(n, t, 1)[0])
