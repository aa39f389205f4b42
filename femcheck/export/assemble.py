"""The common shape of an exported indentation deck: one deformable block (one or more material regions) on
the plane x_normal = 0, a meshed rigid indenter above it, node-to-surface contact, supports, push then load.

Used by the layered scenes (:mod:`femcheck.export.layered`); the constants (penalty, tension, zones) are those
of :mod:`femcheck.export.scenes`, which explains them.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from . import elements
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Surface

PENALTY = 1.0e3       # K = PENALTY E*/h (Pa/m): see femcheck.export.scenes
TENSION = 1.0e-5      # tension at large clearance / the contact's peak pressure


def indented_block(title: str, dim: int, points: np.ndarray, cells: np.ndarray, region: np.ndarray,
                   regions: dict[int, tuple[str, str]], materials: dict[str, tuple[float, float]], order: int,
                   in_zone: Callable, supports: list[tuple[str, Callable, tuple[int, ...]]],
                   indenter: tuple[np.ndarray, np.ndarray], layer: float, e_star: float, h_el: float,
                   p_ref: float, load: float, push: float, info: dict) -> Deck:
    """The deck of a block ``points`` (dim, N) / linear ``cells`` (dim + 1, M) whose contact face is
    x_dim = 0 (top), ``region`` per cell mapped by ``regions`` to (element set, material name); slave faces on the
    top where ``in_zone(X)``; ``supports`` (node set name, where(X), fixed dofs); ``indenter`` (points, C3D8 /
    CPE4 cells) the rigid layer from :mod:`femcheck.export.indenter` (of ``layer`` m thickness); penalty
    K = PENALTY E*/h_el, tension TENSION p_ref; ``load`` (N, on the modelled part) after ``push`` (m)."""
    normal = dim - 1
    if dim == 3:
        cells = elements.orient_tets(points, cells)
        edges, faces, itype = elements.TET_EDGES, elements.TET_FACES, "C3D8"
    else:
        cells = elements.orient_tris(points, cells)
        edges, faces, itype = elements.TRI_EDGES, elements.TRI_EDGES, "CPE4"
    if order == 2:
        points, cells = elements.promote(points, cells, edges)
    n_block = points.shape[1]
    span = float(np.ptp(points, axis=1).max())
    tiny = 1e-9 * span
    etype = elements.ELEMENT_TYPE[(dim, order)]
    on_top = lambda X: np.abs(X[normal]) < tiny  # noqa: E731
    blocks, surfaces_sel = [], []
    first = 1
    for r, (elset, material) in regions.items():
        idx = np.flatnonzero(region == r)
        if idx.size == 0:
            continue
        blk = ElementBlock(etype, cells[:, idx], elset, material, first)
        sel, face = elements.faces_on(points, blk.cells, faces, lambda X: on_top(X) & in_zone(X))
        surfaces_sel.append((blk.ids[sel], face))
        blocks.append(blk)
        first += idx.size
    ipts, icells = indenter
    base = n_block
    pts = np.concatenate([points, ipts], axis=1)
    icells = icells + base
    top_level = float(ipts[normal].min()) + layer
    ref_pt = np.zeros((dim, 2))
    ref_pt[normal] = top_level
    pts = np.concatenate([pts, ref_pt], axis=1)
    ref = base + ipts.shape[1]
    blocks.append(ElementBlock(itype, icells, "EINDENTER", "INDENTER", first))
    P = points
    top = np.flatnonzero(on_top(P))
    nsets = {name: np.flatnonzero(where(P)) for name, where, _ in supports}
    nsets.update({"NTOP": top[in_zone(P[:, top])], "NINDENTER": np.arange(base, base + ipts.shape[1]),
                  "NREF": np.array([ref]), "NROT": np.array([ref + 1])})
    surfaces = [Surface("SSLAVE", np.concatenate([e for e, _ in surfaces_sel]),
                        np.concatenate([f for _, f in surfaces_sel])),
                Surface("SMASTER", blocks[-1].ids, np.ones(icells.shape[1], dtype=np.int64))]
    fixed = [Fixed(name, dofs) for name, _, dofs in supports]
    fixed += [Fixed("NREF", tuple(range(1, dim))), Fixed("NROT", (1, 2, 3))]
    contact = Contact("SSLAVE", "SMASTER", PENALTY * e_star / h_el, TENSION * p_ref)
    info = {"order": order, "element": etype, "h_contact": h_el, "block_nodes": n_block,
            "block_elements": int(cells.shape[1]), "block_dofs": dim * n_block, "load_modelled": load, **info}
    mats = {**materials, "INDENTER": next(iter(materials.values()))}
    return Deck(f"{title}, level {info['level']} (h = {info['h_over_a']:.4g} a), {etype}", dim, pts, blocks, nsets,
                surfaces, mats, fixed, contact, RigidIndenter("NINDENTER", "EINDENTER", ref, ref + 1, dim), push,
                load, info)
