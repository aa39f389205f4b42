"""Thin elastic layer bonded to a rigid base, pressed by a rigid cylinder (line) or sphere (circular contact):
Johnson's thin-layer closed forms (Johnson, *Contact Mechanics*, 1985, §5.9; seed 001 eqs 18-22).

Compressible layer (nu < 0.5). A layer much thinner than the contact cannot strain laterally (seed 001 eq 18),
so it responds like a Winkler foundation with the constrained modulus M = (1 - nu) E / ((1 + nu)(1 - 2 nu)):
p = (M / b) (delta - r^2 / 2R), delta = a^2 / 2R (seed 001 eqs 19-21). Load balance fixes the size:

    line:      W' = 2 M a^3 / (3 R b)      ->  a = (3 R b W' / (2 M))^(1/3)     (seed 001 eq 22 prints 1/4)
    circular:  P  = pi M a^4 / (4 R b)     ->  a = (4 R b P / (pi M))^(1/4)

Incompressible layer (nu = 0.5). M is infinite and the Winkler picture fails: the layer carries load by
squeezing material out sideways, like a lubricant film. With the layer bonded to the base, the lateral
displacement across the thickness is parabolic; continuity of the squeezed volume gives

    line:      d2p/dx2 = -(k) (delta - x^2 / 2R),    circular:  (1/r) d/dr (r dp/dr) = -(k) (delta - r^2 / 2R)

with k = 3 G / b^3 for a frictionless indenter (no shear on the top face) or 12 G / b^3 if the layer also adheres
to the indenter. The free boundary has p = dp/dn = 0 at the edge, which gives

    line:      p = k (a^2 - x^2)^2 / (24 R),  delta = a^2 / (6 R),  W' = 2 k a^5 / (45 R)
    circular:  p = k (a^2 - r^2)^2 / (32 R),  delta = a^2 / (4 R),  P  = pi k a^6 / (96 R)

All SI: E, G, M, p in Pa; R, b, a, delta in m; W' in N/m, P in N.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError

# Above this Poisson's ratio the compressible formula is ill-conditioned (M grows as 1/(1 - 2 nu)) and the
# physics is the squeeze-film one: callers must choose the incompressible form explicitly.
NU_COMPRESSIBLE_MAX = 0.499


@dataclass(frozen=True)
class ThinLayerContact:
    """Half-width or radius ``a`` (m), peak pressure ``p_max`` (Pa), rigid approach ``approach`` (m) and the
    pressure as a function of the in-plane coordinate (``pressure(x)``; Pa)."""

    a: float
    p_max: float
    approach: float
    geometry: str          # "line" or "circular"
    model: str             # "compressible" or "incompressible"
    _k: float              # M / b (compressible) or the squeeze constant k (incompressible)
    _R: float

    def pressure(self, x: np.ndarray) -> np.ndarray:
        s = np.clip(self.a**2 - np.asarray(x, dtype=float) ** 2, 0.0, None)
        if self.model == "compressible":
            return self._k * s / (2.0 * self._R)
        return self._k * s**2 / ((24.0 if self.geometry == "line" else 32.0) * self._R)


def constrained_modulus(E: float, nu: float) -> float:
    """M = (1 - nu) E / ((1 + nu)(1 - 2 nu)) in Pa (lambda + 2 mu)."""
    return (1.0 - nu) * E / ((1.0 + nu) * (1.0 - 2.0 * nu))


def _check(E: float, thickness: float, radius: float, load: float) -> None:
    for name, v in (("layer.E", E), ("layer.thickness", thickness), ("geometry.radius", radius), ("load", load)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(name, f"{v!r}; allowed (0, inf)")


def compressible(E: float, nu: float, thickness: float, radius: float, load: float,
                 geometry: str = "line") -> ThinLayerContact:
    """Thin compressible layer (seed 001 eqs 18-22, with the load-balance exponent). ``load`` is W' (N/m) for
    ``geometry="line"`` and P (N) for ``"circular"``."""
    _check(E, thickness, radius, load)
    if not -1.0 < nu <= NU_COMPRESSIBLE_MAX:
        raise InputError("layer.nu", f"{nu:g} for the compressible thin-layer formula; allowed (-1, "
                         f"{NU_COMPRESSIBLE_MAX}] (use the incompressible form near 0.5)")
    kb = constrained_modulus(E, nu) / thickness
    if geometry == "line":
        a = (3.0 * radius * load / (2.0 * kb)) ** (1.0 / 3.0)
    elif geometry == "circular":
        a = (4.0 * radius * load / (np.pi * kb)) ** 0.25
    else:
        raise InputError("geometry", f"{geometry!r}; allowed: line, circular")
    return ThinLayerContact(float(a), float(kb * a * a / (2.0 * radius)), float(a * a / (2.0 * radius)),
                            geometry, "compressible", float(kb), radius)


def incompressible(E: float, thickness: float, radius: float, load: float, geometry: str = "line",
                   top: str = "frictionless") -> ThinLayerContact:
    """Thin incompressible layer (nu = 0.5) bonded to a rigid base, squeeze-film solution (module docstring);
    ``top`` is "frictionless" (k = 3G/b^3) or "bonded" (k = 12G/b^3, the layer adheres to the indenter)."""
    _check(E, thickness, radius, load)
    G = E / 3.0
    if top not in ("frictionless", "bonded"):
        raise InputError("layer.top", f"{top!r}; allowed: frictionless, bonded")
    k = (3.0 if top == "frictionless" else 12.0) * G / thickness**3
    if geometry == "line":
        a = (45.0 * radius * load / (2.0 * k)) ** 0.2
        p0, delta = k * a**4 / (24.0 * radius), a * a / (6.0 * radius)
    elif geometry == "circular":
        a = (96.0 * radius * load / (np.pi * k)) ** (1.0 / 6.0)
        p0, delta = k * a**4 / (32.0 * radius), a * a / (4.0 * radius)
    else:
        raise InputError("geometry", f"{geometry!r}; allowed: line, circular")
    return ThinLayerContact(float(a), float(p0), float(delta), geometry, "incompressible", float(k), radius)
