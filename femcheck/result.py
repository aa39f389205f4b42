"""Result objects shared by every model, the runner, the comparison and the report."""
from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np


@dataclass
class ModelResult:
    """What one model returns for one scene.

    ``quantities``: scalar quantities of interest in SI units, named as in DESIGN.md (``p_max``, ...); a model
    leaves out what it cannot produce. ``stats``: solver statistics (iterations, residuals, DOFs, mesh
    levels, ...), JSON-serialisable. ``fields``: arrays on the model's own grid (e.g. ``x``, ``pressure``),
    kept out of the JSON. ``status`` is ``ok``, ``failed`` (``error`` says why) or ``skipped``.
    """

    model: str
    status: str = "ok"
    time_s: float = 0.0
    quantities: dict[str, float] = field(default_factory=dict)
    stats: dict[str, Any] = field(default_factory=dict)
    fields: dict[str, np.ndarray] = field(default_factory=dict)
    error: str | None = None
    cached: bool = False

    def to_json(self) -> dict[str, Any]:
        out = {"status": self.status, "time_s": self.time_s, "quantities": dict(self.quantities),
               "stats": _jsonable(self.stats)}
        if self.error is not None:
            out["error"] = self.error
        if self.cached:
            out["cached"] = True
        return out


# Verdicts of a comparison (compare.py decides them), from the worst to the best for a scene:
#   ungraded              the scene gives no tolerance for it: an error of the scene (built-in scenes have none)
#   not valid here        outside its tolerance (a candidate: the scene fails) or its band (a contrast: shown)
#   reference uncertified the reference quantity's convergence certificate says certified: false; cannot pass
#   contrast              a contrast model (models.contrast) within its band: shown, not claimed valid
#   valid                 a candidate model within its tolerance
VERDICTS = ("ungraded", "not valid here", "reference uncertified", "contrast", "valid")


@dataclass
class Comparison:
    """One quantity of ``model`` against ``reference``: rel_error = |value - ref| / |ref| (profile norms are
    already relative and carry reference_value 0). ``verdict`` is one of :data:`VERDICTS`; ``passed`` (``pass``
    in the JSON) is true only for ``valid``; ``contrast`` marks a contrast model (``models.contrast``); ``note``
    says why a verdict is not ``valid`` where the numbers alone do not (an uncertified reference, no tolerance)."""

    quantity: str
    model: str
    reference: str
    value: float
    reference_value: float
    rel_error: float
    tolerance: float | None
    passed: bool
    verdict: str = "valid"
    contrast: bool = False
    note: str = ""

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d["pass"] = d.pop("passed")
        return d


@dataclass
class RunResult:
    """A scene run: parameters, per-model results and comparisons (the ``--json`` object). ``not_compared``:
    quantities left out of the comparisons and why (e.g. a peak that grows with refinement by nature)."""

    scene: str
    params: dict[str, Any]
    models: dict[str, ModelResult]
    comparisons: list[Comparison]
    kind: str = ""
    description: str = ""
    not_compared: dict[str, str] = field(default_factory=dict)

    @property
    def problems(self) -> list[str]:
        """Why the scene fails, one line each: a model that failed, a candidate model not valid here, a
        comparison without a tolerance. A contrast outside its band and an uncertified reference are shown in
        the comparisons but do not fail the scene."""
        out = [f"{name} failed: {m.error}" for name, m in self.models.items() if m.status == "failed"]
        for c in self.comparisons:
            if c.verdict == "not valid here" and not c.contrast:
                out.append(f"{c.model} {c.quantity} off {c.reference} by {c.rel_error:.3g} > tolerance "
                           f"{c.tolerance:.3g}")
            elif c.verdict == "ungraded":
                out.append(f"{c.model} {c.quantity} against {c.reference}: {c.note}")
        return out

    @property
    def passed(self) -> bool:
        return not self.problems

    @property
    def verdict(self) -> str:
        """The scene's verdict: FAIL (a problem), NOTHING COMPARED, INFORMATIONAL (only contrast models were
        compared: nothing here is claimed valid, so nothing can pass) or PASS."""
        if self.problems:
            return "FAIL"
        if not self.comparisons:
            return "NOTHING COMPARED"
        return "INFORMATIONAL" if all(c.contrast for c in self.comparisons) else "PASS"

    def to_json(self) -> dict[str, Any]:
        out = {"scene": self.scene, "verdict": self.verdict, "params": _jsonable(self.params),
               "models": {k: v.to_json() for k, v in self.models.items()},
               "comparisons": [c.to_json() for c in self.comparisons]}
        if self.not_compared:
            out["not_compared"] = dict(self.not_compared)
        return out


NONFINITE = {math.inf: "Infinity", -math.inf: "-Infinity"}


def strict_json(obj: Any) -> Any:
    """``obj`` with every non-finite number written as the string "Infinity", "-Infinity" or "NaN" (what
    Python's ``float()`` and JavaScript's ``Number()`` read back), so that :func:`dumps` writes standard JSON (RFC
    8259 has no infinite numbers; an infinite fatigue life is one)."""
    if isinstance(obj, dict):
        return {str(k): strict_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [strict_json(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return strict_json(obj.tolist())
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else NONFINITE.get(v, "NaN")
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def dumps(obj: Any, **kw) -> str:
    """Standard JSON of ``obj`` (:func:`strict_json`; a bare NaN or Infinity is refused)."""
    return json.dumps(strict_json(obj), allow_nan=False, **kw)


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if np.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


@dataclass
class StressCase:
    """One case of a stability sweep (:mod:`femcheck.stability`): the overrides it applies and, after the run,
    its status (ok | failed | refused | inaccurate | unchecked: compared with no reference), per-model
    summaries and the problems found."""

    label: str
    overrides: dict[str, Any]
    status: str = "pending"          # ok | failed | refused | inaccurate | unchecked
    models: dict[str, dict] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        return {"label": self.label, "overrides": self.overrides, "status": self.status,
                "problems": self.problems, "models": self.models}
