"""Post-processing of 3D P1 solutions: element stresses, a light surface view for report pictures, and
``.vtu`` export through meshio."""
from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from ..materials import Elastic
from ..meshes.block import TetMesh

_TET_FACES = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])


def p1_stress(points: np.ndarray, tets: np.ndarray, u: np.ndarray, material: Elastic) -> np.ndarray:
    """Cauchy stress (M, 3, 3) in Pa of each linear tetrahedron (constant strain) from nodal displacements
    ``u`` (3, N) in m: eps = sym(grad u) with grad from the inverse of the edge matrix, sigma = lam tr(eps) I
    + 2 mu eps."""
    x = points[:, tets]                                   # (3, 4, M)
    edges = np.transpose(x[:, 1:, :] - x[:, :1, :], (2, 0, 1))       # (M, 3, 3): columns x_k - x_0
    inv = np.linalg.inv(edges)                            # rows: gradients of barycentric coordinates 1..3
    grads = np.concatenate([-inv.sum(axis=1, keepdims=True), inv], axis=1)   # (M, 4, 3)
    ue = np.transpose(u[:, tets], (2, 0, 1))              # (M, 3, 4)
    grad_u = ue @ grads                                   # (M, 3, 3): d u_i / d x_j
    eps = 0.5 * (grad_u + np.transpose(grad_u, (0, 2, 1)))
    lam, mu = material.lame()
    return lam * np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3) + 2.0 * mu * eps


def von_mises(sigma: np.ndarray) -> np.ndarray:
    s = sigma - np.trace(sigma, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.einsum("...ij,...ij->...", s, s))


def nodal_average(n_nodes: int, tets: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Node values as the mean of the adjacent elements' values."""
    total, count = np.zeros(n_nodes), np.zeros(n_nodes)
    np.add.at(total, tets.ravel(), np.repeat(values[None, :], 4, axis=0).ravel())
    np.add.at(count, tets.ravel(), 1.0)
    return np.divide(total, count, out=np.zeros(n_nodes), where=count > 0)


def surface_view(mesh: TetMesh, extent: tuple[float, float, float], y_from: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Triangles of the block's faces x = 0, y = 0 and z = 0 within x <= extent[0], y_from <= y <= extent[1],
    z >= -extent[2] (m): what a picture of the contact region shows (the symmetry planes are sections through
    the stress field). Returns (node indices used, triangles (3, K) renumbered to them)."""
    P = mesh.points
    inside = ((P[0] <= extent[0]) & (P[1] <= extent[1]) & (P[1] >= y_from) & (P[2] >= -extent[2]))
    inside = inside[mesh.tets].all(axis=0)
    faces = np.sort(mesh.tets[:, inside].T[:, _TET_FACES].reshape(-1, 3), axis=1)
    uniq, counts = np.unique(faces, axis=0, return_counts=True)
    boundary = uniq[counts == 1]
    tol = 1e-9 * max(extent)
    on_plane = np.zeros(len(boundary), dtype=bool)
    for axis in range(3):
        on_plane |= (np.abs(P[axis][boundary]) < tol).all(axis=1)
    tri = boundary[on_plane]
    nodes, renumbered = np.unique(tri, return_inverse=True)
    return nodes, renumbered.reshape(tri.shape).T


def write_vtu(path: Path, mesh: TetMesh, u: np.ndarray, pressure: np.ndarray, vm: np.ndarray) -> Path:
    """Mesh with point data ``displacement`` (m) and ``contact_pressure`` (Pa) and cell data ``von_mises``
    (Pa), written atomically through meshio."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    out = meshio.Mesh(mesh.points.T, [("tetra", mesh.tets.T)],
                      point_data={"displacement": u.T, "contact_pressure": pressure},
                      cell_data={"von_mises": [vm]})
    tmp = path.with_suffix(".tmp.vtu")
    meshio.write(tmp, out)
    tmp.replace(path)
    return path


def report_views(mesh: TetMesh, u_nodes: np.ndarray, pressure_all: np.ndarray, material: Elastic, name: str,
                 extent: tuple[float, float, float], stats: dict, y_from: float = 0.0) -> dict[str, np.ndarray]:
    """For a model's finest level: the full solution as ``<cache>/results/fem-<name>.vtu`` (path in
    ``stats["vtu"]``), and a light surface view of the contact region (symmetry-plane sections and contact face
    within ``extent``, nodal von Mises and pressure, float32) as fields for the report's pictures."""
    from ..cache import cache_dir

    vm = von_mises(p1_stress(mesh.points, mesh.tets, u_nodes, material))
    stats["vtu"] = str(write_vtu(cache_dir() / "results" / f"fem-{name}.vtu", mesh, u_nodes, pressure_all, vm))
    stats["von_mises_max_element"] = float(vm.max())
    nodes, tri = surface_view(mesh, extent, y_from)
    vm_nodes = nodal_average(mesh.n_nodes, mesh.tets, vm)
    return {"view_points": mesh.points[:, nodes].astype(np.float32), "view_triangles": tri.astype(np.int32),
            "view_von_mises": vm_nodes[nodes].astype(np.float32),
            "view_pressure": pressure_all[nodes].astype(np.float32)}
