"""Decks of the layered scenes (layer-point, layer-line, layer-rigid): a rigid sphere or cylinder on a block
coated with one bonded layer, femcheck's own coated meshes (:mod:`femcheck.meshes.coated`).

- line contact (``load.per_length``): the half block of :func:`femcheck.fem.layered_line.solve_level` at
  ``level``, scaled by the same reference half-width a_ref (:func:`femcheck.fem.layered_line.reference_width`:
  pilot solves and edge alignment, 1-5 s), CPE3 / CPE6; structured layer rows, graded substrate;
- point contact (``load.normal``): the quarter block of :func:`femcheck.fem.layered_point.solve_level`
  (layer extruded through its thickness, unstructured substrate), C3D4 / C3D10, scaled by femcheck's own
  a_ref (:func:`femcheck.fem.layered_point.reference_radius`: pilot solves on the coarsest mesh, 1.7 s on
  layer-point; the closed-form guess alone is 11 % off there, 148 against 134 um).
Materials: element sets EBLOCK (the layer, material LAYER) and ESUBSTRATE (SUBSTRATE), sharing the interface
nodes (perfect bond). A rigid substrate is not meshed: the layer's bottom is clamped (layer-rigid). Supports:
clamped bottom, symmetry planes x = 0 (and y = 0 in 3D). The indenter is rigid as in the scenes (E* of the
contact is the layered block's own response); the penalty uses the stiffer of the two plane-strain moduli.
"""
from __future__ import annotations

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..meshes.coated import LAYER, SUBSTRATE, LayerSizing, coated_block_half, coated_block_quarter
from . import indenter
from .assemble import indented_block
from .model import Deck

MASTER_CELLS_PER_A = 32
SLAVE_ZONE, MASTER_ZONE = 1.0, 1.25


def _moduli(layer, sub) -> tuple[float, float]:
    """(largest plane-strain modulus E/(1 - nu^2) of the meshed materials (Pa), the indentation's reference
    modulus: the substrate's when elastic, else the layer's)."""
    e_layer = layer.E / (1.0 - layer.nu**2)
    if sub.rigid:
        return e_layer, e_layer
    e_sub = sub.E / (1.0 - sub.nu**2)
    return max(e_layer, e_sub), e_sub


def layered(params: dict, level: int, order: int) -> Deck:
    """The deck of a layer_contact scene at mesh ``level`` (see the module doc)."""
    from ..fem import layered_line as ll
    from ..fem import layered_point as lp
    from ..problems.layer_contact import geometry_of, layer_params

    p = layer_params(params)
    layer, sub, t = ll.materials_of(p)
    R = float(p["geometry.radius"])
    line = geometry_of(p) == "line"
    s = ll.settings(p) if line else lp.settings(p)
    if not 0 <= level < s.levels:
        raise InputError("--level", f"{level} is not a mesh level of this scene; allowed 0..{s.levels - 1} "
                         "(numerics.fem_levels; 0 = coarsest)")
    e_max, e_ref = _moduli(layer, sub)
    regions = {LAYER: ("EBLOCK", "LAYER"), SUBSTRATE: ("ESUBSTRATE", "SUBSTRATE")}
    materials = {"LAYER": (layer.E, layer.nu)}
    if not sub.rigid:
        materials["SUBSTRATE"] = (sub.E, sub.nu)
    coat = {"layer": {"E": layer.E, "nu": layer.nu, "thickness": t},
            "substrate": "rigid" if sub.rigid else {"E": sub.E, "nu": sub.nu}}
    if line:
        W = float(p["load.per_length"])
        a_ref, _ = ll.reference_width(R, layer, sub, t, W, s)
        zone = s.contact_zone * a_ref
        sizing = LayerSizing(s.h_contact * a_ref, zone, s.grading, s.h_max * a_ref, s.layer_elements)
        depth = max(s.block_depth * a_ref, 2.0 * t)
        lm = coated_block_half(s.block_width * a_ref, depth, t, sizing, level, rigid_substrate=sub.rigid)
        h_el = s.h_contact * a_ref / 2**level
        bottom = -t if sub.rigid else -lm.depth
        tiny = 1e-9 * a_ref
        gap = lambda x: R - np.sqrt(np.clip(R * R - x * x, 0.0, None))  # noqa: E731
        ind = indenter.layer_2d(gap, MASTER_ZONE * zone, a_ref / (2 * MASTER_CELLS_PER_A), 0.25 * a_ref)
        supports = [("NBOTTOM", lambda X: X[1] < bottom + tiny, (1, 2)), ("NXSYM", lambda X: X[0] < tiny, (1,))]
        p_ref = hertz.line_contact(W, R, e_ref).p_max
        info = {"scene_kind": "layer_contact", "level": level, "h_over_a": h_el / a_ref, "a_ref": a_ref,
                "block_width": lm.width, "block_depth": lm.depth, "layer_rows": lm.layer_rows, **coat,
                "thickness": 1.0, "symmetry": "half (x = 0)", "normal": "y", "load_total": W,
                "hertz_substrate" if not sub.rigid else "hertz_layer": {"p_max": p_ref}}
        return indented_block("femcheck layered line contact (plane strain)", 2, lm.mesh.points, lm.mesh.triangles,
                              lm.region, regions, materials, order,
                              lambda X: X[0] <= SLAVE_ZONE * zone + tiny, supports, ind, 0.25 * a_ref, e_max, h_el,
                              p_ref, 0.5 * W, a_ref * a_ref / (2.0 * R), info)
    load = float(p["load.normal"])
    a_ref, _ = lp.reference_radius(R, layer, sub, t, load, s)
    zone = s.contact_zone * a_ref
    L = s.block * a_ref
    depth = max(L, 2.0 * t)
    sizing = LayerSizing(s.h_contact * a_ref, zone, s.grading, s.h_max * a_ref, s.layer_elements)
    lm = coated_block_quarter(L, depth, t, sizing, level, rigid_substrate=sub.rigid)
    h_el = s.h_contact * a_ref / 2**level
    tiny = 1e-9 * L
    bottom = -lm.depth
    gap = lambda x, y: R - np.sqrt(np.clip(R * R - x * x - y * y, 0.0, None))  # noqa: E731
    sp = a_ref / MASTER_CELLS_PER_A
    ind = indenter.layer_3d(gap, MASTER_ZONE * zone, MASTER_ZONE * zone, (sp, sp), 0.25 * a_ref)
    supports = [("NBOTTOM", lambda X: X[2] < bottom + tiny, (1, 2, 3)), ("NXSYM", lambda X: X[0] < tiny, (1,)),
                ("NYSYM", lambda X: X[1] < tiny, (2,))]
    p_ref = hertz.point_contact(load, R, e_ref).p_max
    info = {"scene_kind": "layer_contact", "level": level, "h_over_a": h_el / a_ref, "a_ref": a_ref,
            "block_side": L, "block_depth": lm.depth, "layer_rows": lm.layer_rows, **coat,
            "symmetry": "quarter (x = 0, y = 0)", "normal": "z", "load_total": load,
            "hertz_substrate" if not sub.rigid else "hertz_layer": {"p_max": p_ref}}
    return indented_block("femcheck layered point contact", 3, lm.mesh.points, lm.mesh.tets, lm.region, regions,
                          materials, order,
                          lambda X: X[0] ** 2 + X[1] ** 2 <= (SLAVE_ZONE * zone) ** 2 * (1 + 1e-9), supports, ind,
                          0.25 * a_ref, e_max, h_el, p_ref, 0.25 * load, 0.5 * a_ref * a_ref / R, info)
