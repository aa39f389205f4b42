"""Planar (2D, plane-strain) tangential contact of quasi-identical cylinders: Carter's steady rolling and the
2D Cattaneo shift.

Frame and signs (shared with :mod:`femcheck.cect.line`): x is the rolling direction, z the common normal.
Body 1 is the upper body (the cylinder), body 2 the lower one (the block). ``traction`` q(x) (Pa) is the
tangential traction exerted **on body 1 by body 2**. In rolling the contact moves in +x over both surfaces,
so material flows through it in -x and enters at the leading edge x = +a. The creepage xi (-) is the rigid
slip velocity of body 1 relative to body 2 (in +x) divided by the rolling speed V. Coulomb friction makes
the traction oppose the slip, so the creep force opposes xi (Kalker's convention, Johnson 1985 §8.2):
F'_x = int q dx = -(pi a E*/2) xi for small xi.

Elastic constants: E* is the plane-strain contact modulus, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
(:func:`femcheck.materials.effective_modulus`); with Kalker's combined constants 1/G = (1/G1 + 1/G2)/2,
nu/G = (nu1/G1 + nu2/G2)/2 it equals G/(1 - nu). The same E* governs the tangential surface displacements
(Johnson 1985 eq. 2.25a: d u_x/dx = -(2(1 - nu^2)/(pi E)) int q(s)/(x - s) ds per body). The closed forms
assume quasi-identical bodies ((1 - 2 nu1)/G1 = (1 - 2 nu2)/G2), i.e. no normal-tangential coupling.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def _check(load_per_length: float, half_width: float, modulus: float, mu: float) -> None:
    if not (load_per_length > 0 and half_width > 0 and modulus > 0 and mu > 0):
        raise ValueError("load_per_length, half_width, modulus and mu must be positive")


def _semi_ellipse(x: np.ndarray, centre: float, half: float) -> np.ndarray:
    """sqrt(1 - ((x - centre)/half)^2) inside |x - centre| < half, 0 outside (0 everywhere if half == 0)."""
    if half <= 0.0:
        return np.zeros_like(x)
    s = 1.0 - ((x - centre) / half) ** 2
    return np.sqrt(np.clip(s, 0.0, None))


def normalized_creepage(xi: float | np.ndarray, p_max: float, modulus: float, mu: float) -> float | np.ndarray:
    """xi* = E* xi / (2 mu p0) (seed 000 eq 8, with E* = E/(2(1 - nu^2)) for identical bodies); the contact
    saturates (full slip) at |xi*| >= 1."""
    return modulus * np.asarray(xi, dtype=float) / (2.0 * mu * p_max)


def carter_creep_force(xi: float | np.ndarray, load_per_length: float, half_width: float, modulus: float,
                       mu: float) -> float | np.ndarray:
    """Carter's creep force per unit length (N/m), vectorised over xi (seed 000 eq 11; Johnson 1985 eq. 8.23):

        F'_x = -sgn(xi) mu W' (1 - c'^2),   c' = c/a = 1 - min(1, |xi*|),   xi* = E* xi / (2 mu p0),

    with p0 = 2 W'/(pi a) the Hertz peak pressure. Inputs: W' (N/m), a (m), E* (Pa), mu (-)."""
    _check(load_per_length, half_width, modulus, mu)
    p0 = 2.0 * load_per_length / (np.pi * half_width)
    xs = normalized_creepage(xi, p0, modulus, mu)
    cp = 1.0 - np.minimum(1.0, np.abs(xs))
    return -np.sign(xs) * mu * load_per_length * (1.0 - cp**2)


@dataclass(frozen=True)
class CarterSolution:
    """Carter's 2D steady-rolling solution (Carter 1926; Johnson 1985 §8.2; seed 000 eqs 8-11).

    ``half_width`` a (m), ``p_max`` p0 (Pa), ``load_per_length`` W' (N/m), ``modulus`` E* (Pa), ``mu``,
    ``creepage`` xi (-), ``normalized_creepage`` xi* (-), ``stick_half_width`` c (m): the adhesion zone is
    a - 2c < x <= a (at the leading edge), ``creep_force`` F'_x (N/m), ``adhesion_length`` 2c (m).
    """

    half_width: float
    p_max: float
    load_per_length: float
    modulus: float
    mu: float
    creepage: float
    normalized_creepage: float
    stick_half_width: float
    creep_force: float

    @property
    def adhesion_length(self) -> float:
        return 2.0 * self.stick_half_width

    @property
    def adhesion_fraction(self) -> float:
        """Adhesion length / contact length 2a (-)."""
        return self.stick_half_width / self.half_width

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """Hertz pressure p0 sqrt(1 - x^2/a^2) (Pa)."""
        return self.p_max * _semi_ellipse(np.asarray(x, dtype=float), 0.0, self.half_width)

    def traction(self, x: np.ndarray) -> np.ndarray:
        """Tangential traction on body 1 (Pa), seed 000 eq 9 / Johnson eq. 8.20:
        q = -sgn(xi) mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - (x - d)^2/c^2)],  d = a - c."""
        x = np.asarray(x, dtype=float)
        a, c = self.half_width, self.stick_half_width
        shape = _semi_ellipse(x, 0.0, a) - (c / a) * _semi_ellipse(x, a - c, c)
        return -np.sign(self.creepage) * self.mu * self.p_max * shape

    def slip(self, x: np.ndarray) -> np.ndarray:
        """Slip velocity of body 1 relative to body 2 divided by the rolling speed, s/V (-) (seed 000 eq 10):
        0 in the adhesion zone, (xi/xi*) sqrt((x' - (1 - c'))^2 - c'^2) for x' = x/a <= 1 - 2c' (with full
        slip, c' = 0: xi - (2 mu p0/E*) x/a, the rigid creepage minus the elastic strain of full-slip
        tractions). Zero outside the contact (not defined there)."""
        x = np.asarray(x, dtype=float)
        a, c = self.half_width, self.stick_half_width
        xs, cp = self.normalized_creepage, c / a
        xp = x / a
        inside = np.abs(xp) <= 1.0
        if self.creepage == 0.0:
            return np.zeros_like(x)          # free rolling of quasi-identical bodies: no slip anywhere
        if cp <= 0.0:
            s = self.creepage - np.sign(self.creepage) * (2.0 * self.mu * self.p_max / self.modulus) * xp
        else:
            arg = np.clip((xp - (1.0 - cp)) ** 2 - cp**2, 0.0, None)
            s = np.where(xp <= 1.0 - 2.0 * cp, (self.creepage / xs) * np.sqrt(arg), 0.0)
        return np.where(inside, s, 0.0)


def carter_rolling(load_per_length: float, half_width: float, modulus: float, mu: float,
                   xi: float) -> CarterSolution:
    """Carter's solution for steady rolling of quasi-identical cylinders with creepage ``xi`` (-) under
    W' (N/m) with Hertz half-width a (m), contact modulus E* (Pa) and friction coefficient mu (-).

    Derivation (Johnson 1985 §8.2): the full-slip traction -mu p0 sqrt(1 - x^2/a^2) plus the corrective
    +mu p0 (c/a) sqrt(1 - (x-d)^2/c^2) give a uniform strain d u/dx = 2 mu p0 d / (E* a) over |x - d| < c, which
    equals xi (no slip) when d/a = xi*, i.e. c/a = 1 - |xi*|; the adhesion zone touches the leading edge.
    """
    _check(load_per_length, half_width, modulus, mu)
    p0 = 2.0 * load_per_length / (np.pi * half_width)
    xs = float(normalized_creepage(xi, p0, modulus, mu))
    c = half_width * (1.0 - min(1.0, abs(xs)))
    force = float(carter_creep_force(xi, load_per_length, half_width, modulus, mu))
    return CarterSolution(float(half_width), float(p0), float(load_per_length), float(modulus), float(mu),
                          float(xi), xs, float(c), force)


@dataclass(frozen=True)
class CattaneoLineSolution:
    """2D Cattaneo problem: a cylinder pressed by W' (N/m), then pushed tangentially by Q' (N/m), |Q'| < mu W'.

    ``stick_half_width`` c (m), ``shift`` (m): the micro-slip part of the rigid shift of the cylinder
    relative to the block in the direction of Q' (delta(Q') - delta_stick(Q'), see :func:`cattaneo_line`),
    ``half_width`` a (m), ``p_max`` p0 (Pa), ``tangential_per_length`` Q' (N/m).
    """

    half_width: float
    p_max: float
    load_per_length: float
    tangential_per_length: float
    modulus: float
    mu: float
    stick_half_width: float
    shift: float

    def pressure(self, x: np.ndarray) -> np.ndarray:
        return self.p_max * _semi_ellipse(np.asarray(x, dtype=float), 0.0, self.half_width)

    def traction(self, x: np.ndarray) -> np.ndarray:
        """Traction on the cylinder (Pa), opposing Q' (Johnson 1985 eq. 7.14-7.15 in 2D):
        q = -sgn(Q') mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)]."""
        x = np.asarray(x, dtype=float)
        a, c = self.half_width, self.stick_half_width
        shape = _semi_ellipse(x, 0.0, a) - (c / a) * _semi_ellipse(x, 0.0, c)
        return -np.sign(self.tangential_per_length) * self.mu * self.p_max * shape


def cattaneo_line(load_per_length: float, half_width: float, modulus: float, mu: float,
                  tangential_per_length: float) -> CattaneoLineSolution:
    """2D Cattaneo (plane strain) partial slip of quasi-identical bodies (Johnson 1985 §7.1, 2D form).

    Stick half-width:  c = a sqrt(1 - |Q'|/(mu W')).
    Shift: the 2D rigid shift is undefined (the half-plane displacement grows like log r), so the reported
    ``shift`` is its micro-slip part, delta(Q') - delta_stick(Q'), delta_stick being the shift of the same
    contact fully adhered under the same Q' (traction Q'/(pi sqrt(a^2 - x^2)), uniform displacement
    (2 Q'/(pi E*)) ln(2 L/a) for a datum L). Integrating the log kernel over the two semi-ellipses
    (int_{-1}^{1} sqrt(1 - t^2) ln|X - t| dt = (pi/2)(X^2 - 1/2 - ln 2), |X| <= 1) gives, with k = c/a,

        shift = sgn(Q') (mu p0 a / E*) [ (1 - k^2)/2 + k^2 ln k ] = sgn(Q') (2 mu W'/(pi E*)) [ ... ]  (m),

    which is 0 at Q' = 0 and mu p0 a/(2 E*) at the onset of sliding. Raises ValueError for |Q'| >= mu W'.
    """
    _check(load_per_length, half_width, modulus, mu)
    ratio = abs(tangential_per_length) / (mu * load_per_length)
    if ratio >= 1.0:
        raise ValueError(f"|Q'| = {abs(tangential_per_length):g} N/m >= mu W' = {mu * load_per_length:g} N/m: "
                         "the cylinder slides; no static partial-slip solution")
    p0 = 2.0 * load_per_length / (np.pi * half_width)
    k = np.sqrt(1.0 - ratio)
    bracket = 0.5 * (1.0 - k * k) + (k * k * np.log(k) if k > 0 else 0.0)
    shift = np.sign(tangential_per_length) * mu * p0 * half_width / modulus * bracket
    return CattaneoLineSolution(float(half_width), float(p0), float(load_per_length), float(tangential_per_length),
                                float(modulus), float(mu), float(half_width * k), float(shift))
