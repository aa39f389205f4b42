"""Influence coefficients of two elastic half-spaces in contact: surface displacement differences due to uniform
tractions on rectangular elements (Boussinesq-Cerruti), for Kalker's exact theory.

Conventions (shared with :mod:`femcheck.cect.exact`): x rolling direction, y lateral, z the common normal pointing
into body 1. ``p = (px, py, pn)`` is the traction exerted *on body 1* (pn > 0 compressive); body 2 carries -p.
The tangential displacement difference is u = u(body 1) - u(body 2); the normal one is the sum of the two
inward displacements, i.e. the elastic opening of the gap.

Point-force surface Green's functions of one half-space (shear modulus G_i, Poisson nu_i), z into the body, at
offset (x, y) from the force, r = sqrt(x^2 + y^2) (Johnson 1985, eqs 3.19-3.20 and 3.86-3.87; Love 1929):
  u_x = Fx/(2 pi G) [(1 - nu)/r + nu x^2/r^3] + Fy/(2 pi G) nu x y/r^3 - Fz (1 - 2nu)/(4 pi G) x/r^2
  u_y = Fx/(2 pi G) nu x y/r^3 + Fy/(2 pi G) [(1 - nu)/r + nu y^2/r^3] - Fz (1 - 2nu)/(4 pi G) y/r^2
  u_z = Fx (1 - 2nu)/(4 pi G) x/r^2 + Fy (1 - 2nu)/(4 pi G) y/r^2 + Fz (1 - nu)/(2 pi G)/r
(the sign of the Cerruti normal term follows from Betti's reciprocity with Boussinesq's inward radial
displacement). Adding body 2 (mirrored, loaded by -p) gives Kalker's combined form (Kalker 1990, §1.5;
Vollebregt's CONTACT user guide) with
  1/G = (1/G1 + 1/G2)/2,  nu/G = (nu1/G1 + nu2/G2)/2,  K = (G/4) [(1 - 2nu1)/G1 - (1 - 2nu2)/G2]:
  A_xx = 1/(pi G) [(1 - nu)/r + nu x^2/r^3],  A_xy = A_yx = 1/(pi G) nu x y/r^3,
  A_yy = 1/(pi G) [(1 - nu)/r + nu y^2/r^3],  A_zz = 1/(pi G) (1 - nu)/r,
  A_xz = -K/(pi G) x/r^2,  A_yz = -K/(pi G) y/r^2,  A_zx = +K/(pi G) x/r^2,  A_zy = +K/(pi G) y/r^2.
K = 0 for quasi-identical bodies (same (1 - 2nu)/G), and then normal and tangential problems uncouple.

Integrating over a dx x dy rectangle: with lags X = t_x -/+ dx/2, Y = t_y -/+ dy/2 of the field point from the
rectangle's edges, int int f = F(Xp, Yp) - F(Xp, Ym) - F(Xm, Yp) + F(Xm, Ym) with the double antiderivatives
  1/r      -> X asinh(Y/|X|) + Y asinh(X/|Y|)       (Love 1929; as in femcheck.bem.influence)
  x^2/r^3  -> Y asinh(X/|Y|)
  y^2/r^3  -> X asinh(Y/|X|)
  x y/r^3  -> -r
  x/r^2    -> X atan(Y/X) + (Y/2) ln(X^2 + Y^2)
  y/r^2    -> Y atan(X/Y) + (X/2) ln(X^2 + Y^2)
(each continuous, with an integrable derivative, across X = 0 and Y = 0, so the corner sum is exact for cells
containing the field point). All coefficients are in m/Pa (displacement per unit traction).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import InputError
from ..materials import Elastic


@dataclass(frozen=True)
class CombinedConstants:
    """Kalker's combined elastic constants of a body pair: ``shear_modulus`` G (Pa), ``poisson`` nu (-) and the
    difference parameter ``coupling`` K (-), Kalker (1990) eq. 1.5.x / Johnson (1985) §8.4."""

    shear_modulus: float
    poisson: float
    coupling: float

    @property
    def contact_modulus(self) -> float:
        """E* (Pa) with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 = (1 - nu)/G."""
        return self.shear_modulus / (1.0 - self.poisson)


def combined_constants(body1: Elastic, body2: Elastic) -> CombinedConstants:
    """1/G = (1/G1 + 1/G2)/2, nu/G = (nu1/G1 + nu2/G2)/2, K = (G/4)[(1 - 2nu1)/G1 - (1 - 2nu2)/G2]; a rigid body
    contributes zero compliance (1/G_i = 0)."""
    if body1.rigid and body2.rigid:
        raise InputError("materials.body2.rigid", "both bodies rigid: at least one must be elastic")
    inv = [0.0 if b.rigid else 1.0 / b.shear_modulus for b in (body1, body2)]
    nus = [0.0 if b.rigid else b.nu for b in (body1, body2)]
    inv_g = 0.5 * (inv[0] + inv[1])
    g = 1.0 / inv_g
    nu = g * 0.5 * (nus[0] * inv[0] + nus[1] * inv[1])
    k = 0.25 * g * ((1.0 - 2.0 * nus[0]) * inv[0] - (1.0 - 2.0 * nus[1]) * inv[1])
    return CombinedConstants(float(g), float(nu), float(k))


def _asinh_ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num * asinh(den/|num|), taken as 0 where num = 0 (its limit)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(num != 0, num * np.arcsinh(den / np.abs(np.where(num != 0, num, 1.0))), 0.0)


def _atan_log(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """u atan(v/u) + (v/2) ln(u^2 + v^2): antiderivative of u/r^2 (0 at u = 0 resp. v = 0 by continuity)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(u != 0, u * np.arctan(v / np.where(u != 0, u, 1.0)), 0.0)
        r2 = u * u + v * v
        t2 = np.where(v != 0, 0.5 * v * np.log(np.where(r2 > 0, r2, 1.0)), 0.0)
    return t1 + t2


_ANTIDERIVATIVES: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    "1/r": lambda X, Y: _asinh_ratio(X, Y) + _asinh_ratio(Y, X),
    "xx/r3": lambda X, Y: _asinh_ratio(Y, X),
    "yy/r3": lambda X, Y: _asinh_ratio(X, Y),
    "xy/r3": lambda X, Y: -np.sqrt(X * X + Y * Y),
    "x/r2": lambda X, Y: _atan_log(X, Y),
    "y/r2": lambda X, Y: _atan_log(Y, X),
}


def rectangle_integral(name: str, tx: np.ndarray, ty: np.ndarray, dx: float, dy: float) -> np.ndarray:
    """int int f(tx - s, ty - t) ds dt over the rectangle |s| < dx/2, |t| < dy/2 for f one of ``1/r``,
    ``xx/r3``, ``yy/r3``, ``xy/r3``, ``x/r2``, ``y/r2`` (units m for 1/r-like kernels, m^0 * m for x/r2)."""
    F = _ANTIDERIVATIVES[name]
    tx, ty = np.asarray(tx, dtype=float), np.asarray(ty, dtype=float)
    xp, xm, yp, ym = tx + 0.5 * dx, tx - 0.5 * dx, ty + 0.5 * dy, ty - 0.5 * dy
    return F(xp, yp) - F(xp, ym) - F(xm, yp) + F(xm, ym)


COMPONENTS = ("xx", "xy", "yx", "yy", "zz", "xz", "yz", "zx", "zy")


def influence(component: str, tx: np.ndarray, ty: np.ndarray, dx: float, dy: float,
              constants: CombinedConstants) -> np.ndarray:
    """A_ij (m/Pa): displacement difference in direction i at lag (tx, ty) (m) from the centre of a dx x dy (m)
    element carrying a unit uniform traction (1 Pa) in direction j; i, j in x, y, z (z = normal). See the module
    docstring for the formulas (Kalker 1990 §1.5, Johnson 1985 §3.2 and §3.6)."""
    G, nu, K = constants.shear_modulus, constants.poisson, constants.coupling
    c = 1.0 / (np.pi * G)
    R = lambda name: rectangle_integral(name, tx, ty, dx, dy)  # noqa: E731
    if component == "xx":
        return c * ((1.0 - nu) * R("1/r") + nu * R("xx/r3"))
    if component == "yy":
        return c * ((1.0 - nu) * R("1/r") + nu * R("yy/r3"))
    if component in ("xy", "yx"):
        return c * nu * R("xy/r3")
    if component == "zz":
        return c * (1.0 - nu) * R("1/r")
    if component in ("xz", "zx"):
        return (-1.0 if component == "xz" else 1.0) * c * K * R("x/r2")
    if component in ("yz", "zy"):
        return (-1.0 if component == "yz" else 1.0) * c * K * R("y/r2")
    raise ValueError(f"component must be one of {COMPONENTS}, got {component!r}")


def point_force_displacement(component: str, x: np.ndarray, y: np.ndarray,
                             constants: CombinedConstants) -> np.ndarray:
    """Point-force (1 N) Green's function A_ij(x, y) (m/N) of the body pair, the integrand of :func:`influence`
    (used to verify the closed forms by quadrature)."""
    G, nu, K = constants.shear_modulus, constants.poisson, constants.coupling
    r2 = x * x + y * y
    r = np.sqrt(r2)
    c = 1.0 / (np.pi * G)
    table = {
        "xx": c * ((1.0 - nu) / r + nu * x * x / (r2 * r)),
        "yy": c * ((1.0 - nu) / r + nu * y * y / (r2 * r)),
        "xy": c * nu * x * y / (r2 * r),
        "zz": c * (1.0 - nu) / r,
        "xz": -c * K * x / r2, "zx": c * K * x / r2,
        "yz": -c * K * y / r2, "zy": c * K * y / r2,
    }
    table["yx"] = table["xy"]
    return table[component]
