"""Frictionless contact of a rigid analytic indenter with a meshed 3D body in mortar form: the contact pressure
is a field of the discrete problem, p_h = sum_i lam_i psi_i with psi_i the linear (P1) hat functions of the
contact face's corner nodes, for linear (P1) or quadratic (P2) displacements.

Weak Signorini conditions (Wohlmuth, Acta Numerica 20, 2011, §3-4; Hueeber & Wohlmuth, CMAME 194, 2005): with
the initial gap h(x, y), the rigid approach delta and the body's normal displacement u_z on the face z = 0,

    g_i = int psi_i (h - delta - u_z) dA >= 0,   lam_i >= 0,   lam_i g_i = 0,   sum_i lam_i w_i = F,

w_i = int psi_i dA. ``lam_i`` are the nodal values of the pressure (Pa), so p_h >= 0 everywhere and the peak of
a centred contact is the centre node's value: no reaction divided by a tributary area, which on quadratic faces
gives nothing (a uniform pressure loads the corners of a P2 triangle with zero force and its mid-sides with a
third each). P1 multipliers with P2 displacements on the same faces satisfy the inf-sup condition (Wohlmuth,
Popp, Gee & Wall, Comput. Mech. 49, 2012, §3).

The body is linear, so the problem condenses onto the face exactly: with B_ij = int psi_i phi_j dA (phi_j the
trace of displacement shape function j in z) and K the stiffness on the free DOFs, u = -K^-1 B^T lam and

    g = h~ - delta w + C lam,   C = B K^-1 B^T (m^5/N),   h~_i = int psi_i h dA (m^3).

C is formed once per mesh from one factorisation of K and one solve per candidate node (femcheck.solvers.multirhs);
the primal-dual active set (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13, 2002) then works on the small dense
system, and the load balance fixes delta exactly in each iteration.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.sparse import csr_matrix
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from ..errors import ConvergenceError


def _trace_functions(L: np.ndarray, order: int) -> np.ndarray:
    """Shape functions of the face triangle at barycentric points L (3, q): (3, q) for P1 (corners), (6, q)
    for P2 (corners L_k (2 L_k - 1), then mid-sides 4 L_a L_b of edges 01, 12, 20)."""
    if order == 1:
        return L
    corners = L * (2.0 * L - 1.0)
    mids = 4.0 * np.stack([L[0] * L[1], L[1] * L[2], L[2] * L[0]])
    return np.vstack([corners, mids])


@dataclass
class MortarFace:
    """Mortar coupling of the candidate corner nodes with the body's z-DOFs: ``B`` (n_c, n_dofs) in m^2,
    ``w`` (n_c,) = int psi_i dA (m^2), ``h`` (n_c,) = int psi_i h dA (m^3)."""

    B: csr_matrix
    w: np.ndarray
    h: np.ndarray


def face_mortar(points: np.ndarray, tris: np.ndarray, face_dofs: np.ndarray, rows: np.ndarray, n_dofs: int,
                gap, order: int, quad_order: int = 8) -> MortarFace:
    """Assemble :class:`MortarFace` over the face triangles ``tris`` (3, T) of ``points`` (3, N).

    ``face_dofs`` (3 or 6, T): the z-DOF of each of the triangle's shape functions (corners, then mid-sides of
    edges 01, 12, 20 for P2); ``rows`` (N,): the multiplier row of each corner node, -1 where the node is no
    candidate; ``gap(x, y)`` the initial gap (m). Corner/mid-side products are polynomials of degree <= 3,
    integrated exactly; ``quad_order`` sets the rule for psi_i h (exact for a paraboloid from order 3)."""
    X, W = get_quadrature(RefTri, quad_order)
    Lq = np.vstack([1.0 - X[0] - X[1], X[0], X[1]])                 # (3, q) barycentric
    phi = _trace_functions(Lq, order)                                # (n_loc, q)
    ref = 2.0 * (Lq * W) @ phi.T                                     # int psi_k phi_j / area, (3, n_loc)
    P = points[:2]
    e1, e2 = P[:, tris[1]] - P[:, tris[0]], P[:, tris[2]] - P[:, tris[0]]
    area = 0.5 * np.abs(e1[0] * e2[1] - e1[1] * e2[0])              # the face is the plane z = 0
    r = rows[tris]                                                   # (3, T)
    keep = r >= 0
    # B: for every (triangle, corner k with a row, local function j)
    t_idx, k_idx = np.nonzero(keep.T)
    n_loc = phi.shape[0]
    vals = area[t_idx, None] * ref[k_idx]                            # (nnz_rows, n_loc)
    Bi = np.repeat(r[k_idx, t_idx], n_loc)
    Bj = face_dofs[:, t_idx].T.ravel()
    n_c = int(rows.max()) + 1
    B = csr_matrix((vals.ravel(), (Bi, Bj)), shape=(n_c, n_dofs))    # duplicates summed
    # w and h~: psi_k = L_k on each triangle
    xq = P[0][tris].T @ Lq, P[1][tris].T @ Lq                         # (T, q) each
    hq = gap(xq[0], xq[1])
    hk = 2.0 * area[:, None] * ((hq * W) @ Lq.T)                     # (T, 3): int L_k h over the triangle
    w = np.zeros(n_c)
    h = np.zeros(n_c)
    np.add.at(w, r[keep], np.broadcast_to(area / 3.0, r.shape)[keep])
    np.add.at(h, r[keep], hk.T[keep])
    return MortarFace(B, w, h)


@dataclass
class MortarSolution:
    """``lam`` nodal pressures (Pa) and weighted gaps ``gap`` (m^3) at the candidate nodes, ``delta`` approach
    (m), ``active`` mask, ``iterations`` of the active set, ``residual`` (complementarity and load, relative)."""

    lam: np.ndarray
    gap: np.ndarray
    delta: float
    active: np.ndarray
    iterations: int
    residual: float
    history: list[int] = field(default_factory=list)
    time_s: float = 0.0


def schur_active_set(C: np.ndarray, w: np.ndarray, h: np.ndarray, force: float, active0: np.ndarray,
                     tol: float = 1e-10, max_iter: int = 50) -> MortarSolution:
    """Solve g = h - delta w + C lam >= 0, lam >= 0, lam g = 0, w . lam = ``force`` (N) by the primal-dual active
    set. On the active set A: C_AA lam_A = delta w_A - h_A, and the load balance gives
    delta = (F + w_A' C_AA^-1 h_A) / (w_A' C_AA^-1 w_A). Raises :class:`ConvergenceError` when the set cycles
    or the settled state violates the conditions beyond ``tol``."""
    t0 = time.perf_counter()
    active = np.asarray(active0, dtype=bool).copy()
    history = []
    gap_scale = float(np.max(np.abs(h))) or 1.0
    for it in range(1, max_iter + 1):
        if not active.any():
            raise ConvergenceError("mortar active set", it, np.inf, tol, "active set became empty")
        A = np.flatnonzero(active)
        history.append(A.size)
        try:
            fac = cho_factor(C[np.ix_(A, A)])
        except np.linalg.LinAlgError as exc:
            raise ConvergenceError("mortar active set", it, np.inf, tol, f"condensed compliance not SPD ({exc})")
        yw, yh = cho_solve(fac, w[A]), cho_solve(fac, h[A])
        delta = (force + w[A] @ yh) / (w[A] @ yw)
        lam = np.zeros_like(w)
        lam[A] = delta * yw - yh
        gap = h - delta * w + C @ lam
        new = np.where(active, lam > 0.0, gap < 0.0)
        if np.array_equal(new, active):
            lam_ref = force / w[A].sum()
            balance = abs(w @ lam - force) / force
            residual = float(max(max(0.0, -lam.min()) / lam_ref,
                                 max(0.0, -gap[~active].min(initial=0.0)) / gap_scale,
                                 float(np.max(np.abs(gap[A]))) / gap_scale, balance))
            if residual > tol:
                raise ConvergenceError("mortar active set", it, residual, tol,
                                       "active set settled on a state that violates contact")
            return MortarSolution(lam, gap, float(delta), active, it, residual, history, time.perf_counter() - t0)
        active = new
    raise ConvergenceError("mortar active set", max_iter, np.inf, tol, "active set cycling")
