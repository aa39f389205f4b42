"""The potential contact surface of a conformal rolling contact and its developed (x, s) grid: exact undeformed
distance by ray intersection, 3D rigid slip, local rolling speeds V(s) and the variable-dq factor kappa(s)
(seed 000 §3.2, eqs 5-7, 12-15 and 21; spec srb-rolling §2.3-2.5).

The surface is prismatic (seed 000 §3.2, Fig. 4): a circular profile of radius r_g and centre G (the groove
circle of the ring) extruded along the rolling direction e_x (perpendicular to the profile's plane). With m0 the
unit vector from G to the reference point s = 0 and tau0 the profile tangent there (+s sense):

    P0(x, s) = G + r_g (cos(s/r_g) m0 + sin(s/r_g) tau0) + x e_x          (m)
    n(s)     = -(cos(s/r_g) m0 + sin(s/r_g) tau0)     unit normal into the roller (towards G)
    t(s)     = -sin(s/r_g) m0 + cos(s/r_g) tau0        unit tangent, +s; dt/ds = n / r_g

e_x is the rolling direction of femcheck's exact theory: the material of both bodies flows through the grid along
-e_x (leading edge at +x). The triad (e_x, t, n) may be left-handed (both contacts of the bearing are): the
half-space influence coefficients do not care (isotropy), and everything here is written with explicit vectors.
The grid is developed: element size dx x ds, area dx ds (the metric correction along x is O(x^2/rho^2) < 1e-4).

Undeformed distance (spec §2.4): along the line P0 + t n, t_j and t_R are the intersections with the ring and
the roller (:func:`femcheck.geometry.revolution.ray_intersection`); h = t_R - t_j (> 0 open, < 0 overlap).
Exact for any pose; no quadratic lateral approximation (the s^4 terms change the contact width by ~1 %).

Rigid slip (eqs 12-15 in vector form, E2/E6): w = v_roller(P0) - v_ring(P0) (m/s), body 1 = roller, so
w_x = w.e_x, w_s = w.t(s); w.n is a diagnostic. Local rolling speeds (eqs 5-6): V_ring(s) = |v_ring(P0(0, s))|,
V_roller(s) = |v_roller(P0(0, s))| (|omega| times the distance from each axis), V(s) their weighted mean (equal
weights for identical materials; compliance weights 1/E*_B in general, E8), V_ref = V(s_ref) and
kappa(s) = V(s)/V_ref = dq(s)/dq0 (eq 21).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..bem.halfspace import Grid
from .revolution import CrownedBody, GroovedRing, ray_intersection, unit


@dataclass(frozen=True)
class ProfileSurface:
    """Prismatic potential contact surface (module docstring): ``centre`` G (m, 3), ``radius`` r_g (m), ``m0``
    unit vector from G to the reference point s = 0, ``tau0`` unit tangent at s = 0 (+s), ``ex`` unit rolling
    direction (material flows along -ex)."""

    centre: np.ndarray
    radius: float
    m0: np.ndarray
    tau0: np.ndarray
    ex: np.ndarray

    def _cs(self, s):
        th = np.asarray(s, dtype=float)[..., None] / self.radius
        return np.cos(th), np.sin(th)

    def point(self, s) -> np.ndarray:
        c, sn = self._cs(s)
        return self.centre + self.radius * (c * self.m0 + sn * self.tau0)

    def normal(self, s) -> np.ndarray:
        c, sn = self._cs(s)
        return -(c * self.m0 + sn * self.tau0)

    def tangent(self, s) -> np.ndarray:
        c, sn = self._cs(s)
        return -sn * self.m0 + c * self.tau0

    def frame(self, s) -> np.ndarray:
        """(..., 3, 3) local frames: rows e_x, t(s), n(s) (the (x, s, n) components of a vector are frame @ v)."""
        t, n = self.tangent(s), self.normal(s)
        return np.stack([np.broadcast_to(self.ex, t.shape), t, n], axis=-2)


def groove_profile(ring: GroovedRing, reference_point: np.ndarray, lateral: np.ndarray,
                   rolling: np.ndarray) -> ProfileSurface:
    """The ring's groove circle in the meridian plane through ``reference_point`` as the potential contact
    surface (spec §2.3: the profile between roller and groove is taken as the groove; the difference is
    O(delta/r) ~ 1e-4). s = 0 at the groove point on the line from the groove centre through
    ``reference_point``; s increases towards ``lateral`` (e.g. +e_y, the bearing mid-plane); ``rolling`` the
    rolling direction e_x (perpendicular to the meridian plane)."""
    ex = unit(rolling)
    radial = np.asarray(reference_point, dtype=float) - ring.origin
    radial = radial - (radial @ ring.axis) * ring.axis
    G = ring.groove_centre(radial)
    m0 = unit(np.asarray(reference_point, dtype=float) - G)
    tau0 = unit(np.cross(ex, m0))
    if tau0 @ np.asarray(lateral, dtype=float) < 0:
        tau0 = -tau0
    return ProfileSurface(G, ring.groove_radius, m0, tau0, ex)


@dataclass(frozen=True)
class DevelopedGrid:
    """Developed (x, s) grid on ``surface``: the planar ``grid`` (cells nx x ny of dx x ds, centred on 0) with
    x = grid.x along e_x and s = s_centre + grid.y along the profile. Arrays on the grid are (nx, ns)."""

    surface: ProfileSurface
    grid: Grid
    s_centre: float = 0.0

    @property
    def x(self) -> np.ndarray:
        return self.grid.x

    @property
    def s(self) -> np.ndarray:
        return self.s_centre + self.grid.y

    @cached_property
    def points(self) -> np.ndarray:
        """(nx, ns, 3) element centres P0(x, s) (m)."""
        return self.surface.point(self.s)[None, :, :] + self.x[:, None, None] * self.surface.ex

    @cached_property
    def normals(self) -> np.ndarray:
        return self.surface.normal(self.s)

    @cached_property
    def tangents(self) -> np.ndarray:
        return self.surface.tangent(self.s)


def developed_grid(surface: ProfileSurface, half_x: float, half_s: float, nx: int, ns: int,
                   s_centre: float = 0.0) -> DevelopedGrid:
    """nx x ns elements over x in [-half_x, half_x], s in s_centre + [-half_s, half_s] (m) (spec §2.3: half
    widths 1.35 a_H and 1.25 b_H about the pressure centre; keep dx, ds fixed while a Newton iteration runs)."""
    return DevelopedGrid(surface, Grid(int(nx), int(ns), 2.0 * half_x / nx, 2.0 * half_s / ns), float(s_centre))


def undeformed_distance(dg: DevelopedGrid, roller: CrownedBody, ring: GroovedRing) -> np.ndarray:
    """h(x, s) = t_R - t_j (m) along the surface normals (module docstring; spec §2.4)."""
    n = np.broadcast_to(dg.normals[None, :, :], dg.points.shape)
    return ray_intersection(roller, dg.points, n) - ray_intersection(ring, dg.points, n)


@dataclass(frozen=True)
class RigidSlip:
    """Rigid slip on the grid (m/s): ``wx``, ``ws``, ``wn`` (nx, ns) components along e_x, t(s), n(s) of
    w = v_roller - v_ring at P0(x, s)."""

    wx: np.ndarray
    ws: np.ndarray
    wn: np.ndarray


def rigid_slip(dg: DevelopedGrid, roller: CrownedBody, omega_roller: float, ring: GroovedRing,
               ring_rate: float) -> RigidSlip:
    """w = omega_R v x (P - C) - v_ring(P) at the element centres (spec §2.5; seed 000 eqs 12-15 in vector form).
    ``omega_roller`` (rad/s) about the roller axis; ``ring_rate`` the ring's angular velocity (rad/s) about its
    axis in the frame where the contact is stationary (omega_j - omega_m in the bearing), or a rail's speed
    (m/s). Linear in both rates."""
    P = dg.points
    w = roller.velocity(P, omega_roller) - ring.velocity(P, ring_rate)
    return RigidSlip(np.einsum("ijk,k->ij", w, dg.surface.ex), np.einsum("ijk,jk->ij", w, dg.tangents),
                     np.einsum("ijk,jk->ij", w, dg.normals))


@dataclass(frozen=True)
class RollingSpeeds:
    """Local rolling speeds along the profile (m/s, arrays over s): ``ring``, ``roller`` (eqs 5-6), ``mean``
    V(s); ``reference`` V_ref (m/s) and ``kappa`` = V(s)/V_ref (eq 21)."""

    ring: np.ndarray
    roller: np.ndarray
    mean: np.ndarray
    reference: float
    kappa: np.ndarray


def rolling_speeds(dg: DevelopedGrid, roller: CrownedBody, omega_roller: float, ring: GroovedRing,
                   ring_rate: float, s_ref: float | None = None,
                   compliance_weights: tuple[float, float] = (1.0, 1.0)) -> RollingSpeeds:
    """V_ring(s) = |v_ring(P0(0, s))|, V_roller(s) = |omega_roller| rho_v(P0(0, s)); V(s) the mean weighted by
    the compliances (1/E*_roller, 1/E*_ring) (E8; equal for identical materials); V_ref = V(s_ref) interpolated
    (default s_ref = the grid's centre), kappa = V/V_ref."""
    P = dg.surface.point(dg.s)
    v_ring = np.linalg.norm(ring.velocity(P, ring_rate), axis=-1)
    v_roller = abs(omega_roller) * roller.radius_at(P)
    w1, w2 = compliance_weights
    mean = (w1 * v_roller + w2 * v_ring) / (w1 + w2)
    s_ref = dg.s_centre if s_ref is None else s_ref
    ref = float(np.interp(s_ref, dg.s, mean))
    return RollingSpeeds(v_ring, v_roller, mean, ref, mean / ref)
