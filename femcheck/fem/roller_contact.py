"""3D FE model of a finite roller on a raceway (roller scenes): the roller is a rigid analytic indenter with
the scene's profile (flat-ended or crowned; +inf gap beyond its ends) on a quarter block of the equivalent
material (contact modulus E*, see :mod:`femcheck.fem.point_contact`), P1 tetrahedra, active set with AMG-CG.

The fine zone is the box over the roller footprint, |x| <= contact_zone a_H and |y| <= L/2 + one a_H, so the
pressure peaks at the sharp roller ends are resolved as finely as the centre. Levels halve every sizing
length; with three or more, Richardson extrapolation is applied to the centre pressure and half-width.

Quantities (no Hertzian shape assumed; P1 nodal reactions scatter by a few per cent from node to node, so each
comes from a local fit over many nodes, :mod:`femcheck.qoi`): ``p_centre``, the pressure at x = y = 0 (even quartic
over |x| < a_H/2, |y| < L/8); ``half_width`` at the centre (power-law edge with its exponent fitted, nodes of the
strip |y| < L/8); ``p_end``, the pressure on the centre line at three Hertz half-widths from the roller end (a
measure that stays finite under refinement, where the end peak does not); ``edge_peak_y``, the position of the largest nodal pressure
on the centre line x = 0; ``total_force``. The largest nodal pressure ``p_max`` sits at a sharp roller end where the
pressure is singular: it grows with refinement by nature, so it is not a quantity; its level values are in
stats["levels"], the finest in stats["mesh_dependent"], and its certificate says "mesh-dependent by nature".
Per quantity a convergence certificate (stats["certificates"], :func:`femcheck.solvers.convergence.certify`).

Why the centre pressure used to fall 0.75 % per level: it came from a least-squares fit of
p^2 = p0^2 (1 - x^2/a^2) over the whole width of a central band, whose nodes next to the contact edges (where P1
reactions are biased) weigh less on finer meshes; the local centre value does not depend on them.
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
from ..qoi import centre_value_2d, edge, value_on_axis
from ..solvers.convergence import certificate_stats, certify_levels
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


# p_end is taken this many Hertz half-widths from the roller end: a window of +-a_H around it stays clear of the
# singular end (at one half-width the window reaches the end and the fit scattered by 8 % between levels)
END_DISTANCE = 3.0


def centre_quantities(c: QuarterContact, a: float, L: float) -> dict[str, float]:
    """p_centre, half_width (with the edge's fitted exponent) and p_end of one level (see the module doc)."""
    band = L / 8.0
    centre = centre_value_2d(c.xc, c.yc, c.p, 0.5 * a, band)
    strip = c.yc < band
    e = edge(c.xc[strip], c.p[strip], band=0.5, min_points=8, transverse=c.yc[strip])
    end = value_on_axis(c.xc, c.yc, c.p, 0.5 * L - END_DISTANCE * a, 0.5 * a, a)
    return {"p_centre": centre.value, "half_width": e.position, "edge_exponent": e.exponent, "p_end": end.value,
            "p_centre_std": centre.std, "half_width_std": e.std, "p_end_std": end.std}


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
        local = centre_quantities(c, a, L)
        line = np.flatnonzero(c.xc < 1e-9 * L)
        order = line[np.argsort(c.yc[line])]
        cross = np.flatnonzero(c.yc < 1e-9 * L)
        cross = cross[np.argsort(c.xc[cross])]
        levels.append({"h": hk, "h_over_a": hk / a, **local,
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
    names = ("p_centre", "half_width", "p_end", "edge_peak_y")
    finest = {q: levels[-1][q] for q in names}
    stats: dict[str, Any] = {"method": "active_set", "element": "P1 tetrahedra",
                             "solver": "pyamg SA (rigid-body modes) + CG", "finest": finest, "levels": levels,
                             "equivalent_block": {"E": block.E, "nu": block.nu}, "hertz_half_width": a}
    certs = certify_levels(levels, names + ("p_max",), singular=("p_max",))
    stats.update(certificate_stats(certs))
    # the end peak is singular: kept in the stats with its certificate (never certified), not as a quantity that
    # could be compared with another model's equally mesh-dependent peak
    q = {k: certs[k].value for k in names}
    stats["mesh_dependent"] = {"p_max": levels[-1]["p_max"]}
    q["total_force"] = levels[-1]["total_force"]
    # picture: the roller end, where the footprint and the stresses are three-dimensional
    end = export.report_views(fine.mesh, fine.u_nodes, fine.pressure_all, block, f"roller-{levels[-1]['mesh_digest']}",
                              (1.5 * s.contact_zone * a, 0.5 * L + 3.0 * a, 3.0 * a), stats, y_from=0.5 * L - 6.0 * a)
    fields.update(end)
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)
