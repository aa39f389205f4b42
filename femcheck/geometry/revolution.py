"""Bodies of revolution for conformal rolling contact, as exact implicit surfaces (spec srb-rolling §2.2):
a crowned roller or wheel, a grooved ring, and a straight grooved rail.

Every body is described in its meridian half-plane by a circle (the crown arc, the groove), so the surface is
the zero set of the signed distance to that circle in the meridian plane,

    roller / wheel:  F_R(P) = sqrt((rho_v + R - r)^2 + a_v^2) - R,     a_v = (P - C).v, rho_v = |P - C - a_v v|
    ring:            F_j(P) = sqrt((rho - rho_G)^2 + (a - a_G)^2) - r_g, a = (P - O).Y, rho = |P - O - a Y|
    straight rail:   as the ring with rho = (P - O).e_h, the height above the rail's axis plane

(m). These have the same zero set as the quadratic forms of the spec ((rho_v + R - r)^2 + a_v^2 - R^2 ...) but a
unit gradient, which keeps the ray intersection well conditioned. F < 0 on the roller side for both: inside
the crown circle (the roller material) and inside the groove circle (outside the ring material). ``r`` is the
rolling radius at the crown apex (D/2 for a roller); R > r is a barrel (the crown-arc centre lies at R - r on the
opposite side of the axis), R < r a wheel-like profile (centre on the same side): the same formula holds.

:func:`ray_intersection` finds t with F(P0 + t n) = 0 by Newton from t = 0 (spec §2.4), vectorised over grids.
Lengths m, angles rad, angular velocities rad/s, velocities m/s; points and directions are 3-vectors in any
common Cartesian frame (the bearing frame B for the spherical roller bearing).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError


def unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def _dot(P: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.einsum("...k,k->...", P, v)


@dataclass(frozen=True)
class CrownedBody:
    """Roller or wheel: body of revolution about ``axis`` (unit v) through ``centre`` C with a circular crown of
    radius ``crown_radius`` R whose apex lies at ``rolling_radius`` r from the axis (D/2 of a roller).
    Implicit surface F_R of the module docstring."""

    centre: np.ndarray
    axis: np.ndarray
    rolling_radius: float
    crown_radius: float

    def _local(self, P: np.ndarray):
        d = np.asarray(P, dtype=float) - self.centre
        a = _dot(d, self.axis)
        radial = d - a[..., None] * self.axis
        rho = np.linalg.norm(radial, axis=-1)
        return a, rho, radial

    def implicit(self, P: np.ndarray) -> np.ndarray:
        a, rho, _ = self._local(P)
        return np.hypot(rho + self.crown_radius - self.rolling_radius, a) - self.crown_radius

    def gradient(self, P: np.ndarray) -> np.ndarray:
        a, rho, radial = self._local(P)
        e_rho = radial / np.where(rho > 0, rho, 1.0)[..., None]
        c = rho + self.crown_radius - self.rolling_radius
        d = np.hypot(c, a)[..., None]
        return (c[..., None] * e_rho + a[..., None] * self.axis) / d

    def radius_at(self, P: np.ndarray) -> np.ndarray:
        """Distance of P from the axis (m): the local rolling radius of a surface point."""
        return self._local(P)[1]

    def axial_coordinate(self, P: np.ndarray) -> np.ndarray:
        return self._local(P)[0]

    def velocity(self, P: np.ndarray, omega: float) -> np.ndarray:
        """Velocity (m/s) of the body's material at P when it spins at ``omega`` (rad/s) about its axis."""
        return omega * np.cross(self.axis, np.asarray(P, dtype=float) - self.centre)

    def translated(self, d: np.ndarray) -> "CrownedBody":
        return CrownedBody(self.centre + np.asarray(d, dtype=float), self.axis, self.rolling_radius,
                           self.crown_radius)


@dataclass(frozen=True)
class GroovedRing:
    """Ring with a circular groove: body of revolution about ``axis`` (unit, Y of the bearing) through ``origin``
    O; its meridian groove circle has centre (``groove_axial`` a_G, ``groove_radial`` rho_G) and radius
    ``groove_radius`` r_g. ``rail_height`` (a unit vector e_h, default None) makes it a straight grooved rail
    along axis x e_h: rho is then the height (P - O).e_h above the rail's axis plane (the limit rho_G -> inf).
    Implicit surface F_j of the module docstring; F < 0 inside the groove circle (the roller side)."""

    origin: np.ndarray
    axis: np.ndarray
    groove_axial: float
    groove_radial: float
    groove_radius: float
    rail_height: np.ndarray | None = None

    @property
    def straight(self) -> bool:
        return self.rail_height is not None

    def _local(self, P: np.ndarray):
        d = np.asarray(P, dtype=float) - self.origin
        a = _dot(d, self.axis)
        if self.straight:
            rho = _dot(d, self.rail_height)
            e_rho = np.broadcast_to(self.rail_height, d.shape)
        else:
            radial = d - a[..., None] * self.axis
            rho = np.linalg.norm(radial, axis=-1)
            e_rho = radial / np.where(rho > 0, rho, 1.0)[..., None]
        return a, rho, e_rho

    def implicit(self, P: np.ndarray) -> np.ndarray:
        a, rho, _ = self._local(P)
        return np.hypot(rho - self.groove_radial, a - self.groove_axial) - self.groove_radius

    def gradient(self, P: np.ndarray) -> np.ndarray:
        a, rho, e_rho = self._local(P)
        c, e = rho - self.groove_radial, a - self.groove_axial
        d = np.hypot(c, e)[..., None]
        return (c[..., None] * e_rho + e[..., None] * self.axis) / d

    def radius_at(self, P: np.ndarray) -> np.ndarray:
        """Distance of P from the ring axis (m); +inf for a straight rail."""
        a, rho, _ = self._local(P)
        return np.full(np.shape(rho), np.inf) if self.straight else rho

    def velocity(self, P: np.ndarray, rate: float) -> np.ndarray:
        """Velocity (m/s) of the ring's material at P: a ring turning at ``rate`` (rad/s) about its axis, or a
        straight rail translating at ``rate`` (m/s) along axis x e_h (its length direction)."""
        P = np.asarray(P, dtype=float)
        if self.straight:
            return np.broadcast_to(rate * np.cross(self.axis, self.rail_height), P.shape).copy()
        return rate * np.cross(self.axis, P - self.origin)

    def translated(self, d: np.ndarray) -> "GroovedRing":
        return GroovedRing(self.origin + np.asarray(d, dtype=float), self.axis, self.groove_axial,
                           self.groove_radial, self.groove_radius, self.rail_height)

    def groove_centre(self, direction: np.ndarray) -> np.ndarray:
        """The 3D centre of the meridian groove circle in the meridian half-plane containing the unit radial
        ``direction`` (perpendicular to the axis); for a rail the direction is ignored (e_h is used)."""
        e = self.rail_height if self.straight else unit(direction)
        return self.origin + self.groove_axial * self.axis + self.groove_radial * e


def ray_intersection(body, P0: np.ndarray, n: np.ndarray, iterations: int = 12, tol: float = 1e-14) -> np.ndarray:
    """Parameter t (m) of the intersection of the lines P0 + t n with ``body``'s surface F = 0 (spec §2.4): Newton
    from t = 0, t <- t - F / (grad F . n). ``P0`` (..., 3) points, ``n`` (..., 3) unit directions (broadcast).
    The signed-distance F makes each step exact to first order in the distance; 2-4 steps reach 1e-14 m on the
    bearing's grids. Raises ConvergenceError when a line misses the surface (grad F . n -> 0) or Newton stalls."""
    P0 = np.asarray(P0, dtype=float)
    n = np.broadcast_to(np.asarray(n, dtype=float), P0.shape)
    t = np.zeros(P0.shape[:-1])
    step = np.inf
    for it in range(1, iterations + 1):
        P = P0 + t[..., None] * n
        slope = np.einsum("...k,...k->...", body.gradient(P), n)
        if np.any(np.abs(slope) < 1e-6):
            raise ConvergenceError("ray intersection", it, float(np.abs(body.implicit(P)).max()), tol,
                                   "a line runs tangent to the surface (it misses the body)")
        dt = body.implicit(P) / slope
        t = t - dt
        step = float(np.abs(dt).max())
        if step < tol:
            return t
    raise ConvergenceError("ray intersection", iterations, step, tol)
