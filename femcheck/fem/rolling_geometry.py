"""Exact gap and rigid slip of a crowned body of revolution in a grooved ring on a developed grid, for the FE
rolling reference's own models (groove-rolling) and tests (spec srb-rolling §2.2, §2.4-2.5). The bearing's
equilibrium computes these with its own pose geometry and hands them to :func:`femcheck.fem.srb_rolling`.

Implicit surfaces (m; F < 0 on the roller side), all in one Cartesian frame:
    crowned body:  F_R(P) = hypot(rho_v + R - r, a_v) - R,   a_v = (P - C).v, rho_v = |P - C - a_v v|
    grooved ring:  F_j(P) = hypot(rho - rho_G, a - a_G) - r_g, a = (P - O).e, rho = |P - O - a e|
    straight rail: F_j(P) = |(P - G) - ((P - G).e_x) e_x| - r_g  (the groove circle extruded along e_x)
(r the rolling radius at the crown apex, R the crown radius, v the roller axis through C; e the ring axis
through O, (a_G, rho_G) the groove centre in the ring's meridian half-plane). Gap (spec §2.4): along the line
P0 + t n(s) the two surfaces are found by Newton in t from t = 0 and h = t_R - t_j (> 0 open).

Rigid slip (spec §2.5): w = v_roller(P0) - v_ring(P0) with v_roller = omega_R v x (P - C) and v_ring =
Omega e x (P - O) (a rail: V_rail e_x), components along e_x and t(s). Local rolling speeds V_roller(s) =
|omega_R| rho_v, V_ring(s) = |v_ring| at P0(0, s); V(s) their mean (identical materials), V_ref = V(s_ref),
kappa = V/V_ref (seed 000 eqs 5-6, 21).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError
from .contact_grid import ContactGrid


@dataclass(frozen=True)
class Crowned:
    centre: np.ndarray
    axis: np.ndarray
    rolling_radius: float
    crown_radius: float

    def implicit(self, P: np.ndarray) -> np.ndarray:
        d = P - self.centre
        a = d @ self.axis
        rho = np.linalg.norm(d - a[..., None] * self.axis, axis=-1)
        return np.hypot(rho + self.crown_radius - self.rolling_radius, a) - self.crown_radius

    def radius_at(self, P: np.ndarray) -> np.ndarray:
        d = P - self.centre
        a = d @ self.axis
        return np.linalg.norm(d - a[..., None] * self.axis, axis=-1)

    def velocity(self, P: np.ndarray, omega: float) -> np.ndarray:
        return omega * np.cross(self.axis, P - self.centre)


@dataclass(frozen=True)
class Grooved:
    """Ring about ``axis`` through ``origin`` with the groove circle (centre ``groove_centre``, radius
    ``groove_radius``); ``axis`` None: a straight rail along ``rail_direction``. ``reference``: a point of the
    contact; the groove centre's radial coordinate rho_G is then signed, negative when the centre lies across the
    axis from the contact's meridian half-plane (a concave ring whose radius is below the groove radius, e.g.
    ring radius 102.4 mm with a 103 mm groove: the groove circles of the meridian half-planes cross the axis).
    Without it rho_G = |G - axis| (the groove centre on the contact's side, or on the axis)."""

    groove_centre: np.ndarray
    groove_radius: float
    origin: np.ndarray | None = None
    axis: np.ndarray | None = None
    rail_direction: np.ndarray | None = None
    reference: np.ndarray | None = None

    def implicit(self, P: np.ndarray) -> np.ndarray:
        if self.axis is None:
            d = P - self.groove_centre
            d = d - (d @ self.rail_direction)[..., None] * self.rail_direction
            return np.linalg.norm(d, axis=-1) - self.groove_radius
        gd = self.groove_centre - self.origin
        aG = gd @ self.axis
        rG = np.linalg.norm(gd - aG * self.axis)
        if self.reference is not None:
            rd = self.reference - self.origin
            rG = rG if (gd - aG * self.axis) @ (rd - (rd @ self.axis) * self.axis) >= 0 else -rG
        d = P - self.origin
        a = d @ self.axis
        rho = np.linalg.norm(d - a[..., None] * self.axis, axis=-1)
        return np.hypot(rho - rG, a - aG) - self.groove_radius

    def velocity(self, P: np.ndarray, rate: float) -> np.ndarray:
        """rate: angular velocity about the axis (rad/s), or the rail's speed along rail_direction (m/s)."""
        if self.axis is None:
            return np.broadcast_to(rate * self.rail_direction, np.shape(P)).copy()
        return rate * np.cross(self.axis, P - self.origin)


def ray_intersection(body, P0: np.ndarray, n: np.ndarray, iterations: int = 20, tol: float = 1e-14) -> np.ndarray:
    """t with F(P0 + t n) = 0 (Newton from t = 0, derivative by central differences of the unit-gradient
    implicit function)."""
    t = np.zeros(P0.shape[:-1])
    eps = 1e-7
    for _ in range(iterations):
        f = body.implicit(P0 + t[..., None] * n)
        df = (body.implicit(P0 + (t + eps)[..., None] * n) - body.implicit(P0 + (t - eps)[..., None] * n)) / (2 * eps)
        dt = -f / df
        t = t + dt
        if np.abs(dt).max() < tol:
            return t
    raise ConvergenceError("ray intersection (exact gap)", iterations, float(np.abs(dt).max()), tol)


def gap(grid: ContactGrid, roller: Crowned, ring: Grooved) -> np.ndarray:
    """h(x, s) = t_R - t_j (m) on the grid (nx, ns)."""
    P = grid.cell_centres()
    n = np.broadcast_to(grid.normal(grid.s)[None], P.shape)
    return ray_intersection(roller, P, n) - ray_intersection(ring, P, n)


@dataclass
class Kinematics:
    """``slip`` (2, nx, ns) rigid slip (m/s) along e_x, t(s); ``speed`` V_ref (m/s); ``kappa`` (ns,);
    ``roller_speed``, ``ring_speed`` (ns,) local rolling speeds (m/s)."""

    slip: np.ndarray
    speed: float
    kappa: np.ndarray
    roller_speed: np.ndarray
    ring_speed: np.ndarray


def kinematics(grid: ContactGrid, roller: Crowned, omega: float, ring: Grooved, rate: float,
               s_ref: float = 0.0) -> Kinematics:
    P = grid.cell_centres()
    w = roller.velocity(P, omega) - ring.velocity(P, rate)
    t = grid.tangent(grid.s)
    slip = np.stack([w @ grid.ex, np.einsum("ijk,jk->ij", w, t)])
    P0 = grid.profile_point(grid.s)
    v1 = abs(omega) * roller.radius_at(P0)
    v2 = np.linalg.norm(ring.velocity(P0, rate), axis=-1)
    mean = 0.5 * (v1 + v2)
    ref = float(np.interp(s_ref, grid.s, mean))
    return Kinematics(slip, ref, mean / ref, v1, v2)
