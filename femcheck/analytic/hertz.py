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
