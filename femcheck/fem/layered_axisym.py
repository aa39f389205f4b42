"""Axisymmetric FE reference for a rigid sphere on a coated block: the ``fem_axisym`` model of the layered point
scenes, beside the 3D ``fem`` (P1) and ``fem_p2`` of :mod:`femcheck.fem.layered_point` and
:mod:`femcheck.fem.layered_point_p2`.

A sphere pressed on a coated half-space is axisymmetric, so the section (r, z) carries the whole problem: the 2D
machinery of :mod:`femcheck.fem.layered_line` with ``geometry = "axisymmetric"`` (hoop strain u_r / r, weight
2 pi r; :func:`femcheck.fem.layered_line.axisymmetric_elasticity`): P2 triangles, the layer a tensor grid of
element rows *nested* from level to level, the substrate graded by Gmsh, the family aligned so that a vertex lies
on the contact edge of level 1, the exact sphere gap R - sqrt(R^2 - r^2), frictionless active set on the
condensed block, nodal pressures lam_i / w_i with w_i = int phi_i 2 pi r ds (positive for P2 on a line, unlike
the corners of P2 triangles in 3D). The block is a cylinder of radius ``numerics.fem_block`` / 2 and depth
as large, clamped at the bottom, free on its side.

Why: the 3D references of the layered point scenes are not certified on this machine (unstructured 3D levels
scatter; a structured 3D zone needs 0.6-0.9 M P2 DOFs at a/9). The axisymmetric section refines as far as
the certificate needs at a few thousand DOFs.

Quantities: ``p_max`` (Pa, :func:`femcheck.qoi.peak`), ``semi_axis_x`` = ``semi_axis_y`` = the contact radius
(m, from the separation beyond the edge, :func:`femcheck.qoi_separation.radial`), ``contact_area`` = pi a^2
(m^2), each the
certificate's value (:func:`femcheck.solvers.similar_levels.certify_similar`: the layer's rows and the contact
zone are nested from level to level and the family is aligned on the edge, so the levels are similar);
``total_force`` (N). The approach of the cylinder (finest level) is in the stats only: the 3D references' blocks
are square, so their approaches are not the same quantity.
"""
from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np

from ..result import ModelResult
from ..solvers.convergence import certificate_stats
from ..solvers.similar_levels import certify_similar
from .layered_line import settings, solve_family


# The family starts at the 2D family's level 1 (h = numerics.fem_h_contact a / 2): at its level 0 (a/10 by default)
# the separation's edge is pre-asymptotic (hertz, homogeneous: radius -0.18 / +0.040 / +0.006 / -0.004 % of Hertz
# at a/10 / a/20 / a/40 / a/80), and a level of the section costs seconds.
FIRST_LEVEL = 1


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem_axisym`` model from flat parameters: ``layer.E|nu|thickness``, ``materials.substrate.E|nu|rigid``,
    ``geometry.radius`` (m), ``load.normal`` (N) and the ``numerics.fem_*`` keys of the 2D layered FE
    (:data:`femcheck.fem.layered_line.FEM_SCHEMA`)."""
    t_start = time.perf_counter()
    s = replace(settings(params), geometry="axisymmetric")
    # the candidate zone also carries the separation beyond the edge, from which the radius is fitted out to
    # (1.3 + one element) a: 1.6 a at least
    s = replace(s, contact_zone=max(s.contact_zone, 1.6))
    layer, sub, t, a_ref, pilots, levels = solve_family(params, s, FIRST_LEVEL, progress)
    fine = levels[-1]
    rows = [{"h": lv.h, "h_over_a": lv.h / a_ref, "layer_rows": lv.layer_rows, "n_dofs": lv.n_dofs,
             "n_elements": lv.n_elements, "p_max": lv.p_max, "semi_axis_x": lv.half_width,
             "contact_area": np.pi * lv.half_width**2, "edge_exponent": lv.edge_exponent,
             "edge_misfit": lv.edge_misfit, "approach_block": lv.approach, "p_max_std": lv.p_max_std,
             "semi_axis_x_std": lv.half_width_std, "iterations": lv.iterations, "residual": lv.residual,
             "total_force": lv.total_force, "time_s": lv.time_s} for lv in levels]
    certs = {n: certify_similar(rows, n) for n in ("p_max", "semi_axis_x", "contact_area")}
    certs["semi_axis_y"] = certs["semi_axis_x"]          # axisymmetric: one radius
    stats: dict[str, Any] = {
        "method": "active_set", "geometry": "axisymmetric", "element_order": s.order,
        "formulation": fine.formulations, "a_ref": a_ref, "pilot_radii": pilots, "levels": rows,
        "finest": {"p_max": fine.p_max, "semi_axis_x": fine.half_width, "approach_block": fine.approach},
        "thickness_over_a": t / fine.half_width,
        "substrate": "rigid" if sub.rigid else {"E": sub.E, "nu": sub.nu},
        "block": {"radius": 0.5 * s.block_width * a_ref, "depth": max(s.block_depth * a_ref, 2.0 * t),
                  "model": "axisymmetric section"}}
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    q["total_force"] = fine.total_force
    # the profile mirrored about the axis (the pressure is even in r): the node on the axis has no ring area and
    # so no pressure of its own, and the profile starts at the first node off it
    fields = {"x": np.concatenate([-fine.x[::-1], fine.x]), "pressure": np.concatenate([fine.p[::-1], fine.p])}
    return ModelResult("fem_axisym", time_s=time.perf_counter() - t_start, quantities=q, stats=stats,
                       fields=fields)
