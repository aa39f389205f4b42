"""Coulomb friction on a condensed 3D contact system: normal and tangential contact of the cells of one or more
contacts solved together by a semi-smooth Newton method (primal-dual active set) with a damped step; the 3D
extension of :mod:`femcheck.solvers.coulomb` used by the FE rolling reference.

Unknowns: tractions p = (p_x, p_s, p_n) (Pa) on body 1 on N cells (component-major vector [p_x, p_s, p_n]) and K
scalar unknowns theta (rigid approaches, a creepage, ...) tied to K linear constraints. With linear bodies every
kinematic quantity is affine in them:

    g = g0 + G p + C_g theta           normal gap (m)
    s = s0 + S p + C_s theta           tangential slip (2N,): slip velocity per unit rolling speed (steady rolling)
    L p + L_theta theta = b            e.g. sum p_n dA = N (load control), sum p_x dA = 0 (free rolling)

Contact and friction (Signorini + Coulomb; Johnson 1985 §7.1, Kalker 1990 §1.4): p_n >= 0, g >= 0, p_n g = 0;
|p_t| <= mu p_n; slip s != 0 => p_t = -mu p_n s/|s| (the traction on body 1 opposes its slip). Alart & Curnier's
(1991) equations with the augmented normal traction as the friction bound,

    F_n = p_n - max(0, p_n - r_n g) = 0,    F_t = p_t - Proj_{|q| <= mu max(0, p_n - r_n g)}(p_t - r_t s) = 0,

(r_n, r_t > 0 per cell: the inverse diagonal compliances) are solved by semi-smooth Newton (Hueber, Stadler &
Wohlmuth, SIAM J. Sci. Comput. 30, 2008: in 3D the slip direction is linearised, so each step is one linear
solve on the active cells; Christensen, Klarbring, Pang & Stroemberg, IJNME 42, 1998). A cell with
p_n - r_n g <= 0 is out of contact and carries p = 0 exactly (its rows drop out of the linear system). Steps are
damped by a non-monotone back-tracking search on |F|^2 (Grippo, Lampariello & Lucidi 1986), which the nonsmooth
slip directions need; convergence is declared on max|F| / p_scale < tol with every constraint met.
Dense linear algebra: the FE reference's grids have at most a few thousand contact cells.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from ..errors import ConvergenceError

MEMORY = 8


@dataclass
class ContactSystem:
    """The affine maps above. ``g0`` (N,), ``G`` (N, 3N), ``C_g`` (N, K); ``s0`` (2N,) ordered [s_x, s_s],
    ``S`` (2N, 3N), ``C_s`` (2N, K); ``L`` (K, 3N), ``L_theta`` (K, K), ``b`` (K,); ``mu`` (N,) or scalar;
    ``force_scale`` (N per Pa: a cell area) to express constraint residuals as tractions."""

    g0: np.ndarray
    G: np.ndarray
    C_g: np.ndarray
    s0: np.ndarray
    S: np.ndarray
    C_s: np.ndarray
    L: np.ndarray
    L_theta: np.ndarray
    b: np.ndarray
    mu: np.ndarray | float
    force_scale: float = 1.0

    @property
    def n(self) -> int:
        return self.g0.size

    @property
    def k(self) -> int:
        return self.b.size

    def gap(self, p: np.ndarray, theta: np.ndarray) -> np.ndarray:
        return self.g0 + self.G @ p + self.C_g @ theta

    def slip(self, p: np.ndarray, theta: np.ndarray) -> np.ndarray:
        return self.s0 + self.S @ p + self.C_s @ theta


@dataclass
class ContactSolution:
    """Like scipy.optimize's results: tractions ``p`` (3N,), ``theta`` (K,), ``gap`` (N,), ``slip`` (2N,),
    masks ``contact`` and ``stick`` (N,), ``iterations``, ``residual`` (max|F| / p_scale), ``converged``,
    ``history`` (residual per iteration)."""

    p: np.ndarray
    theta: np.ndarray
    gap: np.ndarray
    slip: np.ndarray
    contact: np.ndarray
    stick: np.ndarray
    iterations: int
    residual: float
    converged: bool
    history: list


def _state(sys: ContactSystem, p, theta, rn, rt, mu):
    n = sys.n
    g = sys.gap(p, theta)
    s = sys.slip(p, theta)
    pt = np.stack([p[:n], p[n:2 * n]])
    pn = p[2 * n:]
    aug = pn - rn * g
    beta = mu * np.maximum(aug, 0.0)
    z = pt - rt * s.reshape(2, n)
    nz = np.hypot(z[0], z[1])
    inside = nz <= beta
    scale = np.where(inside, 1.0, beta / np.where(nz > 0, nz, 1.0))
    F_t = pt - z * scale
    F_n = pn - np.maximum(aug, 0.0)
    F_c = (sys.L @ p + sys.L_theta @ theta - sys.b) / sys.force_scale
    return g, s, aug, beta, z, nz, inside, np.concatenate([F_t.ravel(), F_n, F_c])


def solve(sys: ContactSystem, p0: np.ndarray | None = None, theta0: np.ndarray | None = None,
          tol: float = 1e-9, max_iter: int = 200) -> ContactSolution:
    """Semi-smooth Newton for the system (module docstring). ``p0``, ``theta0``: start (default p = 0, theta = 0;
    give a sensible theta0, e.g. a Hertz approach, for load control). Raises :class:`ConvergenceError` when
    max|F| / p_scale stays above ``tol`` after ``max_iter`` steps (p_scale = the largest traction bound scale,
    max p_n of the iterate)."""
    n, k = sys.n, sys.k
    mu = np.broadcast_to(np.asarray(sys.mu, dtype=float), (n,)).copy()
    rn = 1.0 / np.maximum(np.abs(np.diag(sys.G[:, 2 * n:])), 1e-300)
    Sd = np.abs(np.stack([np.diag(sys.S[:n, :n]), np.diag(sys.S[n:, n:2 * n])])).mean(axis=0)
    rt = 1.0 / np.maximum(Sd, 1e-300)
    p = np.zeros(3 * n) if p0 is None else np.asarray(p0, dtype=float).copy()
    theta = np.zeros(k) if theta0 is None else np.asarray(theta0, dtype=float).copy()
    # theta enters the Newton matrix scaled so that its columns have the size of a traction column
    col = np.ones(k)
    for i in range(k):
        c = np.concatenate([rn * sys.C_g[:, i], np.repeat(rt, 2) * sys.C_s[:, i]])
        col[i] = 1.0 / max(float(np.abs(c).max()), 1e-300)
    history = []
    merits = []
    g, s, aug, beta, z, nz, inside, F = _state(sys, p, theta, rn, rt, mu)
    for it in range(1, max_iter + 1):
        pscale = max(float(np.max(p[2 * n:], initial=0.0)), float(np.max(-rn * sys.g0, initial=0.0)), 1.0)
        res = float(np.abs(F).max()) / pscale
        history.append(res)
        merits.append(float(F @ F))
        if res < tol:
            return ContactSolution(p, theta, g, s, aug > 0, (aug > 0) & inside, it - 1, res, True, history)
        act = np.flatnonzero(aug > 0)
        d = _newton_step(sys, p, act, aug, beta, z, nz, inside, F, rn, rt, mu, col)
        # damped step on the merit |F|^2 (non-monotone reference: the worst of the last few merits)
        ref = max(merits[-MEMORY:]) if it > 1 else np.inf
        step = 1.0
        for _ in range(30):
            p_new = p + step * d[:3 * n]
            th_new = theta + step * d[3 * n:] * col
            st = _state(sys, p_new, th_new, rn, rt, mu)
            m_new = float(st[-1] @ st[-1])
            if m_new < (1.0 - 1e-4 * step) * ref or m_new == 0.0:
                break
            step *= 0.5
        p, theta = p_new, th_new
        g, s, aug, beta, z, nz, inside, F = st
    pscale = max(float(np.max(p[2 * n:], initial=0.0)), 1.0)
    raise ConvergenceError("frictional contact semi-smooth Newton", max_iter, float(np.abs(F).max()) / pscale, tol)


def _newton_step(sys, p, act, aug, beta, z, nz, inside, F, rn, rt, mu, col) -> np.ndarray:
    """Newton direction (dp (3N,), dtheta/col (K,)) for the current sets; inactive cells go to p = 0."""
    n, k = sys.n, sys.k
    a = act.size
    idx_p = np.concatenate([act, n + act, 2 * n + act])           # active unknowns, component-major
    d = np.zeros(3 * n + k)
    inact = np.setdiff1d(np.arange(n), act)
    dp_fixed = np.zeros(3 * n)
    for c in range(3):
        dp_fixed[c * n + inact] = -p[c * n + inact]
    # linearised maps restricted to active rows/columns, with the fixed inactive increments on the rhs
    Ga = sys.G[act]
    Sa = np.vstack([sys.S[act], sys.S[n + act]])                   # (2a, 3N)
    dg0 = Ga @ dp_fixed
    ds0 = Sa @ dp_fixed
    Gc = np.hstack([Ga[:, idx_p], sys.C_g[act] * col])             # (a, 3a + k)
    Sc = np.hstack([Sa[:, idx_p], sys.C_s[np.concatenate([act, n + act])] * col])
    m = 3 * a + k
    J = np.zeros((m, m))
    rhs = np.zeros(m)
    Ft = F[:2 * n].reshape(2, n)[:, act]
    Fn = F[2 * n:3 * n][act]
    Fc = F[3 * n:]
    ins = inside[act]
    rna, rta, mua = rn[act], rt[act], mu[act]
    # normal rows (3a rows ordered: t_x (a), t_s (a), n (a), constraints (k)): F_n = r_n g on active cells
    rows_n = 2 * a + np.arange(a)
    J[rows_n] = rna[:, None] * Gc
    rhs[rows_n] = -(Fn + rna * dg0)
    # tangential rows
    nzs = np.where(nz[act] > 0, nz[act], 1.0)
    ex, ey = z[0, act] / nzs, z[1, act] / nzs
    fac = np.where(ins, 0.0, beta[act] / nzs)
    Pxx, Pyy, Pxy = fac * (1 - ex * ex), fac * (1 - ey * ey), -fac * ex * ey
    Sx, Sy = Sc[:a], Sc[a:]
    # dz = dp_t - r_t ds; stick: dF_t = r_t ds; slip: dF_t = dp_t - n dbeta - P dz, dbeta = mu (dp_n - r_n dg)
    ia = np.arange(a)
    Jx = np.zeros((a, m))
    Jy = np.zeros((a, m))
    # stick part
    st = ins
    Jx[st] = rta[st, None] * Sx[st]
    Jy[st] = rta[st, None] * Sy[st]
    sl = ~ins
    if sl.any():
        r_sl = np.flatnonzero(sl)
        # dp_t - P dp_t + P r_t ds
        Jx[r_sl, r_sl] += 1.0 - Pxx[sl]
        Jx[r_sl, a + r_sl] += -Pxy[sl]
        Jy[r_sl, r_sl] += -Pxy[sl]
        Jy[r_sl, a + r_sl] += 1.0 - Pyy[sl]
        Jx[sl] += (rta[sl] * Pxx[sl])[:, None] * Sx[sl] + (rta[sl] * Pxy[sl])[:, None] * Sy[sl]
        Jy[sl] += (rta[sl] * Pxy[sl])[:, None] * Sx[sl] + (rta[sl] * Pyy[sl])[:, None] * Sy[sl]
        # - n dbeta, dbeta = mu (dp_n - r_n dg)
        dbeta = -(mua[sl] * rna[sl])[:, None] * Gc[sl]
        dbeta[np.arange(r_sl.size), 2 * a + r_sl] += mua[sl]
        Jx[sl] -= ex[sl, None] * dbeta
        Jy[sl] -= ey[sl, None] * dbeta
    J[ia] = Jx
    J[a + ia] = Jy
    # rhs of the tangential rows: -F_t minus the fixed inactive increments' effect
    dsx0, dsy0 = ds0[:a], ds0[a:]
    tx0 = np.where(st, rta * dsx0, rta * (Pxx * dsx0 + Pxy * dsy0))
    ty0 = np.where(st, rta * dsy0, rta * (Pxy * dsx0 + Pyy * dsy0))
    dbeta0 = np.where(st, 0.0, -mua * rna * dg0)
    tx0 = tx0 - np.where(st, 0.0, ex * dbeta0)
    ty0 = ty0 - np.where(st, 0.0, ey * dbeta0)
    rhs[ia] = -(Ft[0] + tx0)
    rhs[a + ia] = -(Ft[1] + ty0)
    # constraint rows
    rows_c = 3 * a + np.arange(k)
    J[rows_c, :3 * a] = sys.L[:, idx_p] / sys.force_scale
    J[rows_c, 3 * a:] = sys.L_theta * col[None, :] / sys.force_scale
    rhs[rows_c] = -(Fc + sys.L @ dp_fixed / sys.force_scale)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", sla.LinAlgWarning)
            x = sla.solve(J, rhs, check_finite=False)
    except (sla.LinAlgError, sla.LinAlgWarning):
        x = sla.lstsq(J, rhs, check_finite=False)[0]
    d = dp_fixed.copy()
    d[idx_p] = x[:3 * a]
    out = np.concatenate([d, x[3 * a:]])
    return out
