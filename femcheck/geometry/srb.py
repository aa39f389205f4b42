"""Local contact geometry of a spherical-roller-bearing roller on its raceways (seed 000, Table 1 and eq 1).

The pitch radius is r_m = (r_E - D/2) cos(alpha): seed 000 prints "(r_E D/2)", the minus sign is lost; with it
the outer rolling radius r_m + (D/2) cos(alpha) equals r_E cos(alpha), as the outer raceway is a sphere of radius
r_E. Rolling radii r_roll = r_m -/+ (D/2) cos(alpha) (eq 1); the rings' longitudinal curvature radii are
r_roll / cos(alpha) (seed 000 §2). Relative radii of curvature, x rolling, y along the roller axis:

    inner:  1/Rx = 2/D + cos(alpha)/r_roll,I     1/Ry = 1/R - 1/r_I      (convex ring, concave groove)
    outer:  1/Rx = 2/D - cos(alpha)/r_roll,E     1/Ry = 1/R - 1/r_E      (concave ring and groove)

Lengths in m, angles in rad. Kept apart from the problem module so that the stored FE references depend on this
geometry and not on the problem module's other code.
"""
from __future__ import annotations

from typing import Any

import numpy as np


def rolling_radii(params: dict[str, Any]) -> dict[str, float]:
    """Rolling radii (m) of the inner and outer contact points about the bearing axis (seed 000 eq 1)."""
    D, alpha = params["geometry.roller_diameter"], params["geometry.contact_angle"]
    r_m = (params["geometry.groove_radius_outer"] - 0.5 * D) * np.cos(alpha)
    return {"inner": r_m - 0.5 * D * np.cos(alpha), "outer": r_m + 0.5 * D * np.cos(alpha)}


def radii(params: dict[str, Any]) -> dict[str, tuple[float, float]]:
    """(Rx, Ry) in m of the inner and outer contact (see the module docstring)."""
    D, R, alpha = params["geometry.roller_diameter"], params["geometry.crown_radius"], params["geometry.contact_angle"]
    r_i, r_e = params["geometry.groove_radius_inner"], params["geometry.groove_radius_outer"]
    roll = rolling_radii(params)
    return {"inner": (1.0 / (2.0 / D + np.cos(alpha) / roll["inner"]), 1.0 / (1.0 / R - 1.0 / r_i)),
            "outer": (1.0 / (2.0 / D - np.cos(alpha) / roll["outer"]), 1.0 / (1.0 / R - 1.0 / r_e))}
