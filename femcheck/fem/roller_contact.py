"""3D FE model of a finite roller on a raceway (roller scenes): the roller is a rigid analytic indenter with
the scene's profile (flat-ended or crowned; +inf gap beyond its ends) on a quarter block of the equivalent
material (contact modulus E*, see :mod:`femcheck.fem.point_contact`), P1 tetrahedra, active set with AMG-CG.

The fine zone is the box over the roller footprint, |x| <= contact_zone a_H and |y| <= L/2 + one a_H, so the
pressure peaks at the sharp roller ends are resolved as finely as the centre. Levels halve every sizing
length; with three or more, Richardson extrapolation is applied to the centre pressure and half-width.

Quantities: ``p_centre`` and ``half_width`` from a least-squares fit of p^2 = p0^2 (1 - x^2/a^2) over the
nodes of the central band |y| <= max(2 h, L/20) (the nodal reactions of P1 scatter by a few per cent from node
to node), ``edge_peak_y`` the position of the largest nodal pressure on the centre line x = 0, ``p_max`` the
largest nodal pressure (at a sharp edge it grows with refinement, as it must), ``total_force``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..geometry import profiles
from ..result import ModelResult
from . import export
from ..solvers.convergence import richardson
from ..meshes.block import BlockSpec
from .point_contact import _body, equivalent_pair
from .quarter_block import QuarterContact, solve_quarter


@dataclass(frozen=True)
class FEMRollerSettings:
    """Lengths in Hertz half-widths a_H (line contact with W/L). Level k has contact size h_contact r^-k,
    grading grading r^-k, cap h_max r^-k (r = ``ratio``); the block extends ``block`` roller lengths beyond the
    footprint in x, y and z."""

    levels: int = 2
    ratio: float = 2.0
    h_contact: float = 0.25
    grading: float = 0.25
    h_max: float = 40.0
    contact_zone: float = 1.8
    block: float = 2.0


def settings(params: dict[str, Any]) -> FEMRollerSettings:
    return FEMRollerSettings(levels=params["numerics.fem_levels"], ratio=params.get("numerics.fem_ratio", 2.0),
                             h_contact=params["numerics.fem_h_contact"],
                             grading=params["numerics.fem_grading"], h_max=params["numerics.fem_h_max"],
                             contact_zone=params["numerics.fem_contact_zone"], block=params["numerics.fem_block"])


def centre_fit(c: QuarterContact, band: float) -> tuple[float, float]:
    """(p0, a) of p^2 = p0^2 (1 - x^2/a^2) fitted over loaded nodes with |y| <= band."""
    sel = (c.yc <= band) & (c.p > 0)
    if sel.sum() < 4:
        raise RuntimeError("too few loaded FE nodes in the central band to fit the pressure")
    A = np.stack([np.ones(sel.sum()), c.xc[sel] ** 2], axis=1)
    coef, *_ = np.linalg.lstsq(A, c.p[sel] ** 2, rcond=None)
    if coef[0] <= 0 or coef[1] >= 0:
        raise RuntimeError("central FE pressure is not Hertz-like (fitted p^2 has no maximum)")
    return float(np.sqrt(coef[0])), float(np.sqrt(-coef[0] / coef[1]))


def model(params: dict[str, Any], progress=None) -> ModelResult:
    if params.get("geometry.tilt", 0.0) != 0.0:
        raise InputError("geometry.tilt", "the FE model is a quarter model and needs an aligned roller; allowed "
                         "for fem: 0 (use bem or finite_line for a tilted roller)")
    R, L, W = params["geometry.radius"], params["geometry.length"], params["load.normal"]
    roller, race = _body(params, "roller"), _body(params, "race")
    block = equivalent_pair(roller, race)
    e_star = block.E / (1.0 - block.nu**2)
    rr = params.get("geometry.race_radius", np.inf)
    h = hertz.line_contact(W / L, hertz.reduced_radius(R, rr), e_star)
    a = h.half_width
    gap = profiles.roller(R, L, params["geometry.crown"], params.get("geometry.crown_radius"),
                          params["geometry.flat_length"], params.get("geometry.crown_design_load"), e_star, rr, 0.0)
    s = settings(params)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        f = s.ratio**-k
        hk = s.h_contact * a * f
        zx, zy = s.contact_zone * a, 0.5 * L + a
        # the block is sized on the roller length: a block only ~20 a deep under a contact 90 a long is a thin
        # layer, which flattens the axial load distribution (centre pressure +3.8 % against the half-space)
        side = s.block * L
        spec = BlockSpec(side, 0.5 * L + side, side, zx, zy, hk, s.grading * f, s.h_max * a * f, zone="box")
        c = solve_quarter(spec, gap, block, 0.25 * W, candidates=lambda x, y: (x <= zx) & (y <= zy),
                          initial=lambda x, y: (x < a) & (y < 0.5 * L), rim=lambda x, y: x > 0.9 * zx)
        p0, half = centre_fit(c, max(2.0 * hk, 0.05 * L))
        line = np.flatnonzero(c.xc < 1e-9 * L)
        order = line[np.argsort(c.yc[line])]
        cross = np.flatnonzero(c.yc < 1e-9 * L)
        cross = cross[np.argsort(c.xc[cross])]
        levels.append({"h": hk, "h_over_a": hk / a, "p_centre": p0, "half_width": half,
                       "edge_peak_y": float(c.yc[order][np.argmax(c.p[order])]), "p_max": float(c.p.max()),
                       "total_force": 4.0 * float(c.lam.sum()), "approach": c.approach, "n_nodes": c.mesh.n_nodes,
                       "n_dofs": c.n_dofs, "n_elements": int(c.mesh.tets.shape[1]), "mesh_digest": spec.digest(),
                       "active_nodes": c.active_nodes, "iterations": c.iterations, "cg_iterations": c.cg_iterations,
                       "residual": c.residual, "time_s": c.time_s, **c.times,
                       "_fields": {"x": c.xc[cross], "pressure": c.p[cross], "y": c.yc[order],
                                   "pressure_axial": c.p[order]}, "_solution": c})
    fields = levels[-1].pop("_fields")
    fine = levels[-1].pop("_solution")
    for lv in levels[:-1]:
        lv.pop("_fields"), lv.pop("_solution")
    names = ("p_centre", "half_width", "edge_peak_y", "p_max")
    finest = {q: levels[-1][q] for q in names}
    stats: dict[str, Any] = {"method": "active_set", "element": "P1 tetrahedra",
                             "solver": "pyamg SA (rigid-body modes) + CG", "finest": finest, "levels": levels,
                             "equivalent_block": {"E": block.E, "nu": block.nu}, "hertz_half_width": a}
    q = dict(finest)
    if s.levels >= 3:
        rich = {n: richardson([lv["h"] for lv in levels], [lv[n] for lv in levels])
                for n in ("p_centre", "half_width")}
        stats["richardson"] = {k: v.as_dict() for k, v in rich.items()}
        q.update({k: v.value for k, v in rich.items()})
    q["total_force"] = levels[-1]["total_force"]
    # picture: the roller end, where the footprint and the stresses are three-dimensional
    end = export.report_views(fine.mesh, fine.u_nodes, fine.pressure_all, block, f"roller-{levels[-1]['mesh_digest']}",
                              (1.5 * s.contact_zone * a, 0.5 * L + 3.0 * a, 3.0 * a), stats, y_from=0.5 * L - 6.0 * a)
    fields.update(end)
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)
