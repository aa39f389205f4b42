"""Test helper: the checks every built-in scene's whole run must pass."""
from __future__ import annotations

from femcheck.result import VERDICTS, Comparison, RunResult


def assert_fully_graded(res: RunResult, name: str) -> None:
    """Every comparison carries a tolerance (or is a contrast judged by its band) and no candidate model is
    'not valid here'."""
    assert res.comparisons, name
    assert all(c.verdict in VERDICTS for c in res.comparisons)
    ungraded = [(c.model, c.reference, c.quantity) for c in res.comparisons if c.verdict == "ungraded"]
    assert not ungraded, ungraded
    assert res.passed, res.problems
    for c in res.comparisons:
        assert isinstance(c, Comparison) and c.passed == (c.verdict == "valid")
