"""A crowned body of revolution rolling in a grooved ring or on a straight grooved rail: the one-contact core of
the spherical roller bearing (scene kind ``groove_rolling``).

Frame (m): the nominal contact point at the origin, X the rolling direction (the material of both bodies flows
through the contact along -X), Y lateral (both axes of revolution are parallel to Y: no contact angle), Z the
nominal contact normal, from the ring into the crowned body. The triad (X, Y, Z) is right-handed.

- Crowned body (body 1): axis Y through C = (0, 0, r), apex radius r (``rolling_radius``), crown radius R; a
  barrel for R > r, wheel-like for R < r (:class:`femcheck.geometry.revolution.CrownedBody`).
- Ring (body 2) with longitudinal curvature k (``ring_curvature``, 1/m): k > 0 a convex ring (the body rolls on
  its outside, like an inner raceway; axis at Z = -1/k), k < 0 a concave ring (the body rolls inside it, like an
  outer raceway; axis at Z = +1/|k|), k = 0 a straight rail along X. Its groove is the circle of radius r_g
  (``groove_radius`` > R) centred at G = (0, 0, r_g) in the plane X = 0.
- Motion: the ring's surface speed at the contact is V (``kinematics.speed``): a ring turns at
  Omega = -V k about its axis, a rail translates at -V along X; the body turns at omega = V_body / r about its
  axis (omega > 0 moves its surface at the contact along -X).
- Hertz radii at the nominal point: 1/Rx = 1/r + k, 1/Ry = 1/R - 1/r_g.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .conformal_surface import ProfileSurface, groove_profile
from .revolution import CrownedBody, GroovedRing

X = np.array([1.0, 0.0, 0.0])
Y = np.array([0.0, 1.0, 0.0])
Z = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class GrooveRolling:
    """Geometry of the single contact (module docstring); lengths m, curvature 1/m."""

    rolling_radius: float
    crown_radius: float
    groove_radius: float
    ring_curvature: float

    @property
    def straight(self) -> bool:
        return self.ring_curvature == 0.0

    def body(self, approach: float = 0.0) -> CrownedBody:
        """The crowned body moved towards the ring by ``approach`` (m) along -Z."""
        return CrownedBody(np.array([0.0, 0.0, self.rolling_radius - approach]), Y, self.rolling_radius,
                           self.crown_radius)

    def ring(self) -> GroovedRing:
        rg, k = self.groove_radius, self.ring_curvature
        if k == 0.0:
            return GroovedRing(np.zeros(3), Y, 0.0, rg, rg, rail_height=Z)
        rho = 1.0 / abs(k)
        if k > 0:                # axis below the contact; the groove centre lies rho + r_g from it, outwards
            return GroovedRing(np.array([0.0, 0.0, -rho]), Y, 0.0, rho + rg, rg)
        # concave: axis above; the groove centre (0, 0, r_g) lies rho - r_g from the axis on the contact's side
        # (negative when the groove circle crosses the axis: the meridian coordinate is then signed)
        return GroovedRing(np.array([0.0, 0.0, rho]), Y, 0.0, rho - rg, rg)

    def surface(self) -> ProfileSurface:
        """The groove circle as the potential contact surface: s = 0 at the origin, +s along +Y, n(0) = +Z."""
        return groove_profile(self.ring(), np.zeros(3), Y, X)

    def ring_rate(self, speed: float) -> float:
        """Ring angular velocity (rad/s) or rail speed (m/s) for the surface speed ``speed`` V (m/s)."""
        return -speed if self.straight else -speed * self.ring_curvature

    @property
    def hertz_radii(self) -> tuple[float, float]:
        """(Rx, Ry) (m) at the nominal point."""
        return (1.0 / (1.0 / self.rolling_radius + self.ring_curvature),
                1.0 / (1.0 / self.crown_radius - 1.0 / self.groove_radius))

    @property
    def crown_half_extent(self) -> float:
        """Half the axial extent of the crown arc (m): where the barrel's profile closes on its axis
        (sqrt(R^2 - (R - r)^2)) or, for a wheel-like crown (R < r), R."""
        R, r = self.crown_radius, self.rolling_radius
        return float(np.sqrt(R ** 2 - (R - r) ** 2)) if R > r else R
