"""Stress tests of numerical stability: run a scene over parameter extremes and list every case that failed
to converge, produced non-finite or non-physical output (negative pressure, load imbalance > 1e-6), left the
scene's tolerance against a reference (quantities: the kind's STRESS_QUANTITIES, default p_max and
half_width), or could not be compared with any reference. Nothing is dropped silently.

Which models run: the scene's ``models.run`` without the models whose results are cached or stored (the FE
references: minutes and gigabytes per case), unless ``models`` names them. Each case is compared with every
reference that ran; a case compared with nothing is ``unchecked`` (e.g. its references were left out, or
skipped because they do not apply there), never ``ok``.
"""
from __future__ import annotations

from typing import Any

from .errors import InputError
from .executor import map_cases
from .problems import problem
from .result import StressCase
from .runner import run
from .scene import Scene

# case status, from the worst: failed (a model failed), inaccurate (a candidate out of tolerance), unchecked
# (nothing to compare with), refused (the inputs are outside a model's range: said so, not a defect), ok
SEVERITY = ("failed", "inaccurate", "unchecked", "refused", "ok")


def default_models(scene: Scene) -> list[str]:
    """``models.run`` without the cached / stored models (the kind's DEPENDS: FE references)."""
    expensive = problem(scene.kind).DEPENDS
    return [m for m in scene["models.run"] if m not in expensive]


def case_models(case: StressCase, models: list[str]) -> list[str]:
    """A case may restrict the models itself (``models.run`` in its overrides, e.g. a rigid substrate on which
    uncoated Hertz does not apply): then the models it allows among ``models``."""
    own = case.overrides.get("models.run")
    return [m for m in models if m in own] if own else list(models)


def _run_case(args: tuple) -> StressCase:
    """Run one case: ``args`` = (scene, case[, models]); models default to :func:`default_models`."""
    scene, case, *rest = args
    names = case_models(case, rest[0] if rest else default_models(scene))
    if not names:
        case.status, case.problems = "refused", ["none of the models asked for runs in this case"]
        return case
    try:
        res = run(scene, case.overrides, models=names, use_cache=False)
    except InputError as err:
        case.status, case.problems = "refused", [str(err)]
        return case
    status = "ok"
    for name, m in res.models.items():
        entry: dict[str, Any] = {"status": m.status, "time_s": m.time_s}
        for key in ("iterations", "residual"):
            if key in m.stats:
                entry[key] = m.stats[key]
        if m.status == "failed":         # "skipped": the model says it does not apply here, not a failure
            case.problems.append(f"{name}: {m.error}")
            status = "failed"
        case.models[name] = entry
    watched = getattr(problem(scene.kind), "STRESS_QUANTITIES", ("p_max", "half_width"))
    compared = [c for c in res.comparisons if c.quantity in watched]
    for c in compared:
        entry = case.models.setdefault(c.model, {})
        entry.setdefault("errors", []).append({"reference": c.reference, "quantity": c.quantity,
                                               "rel_error": c.rel_error, "tolerance": c.tolerance,
                                               "verdict": c.verdict})
        key = f"err_{c.quantity}"
        entry[key] = max(entry.get(key, 0.0), c.rel_error)          # the worst over the references
        if c.verdict in ("not valid here", "ungraded") and not c.contrast:
            tol = "none" if c.tolerance is None else f"{c.tolerance:.3g}"
            case.problems.append(f"{c.model}: {c.quantity} off {c.reference} by {c.rel_error:.3g} relative "
                                 f"(tolerance {tol})")
            status = status if status == "failed" else "inaccurate"
    if not compared and status == "ok":
        refs = [r for r in res.params.get("models.references", ())]
        ran = [r for r in refs if r in res.models and res.models[r].status == "ok"]
        why = ("no reference ran" + (f" (models.references: {', '.join(refs)}; add them with --models)"
                                     if refs else "")) if not ran else \
            f"no model was compared with {', '.join(ran)} on {', '.join(watched)}"
        case.problems.append(f"not compared: {why}")
        status = "unchecked"
    case.status = status
    return case


def stress(scene: Scene, workers: int | None = None, on_done=None, scheduler: str | None = None,
           models: list[str] | None = None) -> list[StressCase]:
    """Run every case of the kind's ``stress_cases(scene)`` with ``models`` (default :func:`default_models`)
    in local worker processes, or on the dask cluster at ``scheduler``, and classify it."""
    names = list(models) if models else default_models(scene)
    cases = problem(scene.kind).stress_cases(scene)
    return map_cases(_run_case, [(scene, c, names) for c in cases], workers, on_done, scheduler)
