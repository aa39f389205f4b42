"""Branches of the roller equilibrium over the load (seed 000 Fig. 17; spec srb-rolling §6, §10.1 item 13): for
each friction coefficient, configuration 1 traced from the highest load downwards and configuration 2 from the
lowest load upwards, by natural continuation in N (the previous equilibrium as the start, its approach scaled as
N^(2/3)); a step that fails (Newton does not converge, or the state jumps to the other branch: skew changes by
more than :data:`JUMP_SKEW`) is halved down to ``min_step``; the branch ends there and the load where it ends is
reported (the fold, to within ``min_step``).

One branch is one case of :func:`femcheck.executor.map_cases` (local processes or dask), so the 2 x n_mu branches
run in parallel. Per point: N, d_y (m), f_x,i, f_x,e (F/(mu N) along x_p), total frictional power P_fric (W),
P_fric,E / P_fric,I, tilt, skew (gamma_p, rad), omega_m / omega_m,o, omega_R / omega_R,o, Newton iterations, time.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..geometry import srb_bearing as sb
from .roller_equilibrium import EquilibriumResult, equilibrium
from .roller_state import Numerics, RollerProblem

JUMP_SKEW = 5e-4          # rad: a larger change of skew between neighbouring loads is a jump to the other branch


@dataclass(frozen=True)
class Branch:
    """One case: ``problem`` (its load is ignored), ``configuration``, the loads from ``start`` to ``stop`` (N) in
    steps of ``step`` (N), halved at failure down to ``min_step``; ``numerics``."""

    problem: RollerProblem
    configuration: int
    start: float
    stop: float
    step: float = 250.0
    min_step: float = 62.5
    numerics: Numerics = Numerics()


def point(problem: RollerProblem, r: EquilibriumResult) -> dict:
    """The Fig. 17 numbers of one converged equilibrium (module docstring)."""
    b = problem.bearing
    s = r.state
    muN = problem.mu * problem.load
    xp = -np.sign(problem.omega_inner - problem.omega_outer) * sb.X
    om0, or0 = sb.nominal_speeds(b, problem.omega_inner, problem.omega_outer)
    Pi, Pe = (s.contacts[c].result.frictional_power for c in sb.CONTACTS)
    return {"load": problem.load, "mu": problem.mu, "configuration": r.configuration,
            "d_y": float((s.centre - b.nominal_centre) @ b.e_y),
            "f_x_inner": float(s.contacts["inner"].force @ xp / muN),
            "f_x_outer": float(s.contacts["outer"].force @ xp / muN),
            "f_lat_inner": s.contacts["inner"].result.force_s / muN,
            "f_lat_outer": s.contacts["outer"].result.force_s / muN,
            "friction_power": Pi + Pe, "power_ratio_outer_inner": Pe / Pi, "tilt": float(r.x[2]),
            "skew": float(-r.x[3]), "omega_m_ratio": float(r.x[4] / om0), "omega_R_ratio": float(r.x[5] / or0),
            "iterations": r.nit, "time_s": r.time_s}


def trace(branch: Branch, keep_last: bool = False) -> dict:
    """Trace one branch (module docstring). Returns {"mu", "configuration", "points": [...], "end": load where the
    branch ends or None (it spans the whole range), "status": text} and, with ``keep_last``, "last": the
    :class:`EquilibriumResult` of the last point."""
    t0 = time.perf_counter()
    pr = replace(branch.problem, load=branch.start)
    sign = 1.0 if branch.stop >= branch.start else -1.0
    r = equilibrium(pr, branch.numerics, configuration=branch.configuration)
    out = {"mu": pr.mu, "configuration": branch.configuration, "points": [], "end": None}
    if not r.success:
        out.update(status=f"not found at {branch.start:g} N: {r.message}", end=branch.start,
                   time_s=time.perf_counter() - t0)
        if keep_last:
            out["last"] = r
        return out
    out["points"].append(point(pr, r))
    N, step = branch.start, branch.step
    while sign * (branch.stop - N) > 1e-9:
        N_new = N + sign * min(step, abs(branch.stop - N))
        pn = replace(pr, load=N_new)
        x0 = r.x
        d0 = r.approach * (N_new / N) ** (2.0 / 3.0)
        # a continuation step starts next to its solution: 8 Newton iterations (pose, speeds and approach) are
        # plenty, and a failing step (past the fold) should not cost more
        rn = equilibrium(pn, branch.numerics, x0=x0, delta0=d0, configuration=branch.configuration, max_iter=8,
                         max_halvings=4)
        if rn.success and abs(rn.x[3] - r.x[3]) <= JUMP_SKEW * max(1.0, step / branch.step):
            out["points"].append(point(pn, rn))
            N, r, pr = N_new, rn, pn
            continue
        if step / 2.0 < branch.min_step - 1e-9:
            out["end"] = N
            out["status"] = (f"ends between {N:g} and {N_new:g} N ("
                             + ("jumps to the other configuration" if rn.success else rn.message) + ")")
            break
        step /= 2.0
    else:
        out["status"] = "spans the range"
    out["time_s"] = time.perf_counter() - t0
    if keep_last:
        out["last"] = r
    return out


def configuration_2(problem: RollerProblem, numerics: Numerics = Numerics(), start_load: float = 2000.0,
                    step: float = 250.0) -> EquilibriumResult:
    """Configuration 2 at ``problem.load``: found from skewed starts at ``start_load`` (or at the load itself if
    lower; the low-load end of Fig. 17, where it exists alone or most clearly) and followed by continuation in N
    up to the load. Followed this way it is the outer branch of the paper's Fig. 19 (skew about -4 mrad at 4 kN,
    mu = 0.3); a skewed start at the load itself can also land on the unstable middle branch between the two
    folds. Status 2 (not found) when the branch does not exist at the start load or ends (folds) below the load,
    with that load in the message."""
    t0 = time.perf_counter()
    start = min(start_load, problem.load)
    out = trace(Branch(problem, 2, start, problem.load, step, numerics=numerics), keep_last=True)
    r = out["last"]
    if not out["points"]:
        return replace(r, time_s=time.perf_counter() - t0)
    if out["end"] is not None:
        return replace(r, success=False, status=2, configuration=2, time_s=time.perf_counter() - t0,
                       message=f"configuration 2 not found at {problem.load:g} N: followed from {start:g} N it "
                               f"{out['status']}")
    return replace(r, time_s=time.perf_counter() - t0, message="converged (configuration 2 followed from "
                   f"{start:g} N)")


def fig17_branches(problem: RollerProblem, mus=(0.1, 0.2, 0.3), loads=(2000.0, 7000.0), step: float = 250.0,
                   numerics: Numerics = Numerics()) -> list[Branch]:
    """The 2 x len(mus) branches of Fig. 17: configuration 1 from the highest load down, 2 from the lowest up."""
    lo, hi = min(loads), max(loads)
    out = []
    for mu in mus:
        p = replace(problem, mu=mu)
        out.append(Branch(p, 1, hi, lo, step, numerics=numerics))
        out.append(Branch(p, 2, lo, hi, step, numerics=numerics))
    return out
