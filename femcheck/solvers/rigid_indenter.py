"""Frictionless contact of a rigid analytic indenter with a meshed 3D body, under load control.

The body's contact face is z = 0 with the body below it. The indenter's surface is z = h(x, y) - delta: h is the
initial gap (m) and delta the rigid approach, the extra unknown that makes the total force equal the load. A
candidate node i (on the face, inside the candidate zone) satisfies the Signorini conditions

    g_i = h_i - delta - u_z,i >= 0,    lam_i >= 0,    lam_i g_i = 0,     sum lam_i = F,

with lam_i the compressive nodal contact force (N). Primal-dual active set (Hintermueller, Ito & Kunisch,
SIAM J. Optim. 13, 2002) in its Signorini form: on the active set A the nodes follow the indenter,
u_z,A = h_A - delta; because the body is linear, u = u0 + delta u1 with u0 for (h_A, delta = 0) and u1 for a
unit approach, so delta follows from the load balance exactly; then A <- {lam > 0 on A} U {g < 0 off A}
until A repeats. Each iteration costs two AMG-CG solves, warm-started from the previous ones.

Nodal pressure p_i = lam_i / w_i with w_i = int phi_i dA, the node's tributary area on the face (lumped).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError
from .elasticity3d import AMGElasticity


@dataclass
class RigidContactSolution:
    """``lam`` compressive nodal forces (N) and ``gap`` (m) at the candidate nodes, ``delta`` approach (m),
    ``active`` mask, ``u`` displacement on the solver's free DOFs (m), ``iterations`` of the active set,
    ``cg_iterations`` per linear solve, ``residual`` (complementarity, relative), ``time_s``."""

    lam: np.ndarray
    gap: np.ndarray
    delta: float
    active: np.ndarray
    u: np.ndarray
    iterations: int
    cg_iterations: list[int] = field(default_factory=list)
    residual: float = 0.0
    time_s: float = 0.0


Split = tuple  # (u0, u1, lam0, lam1, gap0, gap1, cg_iterations): the state is u0 + delta u1, etc.


def _newton(name: str, split, rule, force: float | None, approach: float | None, active0: np.ndarray,
            gap_scale: float, tol: float, max_iter: int) -> RigidContactSolution:
    """Semi-smooth Newton over active sets shared by both methods. ``split(active, warm)`` solves the two
    linear problems of an active set and returns the affine pieces in delta (:data:`Split`); ``rule(active,
    lam, gap)`` is the next active set. Load control finds delta from the load balance, displacement control
    takes it as given. Stops when the active set repeats, then checks the contact conditions against ``tol``."""
    if (force is None) == (approach is None):
        raise ValueError("give exactly one of force (load control) or approach (displacement control)")
    t0 = time.perf_counter()
    active = np.asarray(active0, dtype=bool).copy()
    if not active.any():
        raise ValueError("the initial active set is empty")
    warm, cg_its = (None, None), []
    for it in range(1, max_iter + 1):
        u0, u1, l0, l1, g0, g1, its = split(active, warm)
        warm = (u0, u1)
        cg_its += its
        if l1.sum() <= 0:
            raise ConvergenceError(name, it, np.inf, tol, "body does not resist the approach")
        delta = (force - l0.sum()) / l1.sum() if force is not None else approach
        u, lam, gap = u0 + delta * u1, l0 + delta * l1, g0 + delta * g1
        new = rule(active, lam, gap)
        if np.array_equal(new, active):
            total = float(lam.sum())
            balance = abs(total - force) / force if force is not None else 0.0
            lam_ref = total / active.sum()
            residual = float(max(max(0.0, -lam.min()) / lam_ref, max(0.0, -gap[~active].min(initial=0.0)) / gap_scale,
                                 balance))
            if residual > tol:
                raise ConvergenceError(name, it, residual, tol, "active set settled on a state that violates contact")
            return RigidContactSolution(lam, gap, float(delta), active, u, it, cg_its, residual,
                                        time.perf_counter() - t0)
        active = new
        if not active.any():
            raise ConvergenceError(name, it, np.inf, tol, "active set became empty")
    raise ConvergenceError(name, max_iter, np.inf, tol, "active set cycling")


def active_set(solver: AMGElasticity, z_dofs: np.ndarray, h: np.ndarray, force: float | None,
               active0: np.ndarray, tol: float = 1e-8, max_iter: int = 50,
               approach: float | None = None) -> RigidContactSolution:
    """Solve the rigid-indenter contact on ``solver``'s body by the primal-dual active set.

    ``z_dofs``: indices (into the solver's free DOFs) of the candidates' z-displacements; ``h``: initial gaps
    (m) there; ``force``: load (N) carried by the model (a quarter model carries a quarter) under load control,
    or None with ``approach`` delta (m) given under displacement control; ``active0``: initial active set (e.g.
    inside the Hertz contact). Raises :class:`ConvergenceError` if the active set does not settle within
    ``max_iter`` or the settled state violates the contact conditions beyond ``tol``.
    """
    zero = np.zeros(solver.A.shape[0])

    def split(active, warm):
        idx = z_dofs[active]
        u0, i0 = solver.solve(zero, idx, h[active], warm[0])
        u1, i1 = solver.solve(zero, idx, -np.ones(idx.size), warm[1])
        # compressive contact force = minus the nodal force the constraint exerts in +z
        l0 = np.where(active, -(solver.A @ u0)[z_dofs], 0.0)
        l1 = np.where(active, -(solver.A @ u1)[z_dofs], 0.0)
        return u0, u1, l0, l1, h - u0[z_dofs], -1.0 - u1[z_dofs], [i0.iterations, i1.iterations]

    return _newton("rigid-indenter active set", split, lambda a, lam, gap: np.where(a, lam > 0, gap < 0), force,
                   approach, active0, float(np.ptp(h)) or 1.0, tol, max_iter)


def penalty(solver: AMGElasticity, z_dofs: np.ndarray, h: np.ndarray, force: float, kappa: np.ndarray,
            active0: np.ndarray, tol: float = 1e-8, max_iter: int = 50) -> RigidContactSolution:
    """Penalty method lam_i = kappa_i max(0, -g_i) (kappa in N/m per node), semi-smooth Newton on the active set
    A = {g < 0}, load control. On A the stiffness gains kappa on the z-DOFs and the indenter pushes with
    kappa (h - delta); again u = u0 + delta u1 and delta follows from the load balance. The overlap
    max(-g) ~ lam/kappa is the price of the method; it tends to the active-set solution as 1/kappa."""
    n = solver.A.shape[0]
    kappa = np.broadcast_to(np.asarray(kappa, dtype=float), h.shape)

    def split(active, warm):
        k_full, f0, f1 = np.zeros(n), np.zeros(n), np.zeros(n)
        k_full[z_dofs[active]] = kappa[active]
        f0[z_dofs[active]] = kappa[active] * h[active]       # the indenter at z = h pulls the surface to it
        f1[z_dofs[active]] = -kappa[active]                   # per unit approach
        u0, i0 = solver.solve(f0, x0=warm[0], spring=k_full)
        u1, i1 = solver.solve(f1, x0=warm[1], spring=k_full)
        g0, g1 = h - u0[z_dofs], -1.0 - u1[z_dofs]             # gap = h - delta - u_z, split in delta
        return (u0, u1, np.where(active, -kappa * g0, 0.0), np.where(active, -kappa * g1, 0.0), g0, g1,
                [i0.iterations, i1.iterations])

    # the overlap on the active set is the method's own (reported as penetration), not a violation
    return _newton("rigid-indenter penalty", split, lambda a, lam, gap: gap < 0, force, None, active0,
                   float(np.ptp(h)) or 1.0, tol, max_iter)
