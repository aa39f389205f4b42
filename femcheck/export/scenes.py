"""A scene kind -> the deck of its FE reference: femcheck's own Gmsh mesh of the elastic block at one of the
scene's mesh levels, a meshed rigid indenter with the scene's gap, contact, supports and the two load steps.

Like femcheck's own FE models (:mod:`femcheck.fem.point_contact`, :mod:`femcheck.fem.line_contact` with a rigid
cylinder), the two bodies are replaced by a rigid indenter on one block of the equivalent material
E*(1 - nu^2), nu (:func:`femcheck.fem.point_contact.equivalent_pair`), whose contact modulus is the pair's
E* (Johnson 1985, §4.2: frictionless normal contact depends on E* alone, Dundurs coupling neglected as
Hertz does); the block is the scene's quarter
(3D) or half (2D) with symmetry planes on rollers and a clamped bottom.

Load control in two steps (the formulation the issue measured): step 1 pushes the indenter down by
``push`` = a^2 / (2R) (half the Hertz approach of a sphere) so that contact exists and the rigid body is held;
step 2 releases the push and applies the scene's load on the modelled part (a quarter of ``load.normal`` in 3D,
half of ``load.per_length`` times the unit thickness in 2D) at full value from its first increment.

CalculiX evaluates node-to-surface contact on the deformed surface (the slave nodes' displaced positions), Hertz
and femcheck's FE on the undeformed one: the surface's inward strain u_x/x, of order (1 - 2 nu) p0 / E*
(-0.82 % near the centre in hertz-line), lowers CalculiX's p_max by 0.33 % there (measured against the same deck
at a thousandth of the load). Compare at loads where that strain is small when the discretisation is the
question.

2D (hertz-line): plane-strain CPE3 / CPE6 elements, not one layer of C3D elements. The deck is then the
natural 2D deck for Abaqus (which has plane-strain elements and 2D contact), and CalculiX expands CPE
elements itself into one layer of C3D6 / C3D15 wedges with the plane-strain constraint on the out-of-plane
displacement, so both codes read the same file; an explicit layer would need those constraints written out
and is not what an Abaqus user expects.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..fem import point_contact as fem_point
from ..materials import effective_modulus
from ..meshes.block import BlockSpec, cached_block_quarter
from ..meshes.plane import MeshSpec, block_half
from . import elements, indenter
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Surface

# Penalty stiffness K = PENALTY * E* / h (Pa/m, h the contact element size): the penetration p/K at the peak
# is (2/pi)(h/a)/PENALTY of the sphere's approach a^2/R (8e-5 at h = a/8), well below the element error.
PENALTY = 1.0e3
# Tension at large clearance (CalculiX's sigma_inf of the linear law) as a fraction of the Hertz peak: it pulls
# on open slave nodes near the master, about (tension/p0) of the load over the candidate annulus (1e-5 here);
# zero is not allowed (CalculiX then takes 1.5 MPa, 5e-4 of this scene's p0).
TENSION = 1.0e-5
MASTER_CELLS_PER_A = 32       # indenter grid spacing a/32: bilinear gap error (1/32)^2/8 = 1.2e-4 of the approach
SLAVE_ZONE = 1.0              # slave faces within the scene's contact candidate zone (numerics.fem_contact_zone)
MASTER_ZONE = 1.25            # the master reaches 25 % beyond the slave zone


def _level(params: dict, level: int) -> None:
    n = int(params["numerics.fem_levels"])
    if not 0 <= level < n:
        raise InputError("--level", f"{level} is not a mesh level of this scene; allowed 0..{n - 1} "
                         "(numerics.fem_levels; 0 = coarsest)")


def _nodes_where(points: np.ndarray, where) -> np.ndarray:
    return np.flatnonzero(where(points))


def _append(points: np.ndarray, more: np.ndarray) -> tuple[np.ndarray, int]:
    return np.concatenate([points, more], axis=1), points.shape[1]


def _quarter_block(title: str, spec: BlockSpec, order: int, gap: Callable, in_zone: Callable,
                   master: tuple[float, float], spacing: tuple[float, float], layer: float, e_star: float,
                   p_ref: float, load: float, push: float, material: tuple[float, float], info: dict,
                   exact_end_y: bool = False) -> Deck:
    """The quarter block of ``spec`` (femcheck's cached Gmsh mesh), C3D4 or C3D10, under a meshed rigid indenter
    with lower face z = gap(x, y) over [-2 s_x, master_x] x [-2 s_y, master_y] (``exact_end_y``: the last row at
    master_y exactly, a roller's end), slave faces on z = 0 where ``in_zone(X)``; penalty K = PENALTY E*/h,
    tension TENSION p_ref; the modelled load ``load`` (N) after a push ``push`` (m)."""
    mesh = cached_block_quarter(spec)
    pts = mesh.points
    tets = elements.orient_tets(pts, mesh.tets)
    if order == 2:
        pts, tets = elements.promote(pts, tets, elements.TET_EDGES)
    n_block = pts.shape[1]
    L = spec.length_x
    tiny = 1e-9 * L
    etype = elements.ELEMENT_TYPE[(3, order)]
    sel, face = elements.faces_on(pts, tets, elements.TET_FACES, lambda X: (np.abs(X[2]) < tiny) & in_zone(X))
    ipts, hexes = indenter.layer_3d(gap, master[0], master[1], spacing, layer, exact_end_y=exact_end_y)
    pts, first = _append(pts, ipts)
    hexes = hexes + first
    top_z = float(gap(np.zeros(1), np.zeros(1))[0]) + layer
    pts, ref = _append(pts, np.array([[0.0, 0.0], [0.0, 0.0], [top_z, top_z]]))
    rot = ref + 1
    blocks = [ElementBlock(etype, tets, "EBLOCK", "BLOCK", 1),
              ElementBlock("C3D8", hexes, "EINDENTER", "INDENTER", 1 + tets.shape[1])]
    P = pts[:, :n_block]
    top = _nodes_where(P, lambda X: np.abs(X[2]) < tiny)
    nsets = {"NBOTTOM": _nodes_where(P, lambda X: X[2] < -spec.depth + tiny),
             "NXSYM": _nodes_where(P, lambda X: X[0] < tiny),
             "NYSYM": _nodes_where(P, lambda X: X[1] < tiny),
             "NTOP": top[in_zone(P[:, top])],
             "NINDENTER": np.arange(first, first + ipts.shape[1]),
             "NREF": np.array([ref]), "NROT": np.array([rot])}
    surfaces = [Surface("SSLAVE", blocks[0].ids[sel], face),
                Surface("SMASTER", blocks[1].ids, np.ones(hexes.shape[1], dtype=np.int64))]
    fixed = [Fixed("NBOTTOM", (1, 2, 3)), Fixed("NXSYM", (1,)), Fixed("NYSYM", (2,)), Fixed("NREF", (1, 2)),
             Fixed("NROT", (1, 2, 3))]
    h_el = spec.h_contact
    contact = Contact("SSLAVE", "SMASTER", PENALTY * e_star / h_el, TENSION * p_ref)
    info = {"order": order, "element": etype, "h_contact": h_el, "mesh_digest": spec.digest(), "block_side": L,
            "block_nodes": n_block, "block_elements": int(tets.shape[1]), "block_dofs": 3 * n_block,
            "equivalent_block": {"E": material[0], "nu": material[1]}, "load_modelled": load,
            "symmetry": "quarter (x = 0, y = 0)", "normal": "z", "master_spacing": list(spacing), **info}
    return Deck(f"{title}, level {info['level']} (h = {info['h_over_a']:.4g} a), {etype}", 3, pts, blocks, nsets,
                surfaces, {"BLOCK": material, "INDENTER": material}, fixed, contact,
                RigidIndenter("NINDENTER", "EINDENTER", ref, rot, 3), push, load, info)


def hertz_point(params: dict, level: int, order: int) -> Deck:
    """Point contact (hertz-point, hertz-elliptic): the quarter block of :func:`femcheck.fem.point_contact.solve_level`
    at ``level`` (same BlockSpec, so the same Gmsh mesh from the mesh cache), C3D4 or C3D10."""
    _level(params, level)
    # the FE model's own setup (gap, equivalent block, Hertz semi-axes that size the mesh)
    gap, block, load, ax, ay = fem_point.indenter_setup(params, "export")
    rx, ry = (params["geometry.radius"],) * 2 if "geometry.radius" in params else (params["geometry.Rx"],
                                                                                   params["geometry.Ry"])
    e_star = block.E / (1.0 - block.nu**2)
    h = hertz.elliptic_contact(load, rx, ry, e_star)
    s = fem_point.settings(params)
    f = s.ratio**-level
    big, small = max(ax, ay), min(ax, ay)
    L = s.block * big
    zx, zy = s.contact_zone * ax, s.contact_zone * ay
    zone = "ellipse" if big <= 2.0 * small else "box"
    h_el = s.h_contact * small * f
    spec = BlockSpec(L, L, L, zx, zy, h_el, s.grading * f, s.h_max * big * f, zone)
    tiny = 1e-9 * L
    if zone == "ellipse":
        in_zone = lambda X: (X[0] / zx) ** 2 + (X[1] / zy) ** 2 <= SLAVE_ZONE**2 * (1 + 1e-9)
    else:
        in_zone = lambda X: (X[0] <= SLAVE_ZONE * zx + tiny) & (X[1] <= SLAVE_ZONE * zy + tiny)
    spacing = (ax / MASTER_CELLS_PER_A, ay / MASTER_CELLS_PER_A)
    info = {"scene_kind": "point_contact", "level": level, "h_over_a": h_el / small,
            "hertz": {"p_max": h.p_max, "semi_axis_x": ax, "semi_axis_y": ay, "approach": h.approach}}
    return _quarter_block("femcheck point contact", spec, order, gap, in_zone,
                          (MASTER_ZONE * zx, MASTER_ZONE * zy), spacing, 0.25 * small, e_star, h.p_max, 0.25 * load,
                          0.5 * ax * ay / np.sqrt(rx * ry), (block.E, block.nu), info)


# Roller master grid: across the roller a_H/16 (bilinear gap error (1/16)^2/8 = 4.9e-4 of the approach);
# along it one a_H (a crown's drop varies over the roller length, 45 a_H here, not over a_H)
ROLLER_CELLS_ACROSS = 16


def roller(params: dict, level: int, order: int) -> Deck:
    """Finite roller (roller-finite, roller-crowned): the quarter block of
    :func:`femcheck.fem.roller_contact.model` at ``level`` (same BlockSpec: fine box over the footprint, block
    ``fem_block`` roller lengths), under a rigid roller with the scene's profile (flat-ended or crowned) that ends
    at the roller's end y = L/2 (sharp edge), C3D4 or C3D10."""
    from ..fem import roller_contact as fem_roller
    from ..geometry import profiles

    _level(params, level)
    if params.get("geometry.tilt", 0.0) != 0.0:
        raise InputError("geometry.tilt", "the exported deck is a quarter model and needs an aligned roller; "
                         "allowed: 0")
    R, Lr, W = params["geometry.radius"], params["geometry.length"], float(params["load.normal"])
    block = fem_point.equivalent_pair(fem_point._body(params, "roller"), fem_point._body(params, "race"))
    e_star = block.E / (1.0 - block.nu**2)
    rr = params.get("geometry.race_radius", np.inf)
    Rr = hertz.reduced_radius(R, rr)
    h = hertz.line_contact(W / Lr, Rr, e_star)
    a = h.half_width
    gap = profiles.roller(R, Lr, params["geometry.crown"], params.get("geometry.crown_radius"),
                          params["geometry.flat_length"], params.get("geometry.crown_design_load"), e_star, rr, 0.0)
    s = fem_roller.settings(params)
    f = s.ratio**-level
    hk = s.h_contact * a * f
    zx, zy = s.contact_zone * a, 0.5 * Lr + a
    side = s.block * Lr
    spec = BlockSpec(side, 0.5 * Lr + side, side, zx, zy, hk, s.grading * f, s.h_max * a * f, zone="box")
    tiny = 1e-9 * side
    in_zone = lambda X: (X[0] <= zx + tiny) & (X[1] <= zy + tiny)
    info = {"scene_kind": "roller_contact", "level": level, "h_over_a": hk / a,
            "hertz": {"p_max": h.p_max, "half_width": a, "line_load": W / Lr}}
    return _quarter_block("femcheck finite roller", spec, order, gap, in_zone, (MASTER_ZONE * zx, 0.5 * Lr),
                          (a / ROLLER_CELLS_ACROSS, a), 0.25 * a, e_star, h.p_max, 0.25 * W, a * a / (2.0 * Rr),
                          (block.E, block.nu), info, exact_end_y=True)


def hertz_line(params: dict, level: int, order: int) -> Deck:
    """Line contact (hertz-line): the half block of :func:`femcheck.fem.line_contact.solve_level` at ``level``
    (same MeshSpec, same Gmsh mesh), plane strain CPE3 or CPE6, a rigid cylinder with the exact circular gap
    R - sqrt(R^2 - x^2) on the equivalent block."""
    from ..fem.line_contact import FEMLineSettings
    from ..scene import elastic

    _level(params, level)
    cyl, blk = elastic(params, "cylinder"), elastic(params, "block")
    block = fem_point.equivalent_pair(cyl, blk)
    e_star = effective_modulus(cyl, blk)
    R, W = float(params["geometry.radius"]), float(params["load.per_length"])
    h = hertz.line_contact(W, R, e_star)
    a = h.half_width
    d = FEMLineSettings()
    s = FEMLineSettings(h_contact=params.get("numerics.fem_h_contact", d.h_contact),
                        grading=params.get("numerics.fem_grading", d.grading),
                        contact_zone=params.get("numerics.fem_contact_zone", d.contact_zone),
                        block_width=params.get("numerics.fem_block_width", d.block_width),
                        block_depth=params.get("numerics.fem_block_depth", d.block_depth))
    h_el = s.h_contact * a / 2**level
    x_c = s.contact_zone * a
    D = s.block_depth * a
    mesh = block_half(s.block_width * a, D, MeshSpec(h_el, x_c, s.grading / 2**level, max(h_el, 2.0 * a)))
    pts = mesh.points
    tris = elements.orient_tris(pts, mesh.triangles)
    if order == 2:
        pts, tris = elements.promote(pts, tris, elements.TRI_EDGES)
    n_block = pts.shape[1]
    tiny = 1e-9 * a
    etype = elements.ELEMENT_TYPE[(2, order)]
    in_zone = lambda X: X[0] <= SLAVE_ZONE * x_c + tiny
    sel, face = elements.faces_on(pts, tris, elements.TRI_EDGES, lambda X: (np.abs(X[1]) < tiny) & in_zone(X))
    gap = lambda x: R - np.sqrt(np.clip(R * R - x * x, 0.0, None))
    spacing = a / (2 * MASTER_CELLS_PER_A)
    ipts, quads = indenter.layer_2d(gap, MASTER_ZONE * x_c, spacing, 0.25 * a)
    pts, first = _append(pts, ipts)
    quads = quads + first
    pts, ref = _append(pts, np.array([[0.0, 0.0], [0.25 * a, 0.25 * a]]))
    rot = ref + 1
    blocks = [ElementBlock(etype, tris, "EBLOCK", "BLOCK", 1),
              ElementBlock("CPE4", quads, "EINDENTER", "INDENTER", 1 + tris.shape[1])]
    P = pts[:, :n_block]
    top = _nodes_where(P, lambda X: np.abs(X[1]) < tiny)
    nsets = {"NBOTTOM": _nodes_where(P, lambda X: X[1] < -D + tiny),
             "NXSYM": _nodes_where(P, lambda X: X[0] < tiny),
             "NTOP": top[in_zone(P[:, top])],
             "NINDENTER": np.arange(first, first + ipts.shape[1]),
             "NREF": np.array([ref]), "NROT": np.array([rot])}
    surfaces = [Surface("SSLAVE", blocks[0].ids[sel], face),
                Surface("SMASTER", blocks[1].ids, np.ones(quads.shape[1], dtype=np.int64))]
    fixed = [Fixed("NBOTTOM", (1, 2)), Fixed("NXSYM", (1,)), Fixed("NREF", (1,)), Fixed("NROT", (1, 2, 3))]
    contact = Contact("SSLAVE", "SMASTER", PENALTY * e_star / h_el, TENSION * h.p_max)
    info = {"scene_kind": "line_contact", "level": level, "order": order, "element": etype,
            "h_contact": h_el, "h_over_a": h_el / a, "block_width": s.block_width * a, "block_depth": D,
            "block_nodes": n_block, "block_elements": int(tris.shape[1]), "block_dofs": 2 * n_block,
            "hertz": {"p_max": h.p_max, "half_width": a},
            "equivalent_block": {"E": block.E, "nu": block.nu}, "load_modelled": 0.5 * W,
            "thickness": 1.0, "symmetry": "half (x = 0)", "normal": "y", "master_spacing": spacing}
    return Deck(f"femcheck line contact (plane strain), level {level} (h = {h_el / a:.4g} a), {etype}", 2, pts,
                blocks, nsets, surfaces, {"BLOCK": (block.E, block.nu), "INDENTER": (block.E, block.nu)}, fixed,
                contact, RigidIndenter("NINDENTER", "EINDENTER", ref, rot, 2), a * a / (2.0 * R), 0.5 * W, info)


def _layered(params: dict, level: int, order: int) -> Deck:
    from .layered import layered

    return layered(params, level, order)


def _srb(params: dict, level: int, order: int) -> Deck:
    from .srb import srb

    return srb(params, level, order)


def _bearing(params: dict, level: int, order: int) -> Deck:
    from .bearing import bearing

    return bearing(params, level, order)


def _friction(params: dict, level: int, order: int) -> Deck:
    from .friction import cattaneo

    return cattaneo(params, level, order)


BUILDERS: dict[str, Callable[[dict, int, int], Deck]] = {"point_contact": hertz_point, "line_contact": hertz_line,
                                                         "roller_contact": roller, "layer_contact": _layered,
                                                         "srb_contact": _srb, "line_tangential": _friction,
                                                         "bearing_load": _bearing}


def build(scene, level: int, order: int) -> Deck:
    """The deck of ``scene`` (a validated :class:`femcheck.scene.Scene`) at mesh ``level`` and element ``order``."""
    if scene.kind not in BUILDERS:
        raise InputError("SCENE", f"{scene.name} is a {scene.kind} scene; export covers the kinds "
                         f"{', '.join(BUILDERS)} (e.g. hertz-point, hertz-line)")
    if order not in (1, 2):
        raise InputError("--order", f"{order}; allowed 1 (linear) or 2 (quadratic)")
    return BUILDERS[scene.kind](scene.params, level, order)
