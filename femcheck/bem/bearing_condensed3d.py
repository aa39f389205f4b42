"""3D condensed bearing model (spec bearing-load.md P3): a single-row cylindrical roller bearing
with an elastic outer ring, whose compliance comes from a coarse 3D FE condensed onto the raceway slices
(:mod:`femcheck.fem.ring3d_compliance`), coupled with the ISO/TS 16281 slice law (crowning, misalignment) and
solved for the inner ring's rigid displacements; SI units (m, N, rad).

Roller j at psi_j (rad from the load line, :func:`femcheck.analytic.bearing_load.roller_angles`), slice k at
x_k along the roller (:func:`femcheck.analytic.iso16281.slice_positions`). The inner ring (rigid) moves by
u = (delta_x, delta_y[, theta_x, theta_y]); the point of its raceway under slice (j, k) moves radially by
(G u)_jk = delta_x cos psi_j + delta_y sin psi_j + x_k (theta_y cos psi_j - theta_x sin psi_j) (the radial component
of delta + theta x p, p = r e_r + x_k e_z; the same rows as :func:`femcheck.analytic.iso16281.sliced_equilibrium`).
The slice's elastic deflection (both Hertz contacts, the ISO law's) is what the rigid approach leaves after the
outer raceway has given way:

    d_jk = (G u)_jk - c_jk - sum_lm C_jk,lm q_lm,     q_jk = (c_L/n_s) max(d_jk, 0)^(10/9)   (ISO/TS 16281),
    c_jk = G_r/2 + 2 P(x_k) + x_k tan(theta_mis) cos psi_j,
    equilibrium   G^T q = F = (F_x, F_y[, M_x, M_y]),

with C (m/N) the condensed raceway compliance (patch-averaged radial displacement per unit slice load, away
from the roller; the sum C_outer + C_inner when both rings are elastic: the inner ring on a rigid shaft is the
same builder with its bore clamped), G_r the
diametral clearance, P the ISO logarithmic crown drop of the roller (TS eqs 42-44, both contacts: factor 2) and
theta_mis a prescribed misalignment of the inner ring (its tilt DOFs are then held); with ``free_tilt`` the tilt
is solved for the applied moments instead. C = 0 is the rigid-ring ISO/TS 16281 model.

Solver: Newton on (d, u) for the residuals

    R_1 = d + C q(d) - G u + c = 0,    R_2 = G^T q(d) - F = 0,
    J = [[I + C diag(k), -G], [G^T diag(k), 0]],  k = dq/dd = (10/9)(c_L/n_s) d^(1/9) (0 where open),

started from the rigid-ring solution (C = 0, :func:`femcheck.analytic.bearing_load.solve_rigid`), with
backtracking on the scaled residual max(|R_1|/d_ref, |R_2|/|F|); every slice (open or closed) is an unknown, so the
active set needs no separate loop. The iterations and the residual are reported; non-convergence raises
:class:`femcheck.errors.ConvergenceError`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..analytic.bearing_load import roller_angles, solve_rigid
from ..analytic.iso16281 import crown_drop, slice_law, slice_positions
from ..errors import ConvergenceError


@dataclass(frozen=True)
class SlicedRow:
    """One row of cylindrical rollers: Z ``rollers``, effective ``length`` L_we and ``diameter`` D_we (m),
    diametral ``clearance`` G_r (m), ``slices`` n_s, ``crown`` "none" | "iso", prescribed ``misalignment``
    theta_mis (rad) or ``free_tilt`` (tilt DOFs solved for ``moments``), ``load_angle`` (rad)."""

    rollers: int
    length: float
    diameter: float
    clearance: float = 0.0
    slices: int = 10
    crown: str = "none"
    misalignment: float = 0.0
    free_tilt: bool = False
    load_angle: float = 0.0

    @property
    def psi(self) -> np.ndarray:
        return roller_angles(self.rollers, self.load_angle)

    @property
    def x(self) -> np.ndarray:
        return slice_positions(self.length, self.slices)


def kinematics(row: SlicedRow) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """(G (Z n_s, n_dof), c (Z n_s,), dof names) of the module doc; row index j n_s + k."""
    psi, xk = row.psi, row.x
    cp, sp = np.cos(psi)[:, None], np.sin(psi)[:, None]
    ones = np.ones((1, row.slices))
    cols = [cp * ones, sp * ones]
    dofs = ("delta_x", "delta_y")
    if row.free_tilt:
        cols += [-xk[None, :] * sp, xk[None, :] * cp]
        dofs += ("theta_x", "theta_y")
    G = np.stack(cols, axis=-1).reshape(-1, len(dofs))
    drop = 2.0 * crown_drop(xk, row.length, row.diameter) if row.crown == "iso" else np.zeros(row.slices)
    c = 0.5 * row.clearance + drop[None, :] + np.tan(row.misalignment) * xk[None, :] * cp
    return G, c.ravel(), dofs


@dataclass
class Condensed3DResult:
    """``slice_loads`` q[j, k] (N), ``roller_loads`` Q_j (N), ``deflection`` d[j, k] (m), ``u`` (m, rad) with
    ``dofs``, ``raceway`` (C q)[j, k] (m: the outer raceway's patch-averaged radial displacement), Newton
    ``iterations``, scaled ``residual``, solve ``time_s``."""

    slice_loads: np.ndarray
    roller_loads: np.ndarray
    deflection: np.ndarray
    u: np.ndarray
    dofs: tuple[str, ...]
    raceway: np.ndarray
    iterations: int
    residual: float
    time_s: float

    @property
    def q_max(self) -> float:
        return float(self.roller_loads.max())


def _loads(row: SlicedRow, radial_load: float, moments: tuple[float, float]) -> np.ndarray:
    F = [radial_load, 0.0]
    if row.free_tilt:
        F += list(moments)
    return np.array(F)


def solve(row: SlicedRow, C: np.ndarray | None, radial_load: float, moments: tuple[float, float] = (0.0, 0.0),
          tol: float = 1e-11, max_iter: int = 100) -> Condensed3DResult:
    """Equilibrium of the module doc for the compliance ``C`` (Z n_s x Z n_s, m/N; None: rigid rings)."""
    t0 = time.perf_counter()
    G, c, dofs = kinematics(row)
    law = slice_law(row.length, row.slices)
    F = _loads(row, radial_load, moments)
    n = G.shape[0]
    # rigid-ring start (the rigid ISO/TS 16281 equilibrium with the same rows)
    u0 = np.zeros(len(dofs))
    u0[0] = 0.5 * row.clearance + float(law.deflection(5.0 * radial_load / (row.rollers * row.slices))) \
        + float(c.max() - 0.5 * row.clearance)
    rig = solve_rigid(G, c, law, F, u0)
    u = rig.u.copy()
    if C is None:
        d = rig.delta
        q = law.load(d)
        return Condensed3DResult(q.reshape(row.rollers, -1), q.reshape(row.rollers, -1).sum(axis=1),
                                 d.reshape(row.rollers, -1), u, dofs, np.zeros((row.rollers, row.slices)),
                                 rig.iterations, rig.residual, time.perf_counter() - t0)
    C = np.asarray(C, dtype=float)
    if C.shape != (n, n):
        raise ValueError(f"compliance must be ({n}, {n}) for {row.rollers} rollers x {row.slices} slices, "
                         f"got {C.shape}")
    d, u, it, res = newton(G, c, law, F, C, rig, tol, max_iter)
    q = law.load(d)
    Z = row.rollers
    return Condensed3DResult(q.reshape(Z, -1), q.reshape(Z, -1).sum(axis=1), d.reshape(Z, -1), u, dofs,
                             (C @ q).reshape(Z, -1), it, res, time.perf_counter() - t0)


def newton(G: np.ndarray, c: np.ndarray, law, F: np.ndarray, C: np.ndarray, rigid, tol: float = 1e-11,
           max_iter: int = 100) -> tuple[np.ndarray, np.ndarray, int, float]:
    """(d, u, iterations, scaled residual) of the module doc's Newton for any slice kinematics (G, c), slice
    ``law``, loads ``F`` and compliance ``C`` (m/N), started from the rigid-ring equilibrium ``rigid``
    (:func:`femcheck.analytic.bearing_load.solve_rigid` with the same G, c, law, F)."""
    n, m = G.shape
    u = rigid.u.copy()
    d = rigid.delta.copy()
    d_ref = max(float(np.abs(rigid.delta).max()), 1e-12)
    f_ref = float(np.linalg.norm(F))

    def residual(d, u):
        q = law.load(d)
        r1 = d + C @ q - G @ u + c
        r2 = G.T @ q - F
        return r1, r2, max(float(np.abs(r1).max()) / d_ref, float(np.abs(r2).max()) / f_ref)

    r1, r2, res = residual(d, u)
    it = 0
    while res > tol:
        if it >= max_iter:
            raise ConvergenceError("3D condensed bearing (Newton)", it, res, tol, "iterations exhausted")
        it += 1
        k = law.stiffness(d)
        J = np.zeros((n + m, n + m))
        J[:n, :n] = C * k[None, :]
        J[np.arange(n), np.arange(n)] += 1.0
        J[:n, n:] = -G
        J[n:, :n] = G.T * k[None, :]
        step = np.linalg.solve(J, -np.concatenate([r1, r2]))
        t = 1.0
        while True:
            d_new, u_new = d + t * step[:n], u + t * step[n:]
            n1, n2, res_new = residual(d_new, u_new)
            if res_new < (1.0 - 1e-4 * t) * res or t < 1e-10:
                break
            t *= 0.5
        if t < 1e-10:
            raise ConvergenceError("3D condensed bearing (Newton)", it, res, tol, "line search failed")
        d, u, r1, r2, res = d_new, u_new, n1, n2, res_new
    return d, u, it, res


def solve_direct(row: SlicedRow, K, free: np.ndarray, B: np.ndarray, radial_load: float,
                 moments: tuple[float, float] = (0.0, 0.0), tol: float = 1e-10, max_iter: int = 60) -> Condensed3DResult:
    """The same equilibrium without condensation: Newton on the whole FE ring (free DOFs U) with the nonlinear
    slice springs attached to its patches and the inner ring's rigid DOFs u, i.e. the stationary point of the
    convex potential Pi(U, u) = U^T K U/2 + sum E(G u - c - B^T U) - F . u (E: the slice law's energy):

        K U - B q(d) = 0,   G^T q(d) - F = 0,   d = G u - c - B^T U,
        Hessian [[K + B k B^T, -B k G], [-G^T k B^T, G^T k G]]  (sparse, factorised by PARDISO each iteration),

    with backtracking on Pi. The reference for :func:`solve`: it checks the condensation itself."""
    from scipy.sparse import bmat, csr_matrix, diags
    import pypardiso

    t0 = time.perf_counter()
    G, c, dofs = kinematics(row)
    law = slice_law(row.length, row.slices)
    F = _loads(row, radial_load, moments)
    Kf = K[free][:, free].tocsr()
    Bf = csr_matrix(B[free])
    rig = solve_rigid(G, c, law, F)
    u = rig.u.copy()
    U = np.zeros(Kf.shape[0])
    f_ref = float(np.linalg.norm(F))

    def state(U, u):
        d = G @ u - c - Bf.T @ U
        q = law.load(d)
        gU = Kf @ U - Bf @ q
        gu = G.T @ q - F
        pot = 0.5 * U @ (Kf @ U) + float(np.sum(law.energy(d))) - F @ u
        return d, q, gU, gu, pot

    d, q, gU, gu, pot = state(U, u)
    ref_U = None
    for it in range(1, max_iter + 1):
        k = law.stiffness(d)
        Kd = diags(k)
        H = bmat([[Kf + Bf @ Kd @ Bf.T, -Bf @ Kd @ csr_matrix(G)],
                  [-csr_matrix(G).T @ Kd @ Bf.T, csr_matrix(G.T @ (k[:, None] * G))]], format="csr")
        step = pypardiso.spsolve(H, -np.concatenate([gU, gu]))
        dU, du = step[:Kf.shape[0]], step[Kf.shape[0]:]
        t = 1.0
        while t > 1e-10:
            cand = state(U + t * dU, u + t * du)
            if cand[4] <= pot + 1e-4 * t * float(np.concatenate([gU, gu]) @ step) or \
                    np.linalg.norm(cand[3]) < 0.5 * np.linalg.norm(gu):
                break
            t *= 0.5
        U, u = U + t * dU, u + t * du
        d, q, gU, gu, pot = cand
        ref_U = max(float(np.abs(Bf @ q).max()), 1e-300)
        res = max(float(np.abs(gU).max()) / ref_U, float(np.abs(gu).max()) / f_ref)
        if res < tol:
            Z = row.rollers
            return Condensed3DResult(q.reshape(Z, -1), q.reshape(Z, -1).sum(axis=1), d.reshape(Z, -1), u, dofs,
                                     (Bf.T @ U).reshape(Z, -1), it, res, time.perf_counter() - t0)
    raise ConvergenceError("3D bearing, direct FE Newton", max_iter, res, tol, "iterations exhausted")
