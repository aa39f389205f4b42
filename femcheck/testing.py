"""Assertions for verifying model agreement in a user's own pytest suite (see :mod:`femcheck.pytest_plugin`)."""
from __future__ import annotations

from .result import RunResult


def quantity(result: RunResult, model: str, name: str) -> float:
    """Value of quantity ``name`` of ``model``; ``model@finest`` reads a multi-level model's finest level."""
    base, _, level = model.partition("@")
    m = result.models.get(base)
    if m is None:
        raise AssertionError(f"{result.scene}: model {base!r} was not run (ran: {', '.join(result.models)})")
    if m.status != "ok":
        raise AssertionError(f"{result.scene}: model {base!r} {m.status}: {m.error}")
    values = m.stats.get(level, {}) if level else m.quantities
    if name not in values:
        raise AssertionError(f"{result.scene}: {model} has no quantity {name!r} (has: {', '.join(values)})")
    return float(values[name])


def assert_agree(result: RunResult, name: str, model: str, reference: str, rtol: float) -> float:
    """Assert |q_model - q_reference| <= rtol |q_reference| for quantity ``name``; returns the relative error.

    ``reference`` is another model of the run (e.g. ``"analytic"``, ``"fem"``) or a number (SI units).
    """
    value = quantity(result, model, name)
    ref = float(reference) if isinstance(reference, (int, float)) else quantity(result, reference, name)
    rel = abs(value - ref) / abs(ref)
    if not rel <= rtol:
        raise AssertionError(f"{result.scene}: {model} {name} = {value:.6g} differs from {reference} = {ref:.6g} "
                             f"by {rel:.3g} (relative) > rtol {rtol:.3g}")
    return rel
