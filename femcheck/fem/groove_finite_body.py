"""Free rolling in a grooved ring with finite-body influence coefficients on the conformal exact theory's own
(fine) contact grids: the groove-rolling counterpart of :mod:`femcheck.fem.srb_finite_body`.

The conformal exact theory (:func:`femcheck.cect.groove_contact.solve_groove_cect`) works with the half-space
coefficients on the developed groove grid. The finite-body correction D of :mod:`femcheck.fem.compliance_split`
(the FE crowned body and ring segment of :mod:`femcheck.fem.groove_rolling` minus the half-space) is smooth, so it
enters as a fixed point on the tractions: with the tractions p_k of the last free-rolling solution, the next one
sees the given displacement u = D p_k (:func:`~femcheck.fem.compliance_split.coarse_field`, then the cubic spline
:func:`~femcheck.fem.compliance_split.field_at` at its cells and one cell downstream) as extra gap and rolling
difference (seed 000 eqs 17-21), until u changes by less than ``tol`` of its largest value.

Frames: the exact theory's groove frame (:mod:`femcheck.geometry.groove`: the contact at the origin, the groove
centre at (0, 0, r_g)) and the FE's (:mod:`femcheck.fem.groove_rolling`: the body's axis at the origin, the
groove centre at (0, 0, r_g - r0)) differ by a translation along Z; both developed grids have m0 = -Z,
tau0 = +Y, e_x = +X, so the developed (x, s) and the local traction components are the same in both.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..cect.groove_contact import GrooveSolution
from .compliance_split import Correction, coarse_field, field_at, fixed_point

NAME = "groove"


@dataclass
class GrooveFiniteBody:
    """The converged free rolling ``solution`` with the correction in place, the outer iterations and the relative
    change of the correction's displacement per iteration (``history``), the time (s)."""

    solution: GrooveSolution
    iterations: int
    history: list = field(default_factory=list)
    time_s: float = 0.0


def check_frames(corr: Correction, developed) -> None:
    """The correction grid and the exact theory's developed grid must share m0, tau0, e_x and the profile
    radius (module docstring); raises ValueError."""
    c, sf = corr.grids[NAME], developed.surface
    if abs(c.radius - sf.radius) > 1e-12 * c.radius or any(
            np.linalg.norm(np.asarray(a, dtype=float) - b) > 1e-12 for a, b in
            ((sf.m0, c.m0), (sf.tau0, c.tau0), (sf.ex, c.ex))):
        raise ValueError("the correction grid's profile frame differs from the exact theory's developed grid")


def displacement_of(corr: Correction, coarse: np.ndarray):
    """The ``extra_displacement`` hook of :func:`femcheck.cect.groove_contact.solve_groove_cect`: the coarse
    correction field at the developed grid's cells and one cell downstream."""

    def extra(dg):
        x = np.asarray(dg.x, dtype=float)
        both = field_at(corr, coarse, NAME, np.concatenate([x, x + dg.grid.dx]), dg.s)
        return both[:, :x.size], both[:, x.size:]

    return extra


def tractions(corr: Correction, sol: GrooveSolution) -> dict:
    """The solution's tractions on the correction's profile: {name: (grid, (p_x, p_s, p_n))}."""
    dg, r = sol.grid, sol.result
    return {NAME: (corr.grids[NAME].with_cells(dg.x, dg.s), np.stack([r.px, r.ps, r.pressure]))}


def finite_body_rolling(solve, corr: Correction, start: GrooveSolution | None = None, tol: float = 1e-4,
                        max_outer: int = 20, progress=None) -> GrooveFiniteBody:
    """Free rolling with the finite-body correction (module docstring). ``solve(extra_displacement, omega0)`` is
    the exact theory's free rolling (``solve_groove_cect`` with everything else bound); ``start`` its half-space
    solution (solved if None). Raises ConvergenceError when the fixed point misses ``tol`` in ``max_outer``
    iterations."""
    t0 = time.perf_counter()
    sol = start if start is not None else solve(None, None)
    check_frames(corr, sol.grid)
    fp = fixed_point(lambda u, s: solve(displacement_of(corr, u[NAME]), s.stats["body_angular_velocity"]),
                     lambda s: {NAME: coarse_field(corr, tractions(corr, s))[NAME]}, sol, tol, max_outer,
                     "finite-body free rolling", progress)
    return GrooveFiniteBody(fp.solution, fp.iterations, fp.history, time.perf_counter() - t0)
