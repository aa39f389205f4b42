"""The rigid indenter on the quarter block of :mod:`femcheck.fem.quarter_block` with P1 or P2 displacements and
a mortar contact pressure (:mod:`femcheck.solvers.mortar_indenter`): the pressure is a field of the discrete
problem, p_h = sum_i lam_i psi_i over the face's corner nodes, so its nodal values are pressures and its peak is
the centre node's value, on quadratic faces as on linear ones.

The stiffness is factorised once per mesh and condensed onto the candidate nodes (one solve per candidate), and
the active set runs on that small dense system. The separation of the surfaces at every face DOF is returned
too: it locates the contact edge (:mod:`femcheck.qoi_separation`), where the multiplier's nodal values are
least accurate.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..materials import Elastic
from ..meshes.block import TetMesh
from ..solvers.elasticity3d import make_solid
from ..solvers.mortar_indenter import face_mortar, schur_active_set
from ..solvers.multirhs import SPDFactor
from .quarter_block import Gap, QuarterContact, Region


@dataclass
class MortarContact(QuarterContact):
    """:class:`QuarterContact` with ``p`` the pressure field's nodal values (Pa) at the candidate corner nodes,
    ``lam`` = p w their equivalent nodal forces (N), and ``gap_face`` (3, M): x, y (m) and the separation (m)
    at the face DOFs (corners and, for P2, mid-sides) within 1.5 times the candidates' extent in x and y."""

    gap_face: np.ndarray | None = None
    order: int = 2


def face_dofs(solid, mesh: TetMesh, order: int) -> np.ndarray:
    """z-DOF of every shape function of each top-face triangle: (3, T) corners for P1; (6, T) corners then the
    mid-sides of edges 01, 12, 20 for P2 (skfem numbers a P2 edge DOF by the mesh's edge index)."""
    nodal = solid.basis.nodal_dofs[2]
    tri = mesh.top
    corners = nodal[tri]
    if order == 1:
        return corners
    m = solid.basis.mesh
    nv = m.p.shape[1]
    ed = np.sort(m.edges, axis=0)
    keys = ed[0].astype(np.int64) * nv + ed[1]
    order_k = np.argsort(keys)
    mids = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        lo, hi = np.minimum(tri[a], tri[b]), np.maximum(tri[a], tri[b])
        k = lo.astype(np.int64) * nv + hi
        pos = order_k[np.searchsorted(keys[order_k], k)]
        if not np.array_equal(keys[pos], k):
            raise RuntimeError("a face edge is missing from the tetrahedral mesh's edges")
        mids.append(solid.basis.edge_dofs[2][pos])
    return np.vstack([corners, np.stack(mids)])


def solve_quarter_mortar(mesher: Callable[[], TetMesh], gap: Gap, block: Elastic, quarter_force: float,
                         candidates: Region, initial: Region, rim: Region, order: int = 2, contact_tol: float = 1e-10,
                         backend: str = "auto") -> MortarContact:
    """:func:`femcheck.fem.quarter_block.solve_quarter` with P1 or P2 displacements and the mortar pressure field
    of :mod:`femcheck.solvers.mortar_indenter` (:func:`mortar_on_solid` on the homogeneous quarter block that
    ``mesher()`` returns, its ``spec`` giving the block's depth)."""
    t0 = time.perf_counter()
    mesh = mesher()
    mesh_s = time.perf_counter() - t0
    t = time.perf_counter()
    solid = make_solid(mesh, block, order=order)
    assembly_s = time.perf_counter() - t
    c = mortar_on_solid(solid, mesh, mesh.spec.depth, gap, quarter_force, candidates, initial, rim, order, contact_tol,
                        backend)
    c.times.update(mesh_s=mesh_s, assembly_s=assembly_s)
    c.time_s = time.perf_counter() - t0
    return c


def mortar_on_solid(solid, mesh: TetMesh, depth: float, gap: Gap, quarter_force: float, candidates: Region,
                    initial: Region, rim: Region, order: int = 2, contact_tol: float = 1e-10,
                    backend: str = "auto") -> MortarContact:
    """The rigid indenter with initial gap ``gap(x, y)`` (m) on the quarter block ``solid`` (assembled on
    ``mesh``, P1 or P2 = ``order``; bottom z = -``depth`` clamped, x = 0 and y = 0 on rollers) carrying
    ``quarter_force`` (N). ``candidates``, ``initial``, ``rim`` as in :func:`solve_quarter_mortar`. ``p`` are the
    pressure field's values at the candidate corner nodes (Pa) and ``lam`` = p w the equivalent nodal forces
    (N). The stiffness is factorised once (:class:`femcheck.solvers.multirhs.SPDFactor`, ``backend``) and
    condensed onto the candidate nodes."""
    t0 = time.perf_counter()
    times = {}
    X = solid.basis.doflocs
    tiny = 1e-9 * depth
    fixed = X[2] < -depth + tiny
    fixed[0::3] |= X[0, 0::3] < tiny
    fixed[1::3] |= X[1, 1::3] < tiny
    free = np.flatnonzero(~fixed)
    top = np.unique(mesh.top)
    xt, yt = mesh.points[0, top], mesh.points[1, top]
    sel = candidates(xt, yt)
    sel[sel] &= np.isfinite(gap(xt[sel], yt[sel]))
    cand = top[sel]
    t = time.perf_counter()
    rows = np.full(mesh.n_nodes, -1)
    rows[cand] = np.arange(cand.size)
    # triangles touching a candidate carry its multiplier; the gap is evaluated there only
    tris = mesh.top[:, (rows[mesh.top] >= 0).any(axis=0)]
    sub = TetMesh(mesh.points, mesh.tets, tris, mesh.spec)
    mortar = face_mortar(mesh.points, tris, face_dofs(solid, sub, order), rows, solid.n_dofs,
                         lambda x, y: np.where(np.isfinite(g := gap(x, y)), g, 0.0), order)
    times["mortar_s"] = time.perf_counter() - t
    factor = SPDFactor(solid.K[free][:, free], backend=backend, tol=1e-8)
    Bf = mortar.B[:, free].tocsr()
    KinvBt = factor.solve(Bf.T.toarray())
    C = Bf @ KinvBt
    C = 0.5 * (C + C.T)
    times["factor_s"], times["condense_s"] = factor.stats.factor_s, factor.stats.solve_s
    xc, yc = mesh.points[0, cand], mesh.points[1, cand]
    t = time.perf_counter()
    sol = schur_active_set(C, mortar.w, mortar.h, quarter_force, initial(xc, yc), tol=contact_tol)
    times["contact_s"] = time.perf_counter() - t
    if sol.active[rim(xc, yc)].any():
        raise RuntimeError("FEM contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")
    u_all = np.zeros(solid.n_dofs)
    u_all[free] = -KinvBt @ sol.lam
    factor.free()
    u_nodes = u_all[solid.basis.nodal_dofs]                  # (3, N) at the corner nodes
    # the separation at the face DOFs (corners and, for P2, mid-sides), the primal field from which the contact
    # edge is located, over the candidate zone and half as far again beyond it (the edge fit needs an annulus
    # outside the contact)
    P = mesh.points
    near = np.all((P[0][mesh.top] <= 1.5 * xc.max()) & (P[1][mesh.top] <= 1.5 * yc.max()), axis=0)
    around = TetMesh(mesh.points, mesh.tets, mesh.top[:, near], mesh.spec)
    fz = np.unique(face_dofs(solid, around, order))
    fz = fz[np.isfinite(gap(solid.basis.doflocs[0, fz], solid.basis.doflocs[1, fz]))]
    fx, fy = solid.basis.doflocs[0, fz], solid.basis.doflocs[1, fz]
    gap_face = np.stack([fx, fy, gap(fx, fy) - sol.delta - u_all[fz]])
    pressure_all = np.zeros(mesh.n_nodes)
    pressure_all[cand] = sol.lam
    # overlap of the discrete surface with the indenter at the nodes (the weak condition allows a little)
    h_nodes = gap(xc, yc)
    penetration = float(max(0.0, -(h_nodes - sol.delta - u_nodes[2, cand]).min()))
    return MortarContact(mesh, cand, xc, yc, sol.lam, sol.lam * mortar.w, sol.delta, int(sol.active.sum()),
                          sol.iterations, [], sol.residual, int(free.size), u_nodes, pressure_all,
                          time.perf_counter() - t0, times, f"mortar P{order}/P1, {factor.stats.backend}",
                          penetration, gap_face, order)
