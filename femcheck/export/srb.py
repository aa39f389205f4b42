"""Deck of the spherical-roller-bearing normal contact (srb-normal, kind srb_contact): the conformal sub-model
of :mod:`femcheck.fem.srb_conformal`, both raceway contacts in one deck.

Per contact (inner, outer) the two meshed elastic bodies of :func:`femcheck.fem.srb_conformal.solve_contact` at
``level`` (:func:`femcheck.fem.srb_conformal.segment_specs`, femcheck's cached Gmsh meshes): the barrel-roller
segment (slave, its real crown) on the raceway segment (master, its real groove and the bearing axis tilted by
the contact angle), in the contact's local frame (z the normal into the roller); the outer contact's bodies are
shifted by ``2.5 D`` along x so the two models do not overlap (they share nothing). Half models (x = 0
symmetry) carrying N/2 each. Supports as femcheck's: raceway bottom clamped, x = 0 symmetry on both bodies, the
roller's axial plane z = D/2 a rigid face (node set made a rigid body) driven along z, x and y held. Real
materials (ROLLER, RING), no equivalent body. Quadratic decks put the mid-side nodes of the contact faces on
the exact barrel / groove (:func:`femcheck.meshes.srb_segments._roller_surface`, ``_ring_surface``): a
straight mid-side node would sit h^2/(8 r) off the roller, about 1 % of the Hertz approach at h = 0.35 a.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..materials import effective_modulus
from ..meshes.srb_segments import _ring_surface, _roller_surface, ring_segment, roller_segment
from . import elements
from .assemble import PENALTY, TENSION
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Step, Surface

SHIFT = 2.5          # outer contact's bodies moved by SHIFT * D along x


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
    push, hinfo = [], {}
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
        pts_all += [rp + shift, gp + shift, np.array([[0.0, 0.0], [0.0, 0.0], [r, r]]) + shift]
        n = ref + 2
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
                      f"NROT_{tag}": np.array([ref + 1])})
        fixed += [Fixed(f"NBOTTOM_{tag}", (1, 2, 3)), Fixed(f"NRINGX0_{tag}", (1,)), Fixed(f"NROLLERX0_{tag}", (1,)),
                  Fixed(f"NREF_{tag}", (1, 2)), Fixed(f"NROT_{tag}", (1, 2, 3))]
        contacts.append(Contact(f"SROLLER_{tag}", f"SRING_{tag}", PENALTY * e_star / rspec.h_contact,
                                TENSION * hz.p_max, name=f"SI_{tag}"))
        rigid.append(RigidIndenter(f"NDRIVEN_{tag}", None, ref, ref + 1, 3, f"_{tag}"))
        push.append((ref, 3, -0.5 * hz.approach))
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
            "normal": "z (local, into the roller)", "outer_shift_x": SHIFT * D}
    steps = [Step("step 1: push both rollers by half their Hertz approach", push, increment=0.5),
             Step("step 2: release the push, N/2 on each half roller at full value (load control)",
                  loads=[(ref, 3, -0.5 * load) for ref, _, _ in push], new=True)]
    prints = [("NREF_I", "U", False), ("NREF_O", "U", False), ("NBOTTOM_I", "RF", True), ("NBOTTOM_O", "RF", True)]
    notes = ["inner contact: element sets EROLLER_I / ERING_I; outer: EROLLER_O / ERING_O, shifted by "
             f"{SHIFT * D:.6g} m along x", "contact-face node sets NTOP_I, NTOP_O (the rollers' faces)"]
    return Deck(f"femcheck SRB conformal normal contact, level {level} (h = {h_el / a_in:.4g} a), {etype}", 3, pts,
                blocks, nsets, surfaces, {"ROLLER": (roller_m.E, roller_m.nu), "RING": (ring_m.E, ring_m.nu)},
                fixed, contacts[0], rigid[0], 0.0, 0.5 * load, info, contacts=contacts[1:], rigid=rigid[1:],
                steps=steps, prints=prints, notes=notes)
