"""Steady equilibrium of the roller in seed 000's spherical roller bearing with CECT contacts (seed 000 §3.2,
Fig. 5; spec srb-rolling §3, §6): six unknowns x = (d_Y, d_Z, beta, gamma, omega_m, omega_R) (m, m, rad, rad,
rad/s, rad/s), six equations R(x) = 0 (:mod:`femcheck.cect.roller_state`: forces and moments on the roller).

Method:
- Damped Newton with a one-sided finite-difference Jacobian (the paper's): steps d_Y, d_Z 1 nm, beta, gamma
  0.05 urad, omega_m, omega_R 1e-7 relative (spec §6: small enough that no element enters or leaves contact or
  changes between adhesion and slip, far above the solver tolerances; the number of elements that changed state
  is counted per column and reported). Each column is warm-started from the base state on the same grid; the
  speed columns reuse the base normal solutions (the gap does not depend on the speeds).
- Between full Jacobians, Broyden's (good) rank-one update; a full Jacobian is recomputed when a step reduces the
  scaled residual by less than half. Backtracking: the step is halved until the largest scaled residual
  decreases (at most ``max_halvings``); a step that pushes a contact out of its window, or to a state whose
  contact solve does not converge, counts as a failed trial.
- Grids fixed within an iteration, re-centred on the pressure centres between iterations (on the cell lattice,
  :class:`femcheck.cect.roller_state.GridSpec`).
- Load: the approach delta of the inner ring (spec §2.2) is solved by a secant on log N_I versus log delta so that
  the inner normal force sum p_n dA equals the target N within ``load_rtol`` (1e-4); each secant step re-solves
  the equilibrium from the previous one (warm start and its Jacobian).
- Configurations (spec §6, paper §4.3): 1 from the nominal start; 2 from skewed starts (CONFIG2_STARTS: both
  skew signs, |gamma| 2 and 4 mrad with a tilt and a larger axial offset) whose converged state must differ from configuration 1 (by more than 0.5 mrad in skew): when
  no such state is found the result says so (``status`` 2, ``success`` False), never a silent fallback. A skewed
  start at a load where both configurations exist can also land on the unstable middle branch between the two
  folds (4 kN, mu = 0.3: skew 1.1 mrad instead of Fig. 19's 4 mrad); the scene therefore follows configuration 2
  from a low load (:func:`femcheck.cect.roller_sweep.configuration_2`).

Results as scipy.optimize: :class:`EquilibriumResult` (``success``, ``status``, ``message``, ``nit``, the
residual per component, the state). Non-convergence of the Newton loop gives status 1 (not converged) with the
residual; the kind raises :class:`femcheck.errors.ConvergenceError` from it.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ConvergenceError, InputError
from .conformal import GridTooSmall
from .roller_state import (N_UNKNOWNS, RESIDUALS, UNKNOWNS, GridSpec, Numerics, RollerProblem, RollerState,
                           check_problem, evaluate, fitted, nominal_start)

FD_STEPS = np.array([1e-9, 1e-9, 5e-8, 5e-8, 1e-7, 1e-7])    # m, m, rad, rad, relative, relative (spec §6)
UNKNOWN_SCALE = np.array([1e-6, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3])  # um, urad, 1e-3 relative (spec §6)
# skewed starts of configuration 2 (skew gamma rad, tilt beta rad, extra axial offset d_y m), tried in order, both
# skew signs (Fig. 19: gamma_p = -gamma down to -4 mrad, tilt to -0.4 mrad, larger d_y than configuration 1)
CONFIG2_STARTS = ((2e-3, -2e-4, 4e-5), (-2e-3, -2e-4, 4e-5), (4e-3, -4e-4, 5e-5), (-4e-3, -4e-4, 5e-5))
DISTINCT_SKEW = 5e-4         # rad: a configuration-2 state must differ from configuration 1 by this much in skew


@dataclass
class EquilibriumResult:
    """A roller equilibrium (scipy.optimize style). ``x`` the state (UNKNOWNS), ``success``, ``status``
    (0 converged, 1 Newton did not converge, 2 configuration not found), ``message``, ``nit`` Newton
    iterations (all secant steps), ``njev`` full Jacobians, ``nfev`` state evaluations (each: both contacts),
    ``residual`` (6, N and N m along e_x, e_y, e_z), ``scaled_residual`` (by tol_F, tol_M), ``approach`` delta
    (m), ``state`` the :class:`RollerState` at x, ``configuration`` (1 or 2), ``history`` per iteration,
    ``time_s``, ``state_changes`` the largest number of elements that changed state in a Jacobian column."""

    x: np.ndarray
    success: bool
    status: int
    message: str
    nit: int
    njev: int
    nfev: int
    residual: np.ndarray
    scaled_residual: np.ndarray
    approach: float
    state: RollerState | None
    configuration: int = 1
    grids: GridSpec | None = None
    history: list = field(default_factory=list)
    time_s: float = 0.0
    state_changes: int = 0

    def residual_by_name(self) -> dict:
        return {k: float(v) for k, v in zip(RESIDUALS, self.residual)}

    def unknowns(self) -> dict:
        return {k: float(v) for k, v in zip(UNKNOWNS, self.x)}


@dataclass
class _Counter:
    nfev: int = 0
    njev: int = 0
    nit: int = 0
    changes: int = 0
    history: list = field(default_factory=list)


def _steps(x: np.ndarray) -> np.ndarray:
    h = FD_STEPS.copy()
    h[4:] *= np.maximum(np.abs(x[4:]), 1.0)
    return h


def _state_changes(a: RollerState, b: RollerState) -> int:
    n = 0
    for c in a.contacts:
        ra, rb = a.contacts[c].result, b.contacts[c].result
        if ra.pressure.shape == rb.pressure.shape:
            n += int(np.sum(ra.contact != rb.contact) + np.sum((ra.adhesion != rb.adhesion) & ra.contact & rb.contact))
    return n


def jacobian(problem: RollerProblem, num: Numerics, grids: GridSpec, base: RollerState,
             count: _Counter | None = None) -> np.ndarray:
    """dR_scaled/dx by one-sided differences (6 x 6; columns in the units of x) at ``base`` on ``grids``."""
    h = _steps(base.x)
    J = np.empty((N_UNKNOWNS, N_UNKNOWNS))
    for k in range(N_UNKNOWNS):
        xk = base.x.copy()
        xk[k] += h[k]
        sk = evaluate(problem, num, grids, xk, base.delta, warm=base, reuse_normal=k >= 4)
        J[:, k] = (sk.scaled - base.scaled) / h[k]
        if count is not None:
            count.nfev += 1
            count.changes = max(count.changes, _state_changes(base, sk))
    if count is not None:
        count.njev += 1
    return J


def _centres(state: RollerState) -> dict:
    return {c: state.contacts[c].result.pressure_centre for c in state.contacts}


def newton(problem: RollerProblem, num: Numerics, grids: GridSpec, x0: np.ndarray, delta: float,
           warm: RollerState | None = None, J0: np.ndarray | None = None, max_iter: int = 12,
           max_halvings: int = 6, count: _Counter | None = None):
    """Damped Newton / Broyden on R(x) = 0 at a fixed approach ``delta`` (module docstring). Returns
    (state, J, grids, converged)."""
    count = _Counter() if count is None else count
    if warm is not None:
        grids = grids.recentred(_centres(warm), num.ns)
        state = evaluate(problem, num, grids, x0, delta, warm=warm)
    else:
        state, grids = fitted(problem, num, grids.predicted(problem, x0, num.ns), x0, delta)
    count.nfev += 1
    J = J0
    fresh = False
    for _ in range(max_iter):
        if state.norm < 1.0:
            return state, J, grids, True
        if J is None:
            J = jacobian(problem, num, grids, state, count)
            fresh = True
        count.nit += 1
        step = np.linalg.solve(J * UNKNOWN_SCALE, -state.scaled) * UNKNOWN_SCALE
        lam, new = 1.0, None
        for _ in range(max_halvings + 1):
            try:
                trial = evaluate(problem, num, grids, state.x + lam * step, delta, warm=state)
                count.nfev += 1
                if trial.norm < state.norm:
                    new = trial
                    break
            except (GridTooSmall, ConvergenceError):      # a contact outside its window, or a trial state
                pass                                        # its solver cannot handle: a failed trial, halve
            lam *= 0.5
        count.history.append({"delta": delta, "norm": state.norm, "lambda": lam if new is not None else 0.0,
                              "jacobian": "fd" if fresh else "broyden"})
        if new is None:
            if fresh:
                return state, J, grids, False
            J, fresh = None, False          # a stale (Broyden) Jacobian: recompute and retry
            continue
        ratio = new.norm / state.norm
        dx = new.x - state.x
        J = J + np.outer(new.scaled - state.scaled - J @ dx, dx) / (dx @ dx)      # Broyden's good update
        fresh = False
        if ratio > 0.5:
            J = None
        # re-centre the windows on the new pressure centres (lattice moves: same discretisation)
        g2 = grids.recentred(_centres(new), num.ns)
        if g2 != grids:
            grids = g2
            new = evaluate(problem, num, grids, new.x, delta, warm=new)
            count.nfev += 1
        state = new
    return state, J, grids, state.norm < 1.0


def equilibrium(problem: RollerProblem, num: Numerics = Numerics(), x0: np.ndarray | None = None,
                delta0: float | None = None, configuration: int = 1, load_rtol: float = 1e-4,
                max_secant: int = 12, max_iter: int = 12, max_halvings: int = 6) -> EquilibriumResult:
    """The roller equilibrium with the inner normal force equal to ``problem.load`` (module docstring).

    ``x0``/``delta0``: a start (continuation); default the nominal start (configuration 1) or the skewed starts
    (configuration 2)."""
    check_problem(problem)
    if configuration not in (1, 2):
        raise InputError("equilibrium.configuration", f"{configuration!r}; allowed: 1 or 2")
    t0 = time.perf_counter()
    xn, dn = nominal_start(problem)
    if configuration == 1 or x0 is not None:
        return _at_load(problem, num, xn if x0 is None else x0, dn if delta0 is None else delta0, load_rtol,
                        max_secant, max_iter, configuration, t0, max_halvings)
    ref = _at_load(problem, num, xn, dn, load_rtol, max_secant, max_iter, 1, t0)
    base, d0 = (ref.x, ref.approach) if ref.success else (xn, dn)
    tried = []
    for skew, tilt, dy in CONFIG2_STARTS:
        xs = base.copy()
        xs[2], xs[3] = tilt, skew
        xs[0:2] += dy * problem.bearing.e_y[1:]
        r = _at_load(problem, num, xs, d0, load_rtol, max_secant, max_iter, 2, t0)
        tried.append(r)
        if r.success and (not ref.success or abs(r.x[3] - ref.x[3]) > DISTINCT_SKEW):
            return replace(r, time_s=time.perf_counter() - t0)
    last = tried[-1]
    back = any(t.success for t in tried)
    return replace(last, success=False, status=2, configuration=2, time_s=time.perf_counter() - t0,
                   message="configuration 2 not found: from %d skewed starts (|skew| 2-4 mrad, both signs) Newton %s"
                   % (len(tried), "returned to configuration 1" if back else "did not converge"))


def _at_load(problem, num, x0, delta0, load_rtol, max_secant, max_iter, configuration, t0,
             max_halvings: int = 6) -> EquilibriumResult:
    count = _Counter()
    grids = GridSpec.of(problem, num)
    N = problem.load
    state, J, x, delta = None, None, np.asarray(x0, dtype=float), float(delta0)
    pts: list[tuple[float, float]] = []
    converged = False
    for _ in range(max_secant):
        try:
            state, J, grids, converged = newton(problem, num, grids, x, delta, warm=state, J0=J, max_iter=max_iter,
                                                max_halvings=max_halvings, count=count)
        except GridTooSmall as err:
            return _result(None, False, 1, f"a contact left its window ({', '.join(err.edges)})", count, grids,
                           delta, configuration, t0, x)
        except ConvergenceError as err:
            return _result(None, False, 1, f"a contact solve failed ({err})", count, grids, delta, configuration,
                           t0, x)
        if not converged:
            break
        NI = state.inner_load
        if abs(NI / N - 1.0) < load_rtol:
            return _result(state, True, 0, "converged", count, grids, delta, configuration, t0)
        pts.append((np.log(delta), np.log(NI)))
        if len(pts) >= 2 and pts[-1][1] != pts[-2][1]:
            (u0, f0), (u1, f1) = pts[-2], pts[-1]
            u = u1 + (np.log(N) - f1) * (u1 - u0) / (f1 - f0)
        else:
            u = pts[-1][0] + (np.log(N) - pts[-1][1]) / 1.5        # Hertz: N ~ delta^1.5
        new_delta = float(np.exp(u))
        # predictor: the roller centre follows about half the ring's extra approach (two similar contacts)
        x = state.x.copy()
        x[0:2] += 0.5 * (new_delta - delta) * problem.approach_vector[1:]
        delta = new_delta
    msg = "Newton did not converge" if not converged else "the approach secant did not reach the load"
    return _result(state, False, 1, msg, count, grids, delta, configuration, t0)


def _result(state, success, status, message, count, grids, delta, configuration, t0, x=None) -> EquilibriumResult:
    R = state.residual if state is not None else np.full(N_UNKNOWNS, np.nan)
    S = state.scaled if state is not None else np.full(N_UNKNOWNS, np.nan)
    return EquilibriumResult(state.x.copy() if state is not None else np.asarray(x), success, status, message,
                             count.nit, count.njev, count.nfev, R, S, delta, state, configuration, grids,
                             count.history, time.perf_counter() - t0, count.changes)


def require_converged(r: EquilibriumResult) -> EquilibriumResult:
    """``r`` when converged; ConvergenceError (status 1) with the iterations and residual otherwise (status 2,
    configuration not found, is a result, not an error)."""
    if r.status == 1:
        raise ConvergenceError("roller equilibrium (Newton, 6 unknowns)", r.nit, float(np.nanmax(np.abs(
            r.scaled_residual))), 1.0, r.message)
    return r
