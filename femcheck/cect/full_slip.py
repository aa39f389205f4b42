"""Full-slip tangential contact model on an elliptical Hertz contact.

Seed 000 (Blanco-Lorenzo et al. 2022): the "usual full slip approach" of its introduction and the full-slip
column of its Table 2 (described in the text of §4.3); Johnson 1985 §8.4. The elastic displacement gradients are
neglected against the rigid slip, so every point slips and the tangential traction is the Coulomb limit
directed against the local rigid slip velocity,

    p_t(x, y) = -mu p(x, y) w / |w|,   w = (xi - phi y, eta + phi x)      (Pa; w normalised by the rolling speed)

with p the Hertz pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2), p0 = 3N/(2 pi a b). The forces are
F = int p_t dA (N) and the spin moment Mz = int (x p_ty - y p_tx) dA (N m). At pure longitudinal creepage the
direction is uniform and Fx = -mu N sign(xi) exactly; at pure spin Mz = -mu sign(phi) (pi/16) p0 a b P with P the
perimeter of the contact ellipse (for a = b: -(3 pi/16) mu N a).

Quadrature: with x = a sqrt(1 - t^2) s, y = b t the load element is p dA = p0 a b (1 - t^2) sqrt(1 - s^2) ds dt,
so a product of Gauss-Chebyshev (second kind, weight sqrt(1 - s^2), ``nx`` nodes along each strip) and
Gauss-Legendre (``ny`` strips in t) integrates the Hertz load exactly (to round-off) for ny >= 2: the sum of the
node loads is N. The traction direction is evaluated at the nodes; where the rigid slip direction jumps (the spin
pole inside the contact) the quadrature converges algebraically.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from femcheck.cect.fastsim import _check_grid
from femcheck.cect.linear import _check_finite, _check_positive


@dataclass(frozen=True, eq=False)
class FullSlipResult:
    """Full-slip solution.

    ``creep_force_x``, ``creep_force_y`` (N), ``spin_moment`` (N m); ``adhesion_fraction`` = 0.0 (the model
    assumes slip everywhere). Fields of shape (ny, nx): ``x``, ``y`` (m) quadrature nodes, ``px``, ``py``
    (Pa) tangential traction, ``pressure`` (Pa) Hertz pressure, ``weights`` (m^2) quadrature area weights with
    sum(weights * pressure) = N to round-off and F = sum(weights * p_t). ``slip_direction_defined`` is False at
    nodes with zero rigid slip (no traction there).
    """

    creep_force_x: float
    creep_force_y: float
    spin_moment: float
    adhesion_fraction: float
    x: np.ndarray
    y: np.ndarray
    px: np.ndarray
    py: np.ndarray
    pressure: np.ndarray
    weights: np.ndarray
    slip_direction_defined: np.ndarray
    nx: int
    ny: int


def full_slip(a: float, b: float, normal_load: float, mu: float, xi: float, eta: float, phi: float,
              nx: int = 40, ny: int = 40) -> FullSlipResult:
    """Full-slip creep forces on a Hertz ellipse (seed 000 full-slip model; equations in the module doc).

    Parameters (SI): ``a``, ``b`` semi-axes along x (rolling) and y (m); ``normal_load`` N (N); ``mu`` Coulomb
    friction coefficient (> 0); ``xi``, ``eta`` creepages (-); ``phi`` spin creepage (1/m); ``nx`` Chebyshev
    nodes along x per strip, ``ny`` Gauss-Legendre strips (both >= 2).
    Raises :class:`femcheck.errors.InputError` on bad input.
    """
    a = _check_positive("semi_axis_x", a)
    b = _check_positive("semi_axis_y", b)
    normal_load = _check_positive("load.normal", normal_load)
    mu = _check_positive("friction.mu", mu)
    xi = _check_finite("kinematics.xi", xi)
    eta = _check_finite("kinematics.eta", eta)
    phi = _check_finite("kinematics.phi", phi)
    nx = _check_grid("numerics.nx", nx)
    ny = _check_grid("numerics.ny", ny)

    p0 = 1.5 * normal_load / (math.pi * a * b)
    t, wt = np.polynomial.legendre.leggauss(ny)
    theta = np.arange(1, nx + 1) * math.pi / (nx + 1)
    s = np.cos(theta)                                   # s = 1 is the leading edge
    ws = math.pi / (nx + 1) * np.sin(theta) ** 2        # Gauss-Chebyshev II weights for sqrt(1 - s^2)

    half = np.sqrt(1.0 - t**2)
    x = a * half[:, None] * s[None, :]
    y = np.broadcast_to((b * t)[:, None], x.shape).copy()
    pressure = p0 * half[:, None] * np.sqrt(1.0 - s**2)[None, :]
    # p dA = p0 a b (1 - t^2) sqrt(1 - s^2) ds dt  ->  weight such that sum(weight * p) = N exactly
    weights = (a * b * half[:, None] * (wt[:, None] * ws[None, :])) / np.sqrt(1.0 - s**2)[None, :]

    wx = xi - phi * y
    wy = eta + phi * x
    speed = np.hypot(wx, wy)
    defined = speed > 0.0
    inv = np.where(defined, 1.0 / np.where(defined, speed, 1.0), 0.0)
    px = -mu * pressure * wx * inv
    py = -mu * pressure * wy * inv

    fx = float(np.sum(weights * px))
    fy = float(np.sum(weights * py))
    mz = float(np.sum(weights * (x * py - y * px)))
    return FullSlipResult(creep_force_x=fx, creep_force_y=fy, spin_moment=mz, adhesion_fraction=0.0,
                          x=x, y=y, px=px, py=py, pressure=pressure, weights=weights,
                          slip_direction_defined=defined, nx=nx, ny=ny)


def full_slip_tractions(pressure: np.ndarray, wx: np.ndarray, wy: np.ndarray,
                        mu: float) -> tuple[np.ndarray, np.ndarray]:
    """Full slip on an arbitrary pressure field (seed 000 Table 2's full-slip columns; spec srb-rolling §4.4):
    p_t = -mu p_n w / |w| element by element, with ``pressure`` p_n (Pa) and the rigid slip (``wx``, ``wy``)
    (any unit; only its direction matters) on the same grid, e.g. the CECT pressure and rigid slip of a
    converged roller equilibrium (:mod:`femcheck.cect.conformal`; resultants by
    :func:`femcheck.cect.conformal.resultants` with ``tractions=``). The elastic slip is neglected; no
    equilibrium is implied. Where w = 0 the traction is 0. Returns (px, py) (Pa)."""
    mu = _check_positive("friction.mu", mu)
    p = np.asarray(pressure, dtype=float)
    speed = np.hypot(wx, wy)
    inv = np.where(speed > 0, 1.0 / np.where(speed > 0, speed, 1.0), 0.0)
    return -mu * p * wx * inv, -mu * p * wy * inv
