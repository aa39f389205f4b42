"""Frictionless contact of a set of rollers between an inner and an outer ring, on condensed compliances, under
load control (2D plane strain; the FE reference and the condensed model of the bearing_load kind).

Every roller j (direction e_j = (cos phi_j, sin phi_j) from the bearing axis) has n candidate node pairs with the
inner raceway and n with the outer raceway, all along e_j. With pair forces lam >= 0 (N/m), the roller's radial
translation rho_j and the inner ring's (shaft's) translation delta = (delta_x, delta_y) relative to the housing:

    inner pair i of roller j:  g_i = g0_i + rho_j - e_j . delta + (W lam)_i
    outer pair i of roller j:  g_i = g0_i - rho_j + (W lam)_i
    g >= 0,  lam >= 0,  lam . g = 0
    roller j:  sum_inner(j) lam - sum_outer(j) lam = 0          (radial equilibrium; the cage holds it tangentially)
    shaft:     sum_inner lam e_j = F'                          (F' = applied load per unit length)

W (m per N/m) is the sum of the rings' and the rollers' condensed compliances along the pair directions. This
is the KKT system of a convex quadratic programme; it is solved by the primal-dual active-set method
(Hintermüller, Ito & Kunisch 2002) with rho_j of a roller without an active pair removed (undefined: the
roller is unloaded, and for the gap test it is centred in its free room), or by the penalty method
lam = kappa max(0, -g) on the same active-set structure.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError


@dataclass
class RollerSetContact:
    """Candidate pairs ordered [inner pairs of roller 0..Z-1 (n each), outer pairs of roller 0..Z-1 (n each)].
    ``g0`` (2Zn,) initial gaps (m), ``W`` (2Zn, 2Zn) compliance, ``directions`` (Z, 2) unit e_j, ``load`` (2,)
    F' (N/m)."""

    g0: np.ndarray
    W: np.ndarray
    directions: np.ndarray
    load: np.ndarray
    n: int

    @property
    def rollers(self) -> int:
        return self.directions.shape[0]

    def pair_roller(self) -> np.ndarray:
        z, n = self.rollers, self.n
        return np.tile(np.repeat(np.arange(z), n), 2)

    def inner(self) -> np.ndarray:
        m = self.rollers * self.n
        return np.arange(2 * m) < m

    def gaps(self, lam: np.ndarray, rho: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """Gaps with the given unknowns (rho of every roller)."""
        j = self.pair_roller()
        inner = self.inner()
        shift = np.where(inner, rho[j] - self.directions[j] @ delta, -rho[j])
        return self.g0 + shift + self.W @ lam

    def centre_free(self, lam: np.ndarray, rho: np.ndarray, delta: np.ndarray, free: np.ndarray) -> np.ndarray:
        """rho of rollers without active pairs: the middle of their radial room (both smallest gaps equal)."""
        rho = rho.copy()
        rho[free] = 0.0
        g = self.gaps(lam, rho, delta).reshape(2, self.rollers, self.n)
        rho[free] = 0.5 * (g[1].min(axis=1) - g[0].min(axis=1))[free]
        return rho

    def free_room(self, lam: np.ndarray, rho: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """Smallest inner plus smallest outer gap of each roller, independent of rho (m): < 0 means the roller
        does not fit (it must carry load)."""
        g = self.gaps(lam, np.zeros(self.rollers), delta).reshape(2, self.rollers, self.n)
        return g[0].min(axis=1) + g[1].min(axis=1)


@dataclass
class RollerSetSolution:
    """Pair forces ``lam`` (N/m), gaps ``gap`` (m), roller translations ``rho`` (m; centred in the free room for
    unloaded rollers), shaft translation ``delta`` (m), ``active`` pairs, ``iterations``, ``residual``
    (max of the complementarity and the relative force balances), ``method``, ``penetration`` (penalty only)."""

    lam: np.ndarray
    gap: np.ndarray
    rho: np.ndarray
    delta: np.ndarray
    active: np.ndarray
    iterations: int
    residual: float
    method: str
    penetration: float = 0.0


def _solve_active(sys: RollerSetContact, active: np.ndarray, soft: np.ndarray | None):
    z = sys.rollers
    idx = np.flatnonzero(active)
    j = sys.pair_roller()[idx]
    inner = sys.inner()[idx]
    loaded = np.unique(j)
    col = np.full(z, -1)
    col[loaded] = np.arange(loaded.size)
    na, nr = idx.size, loaded.size
    # the shaft directions the active rollers can resist (rank 1 when they all lie on one line)
    dirs = sys.directions[np.unique(j[inner])] if inner.any() else np.zeros((0, 2))
    basis = np.eye(2)
    if dirs.shape[0] > 0:
        _, s, vt = np.linalg.svd(dirs, full_matrices=True)
        rank = int(np.sum(s > 1e-9 * s[0]))
        basis = vt[:rank] if rank else np.zeros((0, 2))
    else:
        basis = np.zeros((0, 2))
    nd = basis.shape[0]
    K = np.zeros((na + nr + nd, na + nr + nd))
    K[:na, :na] = sys.W[np.ix_(idx, idx)]
    if soft is not None:
        K[np.arange(na), np.arange(na)] += 1.0 / soft[idx]
    sign = np.where(inner, 1.0, -1.0)
    K[np.arange(na), na + col[j]] = sign
    K[na + col[j], np.arange(na)] = sign
    if nd:
        Ed = -(sys.directions[j] @ basis.T) * inner[:, None]        # (na, nd)
        K[:na, na + nr:] = Ed
        K[na + nr:, :na] = Ed.T
    rhs = np.concatenate([-sys.g0[idx], np.zeros(nr), -(basis @ sys.load)])
    try:
        sol = np.linalg.solve(K, rhs)
    except np.linalg.LinAlgError:
        sol = np.linalg.lstsq(K, rhs, rcond=None)[0]
    lam = np.zeros_like(sys.g0)
    lam[idx] = sol[:na]
    rho = np.zeros(z)
    rho[loaded] = sol[na:na + nr]
    delta = basis.T @ sol[na + nr:] if nd else np.zeros(2)
    free = np.ones(z, bool)
    free[loaded] = False
    rho = sys.centre_free(lam, rho, delta, free)
    return lam, rho, delta


def _residual(sys: RollerSetContact, lam, gap, rho, delta, penalty: bool) -> float:
    fnorm = float(np.linalg.norm(sys.load))
    j = sys.pair_roller()
    inner = sys.inner()
    shaft = np.linalg.norm((lam * inner) @ sys.directions[j] - sys.load) / fnorm
    roller = np.abs(np.bincount(j, weights=np.where(inner, lam, -lam), minlength=sys.rollers)).max() / fnorm
    lam_ref = fnorm / max(1, np.count_nonzero(lam > 0))
    g_ref = float(np.ptp(sys.g0)) or 1.0
    if penalty:
        ncp = max(0.0, -lam.min()) / lam_ref
    else:
        ncp = float(np.abs(np.minimum(lam / lam_ref, gap / g_ref)).max())
    return float(max(shaft, roller, ncp))


def solve(sys: RollerSetContact, active0: np.ndarray, method: str = "active_set", kappa: np.ndarray | None = None,
          tol: float = 1e-9, max_iter: int = 100) -> RollerSetSolution:
    """Primal-dual active set (``active_set``: A = {lam - C g > 0}, C = 1/mean diag W) or penalty (``penalty``:
    A = {g < 0} with lam = kappa (-g) on A); both stop when the active set repeats. A cycling active set
    switches to single-pair updates (the most violated pair of each roller) before giving up."""
    penalty = method == "penalty"
    if penalty and kappa is None:
        raise ValueError("the penalty method needs kappa")
    soft = None if not penalty else np.broadcast_to(np.asarray(kappa, float), sys.g0.shape)
    C = 1.0 / float(np.mean(np.diag(sys.W)))
    active = active0.copy()
    seen: set[bytes] = set()
    cautious = False
    for it in range(1, max_iter + 1):
        lam, rho, delta = _solve_active(sys, active, soft)
        g = sys.gaps(lam, rho, delta)
        new = (g < 0) if penalty else (lam - C * g > 0)
        if np.array_equal(new, active):
            res = _residual(sys, lam, g, rho, delta, penalty)
            if res > tol:
                raise ConvergenceError(f"bearing contact ({method})", it, res, tol, "active set stalled")
            pen = float(max(0.0, -g.min())) if penalty else 0.0
            return RollerSetSolution(lam, g, rho, delta, active, it, res, method, pen)
        key = new.tobytes()
        if key in seen:
            cautious = True
        seen.add(key)
        if cautious:
            # keep the pairs that carry load, add only the most penetrating pair of each roller
            keep = active & (lam > 0)
            viol = np.where(~active & (g < 0), g, 0.0).reshape(2 * sys.rollers, sys.n)
            worst = np.argmin(viol, axis=1)
            add = np.zeros_like(viol, bool)
            rows = np.flatnonzero(viol.min(axis=1) < 0)
            add[rows, worst[rows]] = True
            new = keep | add.ravel()
        if not new.any():
            raise ConvergenceError(f"bearing contact ({method})", it, np.inf, tol, "active set became empty")
        active = new
    raise ConvergenceError(f"bearing contact ({method})", max_iter, np.inf, tol, "active set cycling")
