"""FE surface compliances of one elastic body on the developed grids of its contacts, by unit cell loads on a
factorised stiffness (spec srb-rolling §8.2 items 1-2).

Each body is a half model x >= 0 of a body symmetric about the plane x = 0 (that plane contains the axes of
revolution of roller and rings and the contact normals). A source cell centred on x = 0 loaded along e_x = +-X is
antisymmetric about the plane, loaded along t(s) or n(s) (vectors in the plane) symmetric, so every column is
solved on the half model with u_x = 0 (symmetric) or u_y = u_z = 0 (antisymmetric) on the plane, and receivers
at x < 0 follow by mirroring: u(x, y, z) = (-u_x, u_y, u_z)(-x, y, z) (symmetric) or (u_x, -u_y, -u_z)(-x, y, z)
(antisymmetric). Translation invariance along x (spec §8.2 item 2: the bodies are bodies of revolution, the
developed x is their arc length up to O(x^3/rho^2)) turns the loads at the central station into the full tables

    C[i, j, k, I, J] = u_i(x_I = lag_0 + k dx, s_I) per unit traction p_j on the cell (0, s_J)       (m/Pa)

with lag_0 = x_r[0] - x_s[-1] and k = 0 .. n_r + n_s - 1 (one extra lag downstream for the rolling difference,
as :func:`femcheck.cect.exact.lag_table`): for receiver cell i and source cell j of two grids, k = i - j + n_s - 1.
Components i, j in the local frames (e_x, t(s), n(s)) of the receiving and the loaded cell; the traction acts on
this body (a ring's table is then entered with -p, see :mod:`femcheck.fem.rolling_compliance`).

Supports: a ring segment is clamped on its named far faces. The roller is free: each load column is balanced by
the rigid-body inertia forces it would cause (inertia relief, f - M B (B^T M B)^-1 B^T f with B the rigid modes
of the symmetry class: T_y, T_z, R_x or T_x, R_y, R_z about the origin), solved with three statically
determinate point supports (reaction-free, since the load is balanced) and the rigid motion is then removed
(u - B (B^T M B)^-1 B^T M u). The roller's elastic displacement is thus measured from its mass-weighted mean
rigid motion (its "mean axes"); the pose of the roller in the equilibrium (centre, axis) refers to that motion,
and the balancing inertia forces are exactly those of the steady roller (centrifugal force and gyroscopic
moment are rigid-acceleration body forces of this form).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import csr_matrix
from skfem import Basis, BilinearForm, ElementTetP1, ElementTetP2, ElementVector, MeshTet, asm
from skfem.helpers import dot

from ..materials import Elastic
from ..meshes.srb_segments import BodyMesh
from ..solvers.elasticity3d import make_solid
from ..solvers.multirhs import BLOCK, SPDFactor
from .contact_grid import ContactGrid
from .surface_transfer import cell_loads, receiver_matrix, surface_space

CLASSES = ("symmetric", "antisymmetric")
MIRROR = {"symmetric": np.array([-1.0, 1.0, 1.0]), "antisymmetric": np.array([1.0, -1.0, -1.0])}
COVERAGE_TOL = 0.05          # indicator quadrature error is ~1 %; a cell off the body loses far more


@dataclass
class BodyModel:
    """A meshed half body: ``mesh`` (x >= 0), ``material``, ``clamped`` names of fully clamped faces in
    ``mesh.faces``, ``free`` (no clamp: inertia relief and mean axes), element ``order`` (1 or 2), ``thickness``
    (m, optional): the body's least thickness across its contact zones, so that surface on its far side, at least
    that far from the contact profile, is never taken for the contact face (a slender crowned body's far side lies
    closer than the default search depth of :func:`cell_loads`, 5 ds)."""

    name: str
    mesh: BodyMesh
    material: Elastic
    clamped: tuple[str, ...] = ()
    free: bool = False
    order: int = 1
    thickness: float | None = None


@dataclass
class BodyCompliance:
    """Tables of one body (module docstring): ``tables[(receiver, source)]`` (3, 3, n_r + n_s, ns_r, ns_s) in m/Pa,
    ``lag0[(receiver, source)]`` the lag of index 0 (m), ``dx`` the common cell length along x (m), ``stats``."""

    name: str
    tables: dict[tuple[str, str], np.ndarray]
    lag0: dict[tuple[str, str], float]
    dx: float
    stats: dict = field(default_factory=dict)


def _face_dofs(basis, mesh: BodyMesh, name: str, comps) -> np.ndarray:
    """DOFs of components ``comps`` at the nodes of face ``name`` (P2: and at the mid-edge nodes of edges whose
    ends both lie on it)."""
    nodes = mesh.faces[name]
    nv = mesh.n_nodes
    if basis.N > 3 * nv:                       # P2: edge nodes follow the vertices
        on = np.zeros(nv, dtype=bool)
        on[nodes] = True
        E = basis.mesh.edges
        nodes = np.concatenate([nodes, nv + np.flatnonzero(on[E[0]] & on[E[1]])])
    return np.concatenate([3 * nodes + c for c in comps])


def _rigid_modes(doflocs: np.ndarray, cls: str) -> np.ndarray:
    """(n_dofs, 3) rigid modes of a symmetry class about the origin (interleaved DOFs)."""
    x, y, z = doflocs[:, ::3]
    n = x.size
    B = np.zeros((3 * n, 3))
    if cls == "symmetric":                      # T_y, T_z, R_x
        B[1::3, 0] = 1.0
        B[2::3, 1] = 1.0
        B[1::3, 2], B[2::3, 2] = -z, y
    else:                                       # T_x, R_y, R_z
        B[0::3, 0] = 1.0
        B[0::3, 1], B[2::3, 1] = z, -x
        B[0::3, 2], B[1::3, 2] = -y, x
    return B


def _point_supports(mesh: BodyMesh, cls: str) -> np.ndarray:
    """Statically determinate supports of a free half body on its plane x = 0 (DOF indices): symmetric class
    u_y, u_z at the node A nearest the origin and u_z at B far along y; antisymmetric u_x at A, B and at C far
    along z."""
    P = mesh.points
    x0 = mesh.faces["x0"]
    span = np.ptp(P, axis=1)

    def nearest(target):
        return int(x0[np.argmin(np.linalg.norm(P[:, x0] - np.asarray(target)[:, None], axis=0))])

    A = nearest([0.0, 0.0, 0.0])
    B = nearest([0.0, 0.4 * span[1], 0.0])
    if cls == "symmetric":
        return np.array([3 * A + 1, 3 * A + 2, 3 * B + 2])
    C = nearest([0.0, 0.0, 0.4 * span[2]])
    return np.array([3 * A, 3 * B, 3 * C])


def _mass(mesh: BodyMesh, order: int) -> csr_matrix:
    elem = ElementTetP1() if order == 1 else ElementTetP2()
    basis = Basis(MeshTet(np.ascontiguousarray(mesh.points), np.ascontiguousarray(mesh.tets)), ElementVector(elem),
                  intorder=2 * order)
    return asm(BilinearForm(lambda u, v, w: dot(u, v)), basis).tocsr()


def _stations(receiver: ContactGrid, source: ContactGrid) -> tuple[float, np.ndarray]:
    lag0 = float(receiver.x[0] - source.x[-1])
    return lag0, lag0 + receiver.dx * np.arange(receiver.nx + source.nx)


@dataclass
class _Receivers:
    """Linear map from nodal displacements (n_dofs, q) to local components at the receiving cells of one
    (receiver, source) pair: ``apply(U, cls)`` -> (n_lags * ns_r, 3, q)."""

    lag0: float
    n_lags: int
    offset: float
    centre: tuple | None = None             # (E, mirrored, frames)
    average: tuple | None = None            # (R, station index, mirrored, on_plane)

    def apply(self, U: np.ndarray, cls: str) -> np.ndarray:
        sign = MIRROR[cls]
        if self.centre is not None:
            E, mirrored, frames = self.centre
            u = (E @ U).reshape(-1, 3, U.shape[1])
            u[mirrored] *= sign[None, :, None]
            return np.einsum("pic,pcq->piq", frames, u)
        R, station, mirrored, on_plane = self.average
        base = (R @ U).reshape(-1, 3, U.shape[1])                       # per station |lag|, local comps
        ns = base.shape[0] // (station.max() + 1)
        base = base.reshape(station.max() + 1, ns, 3, U.shape[1])
        out = base[station].copy()                                       # (n_lags, ns, 3, q)
        out[mirrored] *= sign[None, :, None]
        out[on_plane] *= (sign > 0)[None, :, None]                       # odd components average to 0
        return out.reshape(-1, 3, U.shape[1])


def _search_depth(body: BodyModel, grid: ContactGrid) -> float | None:
    """Depth below the contact profile searched for the contact face: 5 ds, or half the body's thickness."""
    return None if body.thickness is None else min(5.0 * grid.ds, 0.5 * body.thickness)


def _centre_receivers(space, rg: ContactGrid, lags: np.ndarray, lag0: float) -> _Receivers:
    """Displacement at the receiving cells' centres (collocation, as the exact theory)."""
    P = rg.point(lags[:, None], rg.s[None, :]).reshape(-1, 3)          # (n_lag * ns_r, 3)
    mirrored = P[:, 0] < 0.0
    P[mirrored, 0] *= -1.0
    E, dist = receiver_matrix(space, P)
    frames = np.broadcast_to(rg.frame(rg.s)[None], (lags.size, rg.ns, 3, 3)).reshape(-1, 3, 3)
    return _Receivers(lag0, lags.size, float(np.abs(dist).max()), centre=(E, mirrored, frames))


def _average_receivers(space, rg: ContactGrid, lags: np.ndarray, lag0: float,
                       nu_max: float | None = None) -> _Receivers:
    """Displacement averaged over the receiving cells (Galerkin): the transpose of the cell loads, per unit
    area. Needs the receiving stations on the lattice k dx (symmetric grids of equal parity)."""
    k = lags / rg.dx
    if np.abs(k - np.round(k)).max() > 1e-6:
        raise ValueError("cell-averaged receivers need the lags on the lattice k dx")
    k = np.round(k).astype(int)
    kmax = int(np.abs(k).max())
    blocks = []
    for j in range(kmax + 1):
        W, _ = cell_loads(space, rg.with_cells(rg.x, rg.s), j * rg.dx, half_model=(j == 0), nu_max=nu_max)
        area = rg.cell_area * (0.5 if j == 0 else 1.0)
        # columns (comp i, cell I) -> rows ordered (cell I, comp i)
        perm = (np.arange(3)[None, :] * rg.ns + np.arange(rg.ns)[:, None]).ravel()
        blocks.append((W[:, perm] / area).T)
    from scipy.sparse import vstack

    R = vstack(blocks).tocsr()
    station = np.abs(k)
    mirrored = k < 0
    on_plane = k == 0
    return _Receivers(lag0, lags.size, 0.0, average=(R, station, mirrored, on_plane))


def body_compliance(body: BodyModel, grids: dict[str, ContactGrid], backend: str = "auto",
                    receivers: str = "centre", progress=None) -> BodyCompliance:
    """Compliance tables of ``body`` for every (receiver, source) pair of ``grids`` (name -> grid in the body's
    model frame). All grids need the same dx. Raises ValueError when a source cell is not wholly on the body's
    contact face (grid beyond the body)."""
    t_all = time.perf_counter()
    dxs = {round(g.dx, 15) for g in grids.values()}
    if len(dxs) != 1:
        raise ValueError("all grids of one body need the same cell length dx")
    dx = next(iter(grids.values())).dx
    times = {}
    t0 = time.perf_counter()
    solid = make_solid(body.mesh, body.material, body.order)
    space = surface_space(solid.basis, body.mesh.tets, body.mesh.top, body.order)
    times["assemble_s"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    loads, coverage = {}, {}
    for name, g in grids.items():
        W, cov = cell_loads(space, g, 0.0, half_model=True, nu_max=_search_depth(body, g))
        if np.any(np.abs(cov - 1.0) > COVERAGE_TOL):
            bad = np.flatnonzero(np.abs(cov - 1.0) > COVERAGE_TOL)
            raise ValueError(f"{body.name}: cells {bad.tolist()} of grid {name!r} are not wholly on the body's "
                             f"contact face (coverage {cov[bad].round(3).tolist()})")
        loads[name], coverage[name] = W, cov
    recv = {}
    for rn, rg in grids.items():
        for sn, sg in grids.items():
            lag0, lags = _stations(rg, sg)
            if receivers == "centre":
                recv[(rn, sn)] = _centre_receivers(space, rg, lags, lag0)
            else:
                recv[(rn, sn)] = _average_receivers(space, rg, lags, lag0, _search_depth(body, rg))
    times["transfer_s"] = time.perf_counter() - t0

    tables = {k: np.zeros((3, 3, v.n_lags, grids[k[0]].ns, grids[k[1]].ns)) for k, v in recv.items()}
    K, doflocs, n = solid.K, solid.basis.doflocs, solid.n_dofs
    free_of = {}
    for cls in CLASSES:
        fixed = [_face_dofs(solid.basis, body.mesh, f, (0, 1, 2)) for f in body.clamped]
        fixed.append(_face_dofs(solid.basis, body.mesh, "x0", (0,) if cls == "symmetric" else (1, 2)))
        if body.free:
            fixed.append(_point_supports(body.mesh, cls))
        free_of[cls] = np.setdiff1d(np.arange(n), np.unique(np.concatenate(fixed)))
    # the basis holds every element's shape functions and gradients at the quadrature points (about 1.7 GB on the
    # finest SRB roller correction): released before the factorisations, which set the peak memory
    del solid
    factor_stats = []
    M = _mass(body.mesh, body.order) if body.free else None
    for cls in CLASSES:
        t0 = time.perf_counter()
        free = free_of[cls]
        if progress:
            progress(f"{body.name}: factorising the {cls} half ({free.size} DOFs)")
        fac = SPDFactor(K[free][:, free], backend)
        dirs = (0,) if cls == "antisymmetric" else (1, 2)
        if body.free:
            B = _rigid_modes(doflocs, cls)
            MB = M @ B
            G = B.T @ MB
        # the loads are solved and reduced to the receivers' tables a block of columns at a time, so that the dense
        # load and displacement arrays stay n x BLOCK (all columns at once: 4 x 0.8 GB on the SRB roller's 677k DOFs)
        for sn in grids:
            cols = np.concatenate([j * grids[sn].ns + np.arange(grids[sn].ns) for j in dirs])
            locs = []
            for k0 in range(0, cols.size, BLOCK):
                F = loads[sn][:, cols[k0:k0 + BLOCK]].toarray()
                if body.free:
                    F -= MB @ np.linalg.solve(G, B.T @ F)            # inertia relief: balanced loads
                U = np.zeros_like(F)
                U[free] = fac.solve(F[free])
                if body.free:
                    U -= B @ np.linalg.solve(G, MB.T @ U)            # mean-axes: no rigid motion left
                locs.append({rn: recv[(rn, sn)].apply(U, cls) for rn in grids})
            for rn in grids:
                rc = recv[(rn, sn)]
                loc = np.concatenate([c[rn] for c in locs], axis=-1)
                loc = loc.reshape(rc.n_lags, grids[rn].ns, 3, len(dirs), grids[sn].ns)
                for a, j in enumerate(dirs):
                    tables[(rn, sn)][:, j] = np.moveaxis(loc[:, :, :, a, :], 2, 0)
        fac.free()
        times[f"{cls}_s"] = time.perf_counter() - t0
        factor_stats.append({"class": cls, "backend": fac.stats.backend, "dofs": int(free.size),
                             "nnz": fac.stats.nnz, "factor_s": fac.stats.factor_s, "solve_s": fac.stats.solve_s,
                             "rhs": fac.stats.rhs, "residual": fac.stats.residual})
    stats = {"n_nodes": int(body.mesh.n_nodes), "n_dofs": int(n), "n_elements": int(body.mesh.tets.shape[1]),
             "order": body.order, "free": body.free, "factorisations": factor_stats,
             "receivers": receivers, "receiver_offset_max": max(v.offset for v in recv.values()),
             "coverage_min": float(min(c.min() for c in coverage.values())),
             "times": {**times, "total_s": time.perf_counter() - t_all}}
    return BodyCompliance(body.name, tables, {k: v.lag0 for k, v in recv.items()}, dx, stats)
