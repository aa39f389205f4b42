"""Gmsh builders for 3D contact models: quarter blocks refined around the contact patch.

The block occupies [0, Lx] x [0, Ly] x [-H, 0]; the contact patch is centred at the origin of the top face and
the planes x = 0 and y = 0 are symmetry planes, so a doubly symmetric scene (sphere, ellipsoid, centred
roller) needs a quarter of the block. Element size is ``h_contact`` inside the (elliptical) patch zone and
grows linearly with the distance from it (Gmsh MathEval background field) up to ``h_max``. Tetrahedra by HXT
(FEM-NOTES: 4-13x faster than the default Delaunay), single-threaded so that a mesh is reproducible.
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass
from pathlib import Path

import meshio
import numpy as np

from .cache import cached
from .plane import _Gmsh


@dataclass(frozen=True)
class BlockSpec:
    """Quarter block and its sizing, lengths in m. The fine zone is the ellipse (x/zx)^2 + (y/zy)^2 <= 1 on the
    top face and the half-ellipsoid below it of depth min(zx, zy) (``zone = "ellipse"``), or the box
    [0, zx] x [0, zy] x [-min(zx, zy), 0] (``zone = "box"``, for a roller); outside, h = h_contact + grading *
    distance, capped at h_max."""

    length_x: float
    length_y: float
    depth: float
    zone_x: float
    zone_y: float
    h_contact: float
    grading: float
    h_max: float
    zone: str = "ellipse"

    def digest(self) -> str:
        return hashlib.sha256(json.dumps(asdict(self), sort_keys=True).encode()).hexdigest()[:16]


@dataclass
class TetMesh:
    """Linear tetrahedra: ``points`` (3, N) m, ``tets`` (4, M); ``top`` (3, K): triangles of the face z = 0."""

    points: np.ndarray
    tets: np.ndarray
    top: np.ndarray
    spec: BlockSpec | None = None

    @property
    def n_nodes(self) -> int:
        return self.points.shape[1]


def background_size(model, expr: str) -> None:
    """Element sizes from the MathEval expression ``expr`` (x, y, z in m) alone, no size from boundaries,
    points or curvature, and HXT for the volumes (call inside an open Gmsh session, before ``generate``)."""
    import gmsh

    f = model.mesh.field
    size = f.add("MathEval")
    f.setString(size, "F", expr)
    f.setAsBackgroundMesh(size)
    for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(opt, 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 10)


def node_table(model) -> tuple[np.ndarray, np.ndarray]:
    """(points (3, N) in m, index): ``index[tag]`` is the column of the Gmsh node ``tag`` (-1 if none)."""
    tags, coords, _ = model.mesh.getNodes()
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    return coords.reshape(-1, 3).T.copy(), index


def drop_unused_nodes(points: np.ndarray, tets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Gmsh keeps a few nodes no tetrahedron uses (geometry points); drop them so every DOF is live. Returns
    (points, tets, remap) with remap[old] = new (-1 for a dropped node), or remap None when nothing is dropped."""
    used = np.unique(tets)
    if used.size == points.shape[1]:
        return points, tets, None
    remap = np.full(points.shape[1], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    return points[:, used], remap[tets], remap


def block_quarter(spec: BlockSpec, threads: int = 1) -> TetMesh:
    """Mesh the quarter block of ``spec`` with Gmsh (OCC box, MathEval size field, HXT).

    One thread by default: HXT with two threads gave a different mesh on every call (14612 / 14639 nodes
    where one thread gives 14651 every time) and so a different reference; one thread was as fast here
    (0.3 s at 15k nodes, 2.3 s at 100k)."""
    with _Gmsh("block_quarter", threads) as model:
        occ = model.occ
        box = occ.addBox(0.0, 0.0, -spec.depth, spec.length_x, spec.length_y, spec.depth)
        occ.synchronize()
        top = [s for _, s in model.getBoundary([(3, box)], oriented=False)
               if abs(model.occ.getCenterOfMass(2, s)[2]) < 1e-12 * spec.depth]
        if len(top) != 1:
            raise RuntimeError("could not identify the top face of the block")
        zz = min(spec.zone_x, spec.zone_y)
        if spec.zone == "box":
            dist = (f"Sqrt(Max(0, x - {spec.zone_x!r})^2 + Max(0, y - {spec.zone_y!r})^2 "
                    f"+ Max(0, -z - {zz!r})^2)")
        else:
            # distance from the fine half-ellipsoid, in the ellipse's own scaled metric (exact on the axes)
            rho = f"Sqrt((x/{spec.zone_x!r})^2 + (y/{spec.zone_y!r})^2 + (z/{zz!r})^2)"
            dist = f"Max(0, {rho} - 1) * {zz!r}"
        background_size(model, f"Min({spec.h_max!r}, {spec.h_contact!r} + {spec.grading!r} * {dist})")
        model.addPhysicalGroup(3, [box], 1)
        model.addPhysicalGroup(2, top, 2)
        model.mesh.generate(3)
        points, index = node_table(model)
        _, elem_tags, elem_nodes = model.mesh.getElements(3, box)
        tets = index[np.asarray(elem_nodes[0], dtype=np.int64)].reshape(-1, 4).T
        _, _, tri_nodes = model.mesh.getElements(2, top[0])
        tris = index[np.asarray(tri_nodes[0], dtype=np.int64)].reshape(-1, 3).T
    points, tets, remap = drop_unused_nodes(points, tets)
    if remap is not None:
        tris = remap[tris]
    return TetMesh(points, tets, tris, spec)


def _read_block(spec: BlockSpec):
    def read(path: Path) -> TetMesh:
        m = meshio.read(path)
        tets = np.asarray(m.cells_dict["tetra"], dtype=np.int64).T
        top = np.asarray(m.cells_dict["triangle"], dtype=np.int64).T
        return TetMesh(np.ascontiguousarray(m.points.T), np.ascontiguousarray(tets), np.ascontiguousarray(top), spec)
    return read


def _write_block(mesh: TetMesh, path: str) -> None:
    meshio.write(path, meshio.Mesh(mesh.points.T, [("tetra", mesh.tets.T), ("triangle", mesh.top.T)]))


def cached_block_quarter(spec: BlockSpec) -> TetMesh:
    """:func:`block_quarter`, meshed once per spec and builder code (:mod:`femcheck.meshes.cache`): stored as
    ``.vtu`` (tetrahedra and the top-face triangles) through meshio and read back on the next call."""
    return cached("block", spec, __name__, ".vtu", lambda: block_quarter(spec), _read_block(spec), _write_block)
