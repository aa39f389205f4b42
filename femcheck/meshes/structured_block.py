"""Gmsh builder for a quarter block with a *structured* contact zone: the box [0, Nx h] x [0, Ny h] x [-Nz h, 0]
under the contact is a transfinite grid of cubes of side h, six tetrahedra each; the rest of the block is
unstructured (HXT, size h + grading * distance from the zone, capped at h_max) and conforms to it.

Why: on re-meshed unstructured levels every local quantity of a contact (the centre pressure, the edge) carries
a mesh-to-mesh scatter of 0.05-0.15 %, as large as the trend between levels, so no order can be observed. With
h refined by a ratio that keeps Nx, Ny, Nz whole (1.5 a / (a/8) = 12, then 18 and 27 at ratio 1.5), the meshes
are geometrically similar where the contact is and the quantities converge smoothly (hertz-point P2: orders
1.4-4.3 over a/8, a/12, a/18; docs/notes/p2-mortar.md).

Same conventions as :mod:`femcheck.meshes.block` (quarter block [0, Lx] x [0, Ly] x [-H, 0], symmetry planes
x = 0 and y = 0, contact face z = 0, one Gmsh thread so that a mesh is reproducible).
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass

import numpy as np

from .block import TetMesh, _read_block, _write_block, background_size, drop_unused_nodes, node_table
from .cache import cached
from .plane import _Gmsh


@dataclass(frozen=True)
class StructuredBlockSpec:
    """Quarter block (m) with a structured zone of about ``zone_x`` x ``zone_y`` x ``zone_depth`` (m, rounded up
    to whole cubes of side ``h_contact``); outside, h = h_contact + grading * distance from the zone, capped at
    h_max."""

    length_x: float
    length_y: float
    depth: float
    zone_x: float
    zone_y: float
    zone_depth: float
    h_contact: float
    grading: float
    h_max: float

    def cells(self) -> tuple[int, int, int]:
        """(Nx, Ny, Nz): cubes of side h_contact along x, y and z."""
        # ceil with a relative slack: a zone meant to hold N cells must not get N + 1 from rounding
        return tuple(int(np.ceil(v / self.h_contact - 1e-6)) for v in (self.zone_x, self.zone_y, self.zone_depth))

    def digest(self) -> str:
        return hashlib.sha256(json.dumps(asdict(self), sort_keys=True).encode()).hexdigest()[:16]


def structured_block_quarter(spec: StructuredBlockSpec, threads: int = 1) -> TetMesh:
    """Mesh the quarter block of ``spec``: OCC box fragmented by the zone box, the zone transfinite (faces
    split "Left": Gmsh's tetrahedra of a transfinite hexahedron match those diagonals only; "Alternate" and
    "Right" leave face edges that no tetrahedron has), the rest HXT with the MathEval size field."""
    nx, ny, nz = spec.cells()
    h = spec.h_contact
    X, Y, Z = nx * h, ny * h, nz * h
    if X >= spec.length_x or Y >= spec.length_y or Z >= spec.depth:
        raise ValueError("the structured zone must lie inside the block")
    with _Gmsh("structured_block_quarter", threads) as model:
        occ = model.occ
        box = occ.addBox(0.0, 0.0, -spec.depth, spec.length_x, spec.length_y, spec.depth)
        zone = occ.addBox(0.0, 0.0, -Z, X, Y, Z)
        occ.fragment([(3, box)], [(3, zone)])
        occ.synchronize()
        vols = [t for _, t in model.getEntities(3)]
        inner = [v for v in vols if occ.getCenterOfMass(3, v)[0] < X]
        if len(vols) != 2 or len(inner) != 1:
            raise RuntimeError("could not split the block into the structured zone and the rest")
        inner = inner[0]
        volumes = [inner, [v for v in vols if v != inner][0]]
        faces = [s for _, s in model.getBoundary([(3, inner)], oriented=False)]
        for c in {abs(c) for s in faces for _, c in model.getBoundary([(2, s)], oriented=False)}:
            x0, y0, z0, x1, y1, z1 = model.getBoundingBox(1, c)
            n = nz if z1 - z0 > 0.5 * h else (nx if x1 - x0 > 0.5 * h else ny)
            model.mesh.setTransfiniteCurve(c, n + 1)
        for s in faces:
            model.mesh.setTransfiniteSurface(s, "Left")
        model.mesh.setTransfiniteVolume(inner)
        top = [s for _, s in model.getBoundary([(3, v) for v in volumes], oriented=False)
               if abs(occ.getCenterOfMass(2, s)[2]) < 1e-12 * spec.depth]
        if len(top) != 2:
            raise RuntimeError("could not identify the top face of the block")
        dist = f"Sqrt(Max(0, x - {X!r})^2 + Max(0, y - {Y!r})^2 + Max(0, -z - {Z!r})^2)"
        background_size(model, f"Min({spec.h_max!r}, {h!r} + {spec.grading!r} * {dist})")
        model.addPhysicalGroup(3, volumes, 1)
        model.addPhysicalGroup(2, top, 2)
        model.mesh.generate(3)
        points, index = node_table(model)
        tets = np.hstack([index[np.asarray(model.mesh.getElements(3, v)[2][0], dtype=np.int64)].reshape(-1, 4).T
                          for v in volumes])
        tris = np.hstack([index[np.asarray(model.mesh.getElements(2, t)[2][0], dtype=np.int64)].reshape(-1, 3).T
                          for t in top])
    points, tets, remap = drop_unused_nodes(points, tets)
    if remap is not None:
        tris = remap[tris]
    return TetMesh(points, tets, tris, spec)


def cached_structured_block_quarter(spec: StructuredBlockSpec) -> TetMesh:
    """:func:`structured_block_quarter`, meshed once per spec and builder code (:mod:`femcheck.meshes.cache`)."""
    return cached("structured_block", spec, __name__, ".vtu", lambda: structured_block_quarter(spec),
                  _read_block(spec), _write_block)
