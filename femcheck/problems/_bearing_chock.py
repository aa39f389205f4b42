"""bearing_load's ``flexible_chock`` model: a multi-row tapered bearing in an elastic chock on a flexible roll
(:mod:`femcheck.bem.mill_chock`), built from the scene's keys; SI units.

The rows are those of the rigid-ring model (row 1 at -(rows - 1) s/2 on the operating side, spacing s, directions
alternating from +); the roll's body is on the +z side (towards the mill roll), its symmetry plane at
z = neck_length + body_half_length from the bearing's middle; the chock's support pad is centred on the load line
``load.offset`` (+z towards the mill roll), where the radial load's line of action crosses the axis: on a spherical
seat (``chock.seat``) the chock turns freely about it, so the rows carry no moment about that point (the rigid-ring
model's load offset, with the same meaning).
"""
from __future__ import annotations

import time
from typing import Any

import numpy as np

from ..analytic.iso16281 import row_layout
from ..errors import InputError
from ..materials import Elastic
from ..result import ModelResult
from ..scene import Key

CHOCK_SCHEMA: dict[str, Key] = {
    "geometry.width": Key("float", "m", "bearing width (flexible_chock: the chock and cone cylinders' length)", lo=0.0),
    "chock.outer_radius": Key("float", "m", "outer radius of the cups + chock cylinder (flexible_chock)", lo=0.0),
    "chock.seat": Key("str", "-", "the chock's support at load.offset (flexible_chock): a spherical seat (turns "
                      "freely) or clamped", choices=("spherical", "clamped")),
    "chock.support_length": Key("float", "m", "axial length of the chock's support patch (flexible_chock)", lo=0.0),
    "chock.support_half_angle": Key("float", "rad", "half-angle of the chock's support patch about the load line "
                                    "(flexible_chock)", lo=0.0, hi=np.pi, hi_closed=True),
    "roll.neck_diameter": Key("float", "m", "roll-neck diameter (flexible_chock)", lo=0.0),
    "roll.neck_length": Key("float", "m", "bearing middle to the roll body's face (flexible_chock)", lo=0.0),
    "roll.body_diameter": Key("float", "m", "roll-body diameter (flexible_chock)", lo=0.0),
    "roll.body_half_length": Key("float", "m", "body face to the mill's symmetry plane (flexible_chock)", lo=0.0),
    "materials.structure.E": Key("float", "Pa", "Young's modulus of chock, cones and roll (flexible_chock)", lo=0.0),
    "materials.structure.nu": Key("float", "-", "Poisson's ratio of chock, cones and roll (flexible_chock)", lo=-1.0,
                                  hi=0.5),
    "numerics.chock_between": Key("int", "-", "flexible_chock: cells from a raceway patch to its sector's edge "
                                  "(around; every direction refined at once needs > 24 GB)", lo=1, hi=6,
                                  lo_closed=True, hi_closed=True),
    "numerics.chock_radial": Key("int", "-", "flexible_chock: cells (times m) through the chock", lo=1, hi=16,
                                 lo_closed=True, hi_closed=True),
    "numerics.chock_slices": Key("int", "-", "flexible_chock: ISO slices per roller (one FE patch each)", lo=1,
                                 hi=30, lo_closed=True, hi_closed=True),
}
FLEXIBLE_CHOCK_KEYS = ("geometry.width", "geometry.bore_diameter", "chock.outer_radius", "chock.support_length", "chock.support_half_angle", "roll.neck_diameter", "roll.neck_length",
                       "roll.body_diameter", "roll.body_half_length", "materials.structure.E",
                       "materials.structure.nu")


def validate_chock(params: dict[str, Any]) -> None:
    """The flexible_chock model's inputs: present, and a geometry the chock, cones and roll can be built on."""
    for key in FLEXIBLE_CHOCK_KEYS:
        if key not in params:
            raise InputError(key, "required by the flexible_chock model")
    if params["bearing.law"] != "iso16281":
        raise InputError("bearing.law", "flexible_chock slices the rollers by ISO/TS 16281; allowed: iso16281")
    if params["load.angle"] != 0.0:
        raise InputError("load.angle", "flexible_chock puts roller 0 on the load line (the chock's support); "
                         "allowed: 0")
    width, rows, s = params["geometry.width"], params["bearing.rows"], params["bearing.row_spacing"]
    span = (rows - 1) * s + params["geometry.roller_length"]
    if span > width:
        raise InputError("geometry.width", f"{width:g} m is narrower than the rows ({span:.4g} m); "
                         f"allowed: >= {span:.4g} m")
    r_o = 0.5 * params["geometry.outer_raceway_diameter"]
    if params["chock.outer_radius"] <= r_o:
        raise InputError("chock.outer_radius", f"{params['chock.outer_radius']:g} m; allowed: > {r_o:.4g} m "
                         "(the cup raceway radius)")
    zc, half = params["load.offset"], 0.5 * params["chock.support_length"]
    if zc - half < -0.5 * width - 1e-12 or zc + half > 0.5 * width + 1e-12:
        raise InputError("load.offset", f"the chock's support pad {zc - half:.4g} .. {zc + half:.4g} m (centred on "
                         f"the load line) must lie on the chock; allowed: within [{-0.5 * width:g}, "
                         f"{0.5 * width:g}] m")
    if params["roll.neck_length"] < 0.5 * width:
        raise InputError("roll.neck_length", f"{params['roll.neck_length']:g} m ends inside the bearing; "
                         f"allowed: >= {0.5 * width:g} m (half the width)")
    if params["roll.neck_diameter"] > params["geometry.bore_diameter"] * (1 + 1e-12):
        raise InputError("roll.neck_diameter", f"{params['roll.neck_diameter']:g} m; allowed: <= the bore "
                         f"{params['geometry.bore_diameter']:g} m")


def parts(p: dict[str, Any]):
    """(MillBearing, Chock, RollNeck, Mesh3D) of the scene parameters ``p``."""
    from ..analytic.roll_neck import ShaftSegment
    from ..bem.mill_chock import Chock, MillBearing, Mesh3D, RollNeck

    rows = row_layout(p["bearing.rows"], p["bearing.row_spacing"], p["bearing.row_arrangement"],
                      p["bearing.contact_angle"])
    zs, signs = tuple(r.z for r in rows), tuple(r.sign for r in rows)
    d_i, d_o, D = p["geometry.inner_raceway_diameter"], p["geometry.outer_raceway_diameter"], p["geometry.roller_diameter"]
    width = p["geometry.width"]
    bearing = MillBearing(p["bearing.rollers"], zs, signs, p["bearing.contact_angle"], 0.25 * (d_i + d_o),
                          p["geometry.roller_length"], D, p["numerics.chock_slices"], 0.5 * d_o, 0.5 * d_i,
                          0.5 * p["geometry.bore_diameter"], width, d_o - d_i - 2.0 * D, p["bearing.crown"])
    steel = Elastic(p["materials.structure.E"], p["materials.structure.nu"])
    zc, half = p["load.offset"], 0.5 * p["chock.support_length"]
    chock = Chock(p["chock.outer_radius"], (zc - half, zc + half), p["chock.support_half_angle"], steel)
    face = p["roll.neck_length"]
    clamp = face + p["roll.body_half_length"]
    neck = RollNeck((ShaftSegment(-0.5 * width, face, p["roll.neck_diameter"]),
                     ShaftSegment(face, clamp, p["roll.body_diameter"])), clamp, steel)
    mesh = Mesh3D(between=p["numerics.chock_between"], radial=p["numerics.chock_radial"])
    return bearing, chock, neck, mesh


def seat_of(p: dict[str, Any]) -> float | None:
    """The chock's seat for :func:`femcheck.bem.mill_chock.solve`: the load line (m) on a spherical seat, None when
    clamped."""
    return p["load.offset"] if p["chock.seat"] == "spherical" else None


def flexible_chock(scene, progress=None) -> ModelResult:
    """Row shares (%), Q_max (N) and the equilibrium of :mod:`femcheck.bem.mill_chock` for the scene."""
    from ..bem import mill_chock as mc

    p = scene.params
    bearing, chock, neck, mesh = parts(p)
    t0 = time.perf_counter()
    if progress:
        progress("chock compliance (3D FE)")
    cc = mc.chock_compliance(bearing, chock, mesh)
    if progress:
        progress("cone compliance (3D FE)")
    ci = mc.cone_compliance(bearing, chock.material, mesh)
    cn = mc.roll_compliance(bearing, neck)
    t_build = time.perf_counter() - t0
    sol = mc.solve(bearing, cc.C + ci.C + cn, p["load.radial"], p["load.axial"], seat=seat_of(p))
    q = {f"row_share_{r + 1}": float(sh) for r, sh in enumerate(sol.row_shares)}
    q["q_max"] = float(sol.roller_loads.max())
    q["total_force"] = float(sol.row_radial.sum())
    stats = {"iterations": sol.iterations, "residual": sol.residual, "dofs": list(sol.dofs),
             "displacement": sol.u.tolist(), "slices": bearing.slices,
             "fe_dofs": {"chock": cc.n_dofs, "cones": ci.n_dofs},
             "asymmetry": {"chock": cc.asymmetry, "cones": ci.asymmetry},
             "compliance_time_s": t_build, "solve_time_s": sol.time_s,
             "assumptions": {"chock_outer_radius_m": chock.outer_radius, "support_z_m": list(chock.support_z),
                             "seat": p["chock.seat"],
                             "support_half_angle_rad": chock.support_half_angle,
                             "roll_clamp_z_m": neck.z_clamp}}
    # roller_loads: each roller position's largest load over the rows (as the rigid-ring model's, for the polar plot)
    fields = {"row_shares": sol.row_shares, "row_roller_loads": sol.roller_loads,
              "roller_loads": sol.roller_loads.max(axis=0), "roller_angle": np.angle(np.exp(1j * bearing.psi))}
    return ModelResult("flexible_chock", quantities=q, stats=stats, fields=fields)
