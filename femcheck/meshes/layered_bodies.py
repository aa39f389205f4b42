"""Gmsh builders for the 3D frictional rolling FE reference (spec srb-rolling §8): a whole crowned roller (or
wheel), a grooved ring segment (curved or straight) and a flat block, each the half x >= 0 of a body symmetric
about the plane x = 0, meshed as a 2D cross-section extruded in layers along the lateral direction and mapped
onto the exact curved body.

Why layers. The contact strips are long along the lateral direction s (2 b ~ 18-20 mm) and narrow along the
rolling direction x (2 a ~ 0.45 mm), and the influence cells dx x ds are ~20 times longer along s than along x.
Isotropic tetrahedra fine enough across the strip would need thousands of layers along it. Meshing the body
isotropically in coordinates compressed along s and stretching it back (the trick of
:mod:`femcheck.meshes.srb_segments`) produces needle and sliver tetrahedra with angles up to ~165 degrees: with
P2 elements at stretch 8 they were 11 % too stiff on single-cell coefficients and 13 % on a smooth Hertzian load
(flat block, measured against Boussinesq-Cerruti). A section mesh (fine near the contact line, graded away,
Gmsh MathEval size field) extruded in layers along s (Gmsh's structured extrusion, each prism split into three
tetrahedra) keeps every face angle <= 90 degrees in the long direction: 1 % on the smooth load with one layer per
influence cell.

Reference coordinates (a, b, c) of the extruded mesh: a = section abscissa (rolling direction, >= 0), b = layer
coordinate (lateral), c = section ordinate (towards the body interior for rings and blocks: c <= 0). The maps:
- flat block: (x, y, z) = (a, b, c), contact face z = 0;
- crowned body (roller, wheel): the section is the half disk a >= 0, a^2 + c^2 <= r^2 (r the rolling radius)
  and the body is its extrusion along the axis b = y, scaled radially by rho(y)/r, rho(y) = r - R + sqrt(R^2 -
  y^2) (crown radius R): contact face = the barrel, exact at every node; frame: axis y, contacts at z = +-rho;
- grooved ring: the section is the rectangle [0, L_x] x [-depth, 0]; b is the arc length s along the groove
  circle (centre G, radius r_g) from the reference point, c = -d with d the depth below the groove:
  P = G + (r_g + d)(cos(s/r_g) m0 + sin(s/r_g) tau0), then moved along the rolling direction by the rotation
  about the ring axis that carries the reference point a along +x (or translated by a along +x for a straight
  rail). The contact face is the exact torus (or grooved cylinder) at every node.
Lengths in m. Meshes are cached (:mod:`femcheck.meshes.cache`).
"""
from __future__ import annotations

from dataclasses import dataclass

import gmsh
import numpy as np

from .block import drop_unused_nodes, node_table
from .plane import _Gmsh
from .cache import cached
from .srb_segments import BodyMesh, _read_body, _write_body


@dataclass(frozen=True)
class SectionSpec:
    """2D cross-section in the (a, c) plane: ``shape`` "half_disk" (radius ``size_a``; a >= 0) or "rectangle"
    ([0, size_a] x [-size_c, 0]); element size ``h_contact`` at the points ``fine`` ((a, c) pairs), growing by
    ``grading`` per unit distance up to ``h_max``; ``align``: abscissae a of extra boundary nodes on the contact
    edge(s) (the influence cells' edges a = dx/2), so that element faces follow the cell boundaries."""

    shape: str
    size_a: float
    size_c: float
    fine: tuple[tuple[float, float], ...]
    h_contact: float
    grading: float
    h_max: float
    align: tuple[float, ...] = ()


@dataclass(frozen=True)
class LayeredSpec:
    """``section`` extruded along b through the layer boundaries ``layers`` (increasing, m)."""

    section: SectionSpec
    layers: tuple[float, ...]


def _f(v) -> str:
    return f"({float(v)!r})"


def _boundary_triangles(tets: np.ndarray) -> np.ndarray:
    """Faces of the tetrahedra that belong to one tetrahedron only (the boundary)."""
    faces = np.concatenate([tets[[0, 1, 2]], tets[[0, 1, 3]], tets[[0, 2, 3]], tets[[1, 2, 3]]], axis=1)
    _, idx, cnt = np.unique(np.sort(faces, axis=0), axis=1, return_index=True, return_counts=True)
    return faces[:, idx[cnt == 1]]


def _layered(spec: LayeredSpec) -> tuple[np.ndarray, np.ndarray]:
    """Reference mesh: points (3, N) in (a, b, c) and tetrahedra (4, M).

    Layers symmetric about b = 0 give a mesh symmetric about b = 0: the half b >= 0 is extruded (with a layer
    boundary added at b = 0 when the central layer straddles it) and mirrored. Why: each extruded prism is split
    into three tetrahedra with one handedness, so a mesh extruded through the whole width is not its own mirror
    image, and a problem symmetric in b (a body rolling in a symmetric groove) then shows a lateral force and a
    spin moment of the order of the discretisation error instead of zero."""
    lay = np.asarray(spec.layers, dtype=float)
    if lay.size < 2 or np.any(np.diff(lay) <= 0):
        raise ValueError("layers must be increasing")
    tol = 1e-9 * float(np.abs(lay).max())
    if lay.size < 3 or not np.allclose(lay, -lay[::-1], rtol=0.0, atol=tol):
        return _extruded(spec.section, lay)
    P, tets = _extruded(spec.section, np.concatenate([[0.0], lay[lay > tol]]))
    on_plane = np.abs(P[1]) <= tol
    # nodes on b = 0 are shared; every other node gets a mirror image numbered after the half's nodes
    image = np.where(on_plane, np.arange(P.shape[1]), P.shape[1] + np.cumsum(~on_plane) - 1)
    mirrored = P[:, ~on_plane] * np.array([[1.0], [-1.0], [1.0]])
    return np.concatenate([P, mirrored], axis=1), np.concatenate([tets, image[tets]], axis=1)


def _extruded(sec: SectionSpec, lay: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The section meshed by Gmsh and extruded through the layer boundaries ``lay`` (one element per layer)."""
    b0 = float(lay[0])
    with _Gmsh("layered_body") as model:
        geo = model.geo
        al = sorted(a for a in sec.align if 0.0 < a < 0.5 * sec.size_a)
        if sec.shape == "half_disk":
            r = sec.size_a
            c = geo.addPoint(0.0, b0, 0.0)
            # boundary from (0, -r) over (r, 0) to (0, r), through the alignment points near both poles
            angles = ([-0.5 * np.pi] + [-np.arccos(a / r) for a in al] + [0.0]
                      + [np.arccos(a / r) for a in al[::-1]] + [0.5 * np.pi])
            pts = [geo.addPoint(r * np.cos(t), b0, r * np.sin(t))
                   for t in angles]
            curves = [geo.addCircleArc(pts[i], c, pts[i + 1]) for i in range(len(pts) - 1)]
            curves.append(geo.addLine(pts[-1], pts[0]))
        elif sec.shape == "rectangle":
            A, C = sec.size_a, sec.size_c
            top = [(0.0, 0.0)] + [(a, 0.0) for a in al] + [(A, 0.0), (A, -C), (0.0, -C)]
            pts = [geo.addPoint(x, b0, z) for x, z in top]
            curves = [geo.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
        else:
            raise ValueError(f"unknown section shape {sec.shape!r}")
        face = geo.addPlaneSurface([geo.addCurveLoop(curves)])
        total = float(lay[-1] - lay[0])
        heights = list(np.cumsum(np.diff(lay)) / total)
        heights[-1] = 1.0
        geo.extrude([(2, face)], 0.0, total, 0.0, numElements=[1] * len(heights), heights=heights)
        geo.synchronize()
        dist = [f"Sqrt((x - {_f(a)})^2 + (z - {_f(c_)})^2)" for a, c_ in sec.fine]
        d = dist[0] if len(dist) == 1 else f"Min({', '.join(dist)})"
        fid = model.mesh.field.add("MathEval")
        model.mesh.field.setString(fid, "F", f"Min({_f(sec.h_max)}, {_f(sec.h_contact)} + {_f(sec.grading)} * {d})")
        model.mesh.field.setAsBackgroundMesh(fid)
        for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(opt, 0)
        model.mesh.generate(3)
        points, index = node_table(model)
        _, _, nodes = model.mesh.getElements(3)
        tets = index[np.asarray(nodes[0], dtype=np.int64)].reshape(-1, 4).T
    points, tets, _ = drop_unused_nodes(points, tets)
    return points, tets


def _orient(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Tetrahedra with positive volume after a mapping (a map may reverse orientation)."""
    a, b, c, d = (points[:, tets[k]] for k in range(4))
    vol = np.einsum("ij,ij->j", np.cross((b - a).T, (c - a).T).T, d - a)
    t = tets.copy()
    t[[0, 1]] = np.where(vol < 0, tets[[1, 0]], tets[[0, 1]])
    return t


def _cached(kind: str, spec, build) -> BodyMesh:
    """``build(spec)`` once per spec and this module's code (:mod:`femcheck.meshes.cache`): the maps above are
    part of the mesh, so the key is this module's digest (srb_segments' would miss a change to them)."""
    return cached(kind, spec, __name__, ".npz", lambda: build(spec), _read_body, _write_body)


def _body(points: np.ndarray, tets: np.ndarray, contact_nodes: np.ndarray, faces: dict) -> BodyMesh:
    tets = _orient(points, tets)
    bt = _boundary_triangles(tets)
    on = np.zeros(points.shape[1], dtype=bool)
    on[contact_nodes] = True
    top = bt[:, on[bt].all(axis=0)]
    return BodyMesh(points, tets, top, faces)


# --------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CrownedSpec:
    """Crowned body of revolution about the y axis (module docstring): rolling radius r (``rolling_radius``),
    crown radius R, flat ends at |y| = ``half_length``; contact zones at z = +r for +1 and z = -r for -1 in
    ``zones``; layers along y."""

    rolling_radius: float
    crown_radius: float
    half_length: float
    zones: tuple[float, ...]
    layers: tuple[float, ...]
    h_contact: float
    grading: float
    h_max: float
    align: tuple[float, ...] = ()


def crown_rho(y, rolling_radius: float, crown_radius: float):
    """Distance of the crowned surface from the axis at axial position y (m)."""
    return rolling_radius - crown_radius + np.sqrt(crown_radius**2 - np.asarray(y, dtype=float) ** 2)


# the cubic map keeps dX/da >= 1 - 3 (1 - k) >= 0.1 down to this k; below it the exponent shrinks (see _crown_map)
_CUBIC_K = 0.7
_MIN_SLOPE = 0.1
# below this ratio of crown to rolling radius the mapped elements are too flat to be of use (aspect > ~10)
MIN_CROWN_RATIO = 0.1


def _crown_map(a, c, k, r):
    """Section point (a, c) of the disk of radius r -> (X, Z) on the disk of radius k r, keeping X = a near the
    contact generatrices so that the influence cells' edges stay on element faces, with the circle mapped onto
    the circle: Z = c sqrt((k r)^2 - X^2) / sqrt(r^2 - a^2).

    X = a (1 + (k - 1)(a/r)^(n - 1)), monotone in a when its slope at a = r, 1 - n (1 - k), stays positive: the
    cubic n = 3 (X = a (1 + O((a/r)^2)) at the contact) for k >= 0.7, and n = 0.9/(1 - k) below, so that the slope
    never falls under 0.1 (the cubic alone folds the elements near the rim for k < 2/3, reached by a body that
    extends far along a strongly crowned profile, e.g. groove/crown 1.002)."""
    k = np.asarray(k, dtype=float)
    cubic = a * (1.0 + (k - 1.0) * (a / r) ** 2)
    n = (1.0 - _MIN_SLOPE) / np.maximum(1.0 - k, 1e-300)
    X = np.where(k >= _CUBIC_K, cubic, a * (1.0 + (k - 1.0) * (a / r) ** np.maximum(n - 1.0, 0.0)))
    den = np.sqrt(np.maximum(r * r - a * a, 0.0))
    xi = np.where(den > 0, c / np.where(den > 0, den, 1.0), 0.0)
    Z = np.clip(xi, -1.0, 1.0) * np.sqrt(np.maximum((k * r) ** 2 - X * X, 0.0))
    return X, Z


def _crowned(spec: CrownedSpec) -> BodyMesh:
    r, R = spec.rolling_radius, spec.crown_radius
    if not crown_rho(spec.half_length, r, R) >= MIN_CROWN_RATIO * r:
        raise ValueError(f"the crowned body's radius falls below {MIN_CROWN_RATIO:g} of the rolling radius before "
                         "its end: its mapped elements would be too flat")
    sec = SectionSpec("half_disk", r, r, tuple((0.0, float(z) * r) for z in spec.zones), spec.h_contact,
                      spec.grading, spec.h_max, spec.align)
    P, tets = _layered(LayeredSpec(sec, spec.layers))
    a, y, c = P
    tiny = 1e-9 * r
    on_arc = np.abs(np.hypot(a, c) - r) < 1e-7 * r
    X = np.stack([*_crown_map(a, c, crown_rho(y, r, R) / r, r), y])[[0, 2, 1]]
    faces = {"x0": np.flatnonzero(a < tiny), "ends": np.flatnonzero((y < spec.layers[0] + tiny)
                                                                    | (y > spec.layers[-1] - tiny))}
    return _body(X, tets, np.flatnonzero(on_arc), faces)


def crowned_body(spec: CrownedSpec) -> BodyMesh:
    """:class:`CrownedSpec` meshed (cached)."""
    return _cached("crowned-layered", spec, _crowned)


# --------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RingSpec:
    """Grooved ring segment (module docstring): groove centre ``centre`` G, radius ``groove_radius`` r_g, unit
    vectors ``m0`` (from G to the reference point, into the ring) and ``tau0`` (groove tangent, +s) in the plane
    x = 0; ring axis through ``axis_point`` with direction ``axis_dir`` (None: straight rail along x);
    ``length_x`` (arc length of the segment at the reference point), ``depth`` (material below the groove,
    along m0), layers along s (m); fine zone at the reference point."""

    centre: tuple[float, float, float]
    groove_radius: float
    m0: tuple[float, float, float]
    tau0: tuple[float, float, float]
    axis_point: tuple[float, float, float] | None
    axis_dir: tuple[float, float, float] | None
    length_x: float
    depth: float
    layers: tuple[float, ...]
    h_contact: float
    grading: float
    h_max: float
    align: tuple[float, ...] = ()


def _rotate(P: np.ndarray, point: np.ndarray, axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rodrigues: rotate points P (3, n) about the line (point, unit axis) by angles (n,)."""
    v = P - point[:, None]
    k = axis[:, None]
    c, s = np.cos(angle), np.sin(angle)
    return point[:, None] + v * c + np.cross(k.T, v.T).T * s + k * (k * v).sum(axis=0) * (1 - c)


def _ring(spec: RingSpec) -> BodyMesh:
    G, m0, tau0 = (np.asarray(v, dtype=float) for v in (spec.centre, spec.m0, spec.tau0))
    rg = spec.groove_radius
    sec = SectionSpec("rectangle", spec.length_x, spec.depth, ((0.0, 0.0),), spec.h_contact, spec.grading,
                      spec.h_max, spec.align)
    P, tets = _layered(LayeredSpec(sec, spec.layers))
    a, s, c = P
    d = -c
    th = s / rg
    X = G[:, None] + (rg + d) * (np.cos(th) * m0[:, None] + np.sin(th) * tau0[:, None])
    ex = np.array([1.0, 0.0, 0.0])
    if spec.axis_dir is None:
        X = X + a * ex[:, None]
    else:
        O, e = np.asarray(spec.axis_point, dtype=float), np.asarray(spec.axis_dir, dtype=float)
        e = e / np.linalg.norm(e)
        Q = G + rg * m0
        sign = 1.0 if np.cross(e, Q - O) @ ex > 0 else -1.0     # the rotation sense that moves Q along +x
        # each point turns about the ring axis by asin(a / rho): its x coordinate is then exactly a, so the planes
        # a = const (the influence cells' edges, the end face) stay planes x = const
        rel = X - O[:, None]
        rho = np.linalg.norm(rel - e[:, None] * (e[:, None] * rel).sum(axis=0), axis=0)
        X = _rotate(X, O, e, sign * np.arcsin(np.clip(a / rho, -1.0, 1.0)))
    tiny = 1e-9 * spec.length_x
    faces = {"x0": np.flatnonzero(a < tiny), "xend": np.flatnonzero(a > spec.length_x - tiny),
             "bottom": np.flatnonzero(d > spec.depth - tiny)}
    return _body(X, tets, np.flatnonzero(d < tiny), faces)


def grooved_ring(spec: RingSpec) -> BodyMesh:
    """:class:`RingSpec` meshed (cached)."""
    return _cached("ring-layered", spec, _ring)


# --------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BlockSpec:
    """Flat block [0, length_x] x [layers[0], layers[-1]] x [-depth, 0], contact face z = 0, fine at (0, 0)."""

    length_x: float
    depth: float
    layers: tuple[float, ...]
    h_contact: float
    grading: float
    h_max: float
    align: tuple[float, ...] = ()


def _block(spec: BlockSpec) -> BodyMesh:
    sec = SectionSpec("rectangle", spec.length_x, spec.depth, ((0.0, 0.0),), spec.h_contact, spec.grading,
                      spec.h_max, spec.align)
    P, tets = _layered(LayeredSpec(sec, spec.layers))
    tiny = 1e-9 * spec.length_x
    faces = {"x0": np.flatnonzero(P[0] < tiny), "xend": np.flatnonzero(P[0] > spec.length_x - tiny),
             "bottom": np.flatnonzero(P[2] < -spec.depth + tiny)}
    return _body(P, tets, np.flatnonzero(P[2] > -tiny), faces)


def flat_block(spec: BlockSpec) -> BodyMesh:
    """:class:`BlockSpec` meshed (cached)."""
    return _cached("block-layered", spec, _block)


# --------------------------------------------------------------------------------------------------------------
def cell_layers(edges: np.ndarray, lo: float, hi: float, per_cell: int = 1, growth: float = 1.5) -> tuple:
    """Layer boundaries: ``per_cell`` layers per interval of the sorted cell ``edges`` (m), then growing by
    ``growth`` per layer out to ``lo`` and ``hi`` (the body's lateral ends)."""
    e = np.unique(np.asarray(edges, dtype=float))
    inner = np.concatenate([np.linspace(e[i], e[i + 1], per_cell + 1)[:-1] for i in range(e.size - 1)] + [e[-1:]])
    h = float(np.diff(inner).min())
    up, down = [inner[-1]], [inner[0]]
    step = h
    while up[-1] < hi - 1e-12:
        step *= growth
        up.append(min(up[-1] + step, hi))
        if hi - up[-1] < 0.3 * step:
            up[-1] = hi
    step = h
    while down[-1] > lo + 1e-12:
        step *= growth
        down.append(max(down[-1] - step, lo))
        if down[-1] - lo < 0.3 * step:
            down[-1] = lo
    out = np.concatenate([down[::-1], inner[1:-1], up])
    return tuple(float(v) for v in np.unique(out))
