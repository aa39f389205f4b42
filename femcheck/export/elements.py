"""Element types of the exported decks, quadratic promotion of femcheck's linear meshes, face numbering.

Node and face numbering follow the Abaqus convention (CalculiX uses the same): C3D4 faces S1 = 1-2-3,
S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1; C3D10 adds mid-side nodes 5 (1-2), 6 (2-3), 7 (3-1), 8 (1-4), 9 (2-4),
10 (3-4). CPE3 edges S1 = 1-2, S2 = 2-3, S3 = 3-1; CPE6 adds 4 (1-2), 5 (2-3), 6 (3-1). C3D8 faces S1 = 1-2-3-4,
S2 = 5-8-7-6, ...; CPE4 edges S1 = 1-2 ... S4 = 4-1. A face's nodes are its corner nodes (a quadratic face also
carries the mid-side nodes of its edges).
"""
from __future__ import annotations

import numpy as np

TET_FACES = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])      # S1..S4 of C3D4 / C3D10
TRI_EDGES = np.array([[0, 1], [1, 2], [2, 0]])                        # S1..S3 of CPE3 / CPE6
TET_EDGES = np.array([[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]])  # mid-side nodes 5..10 of C3D10
NODES_PER_ELEMENT = {"C3D4": 4, "C3D10": 10, "C3D8": 8, "CPE3": 3, "CPE6": 6, "CPE4": 4, "SPRING2": 2}
ELEMENT_TYPE = {(3, 1): "C3D4", (3, 2): "C3D10", (2, 1): "CPE3", (2, 2): "CPE6"}


def orient_tets(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Tetrahedra (4, M) with positive volume (nodes 1 and 2 swapped where det[x2-x1, x3-x1, x4-x1] < 0)."""
    x = points[:, tets]
    det = np.einsum("im,im->m", np.cross((x[:, 1] - x[:, 0]).T, (x[:, 2] - x[:, 0]).T).T, x[:, 3] - x[:, 0])
    out = tets.copy()
    neg = det < 0
    out[0, neg], out[1, neg] = tets[1, neg], tets[0, neg]
    return out


def orient_tris(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Triangles (3, M) counter-clockwise in the x-y plane (nodes 1 and 2 swapped where the area is negative)."""
    x = points[:, tris]
    area = (x[0, 1] - x[0, 0]) * (x[1, 2] - x[1, 0]) - (x[0, 2] - x[0, 0]) * (x[1, 1] - x[1, 0])
    out = tris.copy()
    neg = area < 0
    out[0, neg], out[1, neg] = tris[1, neg], tris[0, neg]
    return out


def promote(points: np.ndarray, cells: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Quadratic cells from linear ones: one mid-side node per unique edge, placed at the edge's midpoint
    (every exported boundary is straight or planar, so the midpoint lies on it). ``cells`` (k, M) corner
    nodes, ``edges`` (e, 2) local corner pairs in the order of the quadratic element's mid-side nodes.
    Returns (points (d, N + E), cells (k + e, M))."""
    pairs = np.sort(cells[edges].transpose(2, 0, 1).reshape(-1, 2), axis=1)      # (M*e, 2)
    uniq, inverse = np.unique(pairs, axis=0, return_inverse=True)
    mid = 0.5 * (points[:, uniq[:, 0]] + points[:, uniq[:, 1]])
    n = points.shape[1]
    extra = (n + inverse.reshape(-1, edges.shape[0])).T
    return np.concatenate([points, mid], axis=1), np.concatenate([cells, extra], axis=0)


def faces_on(points: np.ndarray, cells: np.ndarray, faces: np.ndarray, where) -> tuple[np.ndarray, np.ndarray]:
    """(element indices, face numbers 1..) of the faces whose corner nodes all satisfy ``where(X)`` (X (d, k))."""
    corner = cells[faces]                                      # (f, k, M)
    ok = np.ones(corner.shape[::2], dtype=bool)                # (f, M)
    for j in range(faces.shape[1]):
        ok &= where(points[:, corner[:, j, :]])
    face, elem = np.nonzero(ok)
    order = np.argsort(elem, kind="stable")
    return elem[order], face[order] + 1


def faces_of_nodes(cells: np.ndarray, faces: np.ndarray, on: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(element indices, face numbers 1..) of the faces whose corner nodes are all flagged in ``on`` (N,) bool."""
    ok = on[cells[faces]].all(axis=1)                          # (f, M)
    face, elem = np.nonzero(ok)
    order = np.argsort(elem, kind="stable")
    return elem[order], face[order] + 1


def midside_nodes(linear: np.ndarray, quadratic: np.ndarray, edges: np.ndarray,
                  pairs: np.ndarray) -> np.ndarray:
    """The mid-side node of each corner-node pair in ``pairs`` (K, 2), looked up in the quadratic cells
    (``quadratic`` from :func:`promote` of ``linear`` with ``edges``); -1 where no cell has that edge."""
    k = linear.shape[0]
    ends = np.sort(linear[edges].transpose(2, 0, 1).reshape(-1, 2), axis=1)
    mids = quadratic[k:].T.reshape(-1)
    table = dict(zip(map(tuple, ends.tolist()), mids.tolist()))
    return np.array([table.get(tuple(sorted(p)), -1) for p in pairs.tolist()], dtype=np.int64)


def with_midside(linear: np.ndarray, quadratic: np.ndarray, edges: np.ndarray, nodes: np.ndarray) -> np.ndarray:
    """``nodes`` (corner-node indices of a face) and the mid-side nodes of the edges joining two of them."""
    k = linear.shape[0]
    on = np.zeros(quadratic.max() + 1, dtype=bool)
    on[nodes] = True
    both = on[linear[edges[:, 0]]] & on[linear[edges[:, 1]]]          # (e, M)
    return np.union1d(nodes, quadratic[k:][both])
