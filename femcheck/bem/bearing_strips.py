"""Coupled-slice model of a cylindrical roller bearing: each slice of a roller carries a Hertz strip at both its
contacts, and the slices see each other through the half-space and the finite bodies; the fast model between the
ISO/TS 16281 slices (:mod:`femcheck.bem.bearing_condensed3d`: independent slices, ``q ~ d^(10/9)``) and the
contact-resolved reference (:mod:`femcheck.bem.bearing_resolved`); SI units (m, N, rad).

The slices are uncoupled in ISO/TS 16281; along a crowned, misaligned roller that lumps the axial spreading of the
pressure into each slice's own law and misplaces the end slices' loads (by ~18 % of the largest slice on the 209
bearing of ``crb-3d-misaligned``). Here slice m of roller j carries q_jm (N) as an elliptical strip at each contact
c (inner, outer),

    p(x, y) = 2 w / (pi b) sqrt(1 - x^2/b^2),  |y - y_m| <= h = L_we/(2 n_s),  w = q/(2h),
    b_c = sqrt(4 R_c w / (pi E*))   (Johnson 1985 eq. 4.45; 1/R_i = 2/D + 1/r_i, 1/R_o = 2/D - 1/r_o),

and slice k's approach is the displacement on its centre line x = 0 averaged over its length (the 2D Hertz
approach is u(0): x^2/(2R) + u(x) is constant across the strip). For two equal elastic bodies
(u = (1/(pi E*)) int p/r dA, E* = E/(2(1 - nu^2)), Johnson 1985 §3.2):

    A_km(b) = 2/(pi^2 E* b (2h)^2) int_{-b}^{b} sqrt(1 - x^2/b^2) [F(s + 2h) - 2 F(s) + F(s - 2h)] dx,
    F(t) = t asinh(t/|x|) - sqrt(t^2 + x^2),   s = y_k - y_m,

(the two y-integrals of 1/r in closed form; the x-integral by Gauss-Legendre after x = b sin(pi tau^2/2), which
makes the logarithmic singularity of the self term at x = 0 smooth). The rollers and rings beyond the half-space
add the finite-body corrections D (m/N) of :mod:`femcheck.fem.crb_corrections` (FE minus half-space, per unit bin
force; bins = slices). With the slice load equal at a roller's two contacts (the roller has no other load, and the
two contacts' own compliances differ by under 1 % of their sum), the roller's radial motion and tilt cancel in the
sum of its two approaches, so the unknowns are those of the ISO model:

    g_jk = sum_m (A^i + A^o)_km q_jm + (D q)_jk - ((G u)_jk - c_jk) >= 0,   q_jk >= 0,   q_jk g_jk = 0,
    G^T q = F,

with G, c the kinematics of :func:`femcheck.bem.bearing_condensed3d.kinematics` (crown drop averaged over each
slice, as the approach is), D = the roller's four blocks summed + both rings' tables. Solver: for fixed strip
widths an active-set loop on the KKT system (dense, Z n_s + 2 unknowns), then the widths from the loads, to a
fixed point (the approach depends on b only through a logarithm). Iterations and residuals are reported;
non-convergence raises :class:`femcheck.errors.ConvergenceError`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..analytic.iso16281 import crown_drop, crown_drop_slice_means
from ..errors import ConvergenceError
from ..materials import Elastic
from .bearing_condensed3d import SlicedRow, kinematics


def _rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    t, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (t + 1.0), 0.5 * w                    # on (0, 1)


# 48 points for a strip and its neighbours (the self term's logarithm at x = 0); 8 beyond, where the kernel is smooth
# over |x| <= b << |s| (8 points: 4e-9 relative at s = 2 lengths; 48 points: 1.2e-7 on the self term, against 400)
_NEAR, _FAR = _rule(48), _rule(8)


def _F(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """F(t) = t asinh(t/x) - sqrt(t^2 + x^2) (x > 0): the double y-integral's antiderivative of 1/r."""
    return t * np.arcsinh(t / x) - np.hypot(t, x)


def _integral(s: np.ndarray, b: np.ndarray, length: float, rule) -> np.ndarray:
    tau, wt = rule
    theta = 0.5 * np.pi * tau**2                       # x = b sin(theta): dx = b cos(theta) pi tau dtau
    x = b[..., None] * np.sin(theta)
    kern = _F(s[..., None] + length, x) - 2.0 * _F(s[..., None], x) + _F(s[..., None] - length, x)
    # 2 int_0^b sqrt(1 - x^2/b^2) kern dx = 2 b int_0^1 cos^2(theta) pi tau kern dtau
    return 2.0 * b * (kern * (np.cos(theta) ** 2 * np.pi * tau * wt)).sum(axis=-1)


def strip_influence(s: np.ndarray, b: np.ndarray, length: float, e_star: float) -> np.ndarray:
    """A(s, b) (m/N): mean approach on the centre line of a slice of length ``length`` at axial offset ``s`` (m)
    from a unit-load elliptical strip of half-width ``b`` (m) and the same length (module doc); broadcasts over
    s and b."""
    s, b = np.broadcast_arrays(np.asarray(s, dtype=float), np.asarray(b, dtype=float))
    out = np.empty(s.shape)
    near = np.abs(s) < 1.5 * length
    out[near] = _integral(s[near], b[near], length, _NEAR)
    out[~near] = _integral(s[~near], b[~near], length, _FAR)
    return 2.0 / (np.pi**2 * e_star * b * length**2) * out


@dataclass
class StripsResult:
    """``slice_loads`` q[j, k] (N), ``roller_loads`` Q_j (N), ``u`` (m) with ``dofs``, ``half_widths`` b[c, j, k]
    (m), active-set ``iterations`` (summed), width fixed-point ``width_iterations``, ``residual`` (the largest
    complementarity and equilibrium violation, scaled by the largest approach and F), ``time_s``."""

    slice_loads: np.ndarray
    roller_loads: np.ndarray
    u: np.ndarray
    dofs: tuple[str, ...]
    half_widths: np.ndarray
    iterations: int
    width_iterations: int
    residual: float
    time_s: float

    @property
    def q_max(self) -> float:
        return float(self.roller_loads.max())


def _active_set(M: np.ndarray, G: np.ndarray, c: np.ndarray, F: np.ndarray, active: np.ndarray,
                max_iter: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """The LCP of the module doc for a fixed M: returns (q, u, active, iterations)."""
    n, m = G.shape
    for it in range(1, max_iter + 1):
        S = np.flatnonzero(active)
        K = np.block([[M[np.ix_(S, S)], -G[S]], [G[S].T, np.zeros((m, m))]])
        sol = np.linalg.solve(K, np.concatenate([-c[S], F]))
        q = np.zeros(n)
        q[S], u = sol[:S.size], sol[S.size:]
        gap = M @ q - (G @ u - c)
        neg = active & (q < 0.0)
        pen = ~active & (gap < -1e-14 * np.abs(c).max())
        if not neg.any() and not pen.any():
            return q, u, active, it
        active = active.copy()
        if neg.any():                      # drop the tensile slices first (the LCP's usual pivoting order)
            active[neg] = False
        else:
            active[pen] = True
    raise ConvergenceError("coupled slices: active set", max_iter, float("nan"), 0.0)


def solve(row: SlicedRow, r_inner: float, r_outer: float, material: Elastic, D: np.ndarray | None,
          radial_load: float, tol: float = 1e-10, max_widths: int = 50, max_active: int = 200) -> StripsResult:
    """Equilibrium of the module doc: ``r_inner``, ``r_outer`` raceway radii (m), ``material`` of all bodies,
    ``D`` (Z n_s, Z n_s) m/N the summed finite-body corrections (None: half-spaces only); prescribed
    misalignment as in ``row``; ``tol`` on the slice loads' change between width iterations (relative to the
    largest)."""
    if row.free_tilt:
        raise ValueError("the coupled-slice model holds the misalignment prescribed (free_tilt is not supported)")
    t0 = time.perf_counter()
    Z, ns, L, Dw = row.rollers, row.slices, row.length, row.diameter
    G, c, dofs = kinematics(row)
    if row.crown == "iso":             # the slice-mean drop, as the approach is a slice mean (module doc)
        c = c + np.tile(2.0 * (crown_drop_slice_means(L, Dw, ns) - crown_drop(row.x, L, Dw)), Z)
    e_star = material.E / (2.0 * (1.0 - material.nu**2))
    h2 = L / ns
    y = row.x
    s = y[:, None] - y[None, :]
    radii = (1.0 / (2.0 / Dw + 1.0 / r_inner), 1.0 / (2.0 / Dw - 1.0 / r_outer))
    F = np.array([radial_load, 0.0])
    D = np.zeros((Z * ns, Z * ns)) if D is None else np.asarray(D, dtype=float)
    # start: every slice loaded with the mean roller load's width
    q = np.full(Z * ns, radial_load / (Z * ns))
    active = np.ones(Z * ns, dtype=bool)
    total_it = 0
    for wit in range(1, max_widths + 1):
        # an unloaded strip's width only matters once it loads: take 1e-3 of the largest (a start for the next pass)
        w = np.maximum(q, 1e-3 * q.max()) / h2
        b = np.stack([np.sqrt(4.0 * R * w / (np.pi * e_star)) for R in radii]).reshape(2, Z, ns)
        M = D.copy()
        for j in np.flatnonzero(active.reshape(Z, ns).any(axis=1)):     # an unloaded roller's columns carry q = 0
            blk = strip_influence(s, b[0, j][None, :], h2, e_star) + strip_influence(s, b[1, j][None, :], h2, e_star)
            M[j * ns:(j + 1) * ns, j * ns:(j + 1) * ns] += blk
        q_new, u, active, it = _active_set(M, G, c, F, active, max_active)
        total_it += it
        change = np.abs(q_new - q).max() / q_new.max()
        q = q_new
        if change < tol:
            gap = M @ q - (G @ u - c)
            res = max(np.abs(np.minimum(gap, 0.0)).max() / np.abs(G @ u - c).max(),
                      np.abs(G.T @ q - F).max() / radial_load)
            return StripsResult(q.reshape(Z, ns), q.reshape(Z, ns).sum(axis=1), u, dofs, b, total_it, wit, float(res),
                                time.perf_counter() - t0)
    raise ConvergenceError("coupled slices: strip widths", max_widths, float(change), tol)

