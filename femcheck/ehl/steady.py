"""Steady EHL solve: full multigrid from the Hertz pressure, then FAS W(2,1) cycles until converged.

Convergence (seed 004 §2.6.4, made scale-free): the mean scaled residual over the pressurised nodes (see
:meth:`Multigrid.residual_norm`) at most ``tol`` and the load error |h^2 sum P - 2 pi/(3 kappa)|/(2 pi/(3 kappa))
at most ``load_tol``; otherwise :class:`~femcheck.errors.ConvergenceError` with the cycle count, the residual and
the load error it stopped at, or where it diverged (:mod:`femcheck.ehl.failures`).
W-cycles: with V-cycles the set of cavitated nodes at the far side edges flipped from cycle to cycle and the load
error stalled near 1e-6; W(2,1) cycles converged monotonically (measured at M = 100, L = 10, 65^2).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from . import failures
from .multigrid import Multigrid, Problem, prolong_cubic


@dataclass
class Solution:
    """A converged EHL solution on the finest grid (dimensionless): nodes x, y; P, H; H0; time T; convergence
    record (``cycles``, ``residual`` mean scaled residual, ``residual_max``, ``load_error``, ``history`` of the
    mean residual per cycle, ``work`` in finest-grid sweeps, ``time_s``)."""

    x: np.ndarray
    y: np.ndarray
    P: np.ndarray
    H: np.ndarray
    H0: float
    T: float
    cycles: int
    residual: float
    residual_max: float
    load_error: float
    history: list[float] = field(default_factory=list)
    work: float = 0.0
    time_s: float = 0.0


def snapshot(mg: Multigrid, cycles: int, history: list[float], t0: float) -> Solution:
    lv = mg.fine
    res, res_max = mg.residual_norm(lv)
    return Solution(lv.film.x.copy(), lv.film.y.copy(), lv.P.copy(), mg.state(lv)[0], mg.H0, mg.T, cycles, res,
                    res_max, mg.load_error(), list(history), mg.sweeps, time.perf_counter() - t0)


def converge(mg: Multigrid, tol: float, load_tol: float, max_cycles: int, what: str,
             before: tuple[float, str] | None = None) -> tuple[int, list[float]]:
    """Cycles on the finest grid until the residual and load criteria hold; else a ConvergenceError
    (:mod:`femcheck.ehl.failures`) with the residual and load error it stopped at. ``before``: the last finite
    residual known before these cycles and where it was measured (reported if the first evaluation is already
    non-finite)."""
    history: list[float] = []
    top = len(mg.levels) - 1
    for k in range(0, max_cycles + 1):
        if k:
            mg.cycle(top)
        res, _ = mg.residual_norm(mg.fine)
        if not np.isfinite(res) or not np.isfinite(mg.H0):
            if history:
                last = (history[-1], f"after cycle {k - 1}" if k > 1 else "before the first cycle")
            else:
                last = before if before is not None else (None, "")
            stage = f"in cycle {k}" if k else "before the first cycle"
            raise failures.diverged(what, k, stage, last[0], last[1], tol)
        history.append(res)
        if res <= tol and mg.load_error() <= load_tol:
            return k, history
    raise failures.not_converged(what, max_cycles, history[-1], tol, mg.load_error(), load_tol,
                                 "finer coarsest grid, more levels or a lower M / higher L may help")


def _start_stage(mg: Multigrid, level: int, what: str, tol: float, last: tuple[float | None, str],
                 stage: str) -> tuple[float, str]:
    """Residual of one full-multigrid stage on its own grid; a non-finite one is a divergence in that stage."""
    lv = mg.levels[level]
    res, _ = mg.residual_norm(lv)
    if not np.isfinite(res) or not np.isfinite(mg.H0):
        raise failures.diverged(what, 0, f"in the full-multigrid start on the {stage}", last[0], last[1], tol)
    return res, f"after the full-multigrid start on the {stage}"


def solve(prob: Problem, n: int, levels: int, tol: float = 1e-7, load_tol: float = 1e-7, max_cycles: int = 60,
          fmg_cycles: int = 3, coarsest_start: int = 200) -> tuple[Solution, Multigrid]:
    """Steady solution on (n+1)^2 nodes with ``levels`` grids (coarsest n/2^(levels-1) intervals)."""
    t0 = time.perf_counter()
    what = f"EHL steady multigrid ({n + 1}^2 nodes)"
    mg = Multigrid(prob, n, levels, gamma=2)
    mg.hertz_start()
    mg.relax_coarsest(coarsest_start)
    last: tuple[float | None, str] = (None, "")
    last = _start_stage(mg, 0, what, tol, last, f"coarsest grid, {mg.levels[0].n + 1}^2")
    for l in range(1, levels):
        mg.levels[l].P = prolong_cubic(mg.levels[l - 1].P)
        if l < levels - 1:
            for _ in range(fmg_cycles):
                mg.cycle(l)
            last = _start_stage(mg, l, what, tol, last, f"{mg.levels[l].n + 1}^2 grid")
    # the finest grid has f = 0, g = load: converge there
    cycles, history = converge(mg, tol, load_tol, max_cycles, what, before=last)
    return snapshot(mg, cycles, history, t0), mg
