"""Coated-block meshes: a layer of thickness t perfectly bonded to a substrate (or to a rigid base), refined
under the contact and coarsening away from it.

The layer is *structured*: its nodes form a tensor grid (in 2D) or an extrusion of the top-face mesh (in 3D),
so that it has a prescribed number of elements through its thickness however thin it is (down to t/a = 0.02),
without forcing the in-plane size down to t. A thin stiff layer bends over a soft substrate and low-order
elements lock in bending; several element rows through the thickness (refined with every mesh level) and P2
elements in 2D keep that under control (convergence is measured over the levels, not assumed).
The substrate is meshed by Gmsh with a graded size field; its top boundary goes through the layer's bottom
nodes, so the mesh is conforming and the interface nodes are shared (perfect bond).

Mesh families for Richardson extrapolation are *nested in the layer*: the level-0 node sequences (in-plane and
through the thickness) are built once and every interval is split into 2^k at level k, while the substrate's size
field halves every length (contact size, grading, cap) per level, like :mod:`femcheck.fem.line_contact`.
All lengths in m.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .plane import TriMesh, _Gmsh
from .block import TetMesh, background_size, drop_unused_nodes, node_table
from .cache import cached_builder

LAYER, SUBSTRATE = 0, 1


@dataclass(frozen=True)
class LayerSizing:
    """Sizing of the coarsest level (m): element size ``h_contact`` over the candidate zone [0, ``x_contact``]
    (and down through the layer), growth ``grading`` per unit distance beyond it, cap ``h_max``; at least
    ``layer_elements`` element rows through the layer thickness."""

    h_contact: float
    x_contact: float
    grading: float
    h_max: float
    layer_elements: int = 2


def graded_sequence(length: float, start: float, h0: float, grading: float, h_max: float,
                    uniform_to: float = 0.0, min_intervals: int = 1) -> np.ndarray:
    """Node positions 0 = s_0 < ... < s_n = ``length``: spacing <= h0 on [0, ``uniform_to``], then spacing
    h0 + grading * (s - uniform_to) capped at h_max (the same law as the Gmsh size field of the substrate,
    with ``start`` the distance already travelled from the fine zone). The graded part is stretched uniformly
    so that the last node lands on ``length``; at least ``min_intervals`` intervals."""
    if length <= 0:
        raise ValueError("length must be positive")
    u = min(uniform_to, length)
    n_u = int(np.ceil(u / h0 - 1e-9)) if u > 0 else 0
    pts = list(np.linspace(0.0, u, n_u + 1)) if n_u else [0.0]
    s = u
    while length - s > 1e-12 * length:
        step = min(h_max, h0 + grading * max(0.0, start + s - u))
        if s + 1.5 * step >= length:       # last interval: avoid a sliver
            s = length
        else:
            s += step
        pts.append(s)
    pts = np.asarray(pts)
    if pts.size - 1 < min_intervals:
        pts = np.linspace(0.0, length, min_intervals + 1)
    return pts


def subdivide(seq: np.ndarray, parts: int) -> np.ndarray:
    """Split every interval of the ascending ``seq`` into ``parts`` equal intervals (nested refinement)."""
    if parts == 1:
        return np.asarray(seq, dtype=float)
    t = np.arange(parts) / parts
    inner = (seq[:-1, None] + np.diff(seq)[:, None] * t[None, :]).ravel()
    return np.append(inner, seq[-1])


@dataclass
class LayeredTriMesh:
    """A coated half block: linear triangles ``mesh`` with ``region`` (per triangle: LAYER or SUBSTRATE),
    the layer's top-node abscissae ``x_top`` (m, ascending, shared with the mesh nodes ``top_nodes``), the
    ``thickness`` t and ``depth`` of the block (m), and ``layer_rows`` element rows through the layer."""

    mesh: TriMesh
    region: np.ndarray
    x_top: np.ndarray
    top_nodes: np.ndarray
    thickness: float
    depth: float
    width: float
    layer_rows: int


def structured_layer(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Tensor grid nodes (x_i, y_j) and its triangles (2 per cell, diagonals alternating cell to cell, so the
    mesh has no preferred direction). Node index = j * nx + i. Returns (points (2, N), triangles (3, M))."""
    nx, ny = x.size, y.size
    X, Y = np.meshgrid(x, y)
    pts = np.stack([X.ravel(), Y.ravel()])
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1))
    i, j = i.ravel(), j.ravel()
    a, b = j * nx + i, j * nx + i + 1             # lower-left, lower-right (row j)
    c, d = a + nx, b + nx                         # upper-left, upper-right (row j + 1)
    flip = (i + j) % 2 == 1
    t1 = np.where(flip, [a, b, d], [a, b, c])
    t2 = np.where(flip, [a, d, c], [b, d, c])
    return pts, np.concatenate([t1, t2], axis=1)


def _substrate(x_top: np.ndarray, y_top: float, width: float, depth: float, h_contact: float,
               x_contact: float, grading: float, h_max: float) -> TriMesh:
    """Gmsh half block [0, width/2] x [-depth, y_top] whose top boundary has nodes exactly at ``x_top``; size
    h = min(h_max, h_contact + grading * d), d the distance from the contact zone [0, x_contact] x {0}."""
    import gmsh

    with _Gmsh("substrate") as model:
        geo = model.geo
        pts = [geo.addPoint(float(x), y_top, 0.0) for x in x_top]
        top = [geo.addLine(pts[i], pts[i + 1]) for i in range(len(pts) - 1)]
        p_br = geo.addPoint(0.5 * width, -depth, 0.0)
        p_bl = geo.addPoint(0.0, -depth, 0.0)
        rest = [geo.addLine(pts[-1], p_br), geo.addLine(p_br, p_bl), geo.addLine(p_bl, pts[0])]
        surf = geo.addPlaneSurface([geo.addCurveLoop(top + rest)])
        geo.synchronize()
        for ln in top:
            model.mesh.setTransfiniteCurve(ln, 2)    # keep the interface nodes exactly at x_top
        f = model.mesh.field
        size = f.add("MathEval")
        f.setString(size, "F", f"Min({h_max!r}, {h_contact!r} + {grading!r} * "
                               f"Sqrt(Max(0, x - {x_contact!r})^2 + y^2))")
        f.setAsBackgroundMesh(size)
        for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(opt, 0)
        model.mesh.generate(2)
        tags, coords, _ = model.mesh.getNodes()
        etypes, _, enodes = model.mesh.getElements(2, surf)
        tri = np.asarray(enodes[list(etypes).index(2)], dtype=np.int64).reshape(-1, 3)
    lookup = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(tags.size)
    used, inverse = np.unique(lookup[tri], return_inverse=True)
    pts = coords.reshape(-1, 3)[used, :2].T.copy()
    return TriMesh(pts, inverse.reshape(tri.shape).T.copy())


@cached_builder("coated-half")
def coated_block_half(width: float, depth: float, thickness: float, sizing: LayerSizing, level: int,
                      rigid_substrate: bool = False) -> LayeredTriMesh:
    """Symmetric half [0, width/2] x [-depth, 0] of a block coated with a layer [-thickness, 0], mesh level
    ``level`` (0 = coarsest; every length halves per level). With ``rigid_substrate`` only the layer is meshed
    (its bottom is then clamped by the caller) and ``depth`` is the thickness.

    In-plane node abscissae: spacing <= h_contact on the candidate zone, graded beyond (nested over levels).
    Through the layer: spacing h_contact growing with depth at ``grading``, at least ``layer_elements`` rows,
    every row split in 2^level.
    """
    s = sizing
    if not (0 < thickness < depth or (rigid_substrate and thickness > 0)):
        raise ValueError("need 0 < thickness < depth")
    if rigid_substrate:
        depth = thickness
    half = 0.5 * width
    parts = 2**level
    x0 = graded_sequence(half, 0.0, s.h_contact, s.grading, s.h_max, uniform_to=s.x_contact)
    d0 = graded_sequence(thickness, 0.0, s.h_contact, s.grading, s.h_max, min_intervals=s.layer_elements)
    x, d = subdivide(x0, parts), subdivide(d0, parts)
    y = -d[::-1]                                   # ascending: y = -t ... 0
    y[0] = -thickness
    pts, tris = structured_layer(x, y)
    nx = x.size
    top_nodes = (y.size - 1) * nx + np.arange(nx)
    region = np.full(tris.shape[1], LAYER)
    if not rigid_substrate:
        f = 1.0 / parts
        sub = _substrate(x, -thickness, width, depth, s.h_contact * f, s.x_contact, s.grading * f, s.h_max * f)
        # Substrate nodes on the interface are the layer's bottom row (same floats by construction).
        on_if = np.abs(sub.points[1] + thickness) <= 1e-12 * depth
        k = np.searchsorted(x, sub.points[0, on_if])
        k = np.clip(k, 0, nx - 1)
        if on_if.sum() != nx or np.abs(x[k] - sub.points[0, on_if]).max() > 1e-9 * s.h_contact:
            raise RuntimeError("substrate interface nodes do not match the layer's bottom nodes")
        index = np.empty(sub.points.shape[1], dtype=np.int64)
        index[on_if] = k                            # layer bottom row: j = 0, node index = i
        rest = np.flatnonzero(~on_if)
        index[rest] = pts.shape[1] + np.arange(rest.size)
        pts = np.concatenate([pts, sub.points[:, rest]], axis=1)
        tris = np.concatenate([tris, index[sub.triangles]], axis=1)
        region = np.concatenate([region, np.full(sub.triangles.shape[1], SUBSTRATE)])
    # counter-clockwise orientation for every triangle (skfem does not need it, but keep the mesh clean)
    P = pts[:, tris]
    area2 = (P[0, 1] - P[0, 0]) * (P[1, 2] - P[1, 0]) - (P[0, 2] - P[0, 0]) * (P[1, 1] - P[1, 0])
    cw = area2 < 0
    tris[1:, cw] = tris[2:0:-1, cw]
    return LayeredTriMesh(TriMesh(pts, tris), region, x, top_nodes, thickness, depth, width, y.size - 1)


@dataclass
class LayeredTetMesh:
    """A coated quarter block [0, L] x [0, L] x [-depth, 0]: linear tetrahedra ``mesh`` (its ``top`` holds the
    triangles of the face z = 0), ``region`` per tetrahedron (LAYER or SUBSTRATE), ``thickness`` t (m),
    ``layer_rows`` element layers through the layer."""

    mesh: TetMesh
    region: np.ndarray
    thickness: float
    depth: float
    length: float
    layer_rows: int


@cached_builder("coated-quarter")
def coated_block_quarter(length: float, depth: float, thickness: float, sizing: LayerSizing, level: int,
                         rigid_substrate: bool = False) -> LayeredTetMesh:
    """Quarter of a coated block (symmetry planes x = 0 and y = 0, contact centred at the origin), mesh level
    ``level`` (every length halves per level).

    The top face is meshed by Gmsh with h = min(h_max, h_contact + grading * d), d the distance from the
    quarter disc of radius x_contact; the layer is that surface mesh *extruded* through the thickness in
    element layers (each prism split into three tetrahedra), with the through-thickness spacing of
    :func:`coated_block_half` (at least ``layer_elements`` rows at level 0, doubled per level). The substrate
    below is meshed unstructured (HXT, one thread: reproducible) with the same size law in 3D distance from the
    fine half-ball; it shares the layer's bottom surface mesh, so the interface nodes are common. With
    ``rigid_substrate`` only the layer is meshed.
    """
    s = sizing
    if not (0 < thickness < depth or (rigid_substrate and thickness > 0)):
        raise ValueError("need 0 < thickness < depth")
    parts = 2**level
    f = 1.0 / parts
    d0 = graded_sequence(thickness, 0.0, s.h_contact, s.grading, s.h_max, min_intervals=s.layer_elements)
    d = subdivide(d0, parts)
    h0, g, hmax, zone = s.h_contact * f, s.grading * f, s.h_max * f, s.x_contact
    with _Gmsh("coated_quarter") as model:
        geo = model.geo
        c = [geo.addPoint(0, 0, 0), geo.addPoint(length, 0, 0), geo.addPoint(length, length, 0),
             geo.addPoint(0, length, 0)]
        lines = [geo.addLine(c[i], c[(i + 1) % 4]) for i in range(4)]
        top = geo.addPlaneSurface([geo.addCurveLoop(lines)])
        out = geo.extrude([(2, top)], 0, 0, -thickness, numElements=[1] * (d.size - 1),
                          heights=list(d[1:] / thickness), recombine=False)
        interface, layer_vol = out[0][1], out[1][1]
        vols = {LAYER: layer_vol}
        if not rigid_substrate:
            out2 = geo.extrude([(2, interface)], 0, 0, -(depth - thickness))
            vols[SUBSTRATE] = out2[1][1]
        geo.synchronize()
        background_size(model, f"Min({hmax!r}, {h0!r} + {g!r} * Max(0, Sqrt(x^2 + y^2 + z^2) - {zone!r}))")
        model.mesh.generate(3)
        points, index = node_table(model)
        tets, region = [], []
        for r, v in vols.items():
            etypes, _, enodes = model.mesh.getElements(3, v)
            if list(etypes) != [4]:
                raise RuntimeError(f"volume {v} was not meshed with tetrahedra only ({list(etypes)})")
            t4 = index[np.asarray(enodes[0], dtype=np.int64)].reshape(-1, 4).T
            tets.append(t4)
            region.append(np.full(t4.shape[1], r))
        etypes, _, enodes = model.mesh.getElements(2, top)
        tris = index[np.asarray(enodes[list(etypes).index(2)], dtype=np.int64)].reshape(-1, 3).T
    tets, region = np.concatenate(tets, axis=1), np.concatenate(region)
    points, tets, remap = drop_unused_nodes(points, tets)
    if remap is not None:
        tris = remap[tris]
    return LayeredTetMesh(TetMesh(points, tets, tris), region, thickness,
                          thickness if rigid_substrate else depth, length, d.size - 1)
