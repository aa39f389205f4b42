"""Structured hexahedral mesh of a bearing ring (a 3D annulus) whose raceway is cut into one load patch per roller
position and ISO/TS 16281 slice, for the 3D condensed bearing model (spec bearing-load.md P3).

The ring r_race <= r <= r_back (the raceway is the surface r = r_race: the bore of an outer ring), -B/2 <= z <= B/2,
is the image of a tensor-product box in (r, theta, z) under (r, theta, z) -> (r cos theta, r sin theta, z), whose
Jacobian r > 0 keeps the hexahedra positively oriented; the nodes of the seam theta = theta_0 + 2 pi are merged
with those of theta_0. Node planes lie on every patch edge:

- circumferentially, a sector of 2 pi/Z per roller centred on the roller angle psi_j, with the patch
  |theta - psi_j| <= a_c meshed by 2 m cells and each of the two remaining parts by ``between`` m cells (uniform);
- axially, the roller's effective length L centred on z = 0 cut into n_s slices of m cells each, and the two ring
  ends outside it (B - L)/2 by ``ends`` m cells each;
- radially, ``radial`` m cells.

So patch (j, k) = {r = r_race, |theta - psi_j| <= a_c, |z - x_k| <= L/(2 n_s)} is a union of whole boundary facets
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

    def __post_init__(self):
        if not 0 < self.patch_half_angle < np.pi / self.rollers:
            raise ValueError("patch_half_angle must lie in (0, pi/Z)")
        if not 0 < self.length <= self.width * (1 + 1e-12):
            raise ValueError("length must lie in (0, width]")


def _theta_nodes(s: RingMeshSpec) -> np.ndarray:
    m, a, half = s.refine, s.patch_half_angle, np.pi / s.rollers
    local = np.concatenate([np.linspace(-half, -a, s.between * m + 1)[:-1], np.linspace(-a, a, 2 * m + 1)[:-1],
                            np.linspace(a, half, s.between * m + 1)[:-1]])
    sector = 2.0 * half
    theta = (s.first_angle + np.arange(s.rollers)[:, None] * sector + local[None, :]).ravel()
    return np.append(theta, theta[0] + 2.0 * np.pi)


def _z_nodes(s: RingMeshSpec) -> np.ndarray:
    m, half_l, half_b = s.refine, 0.5 * s.length, 0.5 * s.width
    mid = np.linspace(-half_l, half_l, s.slices * m + 1)
    if half_b - half_l <= 1e-12 * half_b:
        return mid
    lo = np.linspace(-half_b, -half_l, s.ends * m + 1)[:-1]
    return np.concatenate([lo, mid, -lo[::-1]])


def ring_mesh(s: RingMeshSpec) -> MeshHex:
    """The ring as a skfem ``MeshHex`` (module doc)."""
    r = np.linspace(s.r_race, s.r_back, s.radial * s.refine + 1)
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
