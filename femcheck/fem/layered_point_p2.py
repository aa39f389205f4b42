"""3D FE reference for a rigid sphere on a coated block with quadratic (P2) tetrahedra and a mortar contact
pressure: the ``fem_p2`` model of the layered point scenes, beside the P1 ``fem`` of
:mod:`femcheck.fem.layered_point` (same coated quarter block, Gmsh surface mesh extruded through the layer,
the same pilot radius a_ref).

The pressure is the discrete problem's own field (linear multipliers on the face's corner nodes, weak Signorini
conditions, :func:`femcheck.fem.quarter_mortar.mortar_on_solid`); p_max is its centre value
(:func:`femcheck.qoi.centre_value_2d` over half the contact), the semi-axes come from the separation outside the
contact (:func:`femcheck.qoi_separation.ellipse`), ``approach_block`` is the rigid approach towards the clamped bottom
of the finite block (m). Levels have contact element sizes ``h_contact`` a_ref r^-k (r = ``ratio``, sqrt 2 by
default: a P2 level of a/8 already has as many DOFs as the P1 level of a/16), with the grading and the cap scaled
alike and ceil(``layer_elements`` r^k) element rows through the layer.

Measured on layer-point (t/a = 0.34, 420 GPa on steel), against the layered half-space BEM (Papkovich-Neuber
kernel, 65 cells): p_max +0.98 / +0.30 / +0.12 % at a/4 / a/5.66 / a/8 (36k / 95k / 252k DOFs, 6 / 20 / 88 s);
the P1 reference's finest level (a/16, 237k DOFs) is -1.0 %.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError, InputError
from ..materials import Elastic
from ..meshes.coated import LAYER, SUBSTRATE, LayerSizing, coated_block_quarter
from ..qoi import centre_value_2d
from ..qoi_separation import ellipse
from ..result import ModelResult
from ..solvers.convergence import certificate_stats, certify_levels
from .layered_line import materials_of
from .layered_point import assemble_layered_solid, reference_radius, settings
from .quarter_mortar import mortar_on_solid

QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y", "approach_block")
NU_MAX_P2 = 0.49        # quadratic tetrahedra: no volumetric locking at this Poisson's ratio in the displacement form


@dataclass(frozen=True)
class P2Settings:
    levels: int = 3
    ratio: float = 2.0**0.5
    h_contact: float = 0.25
    grading: float = 0.25
    h_max: float = 2.0
    contact_zone: float = 1.3
    block: float = 20.0
    layer_elements: int = 2
    contact_tol: float = 1e-10


def solve_level(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float, a_ref: float,
                level: int, s: P2Settings) -> dict[str, Any]:
    """One level: its quantities, size and cost (SI)."""
    t0 = time.perf_counter()
    f = s.ratio**-level
    zone = s.contact_zone * a_ref
    L = s.block * a_ref
    depth = max(L, 2.0 * thickness)
    h = s.h_contact * a_ref * f
    sizing = LayerSizing(h, zone, s.grading * f, s.h_max * a_ref * f, int(np.ceil(s.layer_elements / f - 1e-9)))
    lm = coated_block_quarter(L, depth, thickness, sizing, 0, rigid_substrate=substrate.rigid)
    mesh_s = time.perf_counter() - t0
    t = time.perf_counter()
    mats = {LAYER: layer} if substrate.rigid else {LAYER: layer, SUBSTRATE: substrate}
    solid = assemble_layered_solid(lm, mats, order=2)
    assembly_s = time.perf_counter() - t

    def gap(x, y):
        return radius - np.sqrt(radius**2 - x**2 - y**2)

    try:
        c = mortar_on_solid(solid, lm.mesh, lm.depth, gap, 0.25 * load, lambda x, y: x**2 + y**2 <= zone**2,
                            lambda x, y: x**2 + y**2 < a_ref**2, lambda x, y: x**2 + y**2 > (0.9 * zone) ** 2,
                            order=2, contact_tol=s.contact_tol)
    except RuntimeError as exc:
        raise ConvergenceError("FEM P2 layered point contact", 1, np.inf, s.contact_tol, str(exc)) from exc
    loaded = c.p > 0
    rx, ry = float(c.xc[loaded].max()), float(c.yc[loaded].max())
    centre = centre_value_2d(c.xc, c.yc, c.p, 0.5 * rx, 0.5 * ry)
    X, Y, g = c.gap_face
    edges = ellipse(X, Y, g, rx, ry, h)
    i0 = int(np.argmin(c.xc**2 + c.yc**2))
    on_x = np.flatnonzero(np.abs(c.yc) < 1e-9 * L)
    ox = on_x[np.argsort(c.xc[on_x])]
    return {"h": h, "h_over_a": h / a_ref, "layer_rows": lm.layer_rows, "p_max": centre.value,
            "p_max_std": centre.std, "p_max_nodal": float(c.p[i0]),
            "semi_axis_x": edges["semi_axis_x"], "semi_axis_y": edges["semi_axis_y"],
            "semi_axis_x_std": edges["semi_axis_x_std"], "semi_axis_y_std": edges["semi_axis_y_std"],
            "approach_block": c.approach, "total_force": 4.0 * float(c.lam.sum()), "n_nodes": lm.mesh.n_nodes,
            "n_dofs": c.n_dofs, "n_elements": int(lm.mesh.tets.shape[1]), "active_nodes": c.active_nodes,
            "iterations": c.iterations, "residual": c.residual, "linear_solver": c.solver,
            "penetration": c.penetration, "time_s": time.perf_counter() - t0,
            **c.times, "mesh_s": mesh_s, "assembly_s": assembly_s,
            "_fields": {"x": c.xc[ox], "pressure": c.p[ox]}}


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem_p2`` model of the layered point scenes (quantities p_max (Pa), semi_axis_x, semi_axis_y,
    approach_block (m), each the certificate's value; total_force (N) of the finest level)."""
    t_start = time.perf_counter()
    layer, sub, t = materials_of(params)
    for name, mat in (("layer.nu", layer), ("materials.substrate.nu", sub)):
        if not mat.rigid and mat.nu > NU_MAX_P2:
            raise InputError(name, f"{mat.nu:g} for the P2 FEM; allowed (-1, {NU_MAX_P2}]")
    R, load = float(params["geometry.radius"]), float(params["load.normal"])
    p1 = settings(params)
    s = P2Settings(levels=int(params.get("numerics.p2_levels", 3)), h_contact=p1.h_contact, grading=p1.grading,
                   h_max=p1.h_max, contact_zone=p1.contact_zone, block=p1.block, layer_elements=p1.layer_elements)
    if progress:
        progress("FEM P2 pilot solves (contact radius, P1)")
    a_ref, pilots = reference_radius(R, layer, sub, t, load, p1)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM P2 level {k + 1}/{s.levels}")
        levels.append(solve_level(R, layer, sub, t, load, a_ref, k, s))
    fields = levels[-1].pop("_fields")
    for lv in levels[:-1]:
        lv.pop("_fields")
    stats: dict[str, Any] = {
        "method": "mortar active set (P1 multipliers, weak Signorini), condensed onto the contact candidates",
        "element": "P2 tetrahedra (layer: extruded, structured through the thickness)",
        "a_ref": a_ref, "pilot_radii": pilots, "levels": levels,
        "finest": {q: levels[-1][q] for q in QUANTITIES},
        "substrate": "rigid" if sub.rigid else {"E": sub.E, "nu": sub.nu},
        "block": {"side": s.block * a_ref, "depth": max(s.block * a_ref, 2.0 * t), "model": "quarter"}}
    certs = certify_levels(levels, QUANTITIES)
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    q["total_force"] = levels[-1]["total_force"]
    return ModelResult("fem_p2", time_s=time.perf_counter() - t_start, quantities=q, stats=stats, fields=fields)
