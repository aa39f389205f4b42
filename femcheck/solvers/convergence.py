"""Mesh-convergence certification: observed order and Richardson extrapolation (Roache, *Verification and
Validation in Computational Science and Engineering*, 1998, ch. 5)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Extrapolation:
    """``value``: Richardson-extrapolated estimate; ``order``: observed order p (None when the last three
    levels do not converge monotonically); ``error_estimate``: |value - finest|, the estimated discretisation
    error of the finest level (absolute, same units as the quantity); ``finest``: finest-level value."""

    value: float
    order: float | None
    error_estimate: float
    finest: float

    def as_dict(self) -> dict:
        return {"value": self.value, "order": self.order, "error_estimate": self.error_estimate,
                "finest": self.finest}


def richardson(h: list[float], q: list[float], min_order: float = 0.5, max_order: float = 4.0) -> Extrapolation:
    """Extrapolate q(h) -> h = 0 from the last three levels (constant refinement ratio r = h1/h2 = h2/h3).

    p = ln((q1 - q2)/(q2 - q3)) / ln r,  q_ext = q3 + (q3 - q2)/(r^p - 1).
    Outside the asymptotic range (oscillating differences, or p outside [min_order, max_order]) no order is
    claimed: the value stays the finest level and the error estimate is the last change |q3 - q2| (a
    conservative bound rather than an extrapolation).
    """
    if len(h) < 3:
        raise ValueError("Richardson extrapolation needs at least three levels")
    h1, h2, h3 = h[-3:]
    q1, q2, q3 = q[-3:]
    r = h2 / h3
    if not np.isclose(h1 / h2, r, rtol=1e-6):
        raise ValueError("levels must have a constant refinement ratio")
    d12, d23 = q1 - q2, q2 - q3
    if d23 == 0.0:
        return Extrapolation(q3, None, 0.0, q3)
    ratio = d12 / d23
    if ratio > 0:
        p = float(np.log(ratio) / np.log(r))
        if min_order <= p <= max_order:
            ext = q3 + (q3 - q2) / (r**p - 1.0)
            return Extrapolation(float(ext), p, float(abs(ext - q3)), q3)
    return Extrapolation(q3, None, float(abs(d23)), q3)
