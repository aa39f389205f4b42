"""Structured hexahedral mesh of a bearing ring (a 3D annulus) whose raceway is cut into one load patch per roller
position and ISO/TS 16281 slice, for the 3D condensed bearing model (spec bearing-load.md P3).

The ring r_race <= r <= r_back (the raceway is the surface r = r_race: the bore of an outer ring), -B/2 <= z <= B/2,
is the image of a tensor-product box in (r, theta, z) under (r, theta, z) -> (r cos theta, r sin theta, z), whose
Jacobian r > 0 keeps the hexahedra positively oriented; the nodes of the seam theta = theta_0 + 2 pi are merged
with those of theta_0. Node planes lie on every patch edge:

- circumferentially, a sector of 2 pi/Z per roller centred on the roller angle psi_j, with the patch
  |theta - psi_j| <= a_c meshed by 2 m cells and each of the two remaining parts by ``between`` m cells (uniform);
- axially, each row's roller effective length L centred on its ``row_centres`` entry (default one row at z = 0) cut
  into n_s slices of ``per_slice`` m cells each, the two ring ends outside the rows by ``ends`` m cells each and the gaps between
  rows by ``gaps`` m cells each; ``z_breaks`` (e.g. the edges of a support) add node planes, a segment they split
  sharing its cells in proportion to length (at least m each);
- radially, ``radial`` m cells, uniform or growing geometrically from the raceway by ``radial_growth`` per
  cell at m = 1 (its m-th root at level m, so the levels stay nested).

So patch (row i, j, k) = {r = r_race, |theta - psi_j| <= a_c, |z - z_i - x_k| <= L/(2 n_s)} is a union of whole boundary facets
at every refinement m, the load integrals are exact, and refining by m keeps the patches (a nested family of
meshes: the condensed compliance converges as the mesh does, with nothing else changing).

Why a structured mesh built here rather than by Gmsh: the patches must be unions of facets at every level, and a
ring is a tensor product in (r, theta, z); Gmsh's transfinite revolve would give the same nodes with an extra node
ordering to translate. The geometry is exact at the vertices (the facets are chords of the circles: sagitta
(pi/(n_theta))^2/2 of the radius, 4e-5 at the coarsest 112-cell circle).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshHex


@dataclass(frozen=True)
class RingMeshSpec:
    """Geometry (m, rad) and cell counts of :func:`ring_mesh` (module doc)."""

    r_race: float            # raceway radius (m)
    r_back: float            # other surface: outside radius of an outer ring (m)
    width: float             # ring width B (m)
    length: float            # roller effective length L (m), centred on z = 0, L <= B
    rollers: int             # Z
    slices: int              # n_s
    patch_half_angle: float  # a_c (rad)
    first_angle: float = 0.0 # psi_0 (rad): roller j at psi_0 + 2 pi j / Z
    refine: int = 1          # m
    between: int = 3         # cells (times m) from a patch edge to the sector edge
    ends: int = 2            # cells (times m) over each ring end outside the roller length
    radial: int = 1          # cells (times m) through the thickness
    row_centres: tuple = (0.0,)  # z of each row's middle (m)
    gaps: int = 1            # cells (times m) over each gap between neighbouring rows
    z_breaks: tuple = ()     # extra axial node planes (m), e.g. a support's edges
    radial_growth: float = 1.0  # ratio of neighbouring radial cells from the raceway outwards (1: uniform)
    per_slice: int = 1       # axial cells (times m) per slice

    def __post_init__(self):
        if self.per_slice < 1:
            raise ValueError("per_slice must be >= 1")
        if not self.radial_growth > 0:
            raise ValueError("radial_growth must be > 0")
        if not 0 < self.patch_half_angle < np.pi / self.rollers:
            raise ValueError("patch_half_angle must lie in (0, pi/Z)")
        if not 0 < self.length <= self.width * (1 + 1e-12):
            raise ValueError("length must lie in (0, width]")
        zc = np.asarray(self.row_centres, dtype=float)
        tol = 1e-12 * self.width
        if zc.size == 0 or np.any(np.diff(zc) < self.length - tol) or \
                zc[0] - 0.5 * self.length < -0.5 * self.width - tol or zc[-1] + 0.5 * self.length > 0.5 * self.width + tol:
            raise ValueError("row_centres must be ascending, rows at least a roller length apart and inside the width")

    @property
    def rows(self) -> int:
        return len(self.row_centres)


def _theta_nodes(s: RingMeshSpec) -> np.ndarray:
    m, a, half = s.refine, s.patch_half_angle, np.pi / s.rollers
    local = np.concatenate([np.linspace(-half, -a, s.between * m + 1)[:-1], np.linspace(-a, a, 2 * m + 1)[:-1],
                            np.linspace(a, half, s.between * m + 1)[:-1]])
    sector = 2.0 * half
    theta = (s.first_angle + np.arange(s.rollers)[:, None] * sector + local[None, :]).ravel()
    return np.append(theta, theta[0] + 2.0 * np.pi)


def _segment(a: float, b: float, cells: int, breaks: np.ndarray) -> np.ndarray:
    """Nodes on [a, b) with ``cells`` uniform cells, or, where ``breaks`` fall inside, each piece its share."""
    inner = breaks[(breaks > a + 1e-12 * abs(b - a)) & (breaks < b - 1e-12 * abs(b - a))]
    if inner.size == 0:
        return np.linspace(a, b, cells + 1)[:-1]
    edges = np.concatenate([[a], inner, [b]])
    share = np.maximum(1, np.rint(cells * np.diff(edges) / (b - a)).astype(int))
    return np.concatenate([np.linspace(e0, e1, n + 1)[:-1] for e0, e1, n in zip(edges[:-1], edges[1:], share)])


def _z_nodes(s: RingMeshSpec) -> np.ndarray:
    m, half_l, half_b = s.refine, 0.5 * s.length, 0.5 * s.width
    breaks = np.sort(np.asarray(s.z_breaks, dtype=float))
    nodes, z = [], -half_b
    for i, zc in enumerate(s.row_centres):
        lo = zc - half_l
        if lo - z > 1e-12 * half_b:            # ring end (first row) or gap to the previous row
            nodes.append(_segment(z, lo, (s.ends if i == 0 else s.gaps) * m, breaks))
        nodes.append(np.linspace(lo, zc + half_l, s.slices * s.per_slice * m + 1)[:-1])
        z = zc + half_l
    if half_b - z > 1e-12 * half_b:
        nodes.append(_segment(z, half_b, s.ends * m, breaks))
    return np.append(np.concatenate(nodes), half_b if half_b - z > 1e-12 * half_b else z)


def ring_mesh(s: RingMeshSpec) -> MeshHex:
    """The ring as a skfem ``MeshHex`` (module doc)."""
    n = s.radial * s.refine
    # geometric radial cells from the raceway (growth 1: uniform): a patch's local field decays within ~its width
    g = s.radial_growth ** (1.0 / s.refine)
    w = g ** np.arange(n)
    r = s.r_race + (s.r_back - s.r_race) * np.concatenate([[0.0], np.cumsum(w)]) / w.sum()
    if s.r_back < s.r_race:
        r = r[::-1]                    # keep r ascending in the box (orientation)
    theta = _theta_nodes(s)
    z = _z_nodes(s)
    box = MeshHex.init_tensor(r, theta, z)
    rr, tt, zz = box.p
    # merge the seam theta_0 + 2 pi onto theta_0
    nt = theta.size
    it = np.rint(np.interp(tt, theta, np.arange(nt))).astype(np.int64)
    ir = np.rint(np.interp(rr, r, np.arange(r.size))).astype(np.int64)
    iz = np.rint(np.interp(zz, z, np.arange(z.size))).astype(np.int64)
    it_m = np.where(it == nt - 1, 0, it)
    key = (ir * nt + it_m) * z.size + iz
    uniq, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    t = inverse[box.t]
    p = np.stack([rr[first] * np.cos(tt[first]), rr[first] * np.sin(tt[first]), zz[first]])
    return MeshHex(np.ascontiguousarray(p), np.ascontiguousarray(t))
