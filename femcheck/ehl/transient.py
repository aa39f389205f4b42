"""Time marching of the EHL contact with a passing indent (seed 004 §2.6.3; spec §A.4-A.5).

Time step hT = h (finest grid, Courant number 1: the NU2 scheme transports the indent's film without numerical
damping); the coarse grids keep hT (h > hT branch). Start from a converged steady solution whose rho H fills the
two old time levels; per step: move the indent (X_D = X_D0 + (u_D/u_m) T), shift the time levels, and cycle until
the residual and load criteria hold -- the load balance holds at every step (quasi-static), H0 = H0(T).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from . import failures
from .multigrid import Multigrid, inject
from .steady import Solution, converge


@dataclass
class History:
    """Per-step record: time T, indent centre X_D, H0, cycles, residual, load error, the film minimum over the
    pressurised nodes ``h_min``, and the snapshots kept (with the step number of each in ``kept_steps``)."""

    T: list[float] = field(default_factory=list)
    x_indent: list[float] = field(default_factory=list)
    H0: list[float] = field(default_factory=list)
    cycles: list[int] = field(default_factory=list)
    residual: list[float] = field(default_factory=list)
    load_error: list[float] = field(default_factory=list)
    p_max: list[float] = field(default_factory=list)
    h_min: list[float] = field(default_factory=list)
    snapshots: list[Solution] = field(default_factory=list)
    kept_steps: list[int] = field(default_factory=list)


def start(mg: Multigrid, ht: float | None = None) -> float:
    """Turn a converged steady state into the initial condition of a transient: both old time levels = rho H."""
    lv = mg.fine
    ht = lv.h if ht is None else ht
    r = mg.state(lv)[3]
    lv.r1, lv.r2 = r.copy(), r.copy()
    for l in mg.levels:
        l.ht = ht
    _inject_old(mg)
    return ht


def _inject_old(mg: Multigrid) -> None:
    for l in range(len(mg.levels) - 1, 0, -1):
        fine, coarse = mg.levels[l], mg.levels[l - 1]
        coarse.r1, coarse.r2 = inject(fine.r1), inject(fine.r2)


def shift_x(F: np.ndarray, s: float) -> np.ndarray:
    """F moved downstream by s nodes along axis 0 (linear interpolation; zero flows in at the inlet)."""
    k = int(np.floor(s))
    w = s - k
    out = np.zeros_like(F)

    def moved(m):
        g = np.zeros_like(F)
        if m < F.shape[0]:
            g[m:] = F[:F.shape[0] - m]
        return g

    out = (1.0 - w) * moved(k) + (w * moved(k + 1) if w else 0.0)
    return out


def step_name(mg: Multigrid, k: int, steps: int) -> str:
    """Where a time step is, for its failure messages: grid, step k of ``steps``, T and the indent centre."""
    where = f"EHL transient ({mg.fine.n + 1}^2 nodes), step {k} of {steps} (T = {mg.T:.4g}"
    if mg.prob.indent is not None:
        where += f", indent centre X_D = {mg.prob.indent.centre(mg.T):.4g} b"
    return where + ")"


def march(mg: Multigrid, steps: int, tol: float = 1e-7, load_tol: float = 1e-7, max_cycles: int = 40,
          keep: Callable[[int, float], bool] | None = None, progress=None,
          base: np.ndarray | None = None, film_check: bool = True) -> History:
    """March ``steps`` time steps of size hT (set by :func:`start`). ``keep(k, T)`` says which steps to store as
    :class:`Solution` snapshots (pressure and film fields).

    First guess of each step: with ``base`` (the smooth steady pressure), the previous disturbance P - base moved
    with the indent by u_D hT (the pressure disturbance of an indent travels with it); otherwise the linear
    extrapolation in time of P. H0 is extrapolated linearly.

    ``film_check``: every converged step is refused (:class:`~femcheck.ehl.failures.UnderResolvedFilm`, naming
    the step and the indent position) when its film is negative where P > 0, as a steady solution is: each step's
    pressure may be used (kept snapshots, amplitudes, a fatigue-life pass), not only the one at the end."""
    lv = mg.fine
    ht = lv.ht
    hist = History()
    prev = None
    last = None
    for k in range(1, steps + 1):
        t0 = time.perf_counter()
        r = mg.state(lv)[3]
        lv.r2, lv.r1 = lv.r1, r
        _inject_old(mg)
        mg.set_time(mg.T + ht)
        # linear extrapolation in time of P and H0 as the first guess (halves the cycles per step)
        now = (lv.P.copy(), mg.H0)
        if base is not None:
            speed = mg.prob.indent.speed_ratio if mg.prob.indent is not None else 1.0
            lv.P = np.maximum(base + shift_x(now[0] - base, speed * ht / lv.h), 0.0)
        elif prev is not None:
            lv.P = np.maximum(2.0 * now[0] - prev[0], 0.0)
        if prev is not None:
            mg.H0 = 2.0 * now[1] - prev[1]
        prev = now
        where = step_name(mg, k, steps)
        cycles, h = converge(mg, tol, load_tol, max_cycles, where, before=last)
        res, res_max = mg.residual_norm(lv)
        last = (res, f"at the end of step {k}")
        H = mg.state(lv)[0]
        h_min = failures.film_minimum(lv.P, H)
        if film_check:
            failures.check_film(lv.P, H, where, cycles, res, tol)
        hist.T.append(mg.T)
        hist.x_indent.append(mg.prob.indent.centre(mg.T) if mg.prob.indent is not None else np.nan)
        hist.H0.append(mg.H0)
        hist.cycles.append(cycles)
        hist.residual.append(res)
        hist.load_error.append(mg.load_error())
        hist.p_max.append(float(lv.P.max()))
        hist.h_min.append(h_min)
        if keep is not None and keep(k, mg.T):
            hist.snapshots.append(Solution(lv.film.x.copy(), lv.film.y.copy(), lv.P.copy(), H, mg.H0,
                                           mg.T, cycles, res, res_max, mg.load_error(), h, mg.sweeps,
                                           time.perf_counter() - t0))
            hist.kept_steps.append(k)
        if progress:
            progress(f"step {k}/{steps} T={mg.T:.3f} cycles={cycles}")
    return hist
