"""Gmsh builders for the 2D plane-strain section of a cylindrical roller bearing: one roller with a refined
contact zone at each pole, and the rings (annuli) with one refined zone per roller.

Contact zones are polylines through exact circle points whose *perpendicular offsets* t_k from the roller's
radial line are the same on the roller and on the raceway (uniform spacing h_c over [-t_c, t_c]), so every
node pair (and every P2 mid-side pair: the chord midpoints have the mean offset) lies on one line parallel to
the radial direction e_r: node-to-node contact along e_r, with the exact initial gap of the two circles.

Rings are meshed as one sector of angle 2 pi/Z centred on a roller and replicated Z times by rotation
(the paper's geometric-similarity idea applied to the rings): the mesh is then Z-fold symmetric to round-off,
and a ring on an axisymmetric support has a block-circulant contact compliance C_jk = C_0,k-j. The two radial
cuts of a sector carry the same transfinite node distribution, so neighbouring sectors share their nodes.
A housing support arc gets nodes at its ends in every sector (the ends' angles reduced into the sector), so
the clamped arc ends on nodes at every level and the mesh stays symmetric.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from .cache import cached_builder
from .plane import MeshSpec, TriMesh, _contact_polyline, _Gmsh, _size_field, _extract


def counter_clockwise(mesh: TriMesh) -> TriMesh:
    """The same mesh with every triangle's nodes in counter-clockwise order (positive Jacobian)."""
    p, t = mesh.points, mesh.triangles.copy()
    area2 = (p[0, t[1]] - p[0, t[0]]) * (p[1, t[2]] - p[1, t[0]]) - (p[0, t[2]] - p[0, t[0]]) * (p[1, t[1]] - p[1, t[0]])
    flip = area2 < 0
    t[1, flip], t[2, flip] = mesh.triangles[2, flip], mesh.triangles[1, flip]
    return TriMesh(p, t)


@dataclass(frozen=True)
class ZoneSpec:
    """Contact zone: half-length ``t_c`` (m) of perpendicular offsets, ``elements`` per zone (even)."""

    t_c: float
    elements: int

    @property
    def offsets(self) -> np.ndarray:
        """Vertex offsets t_k (m), uniform over [-t_c, t_c]."""
        return np.linspace(-self.t_c, self.t_c, self.elements + 1)


@cached_builder("bearing-roller")
def roller(radius: float, zone: ZoneSpec, spec: MeshSpec) -> TriMesh:
    """Disc of ``radius`` (m) centred at the origin, local frame x = e_r (outward from the bearing axis):
    the inner pole zone (towards the bearing axis) at x = -sqrt(R^2 - t^2), the outer pole zone at
    x = +sqrt(R^2 - t^2), t = y."""
    t = zone.offsets
    xs = np.sqrt(radius**2 - t**2)
    with _Gmsh("roller") as model:
        geo = model.geo
        centre = geo.addPoint(0.0, 0.0, 0.0)
        pts_o, lines_o = _contact_polyline(geo, xs, t)                  # outer pole, t ascending
        pts_i, lines_i = _contact_polyline(geo, -xs[::-1], t[::-1])      # inner pole, t descending
        arc_top = geo.addCircleArc(pts_o[-1], centre, pts_i[0])
        arc_bottom = geo.addCircleArc(pts_i[-1], centre, pts_o[0])
        loop = lines_o + [arc_top] + lines_i + [arc_bottom]
        surf = geo.addPlaneSurface([geo.addCurveLoop(loop)])
        geo.synchronize()
        for ln in lines_o + lines_i:
            model.mesh.setTransfiniteCurve(ln, 2)
        _size_field(model, lines_o + lines_i, spec)
        return counter_clockwise(_extract(model, surf))


@dataclass(frozen=True)
class RingSpec:
    """An annulus r_in < r < r_out with ``rollers`` contact zones on the raceway (``raceway`` = "outer" for the
    inner ring, "inner" for the outer ring) at angles 2 pi j / Z + ``first_angle``; ``support_ends``: angles
    (rad) on the other surface that must be nodes (ends of a housing arc)."""

    r_in: float
    r_out: float
    rollers: int
    raceway: str
    first_angle: float = 0.0
    support_ends: tuple[float, ...] = ()


@cached_builder("bearing-sector")
def _sector(ring: RingSpec, zone: ZoneSpec, spec: MeshSpec) -> TriMesh:
    """The sector |theta| <= pi/Z centred on zone 0 (at theta = 0)."""
    half = np.pi / ring.rollers
    t = zone.offsets
    r_race = ring.r_out if ring.raceway == "outer" else ring.r_in
    r_back = ring.r_in if ring.raceway == "outer" else ring.r_out
    # nodes on the radial cuts: uniform, as fine as the size field is there (the same on both cuts)
    d_cut = r_race * np.sin(half) - zone.t_c
    h_cut = min(spec.h_max, spec.h_contact + spec.grading * max(d_cut, 0.0))
    n_cut = max(2, int(np.ceil((ring.r_out - ring.r_in) / h_cut)))
    ends = sorted({float((a - ring.first_angle + half) % (2.0 * half) - half) for a in ring.support_ends})
    ends = [a for a in ends if -half + 1e-9 < a < half - 1e-9]
    with _Gmsh("ring-sector") as model:
        geo = model.geo
        centre = geo.addPoint(0.0, 0.0, 0.0)
        # raceway: zone polyline (t ascending = counter-clockwise) between two arcs
        xs = np.sqrt(r_race**2 - t**2)
        pts_z, lines_z = _contact_polyline(geo, xs, t)
        p_race_lo = geo.addPoint(r_race * np.cos(-half), r_race * np.sin(-half), 0.0)
        p_race_hi = geo.addPoint(r_race * np.cos(half), r_race * np.sin(half), 0.0)
        race = [geo.addCircleArc(p_race_lo, centre, pts_z[0])] + lines_z + \
               [geo.addCircleArc(pts_z[-1], centre, p_race_hi)]
        # back surface (bore or OD) from +half to -half through the support-end points
        angles = [half] + sorted(ends, reverse=True) + [-half]
        back_pts = [geo.addPoint(r_back * np.cos(a), r_back * np.sin(a), 0.0) for a in angles]
        back = [geo.addCircleArc(back_pts[i], centre, back_pts[i + 1]) for i in range(len(back_pts) - 1)]
        cut_hi = geo.addLine(p_race_hi, back_pts[0])
        cut_lo = geo.addLine(back_pts[-1], p_race_lo)
        surf = geo.addPlaneSurface([geo.addCurveLoop(race + [cut_hi] + back + [cut_lo])])
        geo.synchronize()
        for ln in lines_z:
            model.mesh.setTransfiniteCurve(ln, 2)
        for ln in (cut_hi, cut_lo):
            model.mesh.setTransfiniteCurve(ln, n_cut + 1)
        _size_field(model, lines_z, spec)
        return _extract(model, surf)


def ring(ring_spec: RingSpec, zone: ZoneSpec, spec: MeshSpec) -> TriMesh:
    """Whole ring: the sector rotated to every roller angle and merged (module doc)."""
    sec = counter_clockwise(_sector(ring_spec, zone, spec))
    z = ring_spec.rollers
    n = sec.points.shape[1]
    pts, tris = [], []
    for j in range(z):
        a = ring_spec.first_angle + 2.0 * np.pi * j / z
        c, s = np.cos(a), np.sin(a)
        pts.append(np.array([[c, -s], [s, c]]) @ sec.points)
        tris.append(sec.triangles + j * n)
    points = np.concatenate(pts, axis=1)
    triangles = np.concatenate(tris, axis=1)
    # merge the nodes the sectors share on their radial cuts
    tol = 1e-9 * ring_spec.r_out
    pairs = cKDTree(points.T).query_pairs(tol, output_type="ndarray")
    rep = np.arange(points.shape[1])
    for a, b in sorted(map(tuple, np.sort(pairs, axis=1)), reverse=True):
        rep[b] = rep[a]
    # resolve chains (a node merged into one that was merged again)
    while True:
        nxt = rep[rep]
        if np.array_equal(nxt, rep):
            break
        rep = nxt
    used, inverse = np.unique(rep, return_inverse=True)
    return TriMesh(points[:, used].copy(), inverse[triangles].reshape(triangles.shape))
