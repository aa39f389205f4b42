"""Test helper: the checks every built-in scene's whole run must pass."""
from __future__ import annotations

from femcheck.report.units import unit_of
from femcheck.result import VERDICTS, Comparison, RunResult


def assert_fully_graded(res: RunResult, name: str) -> None:
    """Every comparison carries a tolerance (or is a contrast judged by its band), no candidate model is
    'not valid here', and every quantity of every model (references included) has an SI unit."""
    assert res.comparisons, name
    assert all(c.verdict in VERDICTS for c in res.comparisons)
    ungraded = [(c.model, c.reference, c.quantity) for c in res.comparisons if c.verdict == "ungraded"]
    assert not ungraded, ungraded
    assert res.passed, res.problems
    for c in res.comparisons:
        assert isinstance(c, Comparison) and c.passed == (c.verdict == "valid")
    no_unit = [f"{m}.{q}" for m, r in res.models.items() for q in r.quantities
               if unit_of(q, res.params, res.kind) == "?"]
    assert not no_unit, f"{name}: quantities without a unit: " + ", ".join(no_unit)
