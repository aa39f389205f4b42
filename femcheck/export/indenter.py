"""The indenter of an exported contact scene: one layer of hexahedra (3D) or quadrilaterals (2D) whose lower
face is the indenter's profile, made one rigid body in the deck.

Neither CalculiX nor a portable Abaqus deck has an analytical paraboloid surface, so the profile z = g(x, y)
(m) is sampled on a structured grid of spacing ``spacing`` (m). Bilinear faces between exact nodes overestimate
the gap of a paraboloid by at most s^2 / (8 R) inside a face; relative to the Hertz approach a^2 / R that is
(s/a)^2 / 8 (4.9e-4 at s = a/16; on an ellipse each axis's own semi-axis), far below the element error of the block. The grid starts two cells
before the symmetry planes so that every slave node on x = 0 or y = 0 projects inside a master face.
"""
from __future__ import annotations

from typing import Callable

import numpy as np


def _axis(extent: float, spacing: float, exact_end: bool = False) -> np.ndarray:
    n = int(np.ceil(extent / spacing))
    if exact_end:                    # the last node at ``extent`` itself (a roller's end), spacing <= ``spacing``
        return np.concatenate([spacing * np.arange(-2, 0), np.linspace(0.0, extent, n + 1)])
    return spacing * np.arange(-2, n + 1)


def layer_3d(gap: Callable[[np.ndarray, np.ndarray], np.ndarray], extent_x: float, extent_y: float,
             spacing: tuple[float, float], thickness: float,
             exact_end_y: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(points (3, N), C3D8 cells (8, M) 0-based) of a layer over [-2s_x, extent_x] x [-2s_y, extent_y] with
    spacings ``spacing`` = (s_x, s_y) (each a fraction of its own semi-axis for an elongated contact): lower face
    z = gap(x, y), upper face z = gap + thickness. Nodes 1-4 of each cell lie on the lower face counter-clockwise
    seen from above, so face S1 is the lower face with its outward normal pointing down, at the block.
    ``exact_end_y``: the grid ends at y = extent_y exactly (the gap may be infinite beyond it)."""
    xs, ys = _axis(extent_x, spacing[0]), _axis(extent_y, spacing[1], exact_end_y)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    Z = gap(X, Y)
    nx, ny = X.shape
    low = np.stack([X.ravel(), Y.ravel(), Z.ravel()])
    high = low + np.array([[0.0], [0.0], [thickness]])
    pts = np.concatenate([low, high], axis=1)
    idx = np.arange(nx * ny).reshape(nx, ny)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    top = nx * ny
    cells = np.stack([a, b, c, d, a + top, b + top, c + top, d + top])
    return pts, cells


def layer_2d(gap: Callable[[np.ndarray], np.ndarray], extent: float, spacing: float,
             thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """(points (2, N), CPE4 cells (4, M)) of a strip over [-2s, extent]: lower edge y = gap(x), upper edge
    gap + thickness; counter-clockwise cells whose edge S1 is the lower edge (outward normal down)."""
    xs = _axis(extent, spacing)
    y = gap(xs)
    low = np.stack([xs, y])
    pts = np.concatenate([low, low + np.array([[0.0], [thickness]])], axis=1)
    n = xs.size
    i = np.arange(n - 1)
    return pts, np.stack([i, i + 1, i + 1 + n, i + n])
