"""Convergence certificates over geometrically similar mesh levels (a structured zone refined by a ratio that
keeps its cell counts whole, or a family nested where the contact is): the levels sample the contact at the same
pattern of points, scaled, so the residual of a fit over them (the separation's edge fit, the peak's local
polynomial) is a deterministic misfit that converges with the mesh, not scatter.

On such levels the two-sigma test of :func:`femcheck.solvers.convergence.certify` (a change between levels is
observed only beyond twice the standard errors) could never pass: the fit's standard error tracks the error
itself (hertz-point P2 semi_axis_x: standard error 0.075 / 0.018 / 0.004 % of a where the error against Hertz
is +0.100 / +0.028 / +0.007 %). The standard error therefore enters only as a floor of the estimate, and the
observed order is capped by the formal order of the problem (:func:`femcheck.solvers.convergence.certify_formal`).
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from .convergence import Certificate, certify_formal

# The best energy-norm order any finite element space reaches for the Signorini problem: its solution is at
# most H^{5/2-eps} at the edge of the contact (Kikuchi & Oden 1988; for quadratic elements Hild & Laborde 2002,
# Appl. Numer. Math. 41), so the regularity, not the element order, bounds it at 3/2.
SIGNORINI_ORDER = 1.5


def certify_similar(levels: list[dict[str, Any]], name: str, formal_order: float = SIGNORINI_ORDER,
                    h_key: str = "h") -> Certificate:
    """Certificate of ``name`` over ``levels`` (coarse to fine dicts with ``h_key`` and the quantity, and
    ``<name>_std`` where the quantity is a fit): :func:`certify_formal` at ``formal_order``, the estimate raised
    to twice the finest level's standard error where that is larger."""
    c = certify_formal([lv[h_key] for lv in levels], [lv[name] for lv in levels], formal_order)
    std = levels[-1].get(f"{name}_std")
    if std is None or not np.isfinite(std) or c.value == 0:
        return c
    floor = 2.0 * std / abs(c.value)
    if floor <= c.error_estimate:
        return c
    return replace(c, error_estimate=floor, note=c.note + f"; estimate raised to twice the finest fit's standard "
                   f"error ({floor:.1e})")
