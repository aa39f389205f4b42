"""Coulomb friction on a condensed 2D contact system (node-to-node pairs), semi-smooth Newton / primal-dual
active set with gap, stick and slip sets.

Unknowns per candidate pair i: the compressive normal pair force p_i >= 0 and the tangential pair force q_i
acting on body 1 (the upper body, the cylinder), both in N/m (force per unit length of the line contact);
body 2 receives -p_i, -q_i. With linear bodies every kinematic quantity is affine in the pair forces:

    g = g0 + c_n delta_n + G_p p + G_q q        normal gap (m), delta_n the approach of body 1 (m)
    s = s0 + c_t delta_t + S_p p + S_q q        tangential slip measure of body 1 relative to body 2

``s`` is the slip *increment* (m) of a quasi-static load step (shift problems; delta_t the rigid tangential
shift, an unknown under load control) or the slip *velocity per unit rolling speed* (-) of a steady rolling
contact (Eulerian form, no delta_t). Conditions (Signorini + Coulomb, Johnson 1985 §7.1, Kalker 1990 §1.4):

    p >= 0, g >= 0, p g = 0;    |q| <= mu p;   s != 0  =>  q = -mu p s/|s|;    sum p = W;  [sum q = Q]

Written with tau = -q (the resistive force, parallel to the slip), Alart & Curnier's (1991) equations are

    p = max(0, p - c_N g),      tau = proj_[-mu p, mu p](tau + c_T s),

whose semi-smooth Newton method is the primal-dual active set method of Hueber, Stadler & Wohlmuth
(SIAM J. Sci. Comput. 30, 2008; in 2D the slip direction is a sign, so each Newton step is one linear solve):

    contact  C = {i : p_i - c_N g_i > 0}                      else p_i = q_i = 0
    stick    S = {i in C : |tau_i + c_T s_i| <= mu (p_i - c_N g_i)}   g_i = 0, s_i = 0
    slip     C \\ S, sigma_i = sign(tau_i + c_T s_i)           g_i = 0, q_i = -mu sigma_i p_i

iterated until the sets and slip signs repeat. The normal and tangential problems are solved together
(no Johnson / Panagiotopoulos splitting), so dissimilar materials, whose gap depends on q and whose slip
depends on p, need no special treatment. ``mu = inf`` gives full adhesion (the stick reference of the shift).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError


@dataclass
class FrictionSystem:
    """The affine maps above on n candidate pairs (arrays (n,) and (n, n)); ``load`` W (N/m);
    ``tangential_load`` Q (N/m, force on body 1) when delta_t is an unknown, else None and ``c_t`` unused;
    ``mu`` Coulomb coefficient (-), ``np.inf`` for full adhesion."""

    g0: np.ndarray
    c_n: np.ndarray
    G_p: np.ndarray
    G_q: np.ndarray
    s0: np.ndarray
    c_t: np.ndarray | None
    S_p: np.ndarray
    S_q: np.ndarray
    load: float
    tangential_load: float | None
    mu: float

    @property
    def n(self) -> int:
        return self.g0.size

    def gap(self, p, q, delta_n):
        return self.g0 + delta_n * self.c_n + self.G_p @ p + self.G_q @ q

    def slip(self, p, q, delta_t):
        s = self.s0 + self.S_p @ p + self.S_q @ q
        return s if self.c_t is None else s + delta_t * self.c_t


@dataclass
class FrictionSolution:
    """Solution like scipy.optimize's: pair forces ``p``, ``q`` (N/m), gaps ``gap`` (m), slips ``slip``,
    ``delta_n`` (m), ``delta_t`` (m, 0 without tangential load control), sets ``contact``, ``stick``,
    ``iterations``, ``residual`` (max of the scaled normal and friction complementarity residuals and the
    relative force balances), ``converged``."""

    p: np.ndarray
    q: np.ndarray
    gap: np.ndarray
    slip: np.ndarray
    delta_n: float
    delta_t: float
    contact: np.ndarray
    stick: np.ndarray
    iterations: int
    residual: float
    converged: bool


def _solve_sets(sys: FrictionSystem, contact, stick, sign):
    """One Newton step: the linear system of the current sets on the contact pairs only (pairs out of contact
    carry exactly p = q = 0), dense, rows scaled to comparable size."""
    n = sys.n
    load_t = sys.tangential_load is not None
    C = np.flatnonzero(contact)
    k = C.size
    st = stick[C]
    m = 2 * k + 1 + int(load_t)
    A = np.zeros((m, m))
    b = np.zeros(m)
    gs = 1.0 / np.abs(np.diag(sys.G_p)).mean()          # gap rows -> force units
    ss = 1.0 / max(np.abs(np.diag(sys.S_q)).mean(), 1e-300)
    ip, iq, idn, idt = slice(0, k), slice(k, 2 * k), 2 * k, 2 * k + 1
    # rows 0..k-1: closed gap g_i = 0
    A[:k, ip] = gs * sys.G_p[np.ix_(C, C)]
    A[:k, iq] = gs * sys.G_q[np.ix_(C, C)]
    A[:k, idn] = gs * sys.c_n[C]
    b[:k] = -gs * sys.g0[C]
    # rows k..2k-1: stick s_i = 0, or slip q_i + mu sigma_i p_i = 0
    r_st = k + np.flatnonzero(st)
    c_st = C[st]
    A[r_st, ip] = ss * sys.S_p[np.ix_(c_st, C)]
    A[r_st, iq] = ss * sys.S_q[np.ix_(c_st, C)]
    if load_t:
        A[r_st, idt] = ss * sys.c_t[c_st]
    b[r_st] = -ss * sys.s0[c_st]
    j_sl = np.flatnonzero(~st)
    A[k + j_sl, k + j_sl] = 1.0
    A[k + j_sl, j_sl] = sys.mu * sign[C[j_sl]]
    # force balances
    A[idn, ip] = 1.0
    b[idn] = sys.load
    if load_t:
        A[idt, iq] = 1.0
        b[idt] = sys.tangential_load
    z = np.linalg.solve(A, b)
    p = np.zeros(n)
    q = np.zeros(n)
    p[C], q[C] = z[ip], z[iq]
    return p, q, float(z[idn]), float(z[idt]) if load_t else 0.0


def _residual(sys: FrictionSystem, p, q, g, s, c_n, c_t) -> float:
    """Scaled residual of the Alart-Curnier equations and of the force balances."""
    p_ref = sys.load / max(1, np.count_nonzero(p > 0))
    r_n = np.abs(p - np.maximum(0.0, p - c_n * g)).max() / p_ref
    tau = -q
    bound = np.where(p > 0, sys.mu * np.maximum(p, 1e-300), 0.0)
    r_t = np.abs(tau - np.clip(tau + c_t * s, -bound, bound)).max() / p_ref
    r = max(r_n, r_t, abs(p.sum() - sys.load) / sys.load)
    if sys.tangential_load is not None:
        r = max(r, abs(q.sum() - sys.tangential_load) / sys.load)
    return float(r)


def solve(sys: FrictionSystem, contact0: np.ndarray, tol: float = 1e-9, max_iter: int = 60) -> FrictionSolution:
    """Primal-dual active set / semi-smooth Newton for Signorini + Coulomb on ``sys`` (see the module doc).

    ``contact0``: initial contact guess (e.g. the Hertz zone); the iteration starts from full stick.
    c_N = 1/mean diag G_p and c_T = 1/mean |diag S_q| make the two complementarity functions dimensionally
    consistent. Stops when contact set, stick set and slip signs repeat and the residual is below ``tol``;
    raises :class:`ConvergenceError` when the sets cycle or ``max_iter`` is reached.
    """
    c_n = 1.0 / np.abs(np.diag(sys.G_p)).mean()
    c_t = 1.0 / max(np.abs(np.diag(sys.S_q)).mean(), 1e-300)
    contact = np.asarray(contact0, bool).copy()
    stick = contact.copy()
    sign = np.zeros(sys.n)
    seen = set()
    res = np.inf
    for it in range(1, max_iter + 1):
        p, q, dn, dt = _solve_sets(sys, contact, stick, sign)
        g = sys.gap(p, q, dn)
        s = sys.slip(p, q, dt)
        p_aug = p - c_n * g
        z = -q + c_t * s
        new_contact = p_aug > 0
        new_stick = new_contact & (np.abs(z) <= sys.mu * p_aug)
        new_sign = np.where(new_contact & ~new_stick, np.sign(z), 0.0)
        if (np.array_equal(new_contact, contact) and np.array_equal(new_stick, stick)
                and np.array_equal(new_sign, sign)):
            res = _residual(sys, p, q, g, s, c_n, c_t)
            if res > tol:
                raise ConvergenceError("frictional active set", it, res, tol, "sets repeat but the residual "
                                       "is above tolerance (ill-conditioned contact system?)")
            return FrictionSolution(p, q, g, s, dn, dt, contact, stick, it, res, True)
        key = (new_contact.tobytes(), new_stick.tobytes(), new_sign.tobytes())
        if key in seen:
            res = _residual(sys, p, q, g, s, c_n, c_t)
            raise ConvergenceError("frictional active set", it, res, tol, "contact/stick/slip sets cycle")
        seen.add(key)
        contact, stick, sign = new_contact, new_stick, new_sign
        if not contact.any():
            raise ConvergenceError("frictional active set", it, np.inf, tol, "contact set became empty")
    raise ConvergenceError("frictional active set", max_iter, res, tol, "iteration limit reached")
