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


def active_set(solver: AMGElasticity, z_dofs: np.ndarray, h: np.ndarray, force: float, active0: np.ndarray,
               tol: float = 1e-8, max_iter: int = 50) -> RigidContactSolution:
    """Solve the rigid-indenter contact on ``solver``'s body.

    ``z_dofs``: indices (into the solver's free DOFs) of the candidates' z-displacements; ``h``: initial gaps
    (m) there; ``force``: load (N) carried by the model (a quarter model carries a quarter); ``active0``:
    initial active set (e.g. inside the Hertz contact). Raises :class:`ConvergenceError` if the active set
    does not settle within ``max_iter`` or the settled state violates the contact conditions beyond ``tol``.
    """
    t0 = time.perf_counter()
    n = solver.A.shape[0]
    zero = np.zeros(n)
    active = np.asarray(active0, dtype=bool).copy()
    if not active.any():
        raise ValueError("the initial active set is empty")
    x0 = x1 = None
    cg_its: list[int] = []
    gap_scale = float(np.ptp(h)) or 1.0
    for it in range(1, max_iter + 1):
        idx = z_dofs[active]
        u0, i0 = solver.solve(zero, idx, h[active], x0)
        u1, i1 = solver.solve(zero, idx, -np.ones(idx.size), x1)
        x0, x1 = u0, u1
        cg_its += [i0.iterations, i1.iterations]
        # compressive contact force = minus the nodal force the constraint exerts in +z
        r0, r1 = -(solver.A @ u0)[z_dofs], -(solver.A @ u1)[z_dofs]
        r0[~active], r1[~active] = 0.0, 0.0
        if r1.sum() <= 0:
            raise ConvergenceError("rigid-indenter active set", it, np.inf, tol, "body does not resist the approach")
        delta = (force - r0.sum()) / r1.sum()
        u = u0 + delta * u1
        lam = r0 + delta * r1
        gap = h - delta - u[z_dofs]
        new = np.where(active, lam > 0, gap < 0)
        if np.array_equal(new, active):
            lam_ref = force / active.sum()
            residual = float(max(max(0.0, -lam.min()) / lam_ref, max(0.0, -gap.min()) / gap_scale,
                                 abs(lam.sum() - force) / force))
            if residual > tol:
                raise ConvergenceError("rigid-indenter active set", it, residual, tol, "active set stalled")
            return RigidContactSolution(lam, gap, float(delta), active, u, it, cg_its, residual,
                                        time.perf_counter() - t0)
        active = new
        if not active.any():
            raise ConvergenceError("rigid-indenter active set", it, np.inf, tol, "active set became empty")
    raise ConvergenceError("rigid-indenter active set", max_iter, np.inf, tol, "active set cycling")
