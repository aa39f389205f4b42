"""The validity dashboard: which model can be used in which scene, how wrong it is, what it costs.

One row per scene and model: its role (candidate, contrast, reference), one verdict per reference it was compared
with (an uncertified FE reference does not hide a valid comparison with a closed form), and for each the error of
the kind's design quantity (``DESIGN_QUANTITIES`` of the kind: what an engineer sizes with, e.g. Q_max of a
bearing) beside the worst comparison (the one closest to or furthest beyond its tolerance), and its run time (the
solve time; a stored reference shows the time it was solved in). The same verdicts, one object per scene, model,
reference and quantity, go into ``summary.json`` under ``"validity"``.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..result import VERDICTS, Comparison, ModelResult, RunResult

SEVERITY = {v: i for i, v in enumerate(VERDICTS)}     # lower = worse


def role(run: RunResult, model: str) -> str:
    contrast = run.params.get("models.contrast", ())
    if model in run.params.get("models.references", ()):
        return "reference"
    return "contrast" if model in contrast else "candidate"


def cost(m: ModelResult) -> tuple[float, str]:
    """(seconds, text): the solve time; a stored reference or a cache hit says so and gives the time it was
    solved in (``time_s`` of a stored result is that of its solve)."""
    ref = m.stats.get("reference") if isinstance(m.stats, dict) else None
    if m.cached and isinstance(ref, dict):
        t = float(ref.get("run_time_s", m.time_s))
        return t, f"stored, solved in {_seconds(t)}"
    if m.cached:
        return m.time_s, f"cached, solved in {_seconds(m.time_s)}"
    return m.time_s, _seconds(m.time_s)


def _seconds(t: float) -> str:
    if t < 1e-3:
        return "< 1 ms"
    return f"{t:.3g} s" if t < 100 else f"{t:.0f} s"


def worst(comps: list[Comparison]) -> Comparison:
    """The comparison that matters most: the worst verdict, then the largest error relative to its tolerance."""
    return min(comps, key=lambda c: (SEVERITY[c.verdict],
                                     -(c.rel_error / c.tolerance if c.tolerance else float("inf"))))


def design_quantities(kind: str) -> tuple[str, ...]:
    """The kind's design quantities, most important first (``DESIGN_QUANTITIES``; default p_max)."""
    from ..problems import problem

    try:
        return tuple(getattr(problem(kind), "DESIGN_QUANTITIES", ("p_max",)))
    except (KeyError, ValueError):       # a toy kind in a test
        return ("p_max",)


def _design(comps: list[Comparison], names: tuple[str, ...]) -> Comparison | None:
    """The comparison of the first design quantity present (a per-contact suffix, p_max_inner, counts as p_max;
    of several contacts the one furthest from its reference)."""
    for name in names:
        hits = [c for c in comps if c.quantity == name or c.quantity.startswith(name + "_")]
        if hits:
            return max(hits, key=lambda c: c.rel_error)
    return None


@dataclass
class RefVerdict:
    """A model against one reference: its ``verdict`` (the worst over the quantities compared with that
    reference), the ``worst`` comparison, the ``design`` quantity's comparison (None when not compared) and the
    count of each verdict."""

    reference: str
    verdict: str
    worst: Comparison
    design: Comparison | None
    counts: dict[str, int]

    @property
    def shown(self) -> list[Comparison]:
        """What a dashboard cell shows: the design quantity, then the worst comparison when it is another."""
        return ([self.design] if self.design else []) + ([self.worst] if self.worst is not self.design else [])


@dataclass
class Row:
    scene: str
    model: str
    role: str
    status: str                      # ok | failed | skipped
    verdict: str                     # the worst verdict, or failed | skipped | reference (nothing compared)
    time_s: float
    time_text: str
    per_reference: list[RefVerdict] = field(default_factory=list)     # one verdict per reference
    counts: dict[str, int] = field(default_factory=dict)
    max_rel_error: float | None = None     # largest scalar error (profiles excluded): the chart's y
    note: str = ""

    @property
    def fails_scene(self) -> bool:
        return self.status == "failed" or (self.role != "contrast" and self.verdict in ("not valid here",
                                                                                          "ungraded"))


def rows(run: RunResult) -> list[Row]:
    out = []
    names = design_quantities(run.kind)
    for name, m in run.models.items():
        t, text = cost(m)
        comps = [c for c in run.comparisons if c.model.partition("@")[0] == name]
        r = Row(run.scene, name, role(run, name), m.status, m.status, t, text, note=m.error or "")
        if m.status == "ok":
            if comps:
                for ref in dict.fromkeys(c.reference for c in comps):
                    mine = [c for c in comps if c.reference == ref]
                    w = worst(mine)
                    r.per_reference.append(RefVerdict(ref, w.verdict, w, _design(mine, names),
                                                      {v: sum(c.verdict == v for c in mine) for v in VERDICTS
                                                       if any(c.verdict == v for c in mine)}))
                r.verdict = worst(comps).verdict
                r.counts = {v: sum(c.verdict == v for c in comps) for v in VERDICTS if any(c.verdict == v
                                                                                          for c in comps)}
                scalars = [c.rel_error for c in comps if not c.quantity.startswith("pressure_profile")]
                r.max_rel_error = max(scalars) if scalars else None
            else:
                r.verdict = "reference" if r.role == "reference" else "not compared"
                if r.verdict == "not compared":
                    r.note = r.note or "no reference ran, or every quantity it gives is another model's"
        out.append(r)
    return out


def validity(runs: list[RunResult]) -> list[dict[str, Any]]:
    """One object per scene, model, reference and quantity (``summary.json["validity"]``)."""
    out = []
    for run in runs:
        for c in run.comparisons:
            d = {"scene": run.scene, "model": c.model, "role": role(run, c.model.partition("@")[0]),
                 "reference": c.reference, "quantity": c.quantity, "rel_error": c.rel_error,
                 "tolerance": c.tolerance, "verdict": c.verdict}
            if c.note:
                d["note"] = c.note
            out.append(d)
    return out
