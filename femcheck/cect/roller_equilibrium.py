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
- Load: the approach delta of the inner ring (spec §2.2) is the seventh unknown and the inner normal force
  sum p_n dA = N (within ``load_rtol``, 1e-4; scaled by it) the seventh equation, so one Newton loop finds the
  pose, the speeds and the approach together (a secant on delta around a converged 6-unknown Newton took 9
  iterations at mu = 0.3 against 6 for the first solve alone; the 7 x 7 Jacobian costs one contact solve more).
- Configurations (spec §6, paper §4.3): 1 from the nominal start; 2 from skewed starts (CONFIG2_STARTS: both
  skew signs, |gamma| 2 and 4 mrad with a tilt and a larger axial offset) whose converged state must differ from configuration 1 (by more than 0.5 mrad in skew): when
  no such state is found the result says so (``status`` 2, ``success`` False), never a silent fallback. A skewed
  start at a load where both configurations exist can also land on the unstable middle branch between the two
  folds (4 kN, mu = 0.3: skew 1.1 mrad instead of Fig. 19's 4 mrad); the scene therefore follows configuration 2
  from a low load (:func:`femcheck.cect.roller_sweep.configuration_2`). Where configuration 1 does not exist,
  Newton from the nominal start can land on configuration 2 (mu = 1, 5.5 kN): a nominal-start state with |skew|
  beyond DISTINCT_SKEW is reported as configuration 1 not found (status 2), never under its name.

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
DELTA_STEP = 1e-9                                               # m, the approach's difference step (as d_Y, d_Z)
UNKNOWN_SCALE = np.array([1e-6, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-6])  # um, urad, 1e-3 relative, um (spec §6)
# skewed starts of configuration 2 (skew gamma rad, tilt beta rad, extra axial offset d_y m), tried in order, both
# skew signs (Fig. 19: gamma_p = -gamma down to -4 mrad, tilt to -0.4 mrad, larger d_y than configuration 1)
CONFIG2_STARTS = ((2e-3, -2e-4, 4e-5), (-2e-3, -2e-4, 4e-5), (4e-3, -4e-4, 5e-5), (-4e-3, -4e-4, 5e-5))
DISTINCT_SKEW = 5e-4         # rad: configurations 1 and 2 differ by this much in skew at least (module docstring)


@dataclass
class EquilibriumResult:
    """A roller equilibrium (scipy.optimize style). ``x`` the state (UNKNOWNS), ``success``, ``status``
    (0 converged, 1 Newton did not converge, 2 configuration not found), ``message``, ``nit`` Newton
    iterations, ``njev`` full Jacobians, ``nfev`` state evaluations (each: both contacts),
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


def jacobian(problem: RollerProblem, num: Numerics, grids: GridSpec, base: RollerState, load: float,
             load_rtol: float, count: _Counter | None = None) -> np.ndarray:
    """d(residual)/d(x, delta) by one-sided differences (7 x 7; columns in the units of x and delta) at ``base``
    on ``grids``; rows: the six scaled equilibrium residuals and the scaled load residual (:func:`_residual`)."""
    h = _steps(base.x)
    r0 = _residual(base, load, load_rtol)
    J = np.empty((N_UNKNOWNS + 1, N_UNKNOWNS + 1))
    for k in range(N_UNKNOWNS + 1):
        xk, dk = base.x.copy(), base.delta
        if k < N_UNKNOWNS:
            xk[k] += h[k]
        else:
            dk += DELTA_STEP
        sk = evaluate(problem, num, grids, xk, dk, warm=base, reuse_normal=4 <= k < N_UNKNOWNS)
        J[:, k] = (_residual(sk, load, load_rtol) - r0) / (h[k] if k < N_UNKNOWNS else DELTA_STEP)
        if count is not None:
            count.nfev += 1
            count.changes = max(count.changes, _state_changes(base, sk))
    if count is not None:
        count.njev += 1
    return J


def _residual(state: RollerState, load: float, load_rtol: float) -> np.ndarray:
    """The six scaled equilibrium residuals and the load residual (N_I/N - 1)/load_rtol: converged when all seven
    are below 1 in magnitude."""
    return np.append(state.scaled, (state.inner_load / load - 1.0) / load_rtol)


def _centres(state: RollerState) -> dict:
    return {c: state.contacts[c].result.pressure_centre for c in state.contacts}


def newton(problem: RollerProblem, num: Numerics, grids: GridSpec, x0: np.ndarray, delta0: float, load: float,
           load_rtol: float = 1e-4, J0: np.ndarray | None = None, max_iter: int = 16, max_halvings: int = 6,
           count: _Counter | None = None):
    """Damped Newton / Broyden on the seven equations (six of equilibrium, the inner load) in the seven unknowns
    (x, delta) (module docstring). Returns (state, J, grids, converged)."""
    count = _Counter() if count is None else count
    state, grids = fitted(problem, num, grids.predicted(problem, x0, num.ns), x0, delta0)
    count.nfev += 1
    r = _residual(state, load, load_rtol)
    J = J0
    fresh = False
    for _ in range(max_iter):
        if np.abs(r).max() < 1.0:
            return state, J, grids, True
        if J is None:
            J = jacobian(problem, num, grids, state, load, load_rtol, count)
            fresh = True
        count.nit += 1
        step = np.linalg.solve(J * UNKNOWN_SCALE, -r) * UNKNOWN_SCALE
        z = np.append(state.x, state.delta)
        lam, new = 1.0, None
        for _ in range(max_halvings + 1):
            zt = z + lam * step
            try:
                trial = evaluate(problem, num, grids, zt[:N_UNKNOWNS], float(zt[-1]), warm=state)
                count.nfev += 1
                rt = _residual(trial, load, load_rtol)
                if np.abs(rt).max() < np.abs(r).max():
                    new = trial
                    break
            except (GridTooSmall, ConvergenceError):      # a contact outside its window, or a trial state
                pass                                        # its solver cannot handle: a failed trial, halve
            lam *= 0.5
        count.history.append({"delta": state.delta, "norm": float(np.abs(r).max()),
                              "lambda": lam if new is not None else 0.0, "jacobian": "fd" if fresh else "broyden"})
        if new is None:
            if fresh:
                return state, J, grids, False
            J, fresh = None, False          # a stale (Broyden) Jacobian: recompute and retry
            continue
        ratio = np.abs(rt).max() / np.abs(r).max()
        dz = np.append(new.x, new.delta) - z
        J = J + np.outer(rt - r - J @ dz, dz) / (dz @ dz)      # Broyden's good update
        fresh = False
        if ratio > 0.5:
            J = None
        # re-centre the windows on the new pressure centres (lattice moves: same discretisation)
        g2 = grids.recentred(_centres(new), num.ns)
        if g2 != grids:
            grids = g2
            new = evaluate(problem, num, grids, new.x, new.delta, warm=new)
            count.nfev += 1
            rt = _residual(new, load, load_rtol)
        state, r = new, rt
    return state, J, grids, bool(np.abs(r).max() < 1.0)


def equilibrium(problem: RollerProblem, num: Numerics = Numerics(), x0: np.ndarray | None = None,
                delta0: float | None = None, configuration: int = 1, load_rtol: float = 1e-4,
                max_iter: int = 16, max_halvings: int = 6) -> EquilibriumResult:
    """The roller equilibrium with the inner normal force equal to ``problem.load`` (module docstring).

    ``x0``/``delta0``: a start (continuation); default the nominal start (configuration 1) or the skewed starts
    (configuration 2)."""
    check_problem(problem)
    if configuration not in (1, 2):
        raise InputError("equilibrium.configuration", f"{configuration!r}; allowed: 1 or 2")
    t0 = time.perf_counter()
    xn, dn = nominal_start(problem)
    if configuration == 1 or x0 is not None:
        r = _at_load(problem, num, xn if x0 is None else x0, dn if delta0 is None else delta0, load_rtol,
                     max_iter, configuration, t0, max_halvings)
        if configuration == 1 and x0 is None and r.success and abs(r.x[3]) > DISTINCT_SKEW:
            # Newton left the nominal start's branch: where configuration 1 does not exist (high mu, low N: its
            # fold) it can land on configuration 2 (mu = 1, 5.5 kN: skew 5.0 mrad); every configuration-1 state
            # of Fig. 17 has |skew| <= 0.34 mrad, every configuration-2 state >= 2.1 mrad
            return replace(r, success=False, status=2, message="configuration 1 not found: Newton from the "
                           f"nominal start reached skew {r.x[3] * 1e3:.2f} mrad, beyond configuration 1's "
                           f"{DISTINCT_SKEW * 1e3:g} mrad (another branch)")
        return r
    ref = _at_load(problem, num, xn, dn, load_rtol, max_iter, 1, t0)
    if ref.success and abs(ref.x[3]) > DISTINCT_SKEW:
        # where configuration 1 does not exist (mu = 0.3 below its fold at 3.2 kN) Newton from the nominal start
        # already lands on configuration 2 (2 kN: skew 3.9 mrad); skewed starts built on that state leave the grid
        return replace(ref, configuration=2, time_s=time.perf_counter() - t0,
                       message="converged (configuration 2, reached from the nominal start: configuration 1 does "
                               "not exist at this load)")
    base, d0 = (ref.x, ref.approach) if ref.success else (xn, dn)
    tried = []
    for skew, tilt, dy in CONFIG2_STARTS:
        xs = base.copy()
        xs[2], xs[3] = tilt, skew
        xs[0:2] += dy * problem.bearing.e_y[1:]
        r = _at_load(problem, num, xs, d0, load_rtol, max_iter, 2, t0)
        tried.append(r)
        if r.success and (not ref.success or abs(r.x[3] - ref.x[3]) > DISTINCT_SKEW):
            return replace(r, time_s=time.perf_counter() - t0)
    last = tried[-1]
    back = any(t.success for t in tried)
    return replace(last, success=False, status=2, configuration=2, time_s=time.perf_counter() - t0,
                   message="configuration 2 not found: from %d skewed starts (|skew| 2-4 mrad, both signs) Newton %s"
                   % (len(tried), "returned to configuration 1" if back else "did not converge"))


def _at_load(problem, num, x0, delta0, load_rtol, max_iter, configuration, t0,
             max_halvings: int = 6) -> EquilibriumResult:
    count = _Counter()
    grids = GridSpec.of(problem, num)
    x, delta = np.asarray(x0, dtype=float), float(delta0)
    try:
        state, _, grids, converged = newton(problem, num, grids, x, delta, problem.load, load_rtol,
                                            max_iter=max_iter, max_halvings=max_halvings, count=count)
    except GridTooSmall as err:
        return _result(None, False, 1, f"a contact left its window ({', '.join(err.edges)})", count, grids,
                       delta, configuration, t0, x)
    except ConvergenceError as err:
        return _result(None, False, 1, f"a contact solve failed ({err})", count, grids, delta, configuration, t0, x)
    if converged:
        return _result(state, True, 0, "converged", count, grids, state.delta, configuration, t0)
    return _result(state, False, 1, "Newton did not converge", count, grids, state.delta, configuration, t0)


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
