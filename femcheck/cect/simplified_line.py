"""Kalker's simplified models of 2D (line-contact) steady rolling: linear theory and FASTSIM on one strip.

Quasi-identical cylinders, Hertz half-width a (m), contact modulus E* (Pa), longitudinal creepage xi (-), friction
coefficient mu (-), normal load W' (N/m); forces per unit length (N/m) on body 1, opposing xi (the conventions of
:mod:`femcheck.analytic.carter`).

Linear theory (no slip anywhere, Carter's small-creepage limit; Johnson 1985 §8.2):

    F'_x = -(pi a E* / 2) xi.

FASTSIM in 2D (Kalker 1982, one strip): the surface is a bed of springs of flexibility L (m/Pa), the traction
grows from the leading edge x = a by |xi| dx / L until it reaches the traction bound mu p(x), then follows it:

    |q(x)| = min(|xi| (a - x) / L, mu p(x)),    L = 4 a / (pi E*),

L chosen so that the small-creepage force equals linear theory (integral of |xi| (a - x)/L over the contact =
2 a^2 |xi| / L). With p the Hertz pressure the ramp meets the concave bound once, so the march of FASTSIM and
this minimum are the same thing, and the crossing point and the force have closed forms (no grid).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


def _check(half_width: float, modulus: float, mu: float, load_per_length: float) -> None:
    for name, v in (("half_width", half_width), ("modulus", modulus), ("load.per_length", load_per_length)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(name, f"{v!r}; allowed (0, inf)")
    if not (np.isfinite(mu) and mu > 0):
        raise InputError("friction.mu", f"{mu!r}; allowed (0, inf)")


def linear_line(half_width: float, modulus: float, xi: float) -> float:
    """Creep force per unit length (N/m) of 2D linear theory: -(pi a E*/2) xi."""
    return -0.5 * np.pi * half_width * modulus * xi


@dataclass(frozen=True)
class FastsimLineResult:
    """``creep_force_x`` (N/m), ``adhesion_length`` (m: from the leading edge to where the ramp meets the bound),
    ``adhesion_fraction`` (-), ``flexibility`` L (m/Pa), ``crossing`` x_c (m)."""

    creep_force_x: float
    adhesion_length: float
    adhesion_fraction: float
    flexibility: float
    crossing: float

    def traction(self, x: np.ndarray, half_width: float, p0: float, mu: float, xi: float) -> np.ndarray:
        """q(x) (Pa), zero outside the contact."""
        x = np.asarray(x, dtype=float)
        inside = np.abs(x) < half_width
        bound = mu * p0 * np.sqrt(np.clip(1.0 - (x / half_width) ** 2, 0.0, None))
        ramp = abs(xi) * (half_width - x) / self.flexibility
        return np.where(inside, -np.sign(xi) * np.minimum(ramp, bound), 0.0)


def fastsim_line(load_per_length: float, half_width: float, modulus: float, mu: float, xi: float) -> FastsimLineResult:
    """2D FASTSIM (see the module docstring) for the Hertz pressure p0 sqrt(1 - x^2/a^2), p0 = 2W'/(pi a)."""
    _check(half_width, modulus, mu, load_per_length)
    a = half_width
    p0 = 2.0 * load_per_length / (np.pi * a)
    L = 4.0 * a / (np.pi * modulus)
    if xi == 0.0:
        return FastsimLineResult(0.0, 2.0 * a, 1.0, L, -a)
    # crossing of k (a - x) with mu p0 sqrt(1 - x^2/a^2), k = |xi|/L: with s = x/a, m = mu p0 / (k a),
    # (1 - s)^2 = m^2 (1 - s^2)  ->  s = (1 - m^2) / (1 + m^2)  (the root s = 1 is the leading edge)
    m = mu * p0 / (abs(xi) / L * a)
    s_c = (1.0 - m * m) / (1.0 + m * m)
    x_c = a * s_c
    # slip zone [-a, x_c]: integral of mu p0 sqrt(1 - x^2/a^2); with x = -a cos(t) it is mu p0 a (t/2 - sin(2t)/4)
    t_c = float(np.arccos(-s_c))
    slip = mu * p0 * a * (0.5 * t_c - 0.25 * np.sin(2.0 * t_c))
    # adhesion zone [x_c, a]: the linear ramp, exact
    stick = abs(xi) / L * 0.5 * (a - x_c) ** 2
    force = -np.sign(xi) * (slip + stick)
    return FastsimLineResult(float(force), float(a - x_c), float((a - x_c) / (2.0 * a)), float(L), float(x_c))
