"""Stress tests of numerical stability: run a scene over parameter extremes and list every case that failed
to converge, produced non-finite or non-physical output (negative pressure, load imbalance > 1e-6), or left
the scene's tolerance against its first reference model (quantities: the kind's STRESS_QUANTITIES, default
p_max and half_width). Nothing is dropped silently."""
from __future__ import annotations

from typing import Any

from .errors import InputError
from .executor import map_cases
from .problems import problem
from .runner import run
from .result import StressCase
from .scene import Scene


def _run_case(args: tuple[Scene, StressCase]) -> StressCase:
    scene, case = args
    try:
        res = run(scene, case.overrides, use_cache=False)
    except InputError as err:
        case.status, case.problems = "refused", [str(err)]
        return case
    worst = "ok"
    for name, m in res.models.items():
        entry: dict[str, Any] = {"status": m.status, "time_s": m.time_s}
        for key in ("iterations", "residual"):
            if key in m.stats:
                entry[key] = m.stats[key]
        if m.status == "failed":         # "skipped": the model says it does not apply here, not a failure
            case.problems.append(f"{name}: {m.error}")
            worst = "failed"
        case.models[name] = entry
    prob = problem(scene.kind)
    reference = scene["models.references"][0]
    watched = getattr(prob, "STRESS_QUANTITIES", ("p_max", "half_width"))
    for c in res.comparisons:
        if c.reference == reference and c.quantity in watched:
            case.models.setdefault(c.model, {})[f"err_{c.quantity}"] = c.rel_error
            if c.passed is False:
                case.problems.append(f"{c.model}: {c.quantity} off {reference} by {c.rel_error:.3g} relative "
                                     f"(tolerance {c.tolerance:.3g})")
                worst = worst if worst == "failed" else "inaccurate"
    case.status = worst
    return case


def stress(scene: Scene, workers: int | None = None, on_done=None, scheduler: str | None = None) -> list[StressCase]:
    """Run every case of the kind's ``stress_cases(scene)`` (local worker processes, or the dask cluster at
    ``scheduler``) and classify it."""
    cases = problem(scene.kind).stress_cases(scene)
    return map_cases(_run_case, [(scene, c) for c in cases], workers, on_done, scheduler)
