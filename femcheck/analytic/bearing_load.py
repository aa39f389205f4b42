"""Load distribution over the rollers of a bearing with rigid rings (Stribeck 1901; Sjövall 1933; Harris &
Kotzalas 2007, *Essential Concepts of Bearing Technology*, ch. 7; spec bearing-load.md §3.1), SI units.

Rollers j = 0..Z-1 sit at psi_j = 2 pi j / Z - theta_F from the load line (theta_F = ``load_angle``, the load
line's angle from roller 0). With rigid rings and the inner ring displaced by delta = (delta_x, delta_y) in the
radial plane (x along the load), roller j is compressed by

    delta_j = (delta_x cos psi_j + delta_y sin psi_j) cos alpha + delta_a sin alpha - (P_d/2) cos alpha

(P_d: diametral clearance, negative for preload; alpha: contact angle; delta_a axial displacement) and carries
Q_j = law(delta_j) >= 0. Equilibrium sum_j Q_j dd_j/du = F is the stationarity of the convex potential
Pi(u) = sum_j E(delta_j(u)) - F.u (E = int Q d delta), which :func:`solve_rigid` minimises by Newton's method
(Armijo backtracking, minimum-norm steps where no roller resists, a slide to the next roller where the load has
a component no loaded roller carries). The same solver handles ISO/TS 16281 slices and multi-row bearings
(:mod:`femcheck.analytic.iso16281`): every slice is one "contact" row of the matrix G.

Z -> infinity: Q(psi) = Q_max [1 - (1 - cos psi)/(2 eps)]^n with eps = (1 - P_d/(2 delta_r))/2 and
F_r = Z Q_max J_r(eps) cos alpha, F_a = Z Q_max J_a(eps) sin alpha, where (Sjövall)

    J_r(eps) = 1/(2 pi) int_{-psi_l}^{psi_l} [1 - (1 - cos psi)/(2 eps)]^n cos psi dpsi,   J_a: without cos psi,

psi_l = arccos(1 - 2 eps) (pi for eps >= 1). Constants: 1/J_r(0.5) = 4.3701 (n = 3/2), 4.0850 (n = 10/9), 4 (n = 1).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

from ..errors import ConvergenceError


def load_zone_half_angle(eps: float) -> float:
    """psi_l = arccos(1 - 2 eps) (rad), pi for eps >= 1, 0 for eps <= 0."""
    return float(np.arccos(np.clip(1.0 - 2.0 * eps, -1.0, 1.0)))


def load_integrals(eps: float, exponent: float) -> tuple[float, float]:
    """Sjövall's integrals (J_r, J_a) for load-zone parameter ``eps`` and load-deflection exponent n (module
    doc); adaptive quadrature to 1e-12 relative. eps <= 0 gives (0, 0)."""
    if eps <= 0:
        return 0.0, 0.0
    psi_l = load_zone_half_angle(eps)
    shape = lambda p: max(0.0, 1.0 - (1.0 - np.cos(p)) / (2.0 * eps)) ** exponent
    opts = {"epsabs": 0.0, "epsrel": 1e-12, "limit": 200}
    jr = quad(lambda p: shape(p) * np.cos(p), 0.0, psi_l, **opts)[0] / np.pi
    ja = quad(shape, 0.0, psi_l, **opts)[0] / np.pi
    return float(jr), float(ja)


@dataclass
class Equilibrium:
    """Solution of :func:`solve_rigid`: displacement ``u`` (m / rad), contact deflections ``delta`` (m) and loads
    ``q`` (N), Newton ``iterations`` and the relative force ``residual`` |G^T q - F| / |F|."""

    u: np.ndarray
    delta: np.ndarray
    q: np.ndarray
    iterations: int
    residual: float


def solve_rigid(G: np.ndarray, c: np.ndarray, law, F: np.ndarray, u0: np.ndarray | None = None,
                tol: float = 1e-11, max_iter: int = 200) -> Equilibrium:
    """Minimise Pi(u) = sum_i E(G_i . u - c_i) - F . u: contact i has deflection delta_i = G_i . u - c_i and load
    law.load(delta_i); stationarity is the equilibrium G^T q = F. Newton with Armijo backtracking; where the
    Hessian G^T diag(k) G is singular (directions no loaded contact resists) the step is the minimum-norm one,
    and a load component in such a direction slides u to the next contact that engages. Raises
    ConvergenceError when no contact can carry the load or the residual stays above ``tol``."""
    G = np.asarray(G, dtype=float)
    c = np.asarray(c, dtype=float)
    F = np.asarray(F, dtype=float)
    fnorm = float(np.linalg.norm(F))
    if fnorm == 0.0:
        u = np.zeros(G.shape[1]) if u0 is None else np.asarray(u0, float)
        return Equilibrium(u, G @ u - c, np.zeros(len(c)), 0, 0.0)
    # Work relative to the starting point: u = u0 + v with offsets c' = c - G u0. With a large clearance the
    # deflections delta = G u - c of lightly loaded rollers are tiny differences of large numbers; this way the
    # cancellation happens once, in c' (a clearance change of a few 1e-21 m), and equilibrium is then met to
    # round-off instead of stalling at |delta| * 1e-16.
    origin = np.zeros(G.shape[1]) if u0 is None else np.asarray(u0, dtype=float).copy()
    c = c - G @ origin
    u = np.zeros(G.shape[1])
    span = law_span(law)

    def potential(v: np.ndarray) -> float:
        dv = G @ v - c
        if dv.max() > span:              # beyond the law's range: reject the step
            return np.inf
        return float(np.sum(law.energy(dv)) - F @ v)
    scale = max(float(np.abs(c).max()), 1e-12)
    for it in range(1, max_iter + 1):
        d = G @ u - c
        q = law.load(d)
        grad = G.T @ q - F
        res = float(np.linalg.norm(grad)) / fnorm
        if res <= tol:
            return Equilibrium(origin + u, d, q, it - 1, res)
        k = law.stiffness(d)
        H = G.T @ (k[:, None] * G)
        step, *_ = np.linalg.lstsq(H, -grad, rcond=1e-13)
        # the part of the gradient in the Hessian's null space: load that no loaded contact resists
        Hn = np.linalg.norm(H)
        null = -grad - (H @ np.linalg.pinv(H, rcond=1e-13) @ -grad if Hn > 0 else 0.0)
        if np.linalg.norm(null) > 1e-9 * np.linalg.norm(grad):
            rate = G @ null
            room = -d
            engage = (rate > 0) & (room > -1e-15 * scale)
            if not engage.any():
                raise ConvergenceError("rigid-ring equilibrium", it, res, tol,
                                       "no roller can carry the load in this direction")
            t = float(np.min(np.where(engage, room, np.inf)[engage] / rate[engage]))
            u = u + (t + 1e-9 * scale / float(np.max(rate[engage]))) * null
            continue
        # Armijo backtracking on the convex potential; near the solution the potential's change drowns in its
        # round-off (|Pi| ~ F delta, changes ~ res^2), so a step that lowers the force residual is accepted too
        p0, slope, t = potential(u), float(grad @ step), 1.0
        while t > 1e-12:
            cand = u + t * step
            pc = potential(cand)
            if pc <= p0 + 1e-4 * t * slope:
                break
            if np.isfinite(pc) and abs(pc - p0) <= 1e-12 * (abs(p0) + fnorm * scale) and \
                    np.linalg.norm(G.T @ law.load(G @ cand - c) - F) < np.linalg.norm(grad):
                break
            t *= 0.5
        u = u + t * step
    d = G @ u - c
    q = law.load(d)
    res = float(np.linalg.norm(G.T @ q - F)) / fnorm
    raise ConvergenceError("rigid-ring equilibrium", max_iter, res, tol, "Newton iterations exhausted")


@dataclass
class RigidRing:
    """Discrete rigid-ring solution of a single-row bearing. ``psi`` (rad from the load line), ``deflection``
    delta_j (m, negative = gap), ``loads`` Q_j (N), ``displacement`` (delta_x, delta_y[, delta_a]) of the inner
    ring (m), ``radial_deflection`` |(delta_x, delta_y)| (m), ``eps`` and ``load_zone_angle`` (rad, half-angle)
    from the rigid-ring relation cos psi_l = -c0/(delta_r cos alpha), c0 = delta_a sin alpha - (P_d/2) cos alpha."""

    psi: np.ndarray
    deflection: np.ndarray
    loads: np.ndarray
    displacement: np.ndarray
    radial_deflection: float
    eps: float
    load_zone_angle: float
    iterations: int
    residual: float
    axial_reaction: float = 0.0
    stats: dict = field(default_factory=dict)

    @property
    def q_max(self) -> float:
        return float(self.loads.max())

    @property
    def loaded(self) -> int:
        return int(np.count_nonzero(self.loads > 0))


def roller_angles(rollers: int, load_angle: float) -> np.ndarray:
    """psi_j = 2 pi j / Z - load_angle, wrapped to (-pi, pi]."""
    psi = 2.0 * np.pi * np.arange(rollers) / rollers - load_angle
    return np.angle(np.exp(1j * psi))


def rigid_ring(rollers: int, clearance: float, law, radial_load: float, load_angle: float = 0.0,
               axial_load: float = 0.0, contact_angle: float = 0.0) -> RigidRing:
    """Single-row rigid-ring distribution (module doc). ``clearance`` P_d (m, diametral; < 0 preload),
    ``radial_load`` F_r (N) along the load line, ``axial_load`` F_a (N). With a contact angle and no axial
    load the inner ring is held axially (delta_a = 0) and the induced axial force sum Q_j sin alpha is reported
    as ``axial_reaction``; with an axial load delta_a is free."""
    psi = roller_angles(rollers, load_angle)
    ca, sa = np.cos(contact_angle), np.sin(contact_angle)
    free_axial = axial_load > 0 and contact_angle > 0
    G = np.column_stack([np.cos(psi) * ca, np.sin(psi) * ca] + ([np.full_like(psi, sa)] if free_axial else []))
    c = np.full_like(psi, 0.5 * clearance * ca)
    F = np.array([radial_load, 0.0] + ([axial_load] if free_axial else []))
    # start where the roller on (or nearest to) the load line carries the whole load: Newton then only adds rollers
    j0 = int(np.argmax(np.cos(psi)))
    d0 = float(law.deflection(radial_load / max(np.cos(psi[j0]) * ca, 1e-3)))
    u0 = np.zeros(G.shape[1])
    u0[0] = (0.5 * clearance * ca + min(d0, 0.5 * law_span(law))) / (np.cos(psi[j0]) * ca)
    sol = solve_rigid(G, c, law, F, u0)
    dx, dy = sol.u[0], sol.u[1]
    da = sol.u[2] if free_axial else 0.0
    dr = float(np.hypot(dx, dy))
    c0 = da * sa - 0.5 * clearance * ca
    eps = 0.5 * (1.0 + c0 / (dr * ca)) if dr > 0 else np.inf
    zone = float(np.arccos(np.clip(-c0 / (dr * ca), -1.0, 1.0))) if dr > 0 else 0.0
    reaction = float(np.sum(sol.q) * sa) if not free_axial else 0.0
    return RigidRing(psi, sol.delta, sol.q, sol.u, dr, float(eps), zone, sol.iterations, sol.residual, reaction)


def law_span(law) -> float:
    """Largest deflection a law covers (m): the 2D law's range, unbounded for power laws."""
    return float(getattr(law, "max_deflection", np.inf))


@dataclass
class IntegralModel:
    """Z -> infinity (continuous) distribution: ``q_max`` (N), ``radial_deflection`` delta_r (m), ``eps``,
    ``load_zone_angle`` psi_l (rad), (J_r, J_a) = F_r/(Z Q_max cos alpha), F_a/(Z Q_max sin alpha)."""

    q_max: float
    radial_deflection: float
    eps: float
    load_zone_angle: float
    j_r: float
    j_a: float
    iterations: int
    clearance: float = 0.0
    contact_angle: float = 0.0

    def load(self, psi: np.ndarray, law) -> np.ndarray:
        """Roller load Q(psi) (N) at angle psi from the load line."""
        ca = np.cos(self.contact_angle)
        return law.load((self.radial_deflection * np.cos(psi) - 0.5 * self.clearance) * ca)


def integral_model(rollers: int, clearance: float, law, radial_load: float, contact_angle: float = 0.0) -> IntegralModel:
    """The continuous limit of :func:`rigid_ring` for a radial load (delta_a = 0): solve
    F_r = Z/(2 pi) int Q(delta_r cos psi cos alpha - (P_d/2) cos alpha) cos psi cos alpha dpsi for delta_r
    (monotone: Brent's method), for any law; for a power law this is Z Q_max J_r(eps) cos alpha."""
    ca = np.cos(contact_angle)
    opts = {"epsabs": 0.0, "epsrel": 1e-12, "limit": 200}

    def force(dr: float) -> float:
        lim = np.arccos(np.clip(0.5 * clearance / dr, -1.0, 1.0))
        return rollers / np.pi * quad(lambda p: float(law.load((dr * np.cos(p) - 0.5 * clearance) * ca))
                                      * np.cos(p) * ca, 0.0, lim, **opts)[0]

    lo = max(0.5 * clearance, 0.0) + 1e-300
    hi = max(abs(clearance), float(law.deflection(radial_load / ca))) + 1e-12
    span = law_span(law)
    if np.isfinite(span):
        hi = min(hi, 0.5 * clearance + span / ca * (1 - 1e-12)) if clearance > 0 else min(hi, span / ca)
    it = 0
    while force(hi) < radial_load:
        hi *= 2.0
        it += 1
        if it > 200:
            raise ConvergenceError("integral model", it, np.inf, 0.0, "no deflection carries the load")
    dr = brentq(lambda d: force(d) - radial_load, lo, hi, xtol=1e-18, rtol=1e-14, maxiter=200)
    q_max = float(law.load((dr - 0.5 * clearance) * ca))
    eps = 0.5 * (1.0 - 0.5 * clearance / dr)
    axial = rollers / np.pi * quad(lambda p: float(law.load((dr * np.cos(p) - 0.5 * clearance) * ca)), 0.0,
                                   np.arccos(np.clip(0.5 * clearance / dr, -1.0, 1.0)), **opts)[0]
    return IntegralModel(q_max, float(dr), float(eps), load_zone_half_angle(eps),
                         radial_load / (rollers * q_max * ca), axial / (rollers * q_max), it, clearance,
                         contact_angle)


def zone_from_profile(psi: np.ndarray, s: np.ndarray) -> tuple[float, float]:
    """Load-zone half-angle psi_l (rad) and parameter eps from a discrete interference profile s_j (m: positive =
    roller compressed, negative = free room) at angles psi_j from the load line: on each side the rigid-ring form
    s = delta_r cos psi - c is fitted through the last loaded and the first unloaded roller, cos psi_l = c/delta_r,
    eps = (1 - c/delta_r)/2; the two sides are averaged. When every roller is loaded the fit goes through the
    least-loaded roller and its neighbour on each side (eps > 1, psi_l = pi). For a rigid-ring solution with the
    load on a symmetry line this returns exactly arccos(P_d/(2 delta_r)) and (1 - P_d/(2 delta_r))/2."""
    order = np.argsort(psi)
    p, v = np.asarray(psi, float)[order], np.asarray(s, float)[order]
    z = len(p)
    ratios = []
    for side in (1, -1):
        # walk from the most compressed roller towards one side until s changes sign
        k = int(np.argmax(v))
        for _ in range(z):
            nxt = (k + side) % z
            if v[nxt] <= 0 or nxt == int(np.argmax(v)):
                break
            k = nxt
        nxt = (k + side) % z
        if v[nxt] > 0:           # every roller loaded: use the least loaded one and its neighbour
            k = int(np.argmin(v))
            nxt = (k - side) % z
        ca, cb = np.cos(p[k]), np.cos(p[nxt])
        if np.isclose(ca, cb):
            continue
        dr = (v[k] - v[nxt]) / (ca - cb)
        ratios.append((dr * ca - v[k]) / dr)
    if not ratios:
        return float("nan"), float("nan")
    r = float(np.mean(ratios))
    return float(np.arccos(np.clip(r, -1.0, 1.0))), 0.5 * (1.0 - r)
