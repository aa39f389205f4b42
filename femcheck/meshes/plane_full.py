"""Full (non-symmetric) 2D meshes for frictional line contact, built by mirroring the half meshes of
:mod:`femcheck.meshes.plane` about x = 0 and merging the nodes on the symmetry line.

A tangential load makes the contact unsymmetric (Cattaneo's stick zone stays centred but the traction is
antisymmetric in the mirror sense; Carter's adhesion zone sits at the leading edge), so the frictional models
need both halves. Mirroring keeps the contact nodes of the two bodies at the same abscissae
x_i in [-x_c, x_c] (node-to-node pairs), and a mirror-symmetric mesh adds no spurious asymmetry of its own.
"""
from __future__ import annotations

import numpy as np

from .plane import MeshSpec, TriMesh, block_half, cylinder_half


def mirror_merge(half: TriMesh, tol: float) -> TriMesh:
    """Union of ``half`` (x >= 0) and its mirror image x -> -x, nodes with |x| <= ``tol`` (m) shared.

    Mirrored triangles get their node order reversed so that every triangle keeps a counter-clockwise
    (positive Jacobian) orientation.
    """
    pts = half.points
    on_axis = np.abs(pts[0]) <= tol
    if (pts[0] < -tol).any():
        raise ValueError("half mesh must lie in x >= 0")
    n = pts.shape[1]
    # Nodes off the axis get new indices n, n+1, ...; nodes on the axis map to themselves.
    image = np.arange(n)
    off = np.flatnonzero(~on_axis)
    image[off] = n + np.arange(off.size)
    mirrored_pts = pts[:, off] * np.array([[-1.0], [1.0]])
    points = np.concatenate([pts, mirrored_pts], axis=1)
    points[0, np.flatnonzero(on_axis)] = 0.0
    tri_m = image[half.triangles[::-1]]          # reversed order: mirror flips orientation
    return TriMesh(points, np.concatenate([half.triangles, tri_m], axis=1))


def block_full(width: float, depth: float, spec: MeshSpec) -> TriMesh:
    """Block [-width/2, width/2] x [-depth, 0] (m), contact nodes at +-x_i on y = 0."""
    return mirror_merge(block_half(width, depth, spec), 1e-9 * spec.h_contact)


def cylinder_full(radius: float, spec: MeshSpec) -> TriMesh:
    """Lower half of a cylinder of ``radius`` (m) touching y = 0 at the origin, centre (0, R); the loaded flat
    y = R spans [-R, R]. Contact nodes on the exact circle at +-x_i."""
    return mirror_merge(cylinder_half(radius, spec), 1e-9 * spec.h_contact)
