"""Frictionless contact algorithms on a condensed system (node-to-node pairs, load control).

For linear bodies the gaps of the candidate pairs are affine in the pair forces and the rigid approach:

    g = g0 + delta * c + W lam,        lam >= 0,  g >= 0,  lam . g = 0,    sum(lam) = F

g0: initial gaps (m); c: gap change per unit approach of the loaded body (-1 for a rigid indenter);
W = B K^-1 B^T: contact compliance (m per N/m); lam: compressive pair forces (N/m in 2D); F: applied load. The
approach delta is the extra unknown that makes this *load* control (FEM-NOTES: the approach as unknown).
Two algorithms: the primal-dual active set method (Hintermueller, Ito & Kunisch 2002) and the penalty
method lam = kappa max(0, -g) solved by semi-smooth Newton on the same active-set structure.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError


@dataclass
class CondensedContact:
    g0: np.ndarray
    c: np.ndarray
    W: np.ndarray
    force: float

    def gaps(self, lam: np.ndarray, delta: float) -> np.ndarray:
        return self.g0 + delta * self.c + self.W @ lam


@dataclass
class ContactSolution:
    """Pair forces ``lam`` (N/m), gaps ``gap`` (m), approach ``delta`` (m), ``active`` set, ``iterations``,
    ``residual`` (complementarity: max |min(lam/lam_ref, g/g_ref)|, plus force balance), ``method``;
    ``penetration`` is the largest overlap (m), nonzero only for the penalty method."""

    lam: np.ndarray
    gap: np.ndarray
    delta: float
    active: np.ndarray
    iterations: int
    residual: float
    method: str
    penetration: float


def _solve_active(sys: CondensedContact, active: np.ndarray, soft: np.ndarray | None) -> tuple[np.ndarray, float]:
    """Solve W_AA lam_A + delta c_A = -g0_A (+ lam_A/kappa_A for penalty), sum lam_A = F."""
    idx = np.flatnonzero(active)
    n = idx.size
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = sys.W[np.ix_(idx, idx)]
    if soft is not None:
        A[np.arange(n), np.arange(n)] += 1.0 / soft[idx]
    A[:n, n] = sys.c[idx]
    A[n, :n] = 1.0
    rhs = np.concatenate([-sys.g0[idx], [sys.force]])
    sol = np.linalg.solve(A, rhs)
    lam = np.zeros_like(sys.g0)
    lam[idx] = sol[:n]
    return lam, float(sol[n])


def _initial_active(sys: CondensedContact, active0: np.ndarray | None) -> np.ndarray:
    if active0 is not None and active0.any():
        return active0.copy()
    return sys.g0 <= np.median(sys.g0)


def _residual(sys: CondensedContact, lam: np.ndarray, g: np.ndarray, penalty: bool) -> float:
    lam_ref = sys.force / max(1, np.count_nonzero(lam > 0))
    g_ref = float(np.ptp(sys.g0)) or 1.0
    balance = abs(lam.sum() - sys.force) / sys.force
    if penalty:       # penalty satisfies lam = kappa max(0, -g) exactly; only lam >= 0 and balance remain
        return float(max(balance, max(0.0, -lam.min()) / lam_ref))
    ncp = np.abs(np.minimum(lam / lam_ref, g / g_ref)).max()
    return float(max(ncp, balance))


def active_set(sys: CondensedContact, active0: np.ndarray | None = None, tol: float = 1e-9,
               max_iter: int = 100) -> ContactSolution:
    """Primal-dual active set: A = {i : lam_i - C g_i > 0}, C = 1/mean(diag W); stops when A repeats."""
    C = 1.0 / float(np.mean(np.diag(sys.W)))
    active = _initial_active(sys, active0)
    for it in range(1, max_iter + 1):
        lam, delta = _solve_active(sys, active, None)
        g = sys.gaps(lam, delta)
        new = lam - C * g > 0
        if np.array_equal(new, active):
            res = _residual(sys, lam, g, penalty=False)
            if res > tol:
                raise ConvergenceError("primal-dual active set", it, res, tol, "active set stalled")
            return ContactSolution(lam, g, delta, active, it, res, "active_set", 0.0)
        active = new
        if not active.any():
            raise ConvergenceError("primal-dual active set", it, np.inf, tol, "active set became empty")
    raise ConvergenceError("primal-dual active set", max_iter, np.inf, tol, "active set cycling")


def penalty(sys: CondensedContact, kappa: np.ndarray, active0: np.ndarray | None = None, tol: float = 1e-9,
            max_iter: int = 100) -> ContactSolution:
    """Penalty method lam_i = kappa_i max(0, -g_i) (kappa in N/m per m of overlap), semi-smooth Newton:
    A = {g_i < 0}; stops when A repeats. The overlap max(-g) ~ lam/kappa is reported as ``penetration``."""
    kappa = np.broadcast_to(np.asarray(kappa, dtype=float), sys.g0.shape)
    active = _initial_active(sys, active0)
    for it in range(1, max_iter + 1):
        lam, delta = _solve_active(sys, active, kappa)
        g = sys.gaps(lam, delta)
        new = g < 0
        if np.array_equal(new, active):
            res = _residual(sys, lam, g, penalty=True)
            if res > tol:
                raise ConvergenceError("penalty contact", it, res, tol, "negative pair force")
            return ContactSolution(lam, g, delta, active, it, res, "penalty", float(max(0.0, -g.min())))
        active = new
        if not active.any():
            raise ConvergenceError("penalty contact", it, np.inf, tol, "active set became empty")
    raise ConvergenceError("penalty contact", max_iter, np.inf, tol, "active set cycling")
