"""Cattaneo-Mindlin partial slip of a sphere on a flat under a normal load P and a monotonically applied
tangential force Q < mu P (Johnson 1985 §7.2, eqs 7.39-7.42; Mindlin 1949).

Hertz: a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2). The stick zone is a central circle of radius
  c = a (1 - Q/(mu P))^(1/3)                                                  (Johnson eq. 7.40)
with the tangential traction (in the direction of Q)
  q(r) = mu p0 sqrt(1 - r^2/a^2)  -  (c/a) mu p0 sqrt(1 - r^2/c^2) [r < c]    (Johnson eq. 7.39)
and the rigid tangential shift (compliance of both bodies; Johnson eq. 7.42 for one pair of bodies)
  delta = 3 mu P / (16 a) [(2 - nu1)/G1 + (2 - nu2)/G2] [1 - (1 - Q/(mu P))^(2/3)].
With Kalker's combined constants (2 - nu1)/G1 + (2 - nu2)/G2 = 2 (2 - nu)/G. Like Mindlin, the solution
neglects the coupling of normal and tangential problems for dissimilar bodies (K != 0) and the lateral traction
(of order nu/(2 - nu)) that the exact theory carries; both are small.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .hertz import point_contact


@dataclass(frozen=True)
class MindlinContact:
    """Cattaneo-Mindlin solution: ``contact_radius`` a (m), ``stick_radius`` c (m), ``shift`` delta (m),
    ``p_max`` p0 (Pa), ``mu``, ``normal_load`` P (N), ``tangential_load`` Q (N)."""

    normal_load: float
    tangential_load: float
    mu: float
    contact_radius: float
    stick_radius: float
    shift: float
    p_max: float

    def traction(self, r: np.ndarray) -> np.ndarray:
        """Tangential traction q(r) (Pa) in the direction of Q (Johnson eq. 7.39)."""
        r = np.asarray(r, dtype=float)
        a, c, mp0 = self.contact_radius, self.stick_radius, self.mu * self.p_max
        q = mp0 * np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
        if c > 0:
            q = q - (c / a) * mp0 * np.sqrt(np.clip(1.0 - (r / c) ** 2, 0.0, None))
        return q


def mindlin(normal_load: float, tangential_load: float, radius: float, mu: float, e_star: float,
            compliance_sum: float) -> MindlinContact:
    """Cattaneo-Mindlin for normal load P (N), tangential load Q (N, 0 <= Q < mu P), relative radius R (m),
    friction coefficient mu, contact modulus E* (Pa) and ``compliance_sum`` = (2 - nu1)/G1 + (2 - nu2)/G2 (1/Pa).
    """
    if normal_load <= 0:
        raise InputError("load.normal", f"{normal_load:g} N; allowed: > 0")
    if mu <= 0:
        raise InputError("friction.mu", f"{mu:g}; allowed: > 0")
    if not 0.0 <= tangential_load < mu * normal_load:
        raise InputError("load.tangential", f"{tangential_load:g} N; allowed: [0, mu P) = [0, "
                         f"{mu * normal_load:g}) N (at mu P the contact slides)")
    h = point_contact(normal_load, radius, e_star)
    a = h.semi_axis_x
    ratio = 1.0 - tangential_load / (mu * normal_load)
    c = a * ratio ** (1.0 / 3.0)
    delta = 3.0 * mu * normal_load / (16.0 * a) * compliance_sum * (1.0 - ratio ** (2.0 / 3.0))
    return MindlinContact(normal_load, tangential_load, mu, float(a), float(c), float(delta), float(h.p_max))
