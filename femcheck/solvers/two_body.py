"""Frictionless small-deformation contact between two meshed elastic bodies: node-to-surface, primal-dual
active set, load control.

Geometry. Slave nodes lie on the slave body's contact face, the master surface is the master body's contact
face (triangles). Each slave node x_j is projected once on the master surface (closest point: candidate faces
from a KD-tree of face centroids, barycentric projection on each, the nearest face whose projection falls
inside it); n_j is that face's outward unit normal and N_k(xi_j) the master shape functions at the projection.
The gap is linearised once (small deformation, Wriggers, *Computational Contact Mechanics*, 2006, §4.1):

    g_j = g0_j + n_j . ( u_s(x_j) - sum_k N_k(xi_j) u_m,k ),    g0_j = (x_j - x_proj,j) . n_j,

so the constraint matrix C (rows g_j) is fixed. Signorini: g_j >= 0, lam_j >= 0, lam_j g_j = 0, and K u = f +
C^T lam (lam_j the compressive normal force, N). Master faces: P1 faces (3 corner nodes) for P1 tetrahedra; for
P2 the quadratic face (6 nodes, N = L_i (2 L_i - 1) at corners and 4 L_i L_j at mid-edges on the straight-sided
face), so the master displacement is interpolated with the element's own field.

P2 slave side. The corner shape functions of a 6-node triangle integrate to zero, so nodal (collocation)
contact on a quadratic face gives zero or tensile corner forces under a uniform pressure and the active set
cycles. As in the dual quadratic mortar method (Popp, Wohlmuth, Gee & Wall, SIAM J. Sci. Comput. 34, 2012,
§3.2) the slave face displacements are written in a transformed basis, u_mid = (1 - 2 alpha) u~_mid +
alpha (u~_c1 + u~_c2), corners unchanged (alpha = 1/5): the transformed shape functions keep the partition of
unity and have positive integrals w~ (2 alpha A/3 at a corner, (1 - 2 alpha) A/3 at a mid-edge node per
triangle of area A). The constraint is then imposed on the gap's coefficients in that basis, g~ = T^-1 g, with
each slave coefficient's own normal; lam_j / w~_j are the pressure's coefficients in the transformed basis and
the nodal pressures are T applied to them (mid-edge: (1 - 2 alpha) p~_mid + alpha (p~_c1 + p~_c2)). For P1, T = I and
w_j = A/3 per adjacent triangle (the lumped tributary area).

Solution. On an active set A each active row is eliminated through one slave DOF (the component of largest
|n_j|): u_d = -(g0_j + sum_{l != d} C_jl u_l) / C_jd, i.e. u = T_A v + c. The reduced system T_A^T K T_A v =
T_A^T (f - K c) is symmetric positive definite; it is solved by CG preconditioned with pyamg smoothed
aggregation (near-null space: the six rigid-body modes of each body, restricted to the kept DOFs), or sparse LU
when small. The hierarchy is rebuilt per active set (the coupling changes with it); CG is warm-started. The
multipliers come from the residual at the eliminated DOFs, lam_j = (K u - f)_d / C_jd. Load control: the
slave's driven face moves rigidly by u_z = -delta; u = u0 + delta u1 by linearity, and delta makes the platen
force equal the load. The active set is updated by A <- {lam > 0 on A} U {g < 0 off A} (Hintermueller, Ito &
Kunisch, SIAM J. Optim. 13, 2002) until it repeats; the settled state is checked against the contact conditions.

Length: above 500 lines with this derivation (37 lines) and the ball-on-block verification problem that
exercises it; the solver itself (projection, P2 slave basis, active set) is under 500.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import pyamg
from scipy.sparse import block_diag, coo_matrix, csr_matrix, diags, identity
from scipy.sparse.linalg import cg, splu
from scipy.spatial import cKDTree

from ..errors import ConvergenceError
from ..materials import Elastic
from .elasticity3d import make_solid, rigid_body_modes

Region = Callable[[np.ndarray], np.ndarray]       # (3, n) points (m) -> bool mask
ALPHA_P2 = 0.2                                     # quadratic slave-basis transformation parameter (Popp 2012)
DIRECT_MAX_DOFS = 6_000


@dataclass
class ContactBody:
    """A meshed body: ``mesh`` with ``points`` (3, N), ``tets`` (4, M) and contact-face triangles ``top``
    (3, K); ``material``; ``fixed`` component (0, 1, 2) -> bool mask over nodes where that displacement
    component is zero (symmetry planes, clamps); ``driven`` bool mask of the nodes moved rigidly by
    u_z = -delta (slave only); ``exact_surface`` maps contact-face points to the exact surface (used for the
    initial gap of P2 mid-edge nodes, which the straight-sided elements place off a curved surface)."""

    mesh: object
    material: Elastic
    fixed: dict[int, np.ndarray] = field(default_factory=dict)
    driven: np.ndarray | None = None
    exact_surface: Callable[[np.ndarray], np.ndarray] | None = None


@dataclass
class TwoBodySolution:
    """``x`` (3, n) slave contact points (m), ``normal`` (3, n) master normals, ``lam`` compressive nodal forces
    (N), ``pressure`` lam / w (Pa), ``weight`` w (m^2), ``gap`` (m, coefficient gap), ``active`` mask; ``approach``
    delta (m) of the driven face; ``total_force`` platen force (N); ``u_master``, ``u_slave`` (3, N) nodal
    displacements (m); ``iterations`` of the active set, ``cg_iterations`` per linear solve, ``residual``
    (relative violation of the contact conditions), ``history`` (active nodes, change) per iteration."""

    x: np.ndarray
    normal: np.ndarray
    lam: np.ndarray
    pressure: np.ndarray
    weight: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    approach: float
    total_force: float
    u_master: np.ndarray
    u_slave: np.ndarray
    iterations: int
    cg_iterations: list[int]
    residual: float
    n_dofs: int
    order: int
    linear_solver: str
    history: list[dict] = field(default_factory=list)
    times: dict[str, float] = field(default_factory=dict)


# ---------------------------------------------------------------------------------------------------- geometry
def outward_normals(points: np.ndarray, tets: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """(3, K) outward unit normals of the boundary triangles ``tris`` of the tetrahedral body: each triangle's
    owning tetrahedron is found by a sorted-key lookup; the normal points away from its fourth vertex."""
    n_nodes = np.int64(points.shape[1])
    faces = np.concatenate([tets[[0, 1, 2]], tets[[0, 1, 3]], tets[[0, 2, 3]], tets[[1, 2, 3]]], axis=1)
    opposite = np.concatenate([tets[3], tets[2], tets[1], tets[0]])
    fs = np.sort(faces, axis=0).astype(np.int64)
    keys = (fs[0] * n_nodes + fs[1]) * n_nodes + fs[2]
    order = np.argsort(keys)
    ts = np.sort(tris, axis=0).astype(np.int64)
    tk = (ts[0] * n_nodes + ts[1]) * n_nodes + ts[2]
    pos = np.searchsorted(keys[order], tk)
    pos = np.minimum(pos, keys.size - 1)
    if not np.array_equal(keys[order][pos], tk):
        raise ValueError("contact-face triangles are not faces of the tetrahedral mesh")
    opp = opposite[order][pos]
    x0 = points[:, tris[0]]
    n = np.cross((points[:, tris[1]] - x0).T, (points[:, tris[2]] - x0).T).T
    n /= np.linalg.norm(n, axis=0)
    flip = np.einsum("ij,ij->j", n, points[:, opp] - x0) > 0
    n[:, flip] *= -1.0
    return n


@dataclass
class Projection:
    """Closest-point projection of points on a triangulated surface: ``face`` index, barycentrics ``bary``
    (3, n), outward ``normal`` (3, n), signed distance ``gap`` (m), ``valid`` mask."""

    face: np.ndarray
    bary: np.ndarray
    normal: np.ndarray
    gap: np.ndarray
    valid: np.ndarray


def project(x: np.ndarray, points: np.ndarray, tris: np.ndarray, normals: np.ndarray, k: int = 12,
            tol: float = 1e-3) -> Projection:
    """Project ``x`` (3, n) on the triangles ``tris`` of ``points`` with unit ``normals`` (vectorised).

    Candidate faces: the ``k`` nearest centroids (KD-tree). On each, x_p = x - ((x - x0) . n) n and the
    barycentrics of x_p; a face accepts the point when all barycentrics are >= -tol (a point over a ridge of a
    faceted convex surface, or on a symmetry plane, projects just outside every facet; it is clipped to the
    nearest). Among accepting faces the one with the smallest |distance| wins; a point no face accepts is not
    valid (off the master surface)."""
    cent = points[:, tris].mean(axis=1)
    k = min(k, tris.shape[1])
    _, cand = cKDTree(cent.T).query(x.T, k=k)
    cand = cand.reshape(x.shape[1], k)
    x0 = points[:, tris[0]][:, cand]                          # (3, n, k)
    e1 = points[:, tris[1]][:, cand] - x0
    e2 = points[:, tris[2]][:, cand] - x0
    nn = normals[:, cand]
    v = x[:, :, None] - x0
    dist = np.einsum("inj,inj->nj", v, nn)
    vp = v - dist[None] * nn
    d00, d01, d11 = (np.einsum("inj,inj->nj", a, b) for a, b in ((e1, e1), (e1, e2), (e2, e2)))
    d20, d21 = np.einsum("inj,inj->nj", vp, e1), np.einsum("inj,inj->nj", vp, e2)
    den = d00 * d11 - d01 * d01
    l1 = (d11 * d20 - d01 * d21) / den
    l2 = (d00 * d21 - d01 * d20) / den
    l0 = 1.0 - l1 - l2
    inside = np.minimum(np.minimum(l0, l1), l2) >= -tol
    score = np.where(inside, np.abs(dist), np.inf)
    best = np.argmin(score, axis=1)
    rows = np.arange(x.shape[1])
    valid = np.isfinite(score[rows, best])
    bary = np.clip(np.stack([l0[rows, best], l1[rows, best], l2[rows, best]]), 0.0, 1.0)
    bary /= bary.sum(axis=0)
    face = cand[rows, best]
    return Projection(face, bary, normals[:, face], dist[rows, best], valid)


def _triangle_areas(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    x0 = points[:, tris[0]]
    return 0.5 * np.linalg.norm(np.cross((points[:, tris[1]] - x0).T, (points[:, tris[2]] - x0).T), axis=1)


def _edge_lookup(basis, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Indices of the skfem edges (a, b) (vertex pairs, any order)."""
    E = np.sort(basis.mesh.edges, axis=0).astype(np.int64)
    nv = np.int64(basis.mesh.p.shape[1])
    keys = E[0] * nv + E[1]
    order = np.argsort(keys)
    q = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
    pos = np.searchsorted(keys[order], q)
    if not np.array_equal(keys[order][np.minimum(pos, keys.size - 1)], q):
        raise ValueError("edge not in the mesh")
    return order[pos]


def _p2_face_functions(bary: np.ndarray) -> np.ndarray:
    """(6, n) quadratic triangle shape functions: corners 0, 1, 2 then mid-edges 01, 12, 20."""
    L0, L1, L2 = bary
    return np.stack([L0 * (2 * L0 - 1), L1 * (2 * L1 - 1), L2 * (2 * L2 - 1), 4 * L0 * L1, 4 * L1 * L2,
                     4 * L2 * L0])


# ---------------------------------------------------------------------------------------------- linear solver
class _Reduced:
    """SPD solve of the reduced system: sparse LU up to ``DIRECT_MAX_DOFS``, else CG + pyamg SA."""

    def __init__(self, A: csr_matrix, B: np.ndarray, tol: float, kind: str):
        self.A, self.tol = A, tol
        if kind == "auto":
            kind = "direct" if A.shape[0] <= DIRECT_MAX_DOFS else "amg"
        self.kind = kind
        if kind == "direct":
            self.lu = splu(A.tocsc(), permc_spec="COLAMD")
        elif kind == "amg":
            ml = pyamg.smoothed_aggregation_solver(A, B=B, symmetry="symmetric",
                                                   presmoother=("gauss_seidel", {"sweep": "symmetric"}),
                                                   postsmoother=("gauss_seidel", {"sweep": "symmetric"}))
            self.M = ml.aspreconditioner(cycle="V")
        else:
            raise ValueError(f"solver must be auto, direct or amg, got {kind!r}")

    def solve(self, b: np.ndarray, x0: np.ndarray | None) -> tuple[np.ndarray, int]:
        bnorm = float(np.linalg.norm(b)) or 1.0
        if self.kind == "direct":
            x = self.lu.solve(b)
            its = 1
        else:
            count = [0]
            x, info = cg(self.A, b, x0=x0, rtol=self.tol, atol=0.0, maxiter=1000, M=self.M,
                         callback=lambda _: count.__setitem__(0, count[0] + 1))
            its = count[0]
        res = float(np.linalg.norm(b - self.A @ x) / bnorm)
        if not np.isfinite(res) or res > 10 * self.tol * (1e3 if self.kind == "direct" else 1.0):
            raise ConvergenceError(f"two-body {self.kind} solve", its, res, self.tol)
        return x, its


# ------------------------------------------------------------------------------------------------- the solve
def solve_two_body(master: ContactBody, slave: ContactBody, force: float, candidates: Region, initial: Region,
                   rim: Region | None = None, order: int = 1, solver: str = "auto", cg_tol: float = 1e-10,
                   contact_tol: float = 1e-8, max_iter: int = 40) -> TwoBodySolution:
    """Frictionless contact of ``slave`` pressed by ``force`` (N, carried by the model, e.g. a quarter of the
    load for a quarter model) in -z through its driven face onto ``master``.

    ``candidates(x)``: slave contact-face points that may touch (triangles with all corners inside are used);
    ``initial(x)``: the starting active set; ``rim(x)``: candidates that must stay open (contact there means the
    candidate zone is too small: RuntimeError). ``order`` 1 or 2 (P1 / P2 tetrahedra); ``solver`` "auto",
    "direct" or "amg". Raises :class:`ConvergenceError` when a linear solve misses ``cg_tol``, the active set
    cycles for ``max_iter`` iterations, or the settled state violates the contact conditions beyond
    ``contact_tol`` (relative)."""
    if force <= 0:
        raise ValueError("force must be positive (compressive)")
    if slave.driven is None or not np.any(slave.driven):
        raise ValueError("the slave body needs a driven face")
    t0 = time.perf_counter()
    times: dict[str, float] = {}
    sm, ss = make_solid(master.mesh, master.material, order), make_solid(slave.mesh, slave.material, order)
    times["assembly_s"] = time.perf_counter() - t0
    t = time.perf_counter()
    nm = sm.n_dofs
    n = nm + ss.n_dofs
    K = block_diag([sm.K, ss.K], format="csr")

    # prescribed DOFs and their values per unit approach (driven: u_z = -1)
    fixed = np.zeros(n, dtype=bool)
    u_p1 = np.zeros(n)
    for body, solid, off in ((master, sm, 0), (slave, ss, nm)):
        basis = solid.basis
        edges = basis.mesh.edges if order == 2 else None
        for comp, mask in list(body.fixed.items()) + ([(2, body.driven)] if body.driven is not None else []):
            fixed[off + basis.nodal_dofs[comp, mask]] = True
            if order == 2:
                fixed[off + basis.edge_dofs[comp, mask[edges[0]] & mask[edges[1]]]] = True
        if body.driven is not None:
            u_p1[off + basis.nodal_dofs[2, body.driven]] = -1.0
            if order == 2:
                u_p1[off + basis.edge_dofs[2, body.driven[edges[0]] & body.driven[edges[1]]]] = -1.0
    driven_dofs = np.flatnonzero(u_p1 < 0)

    # slave contact nodes: DOF triples, positions, tributary weights, scalar basis transformation T (u = T u~)
    P_s = slave.mesh.points
    tri = slave.mesh.top
    keep = np.all(candidates(P_s[:, tri.ravel()]).reshape(3, -1), axis=0)
    tri = tri[:, keep]
    if tri.shape[1] == 0:
        raise ValueError("no slave contact-face triangle inside the candidate zone")
    area = _triangle_areas(P_s, tri)
    corners, cinv = np.unique(tri, return_inverse=True)
    cinv = cinv.reshape(tri.shape)
    dofs = [ss.basis.nodal_dofs[:, corners]]
    X = [P_s[:, corners]]
    nc = corners.size
    if order == 1:
        w = np.bincount(cinv.ravel(), np.tile(area / 3.0, 3), minlength=nc)
        Tinv = identity(nc, format="csr")
        T_rows = None
        n_slave = nc
    else:
        a = ALPHA_P2
        ea = np.concatenate([tri[0], tri[1], tri[2]])
        eb = np.concatenate([tri[1], tri[2], tri[0]])
        eid = _edge_lookup(ss.basis, ea, eb)
        edges, einv = np.unique(eid, return_inverse=True)
        ne = edges.size
        E = ss.basis.mesh.edges[:, edges]
        dofs.append(ss.basis.edge_dofs[:, edges])
        X.append(0.5 * (P_s[:, E[0]] + P_s[:, E[1]]))
        w = np.concatenate([np.bincount(cinv.ravel(), np.tile(2 * a * area / 3.0, 3), minlength=nc),
                            np.bincount(einv, np.tile((1 - 2 * a) * area / 3.0, 3), minlength=ne)])
        cpos = np.searchsorted(corners, E)                        # corner slots of each edge's ends
        n_slave = nc + ne
        mid = nc + np.arange(ne)
        # u_mid = (1 - 2a) u~_mid + a (u~_c1 + u~_c2); inverse: u~_mid = (u_mid - a (u_c1 + u_c2)) / (1 - 2a)
        T_rows = (mid, cpos)
        r = np.concatenate([np.arange(nc), mid, mid, mid])
        c = np.concatenate([np.arange(nc), mid, cpos[0], cpos[1]])
        v = np.concatenate([np.ones(nc), np.full(ne, 1 / (1 - 2 * a)), np.full(2 * ne, -a / (1 - 2 * a))])
        Tinv = csr_matrix((v, (r, c)), shape=(n_slave, n_slave))
    sdofs = nm + np.concatenate(dofs, axis=1)                     # (3, n_slave) full numbering
    Xs = np.concatenate(X, axis=1)
    if slave.exact_surface is not None:
        Xs = slave.exact_surface(Xs)

    # full-DOF basis transformation (identity but for the P2 mid-edge slave nodes) and K~ = T^T K T
    Ttr = None
    if T_rows is None:
        Ktil = K
    else:
        mid, cpos = T_rows
        a = ALPHA_P2
        rr, cc, vv = [np.arange(n)], [np.arange(n)], [np.ones(n)]
        for comp in range(3):
            dm = sdofs[comp, mid]
            rr += [dm, dm]
            cc += [sdofs[comp, cpos[0]], sdofs[comp, cpos[1]]]
            vv += [np.full(dm.size, a), np.full(dm.size, a)]
        diag_fix = np.ones(n)
        diag_fix[sdofs[:, mid].ravel()] = 1 - 2 * a
        Ttr = coo_matrix((np.concatenate(vv[1:]), (np.concatenate(rr[1:]), np.concatenate(cc[1:]))),
                         shape=(n, n)).tocsr() + diags(diag_fix)
        Ktil = (Ttr.T @ K @ Ttr).tocsr()

    # master surface and projection of the slave points
    P_m = master.mesh.points
    mtri = master.mesh.top
    normals = outward_normals(P_m, master.mesh.tets, mtri)
    proj = project(Xs, P_m, mtri, normals)
    if not np.all(proj.valid[initial(Xs)]):
        raise ValueError("slave nodes of the initial contact zone do not project on the master surface")
    nvec = proj.normal
    ftri = mtri[:, proj.face]
    if order == 1:
        Nsh = proj.bary
        mdofs = [sm.basis.nodal_dofs[:, ftri[k]] for k in range(3)]
    else:
        Nsh = _p2_face_functions(proj.bary)
        medge = [_edge_lookup(sm.basis, ftri[i], ftri[(i + 1) % 3]) for i in range(3)]
        mdofs = [sm.basis.nodal_dofs[:, ftri[k]] for k in range(3)] + [sm.basis.edge_dofs[:, e] for e in medge]
    rows = np.arange(n_slave)
    Mr, Mc, Mv = [], [], []
    for k, md in enumerate(mdofs):
        for comp in range(3):
            Mr.append(rows)
            Mc.append(md[comp])
            Mv.append(-Nsh[k] * nvec[comp])
    Mmat = csr_matrix((np.concatenate(Mv), (np.concatenate(Mr), np.concatenate(Mc))), shape=(n_slave, n))
    Smat = csr_matrix((nvec.T.ravel(), (np.repeat(rows, 3), sdofs.T.ravel())), shape=(n_slave, n))
    C = (Smat + Tinv @ Mmat).tocsr()                              # gap coefficients g~ = g~0 + C u~
    g0 = Tinv @ proj.gap
    dep_comp = np.argmax(np.abs(nvec), axis=0)
    dep = sdofs[dep_comp, rows]
    c_dep = nvec[dep_comp, rows]
    cand_mask = proj.valid & ~fixed[dep]

    free = np.flatnonzero(~fixed)
    pos = np.full(n, -1)
    pos[free] = np.arange(free.size)
    KFF = Ktil[free][:, free].tocsr()
    KFP = Ktil[free][:, np.flatnonzero(fixed)].tocsr()
    uP1 = u_p1[fixed]
    CF = C[:, free].tocsr()
    CP_u1 = C[:, np.flatnonzero(fixed)] @ uP1                     # gap change of a unit approach, prescribed part
    Kdrv = Ktil[driven_dofs].tocsr()
    modes = np.zeros((n, 12))
    modes[:nm, :6] = rigid_body_modes(sm.basis.doflocs[:, ::3])
    modes[nm:, 6:] = rigid_body_modes(ss.basis.doflocs[:, ::3])
    modesF = modes[free]
    dF = pos[dep]
    times["setup_s"] = time.perf_counter() - t

    cand = np.flatnonzero(cand_mask)
    active = initial(Xs) & cand_mask
    if not active.any():
        raise ValueError("the initial active set is empty")
    gap_scale = float(np.ptp(proj.gap[cand])) or 1.0
    warm = [None, None]
    cg_its: list[int] = []
    history: list[dict] = []
    t = time.perf_counter()
    for it in range(1, max_iter + 1):
        A = np.flatnonzero(active)
        d = dF[A]
        is_dep = np.zeros(free.size, dtype=bool)
        is_dep[d] = True
        indep = np.flatnonzero(~is_dep)
        col = np.full(free.size, -1)
        col[indep] = np.arange(indep.size)
        CA = CF[A].tocoo()
        off = CA.col != d[CA.row]
        Tt = csr_matrix((np.concatenate([np.ones(indep.size), -CA.data[off] / c_dep[A][CA.row[off]]]),
                         (np.concatenate([indep, d[CA.row[off]]]), np.concatenate([np.arange(indep.size),
                                                                                    col[CA.col[off]]]))),
                        shape=(free.size, indep.size))
        Kr = (Tt.T @ KFF @ Tt).tocsr()
        lin = _Reduced(Kr, modesF[indep], cg_tol, solver)
        parts = []
        for s, (gconst, uP) in enumerate(((g0, np.zeros_like(uP1)), (CP_u1, uP1))):
            c = np.zeros(free.size)
            c[d] = -gconst[A] / c_dep[A]
            rhs = Tt.T @ (-(KFP @ uP) - KFF @ c)
            x0 = None if warm[s] is None else warm[s][indep]
            v, its = lin.solve(rhs, x0)
            cg_its.append(its)
            uF = Tt @ v + c
            warm[s] = uF
            r = KFF @ uF + KFP @ uP
            lam = np.zeros(n_slave)
            lam[A] = r[d] / c_dep[A]
            gap = gconst + CF @ uF
            u_full = np.zeros(n)
            u_full[free] = uF
            u_full[fixed] = uP
            parts.append((uF, lam, gap, float((Kdrv @ u_full).sum())))          # platen force on the slave
        (u0, l0, g0p, R0), (u1, l1, g1p, R1) = parts
        if R1 >= 0:
            raise ConvergenceError("two-body active set", it, np.inf, contact_tol, "the bodies do not resist the approach")
        delta = (-force - R0) / R1
        lam, gap = l0 + delta * l1, g0p + delta * g1p
        new = np.zeros(n_slave, dtype=bool)
        new[cand] = np.where(active[cand], lam[cand] > 0, gap[cand] < 0)
        history.append({"active": int(active.sum()), "changed": int((new != active).sum()), "approach": float(delta)})
        if np.array_equal(new, active):
            total = float(-(R0 + delta * R1))
            lam_ref = float(lam[A].mean())
            residual = float(max(max(0.0, -lam[A].min()) / lam_ref,
                                 max(0.0, -gap[cand][~active[cand]].min(initial=0.0)) / gap_scale,
                                 abs(total - force) / force))
            if residual > contact_tol:
                raise ConvergenceError("two-body active set", it, residual, contact_tol,
                                       "active set settled on a state that violates contact")
            if rim is not None and np.any(active & rim(Xs)):
                raise RuntimeError("two-body contact reached the edge of the candidate zone; enlarge it")
            times["contact_s"] = time.perf_counter() - t
            uF = u0 + delta * u1
            u_full = np.zeros(n)
            u_full[free] = uF
            u_full[fixed] = delta * uP1
            if Ttr is not None:
                u_full = Ttr @ u_full                          # back to nodal displacements
            um = u_full[sm.basis.nodal_dofs].reshape(3, -1)
            us = u_full[nm + ss.basis.nodal_dofs].reshape(3, -1)
            times["total_s"] = time.perf_counter() - t0
            pressure = lam / w
            if T_rows is not None:
                # lam / w~ are the pressure's coefficients in the transformed basis; the nodal values are T p~
                mid, cpos = T_rows
                nodal = pressure.copy()
                nodal[mid] = (1 - 2 * ALPHA_P2) * pressure[mid] + ALPHA_P2 * (pressure[cpos[0]] + pressure[cpos[1]])
                pressure = nodal
            return TwoBodySolution(Xs, nvec, lam, pressure, w, gap, active, float(delta), total, um, us, it, cg_its,
                                   residual, int(free.size), order, lin.kind, history, times)
        active = new
        if not active.any():
            raise ConvergenceError("two-body active set", it, np.inf, contact_tol, "active set became empty")
    raise ConvergenceError("two-body active set", max_iter, np.inf, contact_tol, "active set cycling")


# ------------------------------------------------------------------------------------ Hertz validation set-up
@dataclass
class BallOnBlock:
    """One level of the ball-on-block check: fitted ``p_max`` (Pa) and contact ``radius`` (m) (least-squares
    ellipse fit of p^2 over the slave nodes mirrored to the full patch), the Hertz values for comparison, the
    mesh size ``h`` (m), DOFs and the solution."""

    p_max: float
    radius: float
    hertz_p_max: float
    hertz_radius: float
    h: float
    n_dofs: int
    solution: TwoBodySolution


def ball_on_block(radius: float, ball: Elastic, block: Elastic, load: float, h_over_a: float, order: int = 1,
                  block_size: float = 20.0, grading: float = 0.25, h_max_over_a: float = 4.0,
                  solver: str = "auto") -> BallOnBlock:
    """An elastic ball (one eighth of it: x, y >= 0, 0 <= z <= R, driven at z = R) pressed by ``load`` (N, full
    ball) on an elastic quarter block of side and depth ``block_size`` Hertz radii, clamped at the bottom; P1
    or P2 tetrahedra of size ``h_over_a`` a_H in the contact zone (1.3 a_H), ``grading`` a_H-scaled growth, both
    bodies' sizes scaled the same way. The ball is the slave (its nodes lie on the exact sphere), the block's
    flat face the master (exact geometry), so the gap has no faceting error at P1 nodes; P2 mid-edge nodes are
    moved onto the sphere for their initial gap."""
    from ..analytic import hertz
    from ..materials import effective_modulus
    from ..qoi import ellipse_fit
    from ..meshes.block import BlockSpec
    from ..meshes.srb_segments import BallSpec, ball_segment, block_body

    h = hertz.point_contact(load, radius, effective_modulus(ball, block))
    a = h.semi_axis_x
    hc = h_over_a * a
    L = block_size * a
    zone = 1.3 * a
    mb = block_body(BlockSpec(L, L, L, zone, zone, hc, grading, h_max_over_a * a))
    sb = ball_segment(BallSpec(radius, zone, hc, grading, h_max_over_a * a))
    master = ContactBody(mb, block, {0: mb.mask("x0"), 1: mb.mask("y0"), 2: mb.mask("bottom")})
    centre = np.array([[0.0], [0.0], [radius]])
    slave = ContactBody(sb, ball, {0: sb.mask("x0") | sb.mask("driven"), 1: sb.mask("y0") | sb.mask("driven")},
                        driven=sb.mask("driven"),
                        exact_surface=lambda x: centre + radius * (x - centre) / np.linalg.norm(x - centre, axis=0))
    r2 = lambda x: x[0] ** 2 + x[1] ** 2
    sol = solve_two_body(master, slave, 0.25 * load, candidates=lambda x: r2(x) <= zone**2,
                         initial=lambda x: r2(x) < a * a, rim=lambda x: r2(x) > (0.9 * zone) ** 2, order=order,
                         solver=solver)
    xs, ys, p = sol.x[0], sol.x[1], sol.pressure
    fit = ellipse_fit(np.concatenate([xs, -xs, xs, -xs]), np.concatenate([ys, ys, -ys, -ys]), np.tile(p, 4))
    return BallOnBlock(fit["peak"], float(np.sqrt(fit["semi_axis_x"] * fit["semi_axis_y"])), h.p_max, a, hc,
                       sol.n_dofs, sol)
