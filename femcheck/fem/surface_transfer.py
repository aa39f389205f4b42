"""From a meshed body to influence coefficients on a developed grid: nodal forces of uniform cell tractions and
the interpolation of the displacement at cell centres (spec srb-rolling §8.2 item 2).

Definition of the FE influence coefficient (so that it converges with the mesh instead of depending on node
positions): a unit traction (1 Pa) in direction e_j(s_J) (e_x, t(s_J) or n(s_J) of :mod:`femcheck.fem.contact_grid`)
uniform over the cell |x - x_J| <= dx/2, |s - s_J| <= ds/2 of the body's surface, and the displacement taken at
the receiving cell's centre P0(x_I, s_I) (projected on the body's surface) in the receiver's local frame. This is
the collocation of femcheck's exact theory (:mod:`femcheck.cect.influence`: uniform traction on the rectangle,
displacement at the element centre), so the planar large-body limit is Boussinesq-Cerruti's table itself.

Cell loads. The consistent nodal forces f_a = int_cell N_a e_j dA are integrated over the body's surface
triangles by sub-triangle midpoint rules fine enough to resolve the cell edges (each triangle cut into m^2
sub-triangles, m chosen so that the sub-triangles are <= 1/8 of the cell along x and along s); points are
assigned to cells by their developed coordinates. Each column is then scaled so that its total force is exactly
dx ds (or half of it in a half model), removing the O(h/m) area error of the indicator.

P1 and P2 tetrahedra (skfem DOF numbering: node k, component c -> 3 k + c; P2 edge nodes follow the vertices);
the surface trace is the linear or quadratic triangle of the element's own face.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix

from ..solvers.two_body import _edge_lookup, _p2_face_functions, outward_normals, project
from .contact_grid import ContactGrid

SUBCELL = 8            # sub-triangles per cell length along x and along s
MAX_SUBDIVISION = 32


@dataclass
class SurfaceSpace:
    """Trace of a body's P1/P2 field on its contact-face triangles: ``points`` (3, N) vertices (m), ``tris``
    (3, K) vertex indices, ``nodes`` (3 or 6, K) DOF-node indices of each face (vertices, then mid-edges 01, 12,
    20 for P2), ``normals`` (3, K) outward unit normals, ``n_dofs``."""

    points: np.ndarray
    tris: np.ndarray
    nodes: np.ndarray
    normals: np.ndarray
    order: int
    n_dofs: int


def surface_space(basis, tets: np.ndarray, tris: np.ndarray, order: int) -> SurfaceSpace:
    """The contact face ``tris`` of the body meshed by ``tets`` in the skfem vector ``basis`` (order 1 or 2)."""
    points = basis.mesh.p
    normals = outward_normals(points, tets, tris)
    if order == 1:
        nodes = tris
    else:
        nv = points.shape[1]
        e = [_edge_lookup(basis, tris[a], tris[b]) for a, b in ((0, 1), (1, 2), (2, 0))]
        nodes = np.vstack([tris, nv + np.stack(e)])
    return SurfaceSpace(points, tris, nodes, normals, order, basis.N)


def face_functions(order: int, bary: np.ndarray) -> np.ndarray:
    """(3 or 6, n) shape functions of the face at barycentric coordinates ``bary`` (3, n)."""
    return bary if order == 1 else _p2_face_functions(bary)


def _subtriangle_points(m: int) -> tuple[np.ndarray, float]:
    """Barycentric centroids (3, m^2) of the m^2 congruent sub-triangles of a triangle, and their weight
    (fraction of the area, 1/m^2)."""
    pts = []
    for i in range(m):
        for j in range(m - i):
            pts.append(((i + 1 / 3) / m, (j + 1 / 3) / m))
            if i + j <= m - 2:
                pts.append(((i + 2 / 3) / m, (j + 2 / 3) / m))
    p = np.array(pts).T
    return np.vstack([1.0 - p[0] - p[1], p[0], p[1]]), 1.0 / (m * m)


def _areas(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    x0 = points[:, tris[0]]
    return 0.5 * np.linalg.norm(np.cross((points[:, tris[1]] - x0).T, (points[:, tris[2]] - x0).T), axis=1)


def cell_loads(space: SurfaceSpace, grid: ContactGrid, x_centre: float = 0.0,
               half_model: bool = True, nu_max: float | None = None) -> tuple[csr_matrix, np.ndarray]:
    """Nodal forces (N per Pa) of unit tractions on the cells (x_centre, s_J), J = 0..ns-1, in the directions
    e_x, t(s), n(s): a sparse (n_dofs, 3 ns) matrix, column j ns + J for direction j (0 = x, 1 = s, 2 = n).
    ``half_model``: the body is the half x_model >= 0 of a body symmetric about the plane x_model = 0 and the
    cell straddles that plane, so the columns carry half the cell (total force dx ds / 2).
    Only surface points within ``nu_max`` (m, default 5 ds) of the profile count (a body with two contact zones
    has surface on the far side that maps to the same developed coordinates).
    Returns (W, covered) with ``covered`` (ns,) the fraction of each cell's area found on the body (1 when the
    whole cell lies on its surface; < 1 near the body's edges)."""
    dx, ds = grid.dx, grid.ds
    nu_max = 5.0 * ds if nu_max is None else nu_max
    P, T = space.points, space.tris
    xv, sv, nv = grid.developed(P.T)
    tx, ts, tn = xv[T], sv[T], nv[T]
    s_lo, s_hi = grid.s[0] - 0.5 * ds, grid.s[-1] + 0.5 * ds
    hit = ((tx.max(axis=0) >= x_centre - 0.5 * dx) & (tx.min(axis=0) <= x_centre + 0.5 * dx)
           & (ts.max(axis=0) >= s_lo) & (ts.min(axis=0) <= s_hi) & (np.abs(tn).min(axis=0) < nu_max))
    sel = np.flatnonzero(hit)
    ext_x = np.ptp(tx[:, sel], axis=0)
    ext_s = np.ptp(ts[:, sel], axis=0)
    m_sel = np.clip(np.ceil(np.maximum(SUBCELL * ext_x / dx, SUBCELL * ext_s / ds)), 2, MAX_SUBDIVISION).astype(int)
    area = _areas(P, T)
    rows, cols, vals = [], [], []
    cell_area = np.zeros(grid.ns)
    nn = space.nodes.shape[0]
    for m in np.unique(m_sel):
        tri = sel[m_sel == m]
        bary, wfrac = _subtriangle_points(int(m))
        q = bary.shape[1]
        X = np.einsum("ikt,kq->itq", P[:, T[:, tri]], bary)              # (3, t, q)
        xq, sq, _ = grid.developed(X.reshape(3, -1).T)
        xq, sq = xq.reshape(tri.size, q), sq.reshape(tri.size, q)
        J = np.floor((sq - grid.s[0]) / ds + 0.5).astype(int)
        inside = (np.abs(xq - x_centre) <= 0.5 * dx) & (J >= 0) & (J < grid.ns)
        t_i, q_i = np.nonzero(inside)
        if t_i.size == 0:
            continue
        w = area[tri[t_i]] * wfrac                                         # (n,)
        Jq = J[t_i, q_i]
        np.add.at(cell_area, Jq, w)
        N = face_functions(space.order, bary[:, q_i])                      # (nn, n)
        e = np.stack([np.broadcast_to(grid.ex, (Jq.size, 3)), grid.tangent(sq[t_i, q_i]),
                      grid.normal(sq[t_i, q_i])])                          # (3 dirs, n, 3 comps)
        nodes = space.nodes[:, tri[t_i]]                                   # (nn, n)
        for j in range(3):
            for c in range(3):
                v = N * (w * e[j, :, c])[None, :]
                rows.append((3 * nodes + c).ravel())
                cols.append(np.broadcast_to(j * grid.ns + Jq, (nn, Jq.size)).ravel())
                vals.append(v.ravel())
    W = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                   shape=(space.n_dofs, 3 * grid.ns)).tocsr()
    target = grid.cell_area * (0.5 if half_model else 1.0)
    covered = cell_area / target
    scale = np.where(cell_area > 0, target / np.where(cell_area > 0, cell_area, 1.0), 0.0)
    W = W @ csr_matrix((np.tile(scale, 3), (np.arange(3 * grid.ns), np.arange(3 * grid.ns))),
                       shape=(3 * grid.ns, 3 * grid.ns))
    return W.tocsr(), covered


def receiver_matrix(space: SurfaceSpace, points: np.ndarray, tol: float = 2e-2) -> tuple[csr_matrix, np.ndarray]:
    """Interpolation of the nodal displacement at ``points`` (n, 3) projected on the body's contact face:
    sparse (3 n, n_dofs), row 3 i + c the global component c at point i. Returns (E, distance) with the
    signed distance of each point from the surface (m; diagnostics). Raises ValueError when a point does not
    project inside the face."""
    x = np.asarray(points, dtype=float).T
    pr = project(x, space.points, space.tris, space.normals, k=16, tol=tol)
    if not pr.valid.all():
        # stretched faces: the containing triangle's centroid need not be among the nearest few
        bad = np.flatnonzero(~pr.valid)
        again = project(x[:, bad], space.points, space.tris, space.normals, k=256, tol=tol)
        for f in ("face", "gap", "valid"):
            getattr(pr, f)[bad] = getattr(again, f)
        pr.bary[:, bad], pr.normal[:, bad] = again.bary, again.normal
    if not pr.valid.all():
        raise ValueError(f"{int((~pr.valid).sum())} receiver points lie off the body's contact face")
    N = face_functions(space.order, pr.bary)                              # (nn, n)
    nodes = space.nodes[:, pr.face]
    n = points.shape[0]
    rows, cols, vals = [], [], []
    for c in range(3):
        rows.append(np.broadcast_to(3 * np.arange(n) + c, N.shape).ravel())
        cols.append((3 * nodes + c).ravel())
        vals.append(N.ravel())
    E = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                   shape=(3 * n, space.n_dofs)).tocsr()
    return E, pr.gap
