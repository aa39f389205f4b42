"""Strip theory (Haines & Ollerton 1963; seed 000 §3.1, eqs 8-11): Hertz + Carter per strip.

The elliptical Hertz contact (semi-axes a along the rolling direction x, b along y) is cut into strips
parallel to x. Each strip is treated as an independent 2D rolling contact (Carter) with the local Hertz
values: half-length a' = a sqrt(1 - y^2/b^2), peak pressure p0' = p0 sqrt(1 - y^2/b^2) and normal force per
unit width dN/dy = pi a' p0'/2 = (3 N/(4 b))(1 - y^2/b^2). Interaction between strips is neglected.

Creepages: the rigid slip of a strip is w/V = (xi - phi y, eta + phi x) (Kalker's kinematics). Carter's
theory needs a creepage constant along the strip, so the lateral spin part phi x is neglected: spin acts
only through the longitudinal creepage xi - phi y (as in seed 000, which uses pure longitudinal creepage per
strip). Consequently strip theory gives no lateral force from spin (C23 phi term) -- a known limitation of
1D models noted in seed 000 §5.

Elasticity per strip: Kalker's combined constants 1/G = (1/G1 + 1/G2)/2, nu/G = (nu1/G1 + nu2/G2)/2.
Longitudinal (in-plane, plane strain) compliance gives E*_x = G/(1 - nu) (seed 000 eq 8: E/(2(1 - nu^2)) for
identical bodies); lateral traction in a strip is anti-plane shear, whose half-plane surface displacement is
u_y = -(1/(pi G_i)) Q ln|x| per body (Johnson 1985 §2.8), so E*_y = G. For a combined creepage vector
(xi_s, eta) the normalised creepage is the vector xi* = (E*_x xi_s, E*_y eta)/(2 mu p0') and Carter's traction
acts along e = xi*/|xi*| with c' = 1 - min(1, |xi*|): the adhesion zone is then exact; the slip direction
in the slip zone is exactly opposite to the traction only when E*_x = E*_y (nu = 0) or one creepage
vanishes -- otherwise this vector extension is an approximation.

Per strip (unit width, seed 000 eq 11 and its first moment):
    dF/dy = -e (1 - c'^2) mu dN/dy,
    int x q_y dx = e_y mu (dN/dy) a' c'^2 (1 - c')   (the adhesion zone sits at the leading edge),
and the spin moment Mz = int (x q_y - y q_x) dA. Signs follow Kalker: Fx = -G c^2 C11 xi, Fy = -G c^2 C22 eta,
Mz = G c^3 C23 eta - G c^4 C33 phi for small creepages (forces on body 1, the traction opposing its slip).
In the linear limit the sums give C11 = pi^2/(4(1 - nu)), C22 = pi^2/4 (Kalker's a/b -> 0 asymptotes),
C23 = (pi/3) sqrt(a/b) (eta part only) and C33 = pi^2 b/(16 (1 - nu) a).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


@dataclass
class StripTheoryResult:
    """Strip-theory solution. Totals: ``creep_force_x``, ``creep_force_y`` (N), ``spin_moment`` (N m, about
    the contact centre), ``adhesion_fraction`` (adhesion area / contact area, -), ``normal_force`` (N, sum
    over strips = N). Per strip (arrays of ``n_strips``): ``y`` centre (m), ``width`` (m), ``half_length`` a'
    (m), ``p_max`` p0' (Pa), ``strip_normal_force`` (N), ``creepage_x``, ``creepage_y`` (-),
    ``normalized_creepage`` |xi*| (-), ``stick_fraction`` c' (-), ``force_x``, ``force_y`` (N),
    ``moment`` (N m)."""

    creep_force_x: float
    creep_force_y: float
    spin_moment: float
    adhesion_fraction: float
    normal_force: float
    n_strips: int
    y: np.ndarray
    width: float
    half_length: np.ndarray
    p_max: np.ndarray
    strip_normal_force: np.ndarray
    creepage_x: np.ndarray
    creepage_y: np.ndarray
    normalized_creepage: np.ndarray
    stick_fraction: np.ndarray
    force_x: np.ndarray
    force_y: np.ndarray
    moment: np.ndarray
    iterations: int = 0           # closed form per strip: no iteration
    residual: float = 0.0


def _positive(name: str, value: float) -> None:
    if not (np.isfinite(value) and value > 0):
        raise InputError(name, f"{value} is not allowed; allowed: (0, inf)")


def strip_theory(a: float, b: float, normal_load: float, G: float, nu: float, mu: float, xi: float = 0.0,
                 eta: float = 0.0, phi: float = 0.0, n_strips: int = 200) -> StripTheoryResult:
    """Strip theory for an elliptical Hertz contact: semi-axes ``a`` (m, rolling direction x) and ``b`` (m,
    lateral y), ``normal_load`` N (N), Kalker's combined shear modulus ``G`` (Pa) and Poisson's ratio ``nu``,
    friction ``mu``, creepages ``xi``, ``eta`` (-) and spin ``phi`` (1/m), on ``n_strips`` strips of equal
    width. Each strip's normal force is the exact integral of the Hertz load over the strip, so the strip
    forces add up to N exactly; a', p0' are taken at the strip centre. See the module doc for the equations.
    """
    for name, v in (("a", a), ("b", b), ("normal_load", normal_load), ("G", G), ("mu", mu)):
        _positive(name, v)
    if not (-1.0 < nu < 0.5):
        raise InputError("nu", f"{nu} is not allowed; allowed: (-1, 0.5)")
    for name, v in (("xi", xi), ("eta", eta), ("phi", phi)):
        if not np.isfinite(v):
            raise InputError(name, f"{v} is not allowed; allowed: a finite number")
    if int(n_strips) != n_strips or n_strips < 1:
        raise InputError("n_strips", f"{n_strips} is not allowed; allowed: an integer >= 1")
    n = int(n_strips)
    p0 = 3.0 * normal_load / (2.0 * np.pi * a * b)
    dy = 2.0 * b / n
    edges = -b + dy * np.arange(n + 1)
    y = 0.5 * (edges[:-1] + edges[1:])
    # exact strip loads: dN = (3N/(4b)) int (1 - y^2/b^2) dy
    prim = edges - edges**3 / (3.0 * b * b)
    dN = 0.75 * normal_load / b * np.diff(prim)
    shape = np.sqrt(1.0 - (y / b) ** 2)
    a_s, p_s = a * shape, p0 * shape
    e_x, e_y = G / (1.0 - nu), G                      # in-plane and anti-plane strip moduli (Pa)
    cx = xi - phi * y
    cy = np.full(n, float(eta))
    vx = e_x * cx / (2.0 * mu * p_s)
    vy = e_y * cy / (2.0 * mu * p_s)
    mag = np.hypot(vx, vy)
    cp = 1.0 - np.minimum(1.0, mag)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux = np.where(mag > 0, vx / np.where(mag > 0, mag, 1.0), 0.0)
        uy = np.where(mag > 0, vy / np.where(mag > 0, mag, 1.0), 0.0)
    sat = 1.0 - cp**2
    fx = -ux * sat * mu * dN
    fy = -uy * sat * mu * dN
    mz = uy * mu * dN * a_s * cp**2 * (1.0 - cp) - y * fx
    area = np.sum(2.0 * a_s) * dy
    return StripTheoryResult(
        creep_force_x=float(fx.sum()), creep_force_y=float(fy.sum()), spin_moment=float(mz.sum()),
        adhesion_fraction=float(np.sum(2.0 * cp * a_s) * dy / area), normal_force=float(dN.sum()), n_strips=n,
        y=y, width=dy, half_length=a_s, p_max=p_s, strip_normal_force=dN, creepage_x=cx, creepage_y=cy,
        normalized_creepage=mag, stick_fraction=cp, force_x=fx, force_y=fy, moment=mz)
