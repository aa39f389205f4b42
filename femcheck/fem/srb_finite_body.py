"""The roller equilibrium of seed 000's spherical roller bearing with finite-body influence coefficients on the
CECT's own (fine) contact grids: Kalker's exact theory with the half-space coefficients plus the FE finite-body
correction of :mod:`femcheck.fem.compliance_split` (spec srb-rolling §8.2; the split that frees the contact grid
from the FE mesh).

The CECT contact solvers work with translation-invariant half-space operators (DC-FFT). The correction D (the
finite bodies minus the half-space, the roller's inner-outer cross influence included) is smooth, so it enters
as a fixed point on the tractions: with the tractions p_k of the last equilibrium, every contact solve of the next
one sees the extra gap and slip

    g += u_n,   s += kappa(s) [(u_t - u_t') / dx]          (seed 000 eqs 17-21, u' one cell downstream)

with u = D p_k evaluated on its current grid (:func:`femcheck.fem.compliance_split.coarse_field` /
:func:`field_at`), and the whole equilibrium (pose, speeds, approach) is solved again, warm-started, until u
changes by less than ``tol`` of its largest value. The CECT grids coincide with the FE grids in the FE's roller
frame (same groove circles, the same developed x and s, identical local frames; the inner grid moved with its
ring by the approach), so the CECT's (x, s) are the correction's coordinates.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..cect.roller_equilibrium import EquilibriumResult, equilibrium, require_converged
from ..cect.roller_state import Numerics, RollerProblem
from ..geometry import srb_bearing as sb
from .compliance_split import Correction, coarse_field, field_at, fixed_point


@dataclass
class FiniteBodyResult:
    """The converged equilibrium ``result`` with the correction in place, the half-space start ``start``, the
    outer iterations ``iterations`` with the relative change of the correction's displacement per iteration
    (``history``), and the time (s)."""

    result: EquilibriumResult
    start: EquilibriumResult
    iterations: int
    history: list = field(default_factory=list)
    time_s: float = 0.0


def _sources(corr: Correction, r: EquilibriumResult) -> dict[str, tuple[Any, np.ndarray]]:
    out = {}
    for c in sb.CONTACTS:
        st = r.state.contacts[c]
        g = st.inputs.grid
        res = st.result
        out[c] = (corr.grids[c].with_cells(g.x, g.s), np.stack([res.px, res.ps, res.pressure]))
    return out


def offsets_of(corr: Correction, coarse: dict[str, np.ndarray]):
    """The ``offsets`` hook of :class:`femcheck.cect.roller_state.RollerProblem` for the correction's
    displacement ``coarse`` (:func:`femcheck.fem.compliance_split.coarse_field`)."""

    def offsets(c: str, ci) -> tuple[np.ndarray, np.ndarray]:
        g = ci.grid
        dx = float(g.x[1] - g.x[0])
        # the cells and the stations one cell downstream in one spline pass
        both = field_at(corr, coarse[c], c, np.concatenate([g.x, g.x + dx]), g.s)
        u, u_down = both[:, :g.x.size], both[:, g.x.size:]
        kappa = np.asarray(ci.speeds.kappa, dtype=float)
        kappa = kappa[None, :] if kappa.ndim == 1 else kappa
        slip = ci.speeds.reference * kappa[None] * (u[:2] - u_down[:2]) / dx
        return u[2], slip

    return offsets


def finite_body_equilibrium(problem: RollerProblem, num: Numerics, corr: Correction,
                            start: EquilibriumResult | None = None, tol: float = 1e-4, max_outer: int = 20,
                            progress=None) -> FiniteBodyResult:
    """The roller equilibrium with the finite-body correction (module docstring), from the half-space
    equilibrium ``start`` (solved if None). Raises ConvergenceError when the fixed point misses ``tol`` in
    ``max_outer`` iterations."""
    if start is None:
        start = require_converged(equilibrium(problem, num))

    def solve(u: dict[str, np.ndarray], r: EquilibriumResult) -> EquilibriumResult:
        pr = replace(problem, offsets=offsets_of(corr, u))
        return require_converged(equilibrium(pr, num, x0=r.x, delta0=r.approach))

    fp = fixed_point(solve, lambda r: coarse_field(corr, _sources(corr, r)), start, tol, max_outer,
                     "finite-body equilibrium", progress)
    return FiniteBodyResult(fp.solution, start, fp.iterations, fp.history, fp.time_s)
