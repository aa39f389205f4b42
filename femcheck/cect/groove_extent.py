"""Extent of the frictionless conformal normal contact of a crowned body in a groove
(:mod:`femcheck.geometry.groove`): the applicability measure of the groove-rolling scene.

Why a solve and not Hertz: Hertz's elliptic estimate (quadratic gap x^2/(2 Rx) + y^2/(2 Ry), constant Rx) grows
as N^(1/3) without bound, while the conformal patch is bounded by the groove: the exact gap between crown and
groove measured along the groove's normals and the body's longitudinal radius falling away from the apex. Measured
for a ball of radius 100.3 mm in a groove 1.002 times wider on a straight rail (docs/notes/groove-deep.md): Hertz's
half-angle b/r_g is above the solved one by 1.9 % at 20 deg, 5.3 % at 30 deg, 9.8 % at 40 deg, 13.8 % at 45 deg and
18.2 % at 50 deg (groove/crown 1.05: 2.5, 7.9, 16.4, 24.2, 36.2 %), and its longitudinal semi-axis a is 3-16 %
short of the solved patch's (20 % at 1.05).

The solve is the normal problem of :func:`femcheck.cect.groove_contact.solve_groove_cect` without the tangential
one: the same developed (x, s) grid on the groove circle (+-domain Hertz semi-axes, enlarged x 1.3 per touched
side, up to 5 times), the exact undeformed distance along the groove's normals, load control on the pressure
resultant along the nominal normal Z,

    sum_IJ p_J (n_J . Z) dA = N,   h_I(delta) + u_n,I - 0 >= 0,   p_I >= 0,   complementary,

(Polonsky-Keer CG with the rigid approach delta found by a secant) and the lateral edges of
:func:`femcheck.cect.groove_contact.lateral_extent` (power-law edges of the lateral load distribution, the
estimator of every model of the scene). About 0.02 s on 21 x 41 cells; the half-angle on 21 x 41 is within
0.3 % of the free-rolling cect's on 41 x 81 between 10 and 50 deg.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import EllipticContact, elliptic_contact
from ..geometry.conformal_surface import developed_grid, undeformed_distance
from ..geometry.groove import Y, Z, GrooveRolling
from .conformal import GridTooSmall, solve_normal_conformal
from .groove_contact import ENLARGE, MAX_ENLARGEMENTS, GridSpec, lateral_extent
from .influence import CombinedConstants

CHECK_GRID = GridSpec(21, 41)     # cells of the applicability solve (domain from the scene)


@dataclass(frozen=True)
class NormalExtent:
    """The frictionless conformal normal contact's extent: ``half_angle`` (rad, half the lateral extent along the
    groove over r_g), ``half_length_s`` (m, along the groove), ``half_length_x`` (m, the power-law edges of the
    longitudinal load distribution sum_s p(x, s)), ``axial_half_width`` (m, the largest |Y| of the two lateral
    edges on the groove circle: the patch's extent along the body's axis), ``p_max`` (Pa), ``approach`` (m),
    ``hertz`` (the elliptic estimate the grid is sized from), ``cells`` (nx, ns), ``time_s``."""

    half_angle: float
    half_length_s: float
    half_length_x: float
    axial_half_width: float
    p_max: float
    approach: float
    hertz: EllipticContact
    cells: tuple[int, int]
    time_s: float


def _touched(contact: np.ndarray) -> list[str]:
    """The grid sides ("x-", "x+", "s-", "s+") that a contact mask reaches."""
    sides = {"x-": contact[0, :], "x+": contact[-1, :], "s-": contact[:, 0], "s+": contact[:, -1]}
    return [name for name, cells in sides.items() if cells.any()]


def normal_extent(geom: GrooveRolling, load: float, constants: CombinedConstants, spec: GridSpec = CHECK_GRID,
                  influence: str = "halfspace") -> NormalExtent:
    """The frictionless conformal normal contact of ``load`` (N, along Z) and its extent (module docstring).
    Raises ConvergenceError when the grid reaches where the crowned body's profile ends (no ray from the groove
    meets the body: a barrel's crown closes on its axis at acos(1 - r/R) from the apex) and GridTooSmall when the
    contact still reaches the grid's edge after the enlargements."""
    t0 = time.perf_counter()
    rx, ry = geom.hertz_radii
    h = elliptic_contact(load, rx, ry, constants.contact_modulus)
    dom = [spec.domain_x, spec.domain_s]
    ring, surface = geom.ring(), geom.surface()
    for enlargement in range(MAX_ENLARGEMENTS + 1):
        dg = developed_grid(surface, dom[0] * h.semi_axis_x, dom[1] * h.semi_axis_y, spec.cells_x, spec.cells_s)
        wts = np.broadcast_to(dg.normals @ Z, (spec.cells_x, spec.cells_s))
        normal = solve_normal_conformal(dg.grid, lambda d, dg=dg: undeformed_distance(dg, geom.body(d), ring),
                                        constants, load=load, load_weights=wts, influence=influence,
                                        radius=surface.radius, approach0=h.approach)
        touched = _touched(normal.pressure > 0)
        if not touched:
            break
        if enlargement == MAX_ENLARGEMENTS:
            raise GridTooSmall(touched)
        if any(e.startswith("x") for e in touched):
            dom[0] *= ENLARGE
        if any(e.startswith("s") for e in touched):
            dom[1] *= ENLARGE
    left, right = lateral_extent(dg.s, normal.pressure)
    back, front = lateral_extent(dg.x, normal.pressure.T)
    axial = float(np.abs(surface.point(np.array([left, right])) @ Y).max())
    return NormalExtent(0.5 * (right - left) / surface.radius, 0.5 * (right - left), 0.5 * (front - back), axial,
                        float(normal.pressure.max()), float(normal.approach), h, (spec.cells_x, spec.cells_s),
                        time.perf_counter() - t0)
