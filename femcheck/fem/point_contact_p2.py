"""3D FE reference for point contact with quadratic (P2) tetrahedra and a mortar contact pressure: the ``fem_p2``
model beside the P1 ``fem`` of :mod:`femcheck.fem.point_contact` (same equivalent block, quarter model, Gmsh
mesh family and finite-size check).

What differs is what makes quadratic elements usable for contact. The pressure is the discrete problem's own
field, p_h = sum_i lam_i psi_i with P1 multipliers on the face's corner nodes (weak Signorini conditions,
:mod:`femcheck.solvers.mortar_indenter`), not nodal reactions over tributary areas, which on quadratic faces are
meaningless (a uniform pressure puts no force on a P2 triangle's corners). From it and from the displacement:

* ``p_max``: the pressure field's value at the centre of the contact, lam at the face node there (the
  structured zone puts a node at the centre on every level and meshes its neighbourhood alike, so the value
  converges smoothly; on re-meshed unstructured faces it scattered by 0.05-0.15 % from level to level).
  ``p_max_fit`` (diagnostic): :func:`femcheck.qoi.centre_value_2d`, an even quartic through the nodal values
  within half the fitted semi-axes;
* ``semi_axis_x``, ``semi_axis_y``: from the separation of the surfaces outside the contact at every face DOF
  of the annulus around the edge (:func:`femcheck.qoi_separation.ellipse`: the 3/2-power growth outside a
  square-root pressure edge with regular corrections, over an elliptical outline), because the multiplier's
  nodal values at the last active nodes are its least accurate;
* ``approach_block``: the rigid approach of the indenter towards the clamped bottom of the finite block (m);
* ``approach``: the half-space approach, ``approach_block`` plus the block's far-field compliance found by
  extrapolating in the block size. The clamped block of side L adds to the half-space a displacement field that
  scales as F / (E L) (Boussinesq's far field is a point load's at the scale of L), so the approach is
  delta(L) = delta_inf - c / L + O(a^2 / L^3) and one solve at 2L gives delta_inf = 2 delta(2L) - delta(L): an
  FE result on two block sizes, no closed form inside it.

Cost (hertz-point, 2 cores, PARDISO): a/8 44k DOFs 5 s, a/11.3 116k DOFs 25 s, a/16 308k DOFs 138 s.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..meshes.structured_block import StructuredBlockSpec, cached_structured_block_quarter
from ..qoi import centre_value_2d
from ..qoi_separation import ellipse as separation_ellipse
from ..result import ModelResult
from ..solvers.convergence import certificate_stats
from ..solvers.similar_levels import certify_similar
from . import export
from .point_contact import Gap, indenter_setup
from .quarter_mortar import solve_quarter_mortar

QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y", "approach_block")



@dataclass(frozen=True)
class P2Settings:
    """Level k (0 = coarsest) has contact element size ``h_contact`` r^-k (in the short Hertz semi-axis), grading
    ``grading`` r^-k and cap ``h_max`` r^-k (in the long semi-axis), r = ``ratio``; a P2 element of size h has
    nodes every h/2. Around the contact, a structured zone of cubes of side h (``zone`` semi-axes along x and y,
    ``zone_depth`` short semi-axes deep; :mod:`femcheck.meshes.structured_block`):
    with zone / h_contact and r such that every level holds a whole number of cubes (1.5 / 0.125 = 12 and
    r = 1.5: 12, 18, 27), the levels are geometrically similar where the contact is."""

    levels: int = 3
    ratio: float = 1.5
    h_contact: float = 0.125
    zone: float = 1.5
    zone_depth: float = 0.5
    grading: float = 0.25
    h_max: float = 2.0
    contact_zone: float = 1.3
    block: float = 20.0
    contact_tol: float = 1e-10
    finite_size_check: bool = True
    backend: str = "auto"


def settings(params: dict[str, Any]) -> P2Settings:
    return P2Settings(levels=params["numerics.p2_levels"], ratio=params["numerics.p2_ratio"],
                      h_contact=params["numerics.p2_h_contact"], zone=params["numerics.p2_zone"],
                      zone_depth=params["numerics.p2_zone_depth"], grading=params["numerics.fem_grading"],
                      h_max=params["numerics.fem_h_max"], contact_zone=params["numerics.fem_contact_zone"],
                      block=params["numerics.fem_block"], finite_size_check=params["numerics.fem_finite_size_check"])


def solve_level(gap: Gap, block, force: float, ax: float, ay: float, level: int, s: P2Settings,
                block_scale: float = 1.0) -> dict[str, Any]:
    """One mesh level: the level's quantities, its size and cost, and the fields of the finest level."""
    f = s.ratio**-level
    big, small = max(ax, ay), min(ax, ay)
    L = s.block * big * block_scale
    zx, zy = s.contact_zone * ax, s.contact_zone * ay
    spec = StructuredBlockSpec(L, L, L, s.zone * ax, s.zone * ay, s.zone_depth * small, s.h_contact * small * f,
                               s.grading * f, s.h_max * big * f)
    c = solve_quarter_mortar(lambda: cached_structured_block_quarter(spec), gap, block, 0.25 * force,
                             candidates=lambda x, y: (x / zx) ** 2 + (y / zy) ** 2 <= 1.0,
                             initial=lambda x, y: (x / ax) ** 2 + (y / ay) ** 2 < 1.0,
                             rim=lambda x, y: (x / zx) ** 2 + (y / zy) ** 2 > 0.9, order=2,
                             contact_tol=s.contact_tol, backend=s.backend)
    loaded = c.p > 0
    rough_x, rough_y = float(c.xc[loaded].max()), float(c.yc[loaded].max())
    X, Y, g = c.gap_face
    edges = separation_ellipse(X, Y, g, rough_x, rough_y, s.h_contact * small * f)
    centre = centre_value_2d(c.xc, c.yc, c.p, 0.5 * edges["semi_axis_x"], 0.5 * edges["semi_axis_y"])
    i0 = int(np.argmin(c.xc**2 + c.yc**2))
    if np.hypot(c.xc[i0], c.yc[i0]) > 1e-9 * small:
        raise RuntimeError("the contact face has no node at the centre of the contact")
    return {"h": s.h_contact * small * f, "h_over_a": s.h_contact * f, "p_max": float(c.p[i0]),
            "p_max_fit": centre.value, "p_max_fit_std": centre.std,
            "semi_axis_x": edges["semi_axis_x"], "semi_axis_y": edges["semi_axis_y"],
            "semi_axis_x_std": edges["semi_axis_x_std"], "semi_axis_y_std": edges["semi_axis_y_std"],
            "contact_area": float(np.pi * edges["semi_axis_x"] * edges["semi_axis_y"]),
            "approach_block": c.approach, "total_force": 4.0 * float(c.lam.sum()),
            "n_nodes": c.mesh.n_nodes, "n_dofs": c.n_dofs, "n_elements": int(c.mesh.tets.shape[1]),
            "candidates": int(c.cand.size), "active_nodes": c.active_nodes, "iterations": c.iterations,
            "residual": c.residual, "linear_solver": c.solver, "penetration": c.penetration,
            "mesh_digest": spec.digest(), "time_s": c.time_s, **c.times,
            "_fields": c}


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem_p2`` model of the point-contact scenes: per quantity a convergence certificate over
    ``numerics.p2_levels`` levels of ratio ``numerics.p2_ratio`` (stats["certificates"]), the finite-size check
    and the half-space approach from it (module docstring)."""
    gap, block, load, ax, ay = indenter_setup(params, "fem_p2")
    s = settings(params)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM P2 level {k + 1}/{s.levels}")
        levels.append(solve_level(gap, block, load, ax, ay, k, s))
    fine = levels[-1].pop("_fields")
    for lv in levels[:-1]:
        lv.pop("_fields")
    stats: dict[str, Any] = {
        "method": "mortar active set (P1 multipliers, weak Signorini), condensed onto the contact candidates",
        "element": "P2 tetrahedra", "solver": f"{levels[-1]['linear_solver']} factorisation",
        "contact_tol": s.contact_tol, "equivalent_block": {"E": block.E, "nu": block.nu},
        "block": {"side": s.block * max(ax, ay), "depth": s.block * max(ax, ay), "model": "quarter"},
        "levels": levels, "finest": {q: levels[-1][q] for q in QUANTITIES},
    }
    # structured levels: certify_similar (the fits' standard errors a floor, the order capped at Signorini's 3/2;
    # hertz-point a/8, a/12, a/18 observe 2.5 (p_max), 2.9 / 4.3 (semi-axes, y pre-asymptotic at a/8), 1.4)
    certs = {n: certify_similar(levels, n) for n in QUANTITIES + ("contact_area",)}
    q = {k: c.value for k, c in certs.items()}
    if s.finite_size_check:
        if progress:
            progress("FEM P2 finite-size check (block x 2)")
        # on the coarsest level: the far-field compliance is a smooth, global quantity (the approach converges to
        # 2e-4 between levels) and a block twice as large meshed at a/11.3 had 442k DOFs (218 s)
        k = 0
        bigger = solve_level(gap, block, load, ax, ay, k, s, block_scale=2.0)
        bigger.pop("_fields")
        change = {qn: bigger[qn] / levels[k][qn] - 1.0 for qn in QUANTITIES}
        # delta(L) = delta_inf - c/L: the far-field compliance the block lacks, added to the certified value
        far_field = bigger["approach_block"] - levels[k]["approach_block"]
        q["approach"] = q["approach_block"] + 2.0 * far_field
        stats["finite_size"] = {**change, "level": k, "block_side": 2 * s.block * max(ax, ay),
                                "far_field_approach": 2.0 * far_field, "time_s": bigger["time_s"],
                                "n_dofs": bigger["n_dofs"]}
        c = certs["approach_block"]
        certs["approach"] = replace(c, value=q["approach"], finest=c.finest + 2.0 * far_field,
                                    error_estimate=c.error_estimate * abs(c.value / q["approach"]),
                                    note=c.note + "; plus the block's far-field compliance from the block-size "
                                    "extrapolation")
    stats.update(certificate_stats(certs))
    q["total_force"] = levels[-1]["total_force"]
    axis = np.flatnonzero(np.abs(fine.yc) < 1e-9 * s.block * max(ax, ay))
    order = np.argsort(fine.xc[axis])
    fields = {"x": fine.xc[axis][order], "pressure": fine.p[axis][order],
              "pressure_nodes": np.stack([fine.xc, fine.yc, fine.p])}
    fields.update(export.report_views(fine.mesh, fine.u_nodes, fine.pressure_all, block,
                                      f"point-p2-{levels[-1]['mesh_digest']}",
                                      (2.0 * ax, 2.0 * ay, 2.0 * min(ax, ay)), stats))
    return ModelResult("fem_p2", quantities=q, stats=stats, fields=fields)
