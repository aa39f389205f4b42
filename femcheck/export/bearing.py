"""Deck of the 2D bearing sections (crb-rigid-rings, crb-elastic-rings, crb-housing-arc; kind bearing_load): the
plane-strain section of :mod:`femcheck.fem.bearing2d` with every body meshed, unit thickness (forces N/m).

Meshes: femcheck's roller (pole zones of uniform spacing h_c, :func:`femcheck.meshes.bearing2d.roller`) rotated to
every roller position psi_j = 2 pi j/Z - load_angle at the pitch radius (r_i + r_o)/2, and the rings
(:func:`femcheck.meshes.bearing2d.ring`, one zone per roller) at ``level`` (the sizes of
:func:`femcheck.fem.bearing2d.solve_level`); quadratic decks keep the chord mid-side nodes, as femcheck's P2 does.
Supports and load (the FE reference's): the inner ring's bore is tied to a rigid shaft (its nodes one rigid body,
reference node at the bearing centre) that carries F' = F_r / l along +x; the outer ring's outside surface is
clamped over the housing arc |theta| <= ``support.housing_half_angle`` (the full circle by default). Rigid rings
(``materials.rings.rigid``) are meshed annuli made rigid bodies (the inner one carries the load, the outer one is
held), ring thickness R/2 where the scene gives no bore or outside diameter.

Rollers: frictionless contact leaves each roller free to roll around the annulus and to turn about its axis, so
two linear constraints per roller hold those modes without resisting the radial load: the tangential
displacement of the roller's nodes nearest to its centre line at +-R/2 is zero (``*EQUATION`` -sin(psi) u_x +
cos(psi) u_y = 0). Rollers that rigid-ring theory leaves unloaded sit in the clearance with nothing to hold them
radially: they are held at those two nodes and left out of the contact (femcheck's FE also solves only the
rollers that may carry load and checks a posteriori that no other is squeezed). Contact: roller poles (slave)
on the raceways (master), node-to-surface, penalty K = 1e3 E*/h_c. Steps: the shaft pushed by the rigid-ring
displacement (every included roller then touches both raceways), then released and loaded with F' at full value.
The geometry starts with the clearance taken up: the inner ring and the shaft moved by (P_d/2)/cos(psi_e) along
the load (psi_e the outermost roller in contact), each roller centred between the raceways along its radial
line, so that every roller in contact touches or overlaps both raceways from the start. A roller in the open
clearance has no radial stiffness, and CalculiX's push step then fails: measured with the clearance open,
"increment size smaller than minimum" on all three scenes; with only P_d/2 taken up (roller 0 touching, its
neighbours 2 um off) the elastic-ring decks still failed at 3 % of the push.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..meshes import bearing2d as meshes
from . import elements
from .assemble import PENALTY, TENSION
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Step, Surface

RIGID_RING_THICKNESS = 0.5        # of the roller radius, where the scene gives no bore / outside diameter


def _promote(points: np.ndarray, tris: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
    tris = elements.orient_tris(points, tris)
    if order == 2:
        return elements.promote(points, tris, elements.TRI_EDGES)
    return points.copy(), tris


def bearing(params: dict, level: int, order: int) -> Deck:
    from ..fem import bearing2d as fe
    from ..problems.bearing_load import section

    if int(params.get("bearing.rows", 1)) != 1 or "geometry.contact_angle" in params:
        raise InputError("SCENE", "the bearing-section deck is the 2D single-row section; allowed: single-row "
                         "cylindrical roller bearings (crb-*)")
    p = params
    s = fe.FESettings(levels=p["numerics.fem_levels"], ratio=p["numerics.fem_ratio"],
                      h_contact=p["numerics.fem_h_contact"], zone=p["numerics.fem_zone"],
                      grading=p["numerics.fem_grading"], h_max_ring=p["numerics.fem_h_max_ring"],
                      h_max_roller=p["numerics.fem_h_max_roller"])
    if not 0 <= level < s.levels:
        raise InputError("--level", f"{level} is not a mesh level of this scene; allowed 0..{s.levels - 1} "
                         "(numerics.fem_levels; 0 = coarsest)")
    sec = section(p)
    b, rr = fe.reference_half_width(sec)
    scale = s.ratio**-level
    h = s.h_contact * b * scale
    half = max(2, int(round(s.zone / s.h_contact / scale)))
    zone = meshes.ZoneSpec(half * h, 2 * half)
    grading = s.grading * scale
    R = sec.roller_radius
    rigid = sec.ring_material.rigid
    roller = meshes.roller(R, zone, fe._spec(h, zone.t_c, grading, s.h_max_roller * R * scale))
    rp, rt = _promote(roller.points, roller.triangles, order)
    rings = []
    for race, back, which in ((sec.inner_raceway, sec.bore, "outer"), (sec.outer_raceway, sec.outside, "inner")):
        if rigid or back <= 0.0:
            back = race - RIGID_RING_THICKNESS * R if which == "outer" else race + RIGID_RING_THICKNESS * R
        t = abs(race - back)
        support = np.pi if which == "outer" else sec.housing_half_angle
        ends = () if (support >= np.pi or rigid) else (support, -support)
        spec = meshes.RingSpec(min(race, back), max(race, back), sec.rollers, which, -sec.load_angle, ends)
        m = meshes.ring(spec, zone, fe._spec(h, zone.t_c, grading, s.h_max_ring * t * scale))
        rings.append((*_promote(m.points, m.triangles, order), race, back))
    etype = elements.ELEMENT_TYPE[(2, order)]
    loaded = rr.loads > 0
    pts, roll_cells = [], []
    n = 0
    tiny = 1e-9 * R
    slave_in, slave_out, equations, held_a, held_b = [], [], [], [], []
    local_on = np.abs(np.hypot(rp[0], rp[1]) - R) < 1e-9 * R
    zone_in = local_on & (np.abs(rp[1]) <= zone.t_c + tiny) & (rp[0] < 0)
    zone_out = local_on & (np.abs(rp[1]) <= zone.t_c + tiny) & (rp[0] > 0)
    e_in, f_in = elements.faces_of_nodes(rt, elements.TRI_EDGES, zone_in)
    e_out, f_out = elements.faces_of_nodes(rt, elements.TRI_EDGES, zone_out)
    corner = np.unique(roller.triangles)
    ia = corner[np.argmin(np.hypot(rp[0, corner] - 0.5 * R, rp[1, corner]))]
    ib = corner[np.argmin(np.hypot(rp[0, corner] + 0.5 * R, rp[1, corner]))]
    n_roll_el = rt.shape[1]
    # the clearance taken up in the geometry: the inner ring (and the shaft) start moved along the load (+x) by
    # d0 = (P_d/2) / cos(psi_e), psi_e the outermost roller in contact, each roller centred between the moved inner
    # raceway and the outer one along its radial line: the outermost rollers then touch both raceways, the inner
    # ones overlap (d0 <= the rigid-ring displacement, so never beyond their final deflection)
    psi_e = float(np.abs(np.angle(np.exp(1j * sec.angles[loaded]))).max())
    d0 = min(max(0.5 * sec.clearance, 0.0) / np.cos(psi_e), float(rr.displacement[0]))
    for j, psi in enumerate(sec.angles):
        c, sn = np.cos(psi), np.sin(psi)
        rho_in = d0 * c + np.sqrt(sec.inner_raceway**2 - (d0 * sn) ** 2)
        P = np.array([[c, -sn], [sn, c]]) @ rp + 0.5 * (rho_in + sec.outer_raceway) * np.array([[c], [sn]])
        pts.append(P)
        roll_cells.append(rt + n)
        if loaded[j]:
            first = j * n_roll_el
            slave_in.append((first + e_in, f_in))
            slave_out.append((first + e_out, f_out))
            for node in (ia, ib):
                eq = sorted([(n + node, 1, -sn), (n + node, 2, c)], key=lambda t_: -abs(t_[2]))
                equations.append([t_ for t_ in eq if abs(t_[2]) > 1e-12])
        else:
            held_a.append(n + ia)
            held_b.append(n + ib)
        n += P.shape[1]
    n_rollers = n
    ring_base = []
    for k, (rp_, rt_, _, _) in enumerate(rings):
        ring_base.append(n)
        pts.append(rp_ + (np.array([[d0], [0.0]]) if k == 0 else 0.0))
        n += rp_.shape[1]
    ref = n
    pts.append(np.array([[d0, d0], [0.0, 0.0]]))
    points = np.concatenate(pts, axis=1)
    rcells = np.concatenate(roll_cells, axis=1)
    blocks = [ElementBlock(etype, rcells, "EROLLERS", "ROLLER", 1)]
    first = 1 + rcells.shape[1]
    for (rp_, rt_, _, _), base, name in zip(rings, ring_base, ("EINNER", "EOUTER")):
        blocks.append(ElementBlock(etype, rt_ + base, name, "RING", first))
        first += rt_.shape[1]
    ids = blocks[0].ids

    def surf(name, parts):
        return Surface(name, np.concatenate([ids[e] for e, _ in parts]), np.concatenate([f for _, f in parts]))

    surfaces = [surf("SROLL_IN", slave_in), surf("SROLL_OUT", slave_out)]
    for (rp_, rt_, race, _), blk, name in zip(rings, blocks[1:], ("SRACE_IN", "SRACE_OUT")):
        on = np.abs(np.hypot(rp_[0], rp_[1]) - race) < 1e-9 * race
        e, f = elements.faces_of_nodes(rt_, elements.TRI_EDGES, on)
        surfaces.append(Surface(name, blk.ids[e], f))
    nsets = {"NREF": np.array([ref]), "NROT": np.array([ref + 1])}
    fixed = [Fixed("NROT", (1, 2, 3))]
    (ip, _, _, ib_r), (op, _, _, ob_r) = rings
    inner_nodes = ring_base[0] + np.arange(ip.shape[1])
    outer_nodes = ring_base[1] + np.arange(op.shape[1])
    if rigid:
        nsets["NINNER"] = inner_nodes
        nsets["NHOUSING"] = outer_nodes
        shaft = RigidIndenter("NINNER", "EINNER", ref, ref + 1, 1)
    else:
        nsets["NBORE"] = ring_base[0] + np.flatnonzero(np.abs(np.hypot(ip[0], ip[1]) - ib_r) < 1e-9 * ib_r)  # unmoved
        on_od = np.abs(np.hypot(op[0], op[1]) - ob_r) < 1e-9 * ob_r
        theta = np.abs(np.arctan2(op[1], op[0]))
        nsets["NHOUSING"] = ring_base[1] + np.flatnonzero(on_od & (theta <= sec.housing_half_angle + 1e-9))
        shaft = RigidIndenter("NBORE", None, ref, ref + 1, 1)
    fixed.append(Fixed("NHOUSING", (1, 2)))
    if held_a:
        nsets["NHELD"] = np.array(held_a + held_b)
        fixed.append(Fixed("NHELD", (1, 2)))
    e_star = 1.0 / (sec.roller_material.compliance + sec.ring_material.compliance)
    law = sec.roller_law()
    q_max = rr.q_max / sec.length
    p_ref = np.sqrt(q_max * e_star / (np.pi * min(law.rx)))
    K = PENALTY * e_star / h
    contacts = [Contact("SROLL_IN", "SRACE_IN", K, TENSION * p_ref), Contact("SROLL_OUT", "SRACE_OUT", K,
                                                                             TENSION * p_ref)]
    F = sec.load / sec.length
    dx, dy = float(rr.displacement[0]), float(rr.displacement[1])
    steps = [Step("step 1: push the shaft by the rest of the rigid-ring displacement (every included roller then "
                  "touches both raceways)", [(ref, 1, dx - d0), (ref, 2, dy)], increment=0.5),
             Step("step 2: release the push, F' = F_r / l on the shaft at full value (load control)",
                  loads=[(ref, 1, F)], new=True)]
    n_def = points.shape[1] - 2
    info = {"scene_kind": "bearing_load", "level": level, "order": order, "element": etype, "h_contact": h,
            "h_over_a": h / b, "block_nodes": n_def, "block_dofs": 2 * n_def, "roller_nodes": n_rollers,
            "rollers_in_contact": int(loaded.sum()), "rollers": sec.rollers, "rigid_rings": bool(rigid),
            "rigid_ring": {"loads": rr.loads.tolist(), "q_max": rr.q_max, "displacement": [dx, dy]},
            "initial_shift": d0,
            "thickness": 1.0, "load_modelled": F, "symmetry": "none (whole section, plane strain)",
            "normal": "radial", "hertz_half_width_qmax": b}
    notes = [f"the inner ring and the shaft start moved by {d0:.6g} m along +x (the clearance taken up): "
             "the shaft's displacement is that plus U of NREF", f"rollers in contact: {int(loaded.sum())} of {sec.rollers} (rigid-ring load zone); the others held "
             "(node set NHELD)", "each roller in contact: tangential displacement zero at two nodes (*EQUATION)",
             "roller loads: contact forces of SROLL_IN / SROLL_OUT, or the reaction of NHOUSING"]
    mats = {"ROLLER": (sec.roller_material.E, sec.roller_material.nu),
            "RING": (sec.ring_material.E, sec.ring_material.nu) if not rigid else
            (sec.roller_material.E, sec.roller_material.nu)}
    return Deck(f"femcheck bearing section (plane strain), level {level} (h = {h / b:.4g} b), {etype}", 2, points,
                blocks, nsets, surfaces, mats, fixed, contacts[0], shaft, 0.0, F, info, contacts=contacts[1:],
                steps=steps, prints=[("NREF", "U", False), ("NHOUSING", "RF", True)], notes=notes,
                equations=equations)
