"""Hertz contact closed forms (Johnson, *Contact Mechanics*, 1985, ch. 4; seed 001 eqs 1-5).

All inputs and outputs in SI units.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class LineContact:
    """Hertz line contact (plane strain) of a cylinder on a flat (or two parallel cylinders).

    ``half_width`` a (m), ``p_max`` p0 (Pa), ``load`` per unit length (N/m), ``radius`` R (m),
    ``modulus`` E* (Pa).
    """

    load: float
    radius: float
    modulus: float
    half_width: float
    p_max: float

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """Elliptical pressure p(x) = p0 sqrt(1 - x^2/a^2) (seed 001 eq 5), zero outside |x| < a."""
        s = 1.0 - (np.asarray(x, dtype=float) / self.half_width) ** 2
        return self.p_max * np.sqrt(np.clip(s, 0.0, None))


def line_contact(load_per_length: float, radius: float, modulus: float) -> LineContact:
    """Hertz line contact.

    a  = sqrt(4 W' R / (pi E*))        (seed 001 eq 3 with D = 2R, W' = W/L)
    p0 = 2 W' / (pi a)                 (seed 001 eq 4)

    ``radius`` is the reduced radius 1/R = 1/R1 + 1/R2 (seed 001 eq 1), ``modulus`` the combined
    E* of seed 001 eq 2 (see :func:`femcheck.materials.effective_modulus`).
    """
    if load_per_length <= 0 or radius <= 0 or modulus <= 0:
        raise ValueError("load, radius and modulus must be positive")
    a = np.sqrt(4.0 * load_per_length * radius / (np.pi * modulus))
    p0 = 2.0 * load_per_length / (np.pi * a)
    return LineContact(load_per_length, radius, modulus, float(a), float(p0))


def reduced_radius(r1: float, r2: float = np.inf) -> float:
    """1/R = 1/R1 + 1/R2 (seed 001 eq 1); a concave surface has a negative radius."""
    curvature = 1.0 / r1 + (0.0 if np.isinf(r2) else 1.0 / r2)
    if curvature <= 0:
        raise ValueError("surfaces do not close towards each other (total curvature <= 0)")
    return 1.0 / curvature


@dataclass(frozen=True)
class EllipticContact:
    """Hertz contact of two bodies with principal relative radii Rx, Ry (m) under a normal ``load`` (N).

    ``semi_axis_x``, ``semi_axis_y`` (m): semi-axes of the contact ellipse along x and y; ``p_max`` (Pa);
    ``approach`` delta (m); ``modulus`` E* (Pa).
    """

    load: float
    Rx: float
    Ry: float
    modulus: float
    semi_axis_x: float
    semi_axis_y: float
    p_max: float
    approach: float

    @property
    def contact_area(self) -> float:
        return float(np.pi * self.semi_axis_x * self.semi_axis_y)

    def pressure(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """p = p0 sqrt(1 - x^2/a_x^2 - y^2/a_y^2) inside the ellipse (Johnson eq. 4.35)."""
        s = 1.0 - (np.asarray(x) / self.semi_axis_x) ** 2 - (np.asarray(y) / self.semi_axis_y) ** 2
        return self.p_max * np.sqrt(np.clip(s, 0.0, None))


def _curvature_ratio(k: float) -> float:
    """B/A of the gap h = A u^2 + B v^2 whose contact ellipse has axis ratio k = b/a <= 1 (a along u, the
    direction of the smaller curvature A). Johnson (1985) eq 4.39, B/A = [(a/b)^2 E(e) - K(e)] / [K(e) - E(e)]
    with e^2 = 1 - k^2, written with Carlson's R_D (DLMF 19.25.1: K - E = (e^2/3) R_D(0, k^2, 1),
    E - k^2 K = (e^2 k^2/3) R_D(0, 1, k^2)) so that neither difference cancels as e -> 0 or e -> 1."""
    from scipy.special import elliprd

    return float(elliprd(0.0, 1.0, k * k) / elliprd(0.0, k * k, 1.0))


def elliptic_contact(load: float, Rx: float, Ry: float, modulus: float) -> EllipticContact:
    """Exact Hertz solution for an elliptical contact (Johnson 1985 §4.2, eqs 4.36-4.39).

    With A = 1/(2 R_major) <= B = 1/(2 R_minor) (a along the smaller curvature), Johnson's
      A = p0 b (K - E) / (E* a^2 e^2),  P = 2/3 pi a b p0,  delta = p0 b K(e) / E*
    give  a^3 = P R_D(0, k^2, 1) / (2 pi A E*),  b = k a,  p0 = 3 P / (2 pi a b),
    where k = b/a solves B/A = R_D(0, 1, k^2) / R_D(0, k^2, 1) (see :func:`_curvature_ratio`).
    Rx == Ry reduces exactly to the sphere: R_D(0, 1, 1) = 3 pi / 4, a^3 = 3 P R / (4 E*).
    """
    from scipy.optimize import brentq
    from scipy.special import ellipkm1, elliprd

    if load <= 0 or Rx <= 0 or Ry <= 0 or modulus <= 0:
        raise ValueError("load, radii and modulus must be positive")
    r_major, r_minor = max(Rx, Ry), min(Rx, Ry)      # the major axis lies along the larger radius
    A, B = 1.0 / (2.0 * r_major), 1.0 / (2.0 * r_minor)
    ratio = B / A
    if ratio == 1.0:
        k = 1.0
    else:
        k = float(np.exp(brentq(lambda s: np.log(_curvature_ratio(np.exp(s)) / ratio), np.log(1e-9), 0.0,
                                xtol=1e-15, rtol=1e-15)))
    a = (load * elliprd(0.0, k * k, 1.0) / (2.0 * np.pi * A * modulus)) ** (1.0 / 3.0)
    b = k * a
    p0 = 3.0 * load / (2.0 * np.pi * a * b)
    delta = p0 * b * ellipkm1(k * k) / modulus
    ax, ay = (a, b) if Rx >= Ry else (b, a)
    return EllipticContact(load, Rx, Ry, modulus, float(ax), float(ay), float(p0), float(delta))


def point_contact(load: float, radius: float, modulus: float) -> EllipticContact:
    """Hertz sphere on flat: a = (3 P R / (4 E*))^(1/3), p0 = 3P/(2 pi a^2), delta = a^2/R (Johnson eq. 4.22)."""
    return elliptic_contact(load, radius, radius, modulus)
