"""Deck of the spherical-roller-bearing normal contact (srb-normal, kind srb_contact): the conformal sub-model
of :mod:`femcheck.fem.srb_conformal`, both raceway contacts in one deck.

Per contact (inner, outer) the two meshed elastic bodies of :func:`femcheck.fem.srb_conformal.solve_contact` at
``level`` (:func:`femcheck.fem.srb_conformal.segment_specs`, femcheck's cached Gmsh meshes): the barrel-roller
segment (slave, its real crown) on the raceway segment (master, its real groove and the bearing axis tilted by
the contact angle), in the contact's local frame (z the normal into the roller); the outer contact's bodies are
shifted by ``2.5 D`` along x so the two models do not overlap (they share nothing). Half models (x = 0
symmetry) carrying N/2 each. Supports as femcheck's: raceway bottom clamped, x = 0 symmetry on both bodies, the
roller's axial plane z = D/2 a rigid face (node set made a rigid body), x and y held. Real materials (ROLLER,
RING), no equivalent body. Quadratic decks put the mid-side nodes of the contact faces on the exact barrel /
groove (:func:`femcheck.meshes.srb_segments._roller_surface`, ``_ring_surface``): a straight mid-side node would
sit h^2/(8 r) off the roller, about 1 % of the Hertz approach at h = 0.35 a.

Load, two steps: (1) each roller's reference node is pulled along -z through a spring (SPRING2,
k = (N/2) / (PULL delta_H)) whose far node is displaced by (PULL + 1) delta_H: load control that ramps from zero,
ending at (N/2) (1 + (delta_H - delta)/(PULL delta_H)), within |delta_H - delta| / (PULL delta_H) = 6 % of N/2
(the conformal approach delta is 17 % below Hertz's delta_H); (2) the springs removed (``*MODEL CHANGE``) and
N/2 applied on each reference node: exact load control from a state 6 % off it. The increment grows after two
increments of at most GROW_BELOW Newton iterations (at ccx's default 4 the increments stayed at 1-5 % of the
step). Measured at level 0 (h = 0.35 a, 127k DOFs): the previous push-then-release deck (push to delta_H/2,
about 0.47 N) diverged in the release (Newton chatter of 1500-2000 contact springs, residuals 1e6 N); a soft
spring (pre-stretch 1000 delta_H) started with increments of 1/512 and had 4 % of the load after 50 iterations;
this deck: 86 iterations in all, 4 in step 2.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..materials import effective_modulus
from ..meshes.srb_segments import _ring_surface, _roller_surface, ring_segment, roller_segment
from . import elements
from .assemble import TENSION
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Spring, Step, Surface

SHIFT = 2.5          # outer contact's bodies moved by SHIFT * D along x
# Penalty K = SRB_PENALTY E*/h (Pa/m). The point decks' 1e3 E*/h made ccx chatter on this 40:1 conformal patch
# (level 0: 13 Newton iterations and a cut-back on every attempt, no converged increment in 15 min); 1e2 E*/h
# converges in 5-6 iterations per increment. Its penetration p/K = p_max h/(1e2 E*) is 8e-4 of the Hertz approach
# (1.4 GPa x 74 um / (1e2 x 114 GPa) = 9 nm against 11 um): below the element's discretisation error.
SRB_PENALTY = 1.0e2
FIRST_INCREMENT = 1.0 / 64  # ccx cut 1/16 back to 1/64 after 14-15 iterations at h = 0.35, 0.5 and 0.7 a
PULL = 3.0               # spring pre-stretch in Hertz approaches (module doc)
GROW_BELOW = 7


def _body(mesh, order: int, project) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """(points, cells, contact-face node mask, named faces' nodes) of one body; for order 2 promoted, the
    contact face's mid-side nodes projected on the exact surface, the named faces with their mid-side nodes."""
    pts, tets = mesh.points.copy(), elements.orient_tets(mesh.points, mesh.tets)
    top = np.unique(mesh.top)
    faces = dict(mesh.faces)
    if order == 2:
        lin = tets
        pts, tets = elements.promote(pts, tets, elements.TET_EDGES)
        pairs = mesh.top[[[0, 1], [1, 2], [2, 0]]].transpose(2, 0, 1).reshape(-1, 2)
        mid = np.unique(elements.midside_nodes(lin, tets, elements.TET_EDGES, pairs))
        mid = mid[mid >= 0]
        pts[:, mid] = project(pts[:, mid])
        top = np.union1d(top, mid)
        faces = {k: elements.with_midside(lin, tets, elements.TET_EDGES, v) for k, v in faces.items()}
    on = np.zeros(pts.shape[1], dtype=bool)
    on[top] = True
    return pts, tets, on, faces


def srb(params: dict, level: int, order: int) -> Deck:
    from ..fem import srb_conformal as sc

    n_levels = int(params.get("numerics.conformal_levels", sc.FEM_DEFAULTS["numerics.conformal_levels"]))
    if not 0 <= level < n_levels:
        raise InputError("--level", f"{level} is not a mesh level of the conformal model; allowed 0..{n_levels - 1}"
                         " (numerics.conformal_levels; 0 = coarsest)")
    roller_m, ring_m = sc._materials(params)
    e_star = effective_modulus(roller_m, ring_m)
    D = float(params["geometry.roller_diameter"])
    load = float(params["load.normal"])
    etype = elements.ELEMENT_TYPE[(3, order)]
    pts_all, blocks, nsets, surfaces, fixed, contacts, rigid = [], [], {}, [], [], [], []
    n, first = 0, 1
    pull, springs, hinfo = [], [], {}
    for c, tag in (("inner", "I"), ("outer", "O")):
        rspec, gspec, hz, _ = sc.segment_specs(params, c, level)
        shift = np.array([[SHIFT * D if c == "outer" else 0.0], [0.0], [0.0]])
        rm, gm = roller_segment(rspec), ring_segment(gspec)
        rp, rt, ron, rf = _body(rm, order, lambda X: _roller_surface(X, rspec.diameter, rspec.crown_radius))
        gp, gt, gon, gf = _body(gm, order, lambda X: _ring_surface(X, gspec))
        n_r = rp.shape[1]
        driven = rf["driven"]
        rx0 = np.setdiff1d(rf["x0"], driven)
        base_r, base_g = n, n + n_r
        ref = base_g + gp.shape[1]
        r = 0.5 * D
        pts_all += [rp + shift, gp + shift, np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [r, r, 1.5 * r]]) + shift]
        n = ref + 3
        rb = ElementBlock(etype, rt + base_r, f"EROLLER_{tag}", "ROLLER", first)
        first += rt.shape[1]
        gb = ElementBlock(etype, gt + base_g, f"ERING_{tag}", "RING", first)
        first += gt.shape[1]
        blocks += [rb, gb]
        se, sf = elements.faces_of_nodes(rt, elements.TET_FACES, ron)
        me, mf = elements.faces_of_nodes(gt, elements.TET_FACES, gon)
        surfaces += [Surface(f"SROLLER_{tag}", rb.ids[se], sf), Surface(f"SRING_{tag}", gb.ids[me], mf)]
        nsets.update({f"NTOP_{tag}": base_r + np.flatnonzero(ron[:n_r]), f"NDRIVEN_{tag}": base_r + driven,
                      f"NROLLERX0_{tag}": base_r + rx0, f"NRINGX0_{tag}": base_g + gf["x0"],
                      f"NBOTTOM_{tag}": base_g + gf["bottom"], f"NREF_{tag}": np.array([ref]),
                      f"NROT_{tag}": np.array([ref + 1]), f"NPULL_{tag}": np.array([ref + 2])})
        fixed += [Fixed(f"NBOTTOM_{tag}", (1, 2, 3)), Fixed(f"NRINGX0_{tag}", (1,)), Fixed(f"NROLLERX0_{tag}", (1,)),
                  Fixed(f"NREF_{tag}", (1, 2)), Fixed(f"NROT_{tag}", (1, 2, 3)), Fixed(f"NPULL_{tag}", (1, 2))]
        contacts.append(Contact(f"SROLLER_{tag}", f"SRING_{tag}", SRB_PENALTY * e_star / rspec.h_contact,
                                TENSION * hz.p_max, name=f"SI_{tag}"))
        rigid.append(RigidIndenter(f"NDRIVEN_{tag}", None, ref, ref + 1, 3, f"_{tag}"))
        springs.append(Spring(ref, ref + 2, 3, 0.5 * load / (PULL * hz.approach), f"ESPRING_{tag}"))
        pull.append((ref + 2, 3, -(PULL + 1.0) * hz.approach))
        hinfo[c] = {"p_max": hz.p_max, "semi_axis_x": hz.semi_axis_x, "semi_axis_y": hz.semi_axis_y,
                    "approach": hz.approach, "h_contact": rspec.h_contact, "roller_nodes": int(n_r),
                    "ring_nodes": int(gp.shape[1])}
    pts = np.concatenate(pts_all, axis=1)
    deformable = sum(v["roller_nodes"] + v["ring_nodes"] for v in hinfo.values())
    a_in = hinfo["inner"]["semi_axis_x"]
    h_el = hinfo["inner"]["h_contact"]
    info = {"scene_kind": "srb_contact", "level": level, "order": order, "element": etype, "h_contact": h_el,
            "h_over_a": h_el / a_in, "block_nodes": deformable, "block_dofs": 3 * deformable,
            "hertz": hinfo, "load_modelled": 0.5 * load, "symmetry": "half (x = 0), each contact",
            "normal": "z (local, into the roller)", "outer_shift_x": SHIFT * D,
            "load_control": f"spring pull ({PULL:g} Hertz approaches pre-stretch), then N/2 with the springs removed"}
    steps = [Step(f"step 1: each roller pulled through its spring ESPRING_I / ESPRING_O, far end moved by "
                  f"{PULL + 1:g} Hertz approaches (about N/2 on each half roller)", pull, increment=FIRST_INCREMENT,
                  grow_below=GROW_BELOW),
             Step("step 2: springs removed, N/2 on each half roller at full value (load control)",
                  loads=[(sp.a, 3, -0.5 * load) for sp in springs], remove=[sp.elset for sp in springs])]
    prints = [("NREF_I", "U", False), ("NREF_O", "U", False), ("NBOTTOM_I", "RF", True), ("NBOTTOM_O", "RF", True)]
    notes = ["inner contact: element sets EROLLER_I / ERING_I; outer: EROLLER_O / ERING_O, shifted by "
             f"{SHIFT * D:.6g} m along x", "contact-face node sets NTOP_I, NTOP_O (the rollers' faces)",
             "load: springs ESPRING_I / ESPRING_O pull the rollers' reference nodes (step 1), then removed and "
             "N/2 applied on each reference node (step 2)"]
    return Deck(f"femcheck SRB conformal normal contact, level {level} (h = {h_el / a_in:.4g} a), {etype}", 3, pts,
                blocks, nsets, surfaces, {"ROLLER": (roller_m.E, roller_m.nu), "RING": (ring_m.E, ring_m.nu)},
                fixed, contacts[0], rigid[0], 0.0, 0.5 * load, info, contacts=contacts[1:], rigid=rigid[1:],
                steps=steps, prints=prints, notes=notes, springs=springs)
