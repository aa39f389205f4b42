"""Gmsh builders for two-body 3D contact models: a ball segment on a block (Hertz validation) and the barrel
roller / raceway segments of seed 000's spherical roller bearing (Blanco-Lorenzo et al. 2022, Table 1).

Every body is returned as a :class:`BodyMesh`: linear tetrahedra, the triangles of its *contact face* (``top``,
so that the P1 helpers written for :class:`femcheck.meshes.block.TetMesh` apply) and named node sets of the
faces that carry boundary conditions (symmetry planes, clamped or driven faces). Lengths in m.

Local frame of a contact: origin at the nominal contact point, z along the contact normal pointing into the
upper body (ball / roller), x the rolling direction, y across it (along the roller axis). The plane x = 0
contains the axes of revolution of roller and ring, so it is a symmetry plane of the contact; y = 0 is one only
for the ball and the outer raceway (a sphere about the bearing centre), not for the inner raceway (a torus about
the inclined bearing axis), so the SRB segments are half models (x >= 0) and the ball is a quarter (x, y >= 0).

Element size: ``h_contact`` in the fine zone around the contact patch, growing by ``grading`` per unit distance
from it up to ``h_max`` (Gmsh MathEval background field; HXT, one thread for reproducible meshes, FEM-NOTES).
Meshes are cached as ``<cache>/meshes/<kind>-<key>.npz`` (:mod:`femcheck.meshes.cache`).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .plane import _Gmsh
from .block import BlockSpec, background_size, cached_block_quarter, drop_unused_nodes, node_table
from .cache import cached


@dataclass
class BodyMesh:
    """``points`` (3, N) m, ``tets`` (4, M), ``top`` (3, K) triangles of the contact face, ``faces`` name ->
    node indices of the faces that carry boundary conditions."""

    points: np.ndarray
    tets: np.ndarray
    top: np.ndarray
    faces: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return self.points.shape[1]

    def mask(self, name: str) -> np.ndarray:
        m = np.zeros(self.n_nodes, dtype=bool)
        m[self.faces[name]] = True
        return m


def _read_body(path: Path) -> BodyMesh:
    with np.load(path) as z:
        faces = {k[5:]: z[k] for k in z.files if k.startswith("face_")}
        return BodyMesh(z["points"], z["tets"], z["top"], faces)


def _write_body(mesh: BodyMesh, path: str) -> None:
    with open(path, "wb") as fh:
        np.savez(fh, points=mesh.points, tets=mesh.tets, top=mesh.top,
                 **{f"face_{k}": v for k, v in mesh.faces.items()})


def _cached(kind: str, spec, build) -> BodyMesh:
    """``build(spec)`` once per spec and builder code (:mod:`femcheck.meshes.cache`), stored as npz."""
    return cached(kind, spec, __name__, ".npz", lambda: build(spec), _read_body, _write_body)


def _closest_face(model, faces: list[int], point) -> int:
    """The boundary face nearest to ``point`` (a point on that face, away from its edges)."""
    d = [np.linalg.norm(np.asarray(model.getClosestPoint(2, s, point)[0]) - np.asarray(point)) for s in faces]
    return faces[int(np.argmin(d))]


def _extract(model, volume: int, contact: int, named: dict[str, list[int]]) -> BodyMesh:
    model.mesh.generate(3)
    points, index = node_table(model)
    _, _, nodes = model.mesh.getElements(3, volume)
    tets = index[np.asarray(nodes[0], dtype=np.int64)].reshape(-1, 4).T
    _, _, tri = model.mesh.getElements(2, contact)
    top = index[np.asarray(tri[0], dtype=np.int64)].reshape(-1, 3).T
    faces = {}
    for name, surfs in named.items():
        ids = [model.mesh.getNodes(2, s, includeBoundary=True)[0] for s in surfs]
        faces[name] = np.unique(index[np.concatenate(ids).astype(np.int64)])
    points, tets, remap = drop_unused_nodes(points, tets)
    if remap is not None:
        top = remap[top]
        faces = {k: remap[v][remap[v] >= 0] for k, v in faces.items()}
    return BodyMesh(points, tets, top, faces)


# --------------------------------------------------------------------------------------------------------------
# ball segment on a block (Hertz validation)
@dataclass(frozen=True)
class BallSpec:
    """One eighth of a ball of radius ``radius`` touching z = 0 at the origin: x, y >= 0, 0 <= z <= radius (the
    flat face z = radius is the driven face). Fine zone: the ball of radius ``zone`` about the origin."""

    radius: float
    zone: float
    h_contact: float
    grading: float
    h_max: float


def _ball(spec: BallSpec) -> BodyMesh:
    R = spec.radius
    with _Gmsh("ball_segment") as model:
        occ = model.occ
        ball = occ.addSphere(0.0, 0.0, R, R)
        box = occ.addBox(0.0, 0.0, 0.0, 2 * R, 2 * R, R)
        vol, _ = occ.intersect([(3, ball)], [(3, box)])
        occ.synchronize()
        v = vol[0][1]
        surfs = [s for _, s in model.getBoundary([(3, v)], oriented=False)]
        e = 1e-3 * R
        contact = _closest_face(model, surfs, [e, e, R - np.sqrt(R * R - 2 * e * e)])
        named = {"x0": [_closest_face(model, surfs, [0.0, 0.3 * R, 0.5 * R])],
                 "y0": [_closest_face(model, surfs, [0.3 * R, 0.0, 0.5 * R])],
                 "driven": [_closest_face(model, surfs, [0.3 * R, 0.3 * R, R])]}
        dist = f"Max(0, Sqrt(x^2 + y^2 + z^2) - {spec.zone!r})"
        background_size(model, f"Min({spec.h_max!r}, {spec.h_contact!r} + {spec.grading!r} * {dist})")
        return _extract(model, v, contact, named)


def ball_segment(spec: BallSpec) -> BodyMesh:
    """:class:`BallSpec` meshed (cached)."""
    return _cached("ball", spec, _ball)


def block_body(spec: BlockSpec) -> BodyMesh:
    """The quarter block of :func:`femcheck.meshes.block.block_quarter` ([0, Lx] x [0, Ly] x [-H, 0], contact face
    z = 0) with its faces x0, y0 and bottom as node sets."""
    m = cached_block_quarter(spec)
    P, tiny = m.points, 1e-9 * max(spec.length_x, spec.depth)
    faces = {"x0": np.flatnonzero(P[0] < tiny), "y0": np.flatnonzero(P[1] < tiny),
             "bottom": np.flatnonzero(P[2] < -spec.depth + tiny)}
    return BodyMesh(P, m.tets, m.top, faces)


def flipped_block_body(spec: BlockSpec) -> BodyMesh:
    """The quarter block mirrored to [0, Lx] x [0, Ly] x [0, H] (contact face z = 0 below it, face ``top`` at
    z = H); the tetrahedra are re-oriented after the mirror."""
    m = cached_block_quarter(spec)
    P = m.points * np.array([[1.0], [1.0], [-1.0]])
    tets = m.tets[[1, 0, 2, 3]]
    tiny = 1e-9 * max(spec.length_x, spec.depth)
    faces = {"x0": np.flatnonzero(P[0] < tiny), "y0": np.flatnonzero(P[1] < tiny),
             "top": np.flatnonzero(P[2] > spec.depth - tiny)}
    return BodyMesh(P, tets, m.top[[1, 0, 2]], faces)


# --------------------------------------------------------------------------------------------------------------
# seed 000: barrel roller segment and raceway segments, half models x >= 0 in the local contact frame
@dataclass(frozen=True)
class RollerSegmentSpec:
    """Barrel roller of diameter ``diameter`` at its mid-plane and crown radius ``crown_radius`` (seed 000
    Table 1), axis the line z = D/2 along y. Segment: |y| <= ``half_length``, the quadrant between the contact
    generatrix (x = 0, z >= 0) and the plane z = D/2 through the axis (the driven face), i.e. a 90 deg sector
    revolved about the roller axis. Fine zone |x| <= zone_x, |y| <= zone_y, z <= min(zone_x, zone_y).
    ``stretch_y`` >= 1: elements ``stretch_y`` times longer along y than across (see :func:`_stretched_mesh`)."""

    diameter: float
    crown_radius: float
    half_length: float
    zone_x: float
    zone_y: float
    h_contact: float
    grading: float
    h_max: float
    stretch_y: float = 1.0


@dataclass(frozen=True)
class RingSegmentSpec:
    """Raceway segment: the groove circle of radius ``groove_radius`` centred at (0, 0, groove_radius) in the
    meridian plane x = 0 (concave groove: its centre lies on the roller side), revolved about the bearing axis,
    the line through (0, axis_y, axis_z) with direction (0, cos alpha, sin alpha). Material below the groove
    (z down to -depth in the meridian plane), |y| <= half_length, revolved by the angle that moves the contact
    point ``length_x`` along x. The bottom face is clamped. ``stretch_y`` as for :class:`RollerSegmentSpec`."""

    groove_radius: float
    axis_y: float
    axis_z: float
    contact_angle: float
    half_length: float
    length_x: float
    depth: float
    zone_x: float
    zone_y: float
    h_contact: float
    grading: float
    h_max: float
    stretch_y: float = 1.0


def _box_distance(zx: float, zy: float, stretch: float = 1.0) -> str:
    """Gmsh expression of the physical distance from the fine box |x| <= zx, |y| <= zy, |z| <= min(zx, zy),
    evaluated in the y-compressed coordinates of :func:`_stretched_mesh` (physical y = stretch * y)."""
    zz = min(zx, zy)
    return (f"Sqrt(Max(0, Abs(x) - {zx!r})^2 + Max(0, Abs({stretch!r} * y) - {zy!r})^2 + "
            f"Max(0, Abs(z) - {zz!r})^2)")


def _stretched_size(spec) -> str:
    """Size field (compressed coordinates) of a stretched body: a compressed size H gives elements H across
    (x, z) and stretch * H along y. H = min(h_max / stretch, h_contact + grading d), d the *physical* distance
    from the fine box: across the strip the mesh grades like the 2D line-contact meshes (the stress field
    under a 42:1 ellipse is close to plane strain in x-z), along y the elements are stretch times longer, and
    the cap keeps the far field no coarser along y than h_max (capping H at h_max instead, elements of ~b_H
    along y beyond the patch, cost 4 % of the long semi-axis: measured at 0.35 a_H, stretch 4)."""
    s = spec.stretch_y
    d = _box_distance(spec.zone_x, spec.zone_y, s)
    return f"Min({spec.h_max / s!r}, {spec.h_contact!r} + {spec.grading!r} * {d})"


def _revolve_to_positive_x(model, face: int, point, direction, angle: float) -> int:
    """Revolve the meridian face (x = 0) about the axis so that the solid lies in x >= 0; returns the volume."""
    occ = model.occ
    for sign in (1.0, -1.0):
        copy = occ.copy([(2, face)])
        out = occ.revolve(copy, *point, *direction, sign * angle)
        occ.synchronize()
        vol = [t for d, t in out if d == 3][0]
        xmin, _, _, xmax, _, _ = occ.getBoundingBox(3, vol)
        if xmax > 1e3 * abs(xmin):                      # OCC pads bounding boxes by its tolerance
            occ.remove([(2, face)], recursive=True)
            occ.synchronize()
            return vol
        occ.remove([(3, vol)], recursive=True)
        occ.synchronize()
    raise RuntimeError("revolution did not give a solid in x >= 0")


def _meridian_face(occ, R: float, half: float, z_far: float) -> int:
    """Face in the plane x = 0 between the arc z = R - sqrt(R^2 - y^2), |y| <= half, and the line z = z_far."""
    za = R - np.sqrt(R * R - half * half)
    p1 = occ.addPoint(0.0, -half, za)
    p2 = occ.addPoint(0.0, half, za)
    c = occ.addPoint(0.0, 0.0, R)
    p3 = occ.addPoint(0.0, half, z_far)
    p4 = occ.addPoint(0.0, -half, z_far)
    arc = occ.addCircleArc(p1, c, p2)                     # the short arc, through the contact point
    loop = occ.addCurveLoop([arc, occ.addLine(p2, p3), occ.addLine(p3, p4), occ.addLine(p4, p1)])
    return occ.addPlaneSurface([loop])


def _compress_y(model, volume: int, stretch: float) -> None:
    """Map the solid by (x, y, z) -> (x, y / stretch, z) (OCC general transformation: the revolved faces become
    NURBS, an exact representation, and an affine map of a NURBS is exact)."""
    if stretch != 1.0:
        model.occ.dilate([(3, volume)], 0.0, 0.0, 0.0, 1.0, 1.0 / stretch, 1.0)
        model.occ.synchronize()


def _stretched_mesh(model, volume: int, contact: int, named: dict[str, list[int]], stretch: float) -> BodyMesh:
    """Mesh the y-compressed solid with an isotropic size field and map the nodes back, y -> stretch * y: every
    tetrahedron is then ``stretch`` times longer along y than across. The contact ellipses of seed 000 are ~42
    times longer along y than across, so an isotropic mesh fine enough across the patch (x) wastes elements
    along it; the pressure varies over b_H along y and over a_H along x, and the same interpolation error in
    both directions needs h_y / h_x ~ b_H / a_H. The map is affine, so the P1 space on the stretched mesh is
    the P1 space of an anisotropic mesh (no approximation beyond the mesh itself)."""
    mesh = _extract(model, volume, contact, named)
    mesh.points[1] *= stretch
    return mesh


def _roller_surface(points: np.ndarray, diameter: float, crown_radius: float) -> np.ndarray:
    """Closest points on the barrel surface: distance from the roller axis (the line x = 0, z = D/2 along y)
    r - (R - sqrt(R^2 - y^2)) at axial position y; the radial direction about the axis is kept (a radial move is
    normal to the surface up to the crown slope y/R, so the axial coordinate is kept to O((y/R)^2) -- the
    moves are at rounding level anyway)."""
    r, R = 0.5 * diameter, crown_radius
    x, y, z = points
    d = np.stack([x, z - r])
    rho = np.linalg.norm(d, axis=0)
    target = r - (R - np.sqrt(R * R - y * y))
    d *= target / rho
    return np.stack([d[0], y, d[1] + r])


def _ring_surface(points: np.ndarray, spec: "RingSegmentSpec") -> np.ndarray:
    """Closest points on the raceway: the groove circle (centre (0, 0, Rg), radius Rg, in the meridian plane)
    revolved about the bearing axis (through q, direction e). In the (axial t, radial rho) half-plane the
    surface is that circle; the closest point keeps the azimuth about the axis."""
    q = np.array([0.0, spec.axis_y, spec.axis_z])[:, None]
    e = np.array([0.0, np.cos(spec.contact_angle), np.sin(spec.contact_angle)])[:, None]
    c = np.array([0.0, 0.0, spec.groove_radius])[:, None]
    t0 = float(((c - q) * e).sum())
    rho0 = float(np.linalg.norm(c - q - t0 * e))
    v = points - q
    t = (v * e).sum(axis=0)
    radial = v - t * e
    rho = np.linalg.norm(radial, axis=0)
    dt, dr = t - t0, rho - rho0
    k = spec.groove_radius / np.hypot(dt, dr)
    t1, rho1 = t0 + k * dt, rho0 + k * dr
    return q + t1 * e + radial * (rho1 / rho)


def _roller(spec: RollerSegmentSpec) -> BodyMesh:
    R, r = spec.crown_radius, 0.5 * spec.diameter
    s = spec.stretch_y
    with _Gmsh("roller_segment") as model:
        occ = model.occ
        face = _meridian_face(occ, R, spec.half_length, r)
        occ.synchronize()
        v = _revolve_to_positive_x(model, face, (0.0, 0.0, r), (0.0, 1.0, 0.0), 0.5 * np.pi)
        _compress_y(model, v, s)
        surfs = [s_ for _, s_ in model.getBoundary([(3, v)], oriented=False)]
        e = 1e-4 * r
        contact = _closest_face(model, surfs, [e, 0.0, r - np.sqrt(r * r - e * e)])
        named = {"x0": [_closest_face(model, surfs, [0.0, 0.0, 0.5 * r])],
                 "driven": [_closest_face(model, surfs, [0.5 * r, 0.0, r])]}
        background_size(model, _stretched_size(spec))
        mesh = _stretched_mesh(model, v, contact, named, s)
    # contact-face nodes exactly on the barrel (the initial gap is a few um over the patch; the NURBS of the
    # transformed solid put nodes off it by rounding only, this removes even that)
    top = np.unique(mesh.top)
    mesh.points[:, top] = _roller_surface(mesh.points[:, top], spec.diameter, spec.crown_radius)
    return mesh


def roller_segment(spec: RollerSegmentSpec) -> BodyMesh:
    """:class:`RollerSegmentSpec` meshed (cached)."""
    return _cached("roller-aniso2", spec, _roller)   # kind names the builder version


def _ring(spec: RingSegmentSpec) -> BodyMesh:
    Rg = spec.groove_radius
    s = spec.stretch_y
    q = np.array([0.0, spec.axis_y, spec.axis_z])
    e = np.array([0.0, np.cos(spec.contact_angle), np.sin(spec.contact_angle)])
    # the contact point's distance from the bearing axis sets the revolution angle for length_x along x
    rho = np.linalg.norm(-q - np.dot(-q, e) * e)
    with _Gmsh("ring_segment") as model:
        occ = model.occ
        face = _meridian_face(occ, Rg, spec.half_length, -spec.depth)
        occ.synchronize()
        v = _revolve_to_positive_x(model, face, tuple(q), tuple(e), spec.length_x / rho)
        _compress_y(model, v, s)
        surfs = [s_ for _, s_ in model.getBoundary([(3, v)], oriented=False)]
        eps = 1e-4 * spec.zone_x
        contact = _closest_face(model, surfs, [eps, 0.0, 0.0])
        named = {"x0": [_closest_face(model, surfs, [0.0, 0.0, -0.5 * spec.depth])],
                 "bottom": [_closest_face(model, surfs, [eps, 0.0, -spec.depth])]}
        background_size(model, _stretched_size(spec))
        mesh = _stretched_mesh(model, v, contact, named, s)
    top = np.unique(mesh.top)
    mesh.points[:, top] = _ring_surface(mesh.points[:, top], spec)
    return mesh


def ring_segment(spec: RingSegmentSpec) -> BodyMesh:
    """:class:`RingSegmentSpec` meshed (cached)."""
    return _cached("ring-aniso2", spec, _ring)
