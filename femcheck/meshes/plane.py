"""Gmsh builders for 2D plane-strain contact models (symmetric half models, x >= 0).

Contact surfaces are meshed with *matching* node abscissae x_i on both bodies over a candidate zone
[0, x_c], so that frictionless small-deformation contact is node-to-node: the gap of pair i is
g0(x_i) + u_y^upper(x_i) - u_y^lower(x_i). Away from the contact, the element size grows linearly with the
distance to the candidate zone (Gmsh Distance + Threshold fields) up to a cap.
"""
from __future__ import annotations

from dataclasses import dataclass

import gmsh
import numpy as np

from .cache import cached_builder


@dataclass
class TriMesh:
    """Linear triangle mesh: ``points`` (2, N) in m, ``triangles`` (3, M) node indices."""

    points: np.ndarray
    triangles: np.ndarray


@dataclass
class MeshSpec:
    """Element size h_contact (m) on the candidate zone [0, x_contact]; size grows by ``grading`` per unit
    distance (h = h_contact + grading * d) up to ``h_max`` (m)."""

    h_contact: float
    x_contact: float
    grading: float
    h_max: float


class _Gmsh:
    """Context manager: a fresh, quiet Gmsh model (Gmsh keeps global state)."""

    def __init__(self, name: str, threads: int = 1):
        self.name, self.threads = name, threads

    def __enter__(self):
        if gmsh.isInitialized():
            gmsh.finalize()
        gmsh.initialize(interruptible=False)
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", self.threads)
        gmsh.model.add(self.name)
        return gmsh.model

    def __exit__(self, *exc):
        gmsh.finalize()
        return False


def _size_field(model, contact_curves: list[int], spec: MeshSpec) -> None:
    f = model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, "CurvesList", contact_curves)
    f.setNumber(dist, "Sampling", 10)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", spec.h_contact)
    f.setNumber(thr, "SizeMax", spec.h_max)
    f.setNumber(thr, "DistMin", 0.0)
    f.setNumber(thr, "DistMax", (spec.h_max - spec.h_contact) / spec.grading)
    f.setAsBackgroundMesh(thr)
    for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(opt, 0)


def _contact_polyline(geo, xs: np.ndarray, ys: np.ndarray) -> tuple[list[int], list[int]]:
    """Points and one-element lines through (xs, ys); transfinite so Gmsh puts nodes exactly there."""
    pts = [geo.addPoint(float(x), float(y), 0.0) for x, y in zip(xs, ys)]
    lines = [geo.addLine(pts[i], pts[i + 1]) for i in range(len(pts) - 1)]
    return pts, lines


def _extract(model, surface: int) -> TriMesh:
    model.mesh.generate(2)
    tags, coords, _ = model.mesh.getNodes()
    coords = coords.reshape(-1, 3)[:, :2]
    etypes, _, enodes = model.mesh.getElements(2, surface)
    tri = np.asarray(enodes[list(etypes).index(2)], dtype=np.int64).reshape(-1, 3)
    # Renumber Gmsh node tags to 0..N-1 over the nodes this surface uses.
    used, inverse = np.unique(tri, return_inverse=True)
    lookup = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(tags.size)
    pts = coords[lookup[used]].T.copy()
    return TriMesh(pts, inverse.reshape(tri.shape).T.copy())


def _mesh_surface(model, contact: list[int], rest: list[int], spec: MeshSpec) -> TriMesh:
    """Close the boundary (contact polyline + ``rest``), keep one element per contact segment so the nodes
    stay at x_i, grade sizes from the contact, and mesh."""
    surf = model.geo.addPlaneSurface([model.geo.addCurveLoop(contact + rest)])
    model.geo.synchronize()
    for ln in contact:
        model.mesh.setTransfiniteCurve(ln, 2)
    _size_field(model, contact, spec)
    return _extract(model, surf)


def contact_abscissae(spec: MeshSpec) -> np.ndarray:
    """Node abscissae x_i (m) of the candidate contact zone: uniform spacing <= h_contact from 0 to x_c."""
    n = max(2, int(np.ceil(spec.x_contact / spec.h_contact)))
    return np.linspace(0.0, spec.x_contact, n + 1)


@cached_builder("block-half")
def block_half(width: float, depth: float, spec: MeshSpec) -> TriMesh:
    """Half block [0, width/2] x [-depth, 0] (m); top surface y = 0 with contact nodes at x_i."""
    xs = contact_abscissae(spec)
    with _Gmsh("block") as model:
        geo = model.geo
        pts, lines = _contact_polyline(geo, xs, np.zeros_like(xs))
        p_top = geo.addPoint(0.5 * width, 0.0, 0.0)
        p_br = geo.addPoint(0.5 * width, -depth, 0.0)
        p_bl = geo.addPoint(0.0, -depth, 0.0)
        rest = [geo.addLine(pts[-1], p_top), geo.addLine(p_top, p_br), geo.addLine(p_br, p_bl),
                geo.addLine(p_bl, pts[0])]
        return _mesh_surface(model, lines, rest, spec)


@cached_builder("cylinder-half")
def cylinder_half(radius: float, spec: MeshSpec) -> TriMesh:
    """Lower-left quarter of a cylinder of ``radius`` (m) touching y = 0 at the origin, centre (0, R).

    Boundary: contact polyline through the exact circle at x_i, circular arc up to (R, R), the loaded flat
    y = R (rigid-plate displacement applied there), and the symmetry line x = 0.
    """
    xs = contact_abscissae(spec)
    ys = radius - np.sqrt(radius**2 - xs**2)
    with _Gmsh("cylinder") as model:
        geo = model.geo
        pts, lines = _contact_polyline(geo, xs, ys)
        centre = geo.addPoint(0.0, radius, 0.0)
        p_right = geo.addPoint(radius, radius, 0.0)
        rest = [geo.addCircleArc(pts[-1], centre, p_right), geo.addLine(p_right, centre),
                geo.addLine(centre, pts[0])]
        return _mesh_surface(model, lines, rest, spec)
