"""Conformal FE sub-model of seed 000's spherical roller bearing (Blanco-Lorenzo et al. 2022, Table 1): the real
barrel-roller segment pressed on the real inner and outer raceway segments, both meshed and elastic,
frictionless node-to-surface contact (:mod:`femcheck.solvers.two_body`), P1 tetrahedra, load control.

Geometry, in the local frame of each contact (origin at the nominal contact point, z the contact normal into the
roller, x rolling, y along the roller axis; builders in :mod:`femcheck.meshes.srb_segments`):
 - roller: crown arc z = R - sqrt(R^2 - y^2) (crown radius R) revolved about its axis, the line z = D/2; a 90 deg
   sector x >= 0, |y| <= segment * b_H, driven rigidly (u = (0, 0, -delta)) on its axial plane z = D/2;
 - raceway: the groove circle of radius r_I (r_E) centred at (0, 0, r_I) revolved about the bearing axis, which
   passes at the rolling radius r_roll (seed 000 eq 1, with the pitch radius r_m = (r_E - D/2) cos(alpha) of
   :mod:`femcheck.problems.srb_contact`) from the contact point, tilted by the contact angle alpha:
       inner: through (0, r_roll,I sin(alpha), -r_roll,I cos(alpha)) with direction (0, cos(alpha), sin(alpha)),
       outer: through (0, r_roll,E sin(alpha), r_roll,E cos(alpha)) with direction (0, cos(alpha), -sin(alpha)),
   so that the longitudinal curvature radius at the contact is r_roll / cos(alpha) (seed 000 §2) and the outer
   raceway is the sphere of radius r_E about the bearing centre; clamped on its bottom face (depth * b_H).
The plane x = 0 (containing both axes of revolution) is a symmetry plane; y = 0 is not one for the inner ring
(torus about the inclined bearing axis), so both contacts are half models carrying N/2.

Quantities per contact (suffix ``_inner`` / ``_outer``, as :mod:`femcheck.problems.srb_contact` names them), from
the slave (roller) nodes with y measured along the roller generatrix's chord from the middle of the loaded extent
(the inner contact is not symmetric in y): ``p_max`` (Pa, :func:`femcheck.qoi.centre_value_2d`: a local even
quartic about the centre, no Hertzian shape assumed) and ``semi_axis_x``, ``semi_axis_y`` (m,
:func:`femcheck.qoi.semi_axes`: power-law edges with the exponent fitted), ``contact_area`` (m^2, pi a b) and
``total_force`` (N, platen force of the full contact). Per quantity a convergence certificate over the levels
(stats["certificates"]; one level by default, which certifies nothing and says so).
"""
from __future__ import annotations

import time
from typing import Any

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..geometry.srb import radii, rolling_radii
from ..materials import Elastic, effective_modulus
from ..qoi import symmetric_contact
from ..result import ModelResult
from ..scene import Key
from ..solvers.convergence import certificate_stats, certify_levels
from ..meshes.srb_segments import RingSegmentSpec, RollerSegmentSpec, ring_segment, roller_segment
from ..solvers.two_body import ContactBody, solve_two_body

CONTACTS = ("inner", "outer")
QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y")

FEM_SCHEMA: dict[str, Key] = {
    "numerics.conformal_levels": Key("int", "-", "conformal FEM mesh levels (>= 3 for Richardson)", lo=1, hi=4,
                                     lo_closed=True, hi_closed=True),
    "numerics.conformal_h_contact": Key("float", "a_H", "conformal FEM element size over the contact zone, "
                                        "coarsest level (a_H: Hertz rolling-direction semi-axis)", lo=0.05, hi=1.0,
                                        lo_closed=True, hi_closed=True),
    "numerics.conformal_ratio": Key("float", "-", "conformal FEM refinement ratio between levels", lo=1.1, hi=2.0,
                                    lo_closed=True, hi_closed=True),
    "numerics.conformal_grading": Key("float", "-", "conformal FEM element growth per unit distance, coarsest "
                                      "level", lo=0.05, hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.conformal_h_max": Key("float", "b_H", "largest conformal FEM element, coarsest level (b_H: Hertz "
                                    "axial semi-axis)", lo=0.02, hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.conformal_contact_zone": Key("float", "-", "candidate zone / Hertz semi-axes", lo=1.1, hi=2.0,
                                           lo_closed=True, hi_closed=True),
    "numerics.conformal_segment": Key("float", "b_H", "roller and raceway segment half-length along the roller "
                                      "axis (the roller length is not in seed 000's Table 1)", lo=1.2, hi=3.0,
                                      lo_closed=True, hi_closed=True),
    "numerics.conformal_depth": Key("float", "b_H", "raceway segment depth and length in x", lo=0.3, hi=3.0,
                                    lo_closed=True, hi_closed=True),
    "numerics.conformal_stretch": Key("float", "-", "conformal FEM element aspect ratio over the contact zone: "
                                      "size along y (roller axis) / size across (x, z)", lo=1.0, hi=16.0,
                                      lo_closed=True, hi_closed=True),
    "numerics.conformal_solver": Key("str", "-", "linear solver (auto: LU up to 6000 DOFs, AMG-CG above)",
                                     choices=("auto", "direct", "amg")),
}
FEM_DEFAULTS: dict[str, Any] = {
    "numerics.conformal_levels": 1,
    "numerics.conformal_h_contact": 0.35,
    "numerics.conformal_ratio": 1.4142135623730951,
    "numerics.conformal_grading": 0.3,
    "numerics.conformal_h_max": 0.25,
    "numerics.conformal_contact_zone": 1.3,
    "numerics.conformal_segment": 1.5,
    "numerics.conformal_depth": 1.0,
    "numerics.conformal_stretch": 1.0,
    "numerics.conformal_solver": "auto",
}


def contact_geometry(params: dict[str, Any]) -> dict[str, dict[str, float]]:
    """Per contact: groove radius (m), rolling radius (m, seed 000 eq 1 with r_m = (r_E - D/2) cos(alpha)),
    the bearing axis (point y, z and signed tilt in the local frame) and the Hertz radii (Rx, Ry) of
    :func:`femcheck.geometry.srb.radii`."""
    alpha = params["geometry.contact_angle"]
    roll = rolling_radii(params)
    rad = radii(params)
    out = {}
    for c, side in (("inner", -1.0), ("outer", 1.0)):
        r = roll[c]
        out[c] = {"groove_radius": params[f"geometry.groove_radius_{c}"], "rolling_radius": r,
                  "axis_y": r * np.sin(alpha), "axis_z": side * r * np.cos(alpha), "tilt": -side * alpha,
                  "Rx": rad[c][0], "Ry": rad[c][1]}
    return out


def _materials(params: dict[str, Any]) -> tuple[Elastic, Elastic]:
    mats = []
    for body in ("roller", "ring"):
        if params.get(f"materials.{body}.rigid", False):
            raise InputError(f"materials.{body}.rigid", "the conformal FE model meshes both bodies; allowed: false")
        mats.append(Elastic(float(params[f"materials.{body}.E"]), float(params[f"materials.{body}.nu"])))
    return mats[0], mats[1]


def segment_specs(params: dict[str, Any], contact: str, level: int):
    """(roller segment spec, ring segment spec, Hertz solution, candidate zone (zx, zy) m) of one raceway contact
    at mesh ``level``: the meshes of :func:`solve_contact` (also the exported decks')."""
    s = {**FEM_DEFAULTS, **{k: v for k, v in params.items() if k.startswith("numerics.conformal_")}}
    roller, ring = _materials(params)
    g = contact_geometry(params)[contact]
    load = float(params["load.normal"])
    hz = hertz.elliptic_contact(load, g["Rx"], g["Ry"], effective_modulus(roller, ring))
    a, b = hz.semi_axis_x, hz.semi_axis_y
    f = s["numerics.conformal_ratio"] ** -level
    hc, grading = s["numerics.conformal_h_contact"] * a * f, s["numerics.conformal_grading"] * f
    h_max = s["numerics.conformal_h_max"] * b * f
    zf = s["numerics.conformal_contact_zone"]
    zx, zy = zf * a, zf * b
    half = s["numerics.conformal_segment"] * b
    depth = s["numerics.conformal_depth"] * b
    D, R = params["geometry.roller_diameter"], params["geometry.crown_radius"]
    stretch = float(s["numerics.conformal_stretch"])
    rspec = RollerSegmentSpec(D, R, half, zx, zy, hc, grading, h_max, stretch)
    gspec = RingSegmentSpec(g["groove_radius"], g["axis_y"], g["axis_z"], g["tilt"], half, depth, depth, zx, zy, hc,
                            grading, h_max, stretch)
    return rspec, gspec, hz, (zx, zy)


def solve_contact(params: dict[str, Any], contact: str, level: int, nodal: bool = False) -> dict[str, Any]:
    """One raceway contact on one mesh level; returns the level's quantities and solver statistics, with
    ``nodal``: also the roller's contact-candidate nodes ``nodes_x`` (3, n) (m, undeformed, the contact's local
    frame) and their pressures ``nodes_pressure`` (Pa), for node-by-node comparisons on the same mesh."""
    s = {**FEM_DEFAULTS, **{k: v for k, v in params.items() if k.startswith("numerics.conformal_")}}
    roller, ring = _materials(params)
    load = float(params["load.normal"])
    rspec, gspec, hz, (zx, zy) = segment_specs(params, contact, level)
    a, b = hz.semi_axis_x, hz.semi_axis_y
    hc = rspec.h_contact
    t0 = time.perf_counter()
    rm, gm = roller_segment(rspec), ring_segment(gspec)
    mesh_s = time.perf_counter() - t0
    master = ContactBody(gm, ring, {0: gm.mask("x0") | gm.mask("bottom"), 1: gm.mask("bottom"),
                                    2: gm.mask("bottom")})
    slave = ContactBody(rm, roller, {0: rm.mask("x0") | rm.mask("driven"), 1: rm.mask("driven")},
                        driven=rm.mask("driven"))
    sol = solve_two_body(master, slave, 0.5 * load,
                         candidates=lambda x: (np.abs(x[0]) <= zx) & (np.abs(x[1]) <= zy),
                         initial=lambda x: (x[0] / a) ** 2 + (x[1] / b) ** 2 < 0.8,
                         rim=lambda x: (np.abs(x[0]) > 0.9 * zx) | (np.abs(x[1]) > 0.9 * zy),
                         solver=s["numerics.conformal_solver"])
    xs, ys = sol.x[0], sol.x[1]
    loaded = ys[sol.pressure > 0]
    centre_y = 0.5 * (loaded.min() + loaded.max())
    fit = symmetric_contact(xs, ys - centre_y, sol.pressure)
    out = {"contact": contact, "level": level, "h": hc, "h_over_a": hc / a, "p_max": fit["p_max"],
           "semi_axis_x": fit["semi_axis_x"], "semi_axis_y": fit["semi_axis_y"], "centre_y": centre_y,
           "contact_area": float(np.pi * fit["semi_axis_x"] * fit["semi_axis_y"]),
           "edge_exponent_x": fit["exponent_x"], "edge_exponent_y": fit["exponent_y"],
           **{k: v for k, v in fit.items() if k.endswith("_std")},
           "p_max_nodal": float(sol.pressure.max()),
           "total_force": 2.0 * sol.total_force, "approach": sol.approach,
           "n_nodes": int(rm.n_nodes + gm.n_nodes), "n_dofs": sol.n_dofs, "active_nodes": int(sol.active.sum()),
           "iterations": sol.iterations, "cg_iterations": sol.cg_iterations, "residual": sol.residual,
           "linear_solver": sol.linear_solver, "mesh_s": mesh_s, **sol.times,
           "hertz": {"p_max": hz.p_max, "semi_axis_x": a, "semi_axis_y": b}}
    if nodal:
        out.update(nodes_x=sol.x, nodes_pressure=sol.pressure)
    return out


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem_conformal`` model of srb_contact scenes: both raceway contacts on
    ``numerics.conformal_levels`` mesh levels; quantities with suffixes ``_inner`` / ``_outer``."""
    t0 = time.perf_counter()
    s = {**FEM_DEFAULTS, **{k: v for k, v in params.items() if k.startswith("numerics.conformal_")}}
    n_levels = int(s["numerics.conformal_levels"])
    q: dict[str, float] = {}
    stats: dict[str, Any] = {"method": "two-body node-to-surface, primal-dual active set", "element": "P1 tetrahedra",
                             "model": "half (x >= 0), roller and raceway segments meshed", "levels": [],
                             "finest": {}, "geometry": contact_geometry(params)}
    for c in CONTACTS:
        levels = []
        for k in range(n_levels):
            if progress:
                progress(f"conformal FEM {c} raceway, level {k + 1}/{n_levels}")
            levels.append(solve_contact(params, c, k))
        stats["levels"] += levels
        fine = levels[-1]
        stats["finest"].update({f"{n}_{c}": fine[n] for n in QUANTITIES})
        certs = certify_levels(levels, QUANTITIES + ("contact_area",))
        for key, part in certificate_stats(certs).items():
            stats.setdefault(key, {}).update({f"{n}_{c}": v for n, v in part.items()})
        q.update({f"{n}_{c}": cert.value for n, cert in certs.items()})
        q[f"total_force_{c}"] = fine["total_force"]
    q["total_force"] = q["total_force_inner"]
    stats["level_quantities"] = list(QUANTITIES)
    return ModelResult("fem_conformal", time_s=time.perf_counter() - t0, quantities=q, stats=stats)
