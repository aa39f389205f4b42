"""Kalker's linear theory of rolling contact (vanishing creepage, complete adhesion).

For an elliptical Hertz contact with semi-axes a (rolling direction x) and b (lateral y), c = sqrt(a b), combined
shear modulus G (1/G = (1/G1 + 1/G2)/2) and creepages xi (-), eta (-), spin phi (1/m), Kalker's linear theory
(J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*, Kluwer 1990, Table E.3 for the coefficients;
Johnson, *Contact Mechanics*, 1985, §8.4 and Table 8.1) gives

    Fx = -G c^2 C11 xi                              (N)
    Fy = -G c^2 C22 eta - G c^3 C23 phi             (N)
    Mz = +G c^3 C23 eta - G c^4 C33 phi             (N m)

with the dimensionless creep coefficients C_ij(a/b, nu). The coefficients are inputs here: femcheck computes them
with its exact solver; this module holds no table. The equations are valid only for creepages small
compared with mu N / (G c^2 C_ij) (the creep force grows without the Coulomb limit).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from femcheck.errors import InputError


@dataclass(frozen=True)
class LinearCreepResult:
    """Creep forces of Kalker's linear theory.

    ``creep_force_x``, ``creep_force_y`` (N), ``spin_moment`` (N m) on the reference body (sign convention of
    Kalker 1990: the force opposes the creepage); ``adhesion_fraction`` is None (the theory assumes complete
    adhesion and never reaches the traction bound); ``c`` = sqrt(a b) (m).
    """

    creep_force_x: float
    creep_force_y: float
    spin_moment: float
    c: float
    adhesion_fraction: None = None


def _check_positive(key: str, value: float) -> float:
    value = float(value)
    if not math.isfinite(value) or value <= 0.0:
        raise InputError(key, f"must be a finite number > 0, got {value!r}")
    return value


def _check_finite(key: str, value: float) -> float:
    value = float(value)
    if not math.isfinite(value):
        raise InputError(key, f"must be a finite number, got {value!r}")
    return value


def _check_nonnegative(key: str, value: float) -> float:
    value = float(value)
    if not math.isfinite(value) or value < 0.0:
        raise InputError(key, f"must be a finite number >= 0, got {value!r}")
    return value


def linear_creep(a: float, b: float, G: float, c11: float, c22: float, c23: float, c33: float,
                 xi: float, eta: float, phi: float) -> LinearCreepResult:
    """Creep forces and spin moment of Kalker's linear theory (Kalker 1990; Johnson 1985 §8.4).

    Fx = -G c^2 C11 xi;  Fy = -G c^2 C22 eta - G c^3 C23 phi;  Mz = G c^3 C23 eta - G c^4 C33 phi;  c = sqrt(a b).

    Parameters (SI): ``a``, ``b`` semi-axes along x (rolling) and y (m); ``G`` combined shear modulus (Pa);
    ``c11``, ``c22``, ``c23``, ``c33`` Kalker's creep coefficients (-), C11, C22, C33 > 0 (they are the diagonal
    of a positive-definite stiffness), C23 any finite value (it is positive for every a/b and nu in Kalker's
    tables); ``xi``, ``eta`` creepages (-); ``phi`` spin creepage (1/m).
    Raises :class:`femcheck.errors.InputError` on a non-positive size, modulus or diagonal coefficient.
    """
    a = _check_positive("semi_axis_x", a)
    b = _check_positive("semi_axis_y", b)
    G = _check_positive("shear_modulus", G)
    c11 = _check_positive("c11", c11)
    c22 = _check_positive("c22", c22)
    c33 = _check_positive("c33", c33)
    c23 = _check_finite("c23", c23)
    xi = _check_finite("kinematics.xi", xi)
    eta = _check_finite("kinematics.eta", eta)
    phi = _check_finite("kinematics.phi", phi)
    c = math.sqrt(a * b)
    fx = -G * c**2 * c11 * xi
    fy = -G * c**2 * c22 * eta - G * c**3 * c23 * phi
    mz = G * c**3 * c23 * eta - G * c**4 * c33 * phi
    return LinearCreepResult(creep_force_x=fx, creep_force_y=fy, spin_moment=mz, c=c)
