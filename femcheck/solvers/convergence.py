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


# Roache's factor of safety on the grid-convergence index when three or more levels show the expected order
# (Roache 1998 §5.6: 1.25), and when they do not (3.0: a two-level estimate without a verified order).
SAFETY_CERTIFIED = 1.25
SAFETY_UNCERTIFIED = 3.0


@dataclass
class Certificate:
    """Convergence certificate of one quantity over mesh levels (the shared format of every reference's
    ``stats["certificates"][quantity]``; see :meth:`as_dict`).

    ``value``: the value the reference reports (Richardson-extrapolated when certified, else the finest level);
    ``finest``: finest-level value; ``order``: observed order of the last three levels (None when they do not
    converge monotonically); ``error_estimate``: conservative *relative* error of ``value`` (GCI of the finest
    level, Roache eq. 5.6.1, with the safety factor above); ``certified``: the levels are in the asymptotic range;
    ``note``: why (or why not), in words a reader can check against the level table.
    """

    value: float
    finest: float
    order: float | None
    error_estimate: float
    certified: bool
    note: str

    def as_dict(self) -> dict:
        return {"value": self.value, "finest": self.finest, "order": self.order,
                "error_estimate": self.error_estimate, "certified": self.certified, "note": self.note}


def _orders(h: list[float], q: list[float]) -> list[float | None]:
    """Observed order of every consecutive triple of levels (None where the differences change sign or vanish)."""
    out: list[float | None] = []
    for i in range(len(q) - 2):
        r = h[i + 1] / h[i + 2]
        d12, d23 = q[i] - q[i + 1], q[i + 1] - q[i + 2]
        out.append(float(np.log(d12 / d23) / np.log(r)) if d23 != 0 and d12 / d23 > 0 else None)
    return out


# Below this relative change between levels a quantity no longer sees the mesh at the precision of the solvers
# and estimators (contact tolerance 1e-8 to 1e-10, estimator scatter ~1e-5): differences this small carry no order.
CONVERGED_FLOOR = 1e-4


def certify(h: list[float], q: list[float], expected_order: float | None = None, order_band: float = 2.0,
            singular: bool = False, floor: float = CONVERGED_FLOOR, sigma: list[float] | None = None) -> Certificate:
    """Certificate of a quantity computed on levels of mesh size ``h`` (coarse to fine, constant ratio).

    Certified when the last three levels converge monotonically with an observed order p that is consistent:
    within a factor ``order_band`` of ``expected_order`` (the discretisation's theoretical order, when the caller
    knows it), else in [0.5, 4] and, with four or more levels, within 25 % of the order of the previous triple.
    Then ``value`` = Richardson's extrapolation and ``error_estimate`` = 1.25 |value - finest| / |value|.
    Otherwise ``value`` = finest level and ``error_estimate`` = 3 max(last change) / |finest| (a two-level bound,
    not an extrapolation), and the note says why. ``singular``: the quantity grows with refinement by nature (a
    peak at a sharp edge); it is never certified. ``floor``: when the levels are not in the asymptotic range but
    the last two changes are both below it (relative), they agree to the precision the solvers and estimators
    resolve, where no order can be observed; the quantity is then certified as converged, ``value`` = finest
    level, ``error_estimate`` = 3 x the largest of the two changes (Roache's factor without a verified order).
    ``sigma``: the standard error of each level's value when it is estimated from scattered samples (a fit
    over FE nodal reactions, :mod:`femcheck.qoi`). A change between two levels is then *observed* only when it
    exceeds two standard errors of the difference, 2 sqrt(s_i^2 + s_j^2); if either of the last two is not, no
    order can be observed and the quantity is not certified (unless it is converged below ``floor`` with its
    scatter too), and every error estimate is at least 2 s of the finest level.
    """
    h = [float(x) for x in h]
    q = [float(x) for x in q]
    if len(h) != len(q) or not h:
        raise ValueError("certify needs one value per level")
    finest = q[-1]
    scale = abs(finest) if finest != 0 else 1.0
    if singular:
        change = abs(q[-1] - q[-2]) / scale if len(q) > 1 else float("inf")
        return Certificate(finest, finest, None, SAFETY_UNCERTIFIED * change, False,
                           "mesh-dependent by nature (singular at a sharp edge): finest level, not a converged value")
    if len(q) < 3:
        change = abs(q[-1] - q[-2]) / scale if len(q) == 2 else float("inf")
        return Certificate(finest, finest, None, SAFETY_UNCERTIFIED * change, False,
                           f"{len(q)} level(s): no observed order")
    ratios = [h[i] / h[i + 1] for i in range(len(h) - 1)]
    if not np.allclose(ratios, ratios[0], rtol=1e-6):
        raise ValueError("levels must have a constant refinement ratio")
    r = ratios[0]
    orders = _orders(h, q)
    p = orders[-1]
    last_change = abs(q[-1] - q[-2]) / scale
    bound = SAFETY_UNCERTIFIED * max(last_change, abs(q[-2] - q[-3]) / scale)
    scatter = 0.0
    resolved = True
    if sigma is not None:
        sg = [float(x) if x is not None and np.isfinite(x) else 0.0 for x in sigma]
        scatter = 2.0 * sg[-1] / scale
        pair = [2.0 * np.hypot(sg[i], sg[i + 1]) for i in (-3, -2)]
        diffs = [abs(q[-2] - q[-3]), abs(q[-1] - q[-2])]
        resolved = all(d > s_ for d, s_ in zip(diffs, pair))
        bound = max(bound, scatter)
    if q[-1] == q[-2] == q[-3]:
        return Certificate(finest, finest, None, 0.0, False,
                           "the last three levels are equal: the quantity does not see the mesh (a mesh node?)")
    spread = max(last_change, abs(q[-2] - q[-3]) / scale)
    converged = spread < floor and scatter < floor
    why_floor = (f"converged: the last three levels agree within {spread:.1e} "
                 f"(< {floor:g}, below the solvers' and estimators' resolution)")
    if not resolved:
        if converged:
            return Certificate(finest, finest, p, bound, True, why_floor)
        return Certificate(finest, finest, p, bound, False,
                           f"the changes between the last levels ({diffs[0] / scale:.1e}, {diffs[1] / scale:.1e}) are "
                           f"within the scatter of the estimates (2 sigma: {pair[0] / scale:.1e}, "
                           f"{pair[1] / scale:.1e}): no order can be observed")
    if p is None:
        if converged:
            return Certificate(finest, finest, None, bound, True, why_floor)
        return Certificate(finest, finest, None, bound, False,
                           "the last three levels oscillate: not in the asymptotic range")
    if expected_order is not None:
        ok = expected_order / order_band <= p <= expected_order * order_band
        why = f"observed order {p:.2f} {'within' if ok else 'outside'} a factor {order_band:g} of the expected " \
              f"{expected_order:g}"
    else:
        ok = 0.5 <= p <= 4.0
        why = f"observed order {p:.2f} {'in' if ok else 'outside'} [0.5, 4]"
        if ok and len(orders) >= 2 and orders[-2] is not None:
            consistent = abs(orders[-2] - p) <= 0.25 * p
            ok = consistent
            why += f", previous triple {orders[-2]:.2f} ({'consistent' if consistent else 'inconsistent'})"
    if not ok:
        if converged:
            return Certificate(finest, finest, p, bound, True, why_floor)
        return Certificate(finest, finest, p, bound, False, why + ": not in the asymptotic range")
    value = finest + (finest - q[-2]) / (r**p - 1.0)
    err = max(SAFETY_CERTIFIED * abs(value - finest) / (abs(value) if value != 0 else 1.0), scatter)
    return Certificate(float(value), finest, p, float(err), True, why)


def certify_levels(levels: list[dict], names: tuple[str, ...] | list[str], h_key: str = "h",
                   singular: tuple[str, ...] = (), expected_order: dict[str, float] | None = None
                   ) -> dict[str, Certificate]:
    """:func:`certify` for each quantity ``names`` over level dicts (coarse to fine) holding ``h_key`` and the
    quantities (with ``<name>_std``, their standard errors, when the levels carry them); ``singular`` names the
    quantities that grow with refinement by nature (peaks at sharp edges)."""
    h = [lv[h_key] for lv in levels]
    exp = expected_order or {}

    def sigma(n):
        s = [lv.get(f"{n}_std") for lv in levels]
        return s if all(x is not None for x in s) else None

    return {n: certify(h, [lv[n] for lv in levels], exp.get(n), singular=n in singular, sigma=sigma(n))
            for n in names}


def certificate_stats(certs: dict[str, Certificate]) -> dict[str, dict]:
    """``stats["certificates"]`` and, for the report's convergence plot and older readers,
    ``stats["richardson"]`` (value, order, finest and the *absolute* error estimate) from certificates."""
    return {"certificates": {k: c.as_dict() for k, c in certs.items()},
            "richardson": {k: {"value": c.value, "order": c.order if c.certified else None, "finest": c.finest,
                               "error_estimate": c.error_estimate * abs(c.value)} for k, c in certs.items()}}
def certify_formal(h: list[float], q: list[float], formal_order: float | None) -> Certificate:
    """:func:`certify` with the observed order limited by the discretisation's formal order (Roache 1998 §5.9,
    ASME V&V 20: the extrapolation never uses a higher order than the scheme has): when the last three levels
    converge monotonically *faster* than ``formal_order`` (three levels scatter: a small leading coefficient or
    a stick/slip boundary moving irregularly across the nodes give apparent orders of 1.5-4 for a first-order
    quantity), Richardson's extrapolation and the GCI use ``formal_order`` instead. This is conservative if the
    quantity converges at least at its formal order: the extrapolated value then lies between the finest level
    and the limit, and 1.25 |value - finest| bounds the distance to it. ``formal_order`` None: plain
    :func:`certify` with no expected order."""
    c = certify(h, q, expected_order=formal_order)
    if formal_order is None or c.order is None or c.order <= formal_order:
        return c
    r = h[-2] / h[-1]
    value = q[-1] + (q[-1] - q[-2]) / (r**formal_order - 1.0)
    err = SAFETY_CERTIFIED * abs(value - q[-1]) / (abs(value) if value != 0 else 1.0)
    return Certificate(float(value), float(q[-1]), c.order, float(err), True,
                       f"observed order {c.order:.2f} >= the formal order {formal_order:g}: extrapolated at order "
                       f"{formal_order:g}")
