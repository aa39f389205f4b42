"""Bearing load distribution (seed 003; spec bearing-load.md): how a radial (and axial) load shares out over the
rollers of a cylindrical (or, multi-row, tapered) roller bearing.

Models:
  ``rigid_ring``  discrete rigid-ring theory (Stribeck/Sjövall) with the scene's load-deflection law; ISO/TS 16281
                  slices (crown, tilt), and for several rows the 5-DOF equilibrium (:mod:`femcheck.analytic`).
  ``integral``    its Z -> infinity limit with Sjövall's J_r (any law; J_r, J_a reported for the power laws).
  ``condensed``   seed 003's idea in 2D: FE ring compliances at the contact centres, one roller's compliance,
                  Hertz-revised widths (:mod:`femcheck.bem.bearing_condensed`).
  ``flexible_chock`` several tapered rows in an elastic chock (coarse 3D FE, clamped at its support) on a roll
                  neck (Timoshenko beam clamped at the mill's symmetry plane), ISO/TS 16281 slices
                  (:mod:`femcheck.bem.mill_chock`; spec P3, seed 003 Table 3).
  ``fem``         2D plane-strain FE of the section, frictionless contact, load control, geometric similarity,
                  mesh levels with certificates (:mod:`femcheck.fem.bearing2d`). A stored reference.
  ``condensed3d`` one row in 3D: ring compliances condensed from a coarse 3D FE, ISO/TS 16281 slices (spec P3).
  ``coupled_slices`` one row in 3D: Hertz strips coupled along the rollers through the half-space, the FE's
                  finite-body corrections (:mod:`femcheck.bem.bearing_strips`).
  ``resolved``    their reference: every roller's two contacts on fine grids, half-space + FE finite-body
                  corrections, certified in four parts (:mod:`femcheck.problems._bearing_3d`). A stored reference.
Quantities (SI): ``q_max`` (N), ``radial_deflection`` (m, shaft relative to housing), ``loaded_rollers``,
``load_zone_angle`` (rad, half-angle), ``load_zone_parameter`` (eps), ``stribeck_factor`` Z Q_max/F_r,
``total_force`` (N, sum Q_j cos psi_j cos alpha: the equilibrium check), ``rating_life`` (L10r, 1e6 rev, law
iso16281), ``half_width_inner|outer`` (m) and ``p_max_inner|outer`` (Pa) of the most loaded roller (2D law: Hertz
at its load; FE: from the nodal contact forces), ``row_share_<r>`` (%, several rows); field ``roller_loads`` (N) at ``roller_angle`` (rad from the load
line), compared roller by roller as ``roller_loads_max`` = max_j |Q_j - Q_j,ref| / max Q_ref.
The 2D models (condensed, fem) use the plane-strain roller law; every approach is relative to a body reference
(roller centre, tied bore, clamped OD): 2D plane strain has no absolute half-plane approach.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from ..analytic import bearing_laws as laws
from ..analytic import iso16281
from ..analytic.bearing_load import integral_model, load_integrals, rigid_ring as rigid_ring_solve, zone_from_profile
from ..errors import InputError
from ..result import ModelResult
from ..scene import Key, Scene, model_keys, tolerance_key
from ._bearing_2d import DEFAULTS_2D, SCHEMA_2D, section
from ._bearing_3d import DEFAULTS_3D, SCHEMA_3D, condensed3d, coupled_slices, resolved, validate_3d
from ._bearing_chock import CHOCK_SCHEMA, flexible_chock, validate_chock

MODEL_NAMES = ("rigid_ring", "integral", "condensed", "fem", "flexible_chock", "condensed3d", "coupled_slices",
               "resolved", "measured")
# what a bearing is sized with: the largest roller load (life, static capacity), then the deflection
DESIGN_QUANTITIES = ("q_max", "row_share", "radial_deflection")
# Forces are per roller (N; the 2D section's laws give a roller's load for its effective length).
UNITS = {"q_max": "N", "radial_deflection": "m", "loaded_rollers": "- (count)", "load_zone_angle": "rad",
         "load_zone_parameter": "- (eps)", "stribeck_factor": "- (Z Q_max / F_r)", "row_share": "%",
         "rating_life": "1e6 rev", "roller_loads": "- (max |Q - Q_ref| / max Q_ref)", "total_force": "N",
         "slice_loads": "- (max |q - q_ref| / max q_ref)"}
LAWS = ("power", "palmgren", "iso16281", "plane_strain")
MAX_PRELOAD = 0.01          # |P_d| / D: beyond, the rollers would overlap the raceways by more than small strain
ALTERNATIVES: tuple = ()

SCHEMA: dict[str, Key] = {
    "geometry.inner_raceway_diameter": Key("float", "m", "inner raceway diameter d_i", lo=0.0),
    "geometry.outer_raceway_diameter": Key("float", "m", "outer raceway diameter d_o", lo=0.0),
    "geometry.roller_diameter": Key("float", "m", "roller diameter D (mean diameter of a tapered roller)", lo=0.0),
    "geometry.roller_length": Key("float", "m", "effective roller length l (converts N <-> N/m in 2D)", lo=0.0),
    "geometry.bore_diameter": Key("float", "m", "inner-ring bore (elastic rings)", lo=0.0),
    "geometry.outside_diameter": Key("float", "m", "outer-ring outside diameter (elastic rings)", lo=0.0),
    "bearing.rollers": Key("int", "-", "rollers per row Z", lo=3, hi=200, lo_closed=True, hi_closed=True),
    "bearing.contact_angle": Key("float", "rad", "contact angle alpha", lo=0.0, hi=1.2, lo_closed=True, hi_closed=True),
    "bearing.law": Key("str", "-", "roller load-deflection law", choices=LAWS),
    "bearing.load_exponent": Key("float", "-", "exponent n of the power law", lo=1.0, hi=3.0, lo_closed=True,
                                 hi_closed=True),
    "bearing.load_stiffness": Key("float", "N/m^n", "K of the power law (default: ISO/TS 16281 at the nominal "
                                  "Q_max = 4.08 F_r/Z)", lo=0.0),
    "bearing.slices": Key("int", "-", "ISO/TS 16281 slices per roller", lo=1, hi=200, lo_closed=True, hi_closed=True),
    "bearing.crown": Key("str", "-", "roller profile (ISO/TS 16281 logarithmic crown)", choices=("none", "iso")),
    "bearing.tilt": Key("float", "rad", "misalignment of the inner ring (single row, iso16281)", lo=-0.01, hi=0.01,
                        lo_closed=True, hi_closed=True),
    "bearing.rows": Key("int", "-", "rows (iso16281 law)", lo=1, hi=8, lo_closed=True, hi_closed=True),
    "bearing.row_spacing": Key("float", "m", "distance between neighbouring rows", lo=0.0, lo_closed=True),
    "bearing.row_arrangement": Key("str", "-", "contact-angle directions of the rows",
                                   choices=("alternate", "same")),
    "bearing.dynamic_load_rating": Key("float", "N", "C_r (default: ISO 281 from the geometry)", lo=0.0),
    "load.radial": Key("float", "N", "radial load F_r", lo=0.0),
    "load.axial": Key("float", "N", "axial load F_a", lo=0.0, lo_closed=True),
    "load.angle": Key("float", "rad", "load line's angle from roller 0 (0: a roller on the load line)", lo=-np.pi,
                      hi=np.pi, lo_closed=True, hi_closed=True),
    "load.offset": Key("float", "m", "axial position of the radial load from the bearing middle (several rows)"),
    "support.housing_half_angle": Key("float", "rad", "outer ring clamped over |theta| <= this about the load "
                                      "line (pi: full housing)", lo=0.0, hi=np.pi, hi_closed=True),
    "materials.rollers.E": Key("float", "Pa", "Young's modulus of the rollers", lo=0.0),
    "materials.rollers.nu": Key("float", "-", "Poisson's ratio of the rollers", lo=-1.0, hi=0.5),
    "materials.rings.E": Key("float", "Pa", "Young's modulus of the rings", lo=0.0),
    "materials.rings.nu": Key("float", "-", "Poisson's ratio of the rings", lo=-1.0, hi=0.5),
    "materials.rings.rigid": Key("bool", "-", "rigid rings (rigid raceways)"),
    **model_keys(MODEL_NAMES),
    **SCHEMA_2D,
    **CHOCK_SCHEMA,
    **SCHEMA_3D,
    "paper.row_shares_measured": Key("floats", "%", "seed 003 Table 3: measured row shares", lo=0.0, hi=100.0,
                                     lo_closed=True, hi_closed=True),
    "paper.row_shares_gsc": Key("floats", "%", "seed 003 Table 3: GSC-BBEM row shares", lo=0.0, hi=100.0,
                                lo_closed=True, hi_closed=True),
    "paper.row_shares_tbbem": Key("floats", "%", "seed 003 Table 3: T-BBEM row shares", lo=0.0, hi=100.0,
                                  lo_closed=True, hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance (or band, for a contrast) of model.quantity against the "
                                    "references"),
}

DEFAULTS: dict[str, Any] = {
    "bearing.contact_angle": 0.0,
    "bearing.law": "plane_strain",
    "bearing.load_exponent": 10.0 / 9.0,
    "bearing.slices": 30,
    "bearing.crown": "none",
    "bearing.tilt": 0.0,
    "bearing.rows": 1,
    "bearing.row_spacing": 0.0,
    "bearing.row_arrangement": "alternate",
    "load.axial": 0.0,
    "load.angle": 0.0,
    "load.offset": 0.0,
    "support.housing_half_angle": np.pi,
    "materials.rings.rigid": False,
    "models.run": ["rigid_ring", "integral"],
    "models.references": ["rigid_ring"],
    "models.contrast": [],
    **DEFAULTS_2D,
    "chock.seat": "spherical",
    "numerics.chock_between": 1,
    "numerics.chock_radial": 2,
    "numerics.chock_slices": 8,
    **DEFAULTS_3D,
}
REQUIRED = ("geometry.inner_raceway_diameter", "geometry.outer_raceway_diameter", "geometry.roller_diameter",
            "geometry.roller_length", "bearing.rollers", "load.radial", "materials.rollers.E", "materials.rollers.nu")

DEPENDS = {
    "fem": {"params": ("geometry.", "bearing.rollers", "load.radial", "load.angle", "materials.", "support.",
                       "numerics.fem_"), "reference": True, "coarse": {"numerics.fem_levels": 1}},
    "condensed": {"params": ("geometry.", "bearing.rollers", "load.radial", "load.angle", "materials.", "support.",
                             "numerics.condensed_")},
    "flexible_chock": {"params": ("geometry.", "bearing.", "load.", "materials.structure.", "chock.", "roll.",
                                  "numerics.chock_")},
    "condensed3d": {"params": ("geometry.", "bearing.", "load.", "materials.", "support.", "numerics.condensed3d_")},
    "coupled_slices": {"params": ("geometry.", "bearing.", "load.", "materials.", "support.", "numerics.resolved_",
                                  "numerics.strips_")},
    "resolved": {"params": ("geometry.", "bearing.", "load.", "materials.", "support.", "numerics.resolved_"),
                 "reference": True, "coarse": {"numerics.resolved_levels": 1}},
}


def clearance(params: dict[str, Any]) -> float:
    """Diametral clearance P_d = d_o - d_i - 2 D (m; negative: preload)."""
    return params["geometry.outer_raceway_diameter"] - params["geometry.inner_raceway_diameter"] - \
        2.0 * params["geometry.roller_diameter"]


def roller_law(params: dict[str, Any]):
    """The load-deflection law of one roller (both contacts) named by ``bearing.law``."""
    law, length = params["bearing.law"], params["geometry.roller_length"]
    if law == "palmgren":
        return laws.palmgren(length)
    if law == "iso16281":
        return laws.iso16281(length)
    if law == "plane_strain":
        return section(params).roller_law()
    n = params["bearing.load_exponent"]
    if "bearing.load_stiffness" in params:
        return laws.PowerLaw(params["bearing.load_stiffness"], n)
    return laws.power_law_matched(length, n, 4.08 * params["load.radial"] / params["bearing.rollers"])


def validate(params: dict[str, Any]) -> None:
    """Geometry that fits, loads a model can carry, models that apply to the scene."""
    d_i, d_o, D = (params[f"geometry.{k}"] for k in ("inner_raceway_diameter", "outer_raceway_diameter",
                                                     "roller_diameter"))
    pd = clearance(params)
    if pd < -MAX_PRELOAD * D:
        raise InputError("geometry.outer_raceway_diameter",
                         f"{d_o:g} m leaves {0.5 * (d_o - d_i):.4g} m of radial room for rollers of diameter {D:g} m "
                         f"(clearance {pd:.3g} m); allowed: > {d_i + (2 - MAX_PRELOAD) * D:.6g} m "
                         f"(d_i + 2 D, preload up to {MAX_PRELOAD:g} D)")
    z = params["bearing.rollers"]
    pitch = 0.5 * (d_i + d_o)
    if z * D >= np.pi * pitch * np.cos(0.0):
        raise InputError("bearing.rollers", f"{z} rollers of diameter {D:g} m do not fit on the pitch circle "
                         f"{pitch:g} m; allowed: < {int(np.pi * pitch / D)}")
    for key, lo, hi in (("geometry.bore_diameter", 0.0, d_i), ("geometry.outside_diameter", d_o, np.inf)):
        if key in params and not lo < params[key] < hi:
            raise InputError(key, f"{params[key]:g} m is not allowed; allowed: ({lo:g}, {hi:g}) m")
    run = set(params["models.run"]) | set(params["models.references"])
    if "flexible_chock" in run:
        validate_chock(params)
    if run & {"condensed3d", "coupled_slices", "resolved"}:
        validate_3d(params, run)
    two_d = run & {"condensed", "fem"}
    if two_d:
        if params["bearing.rows"] > 1 or params["bearing.contact_angle"] > 0 or params["load.axial"] > 0:
            raise InputError("models.run", f"{', '.join(sorted(two_d))}: 2D plane-strain models of a single-row "
                             "radial bearing (rows 1, contact angle 0, no axial load)")
        if not params["materials.rings.rigid"]:
            for key in ("geometry.bore_diameter", "geometry.outside_diameter", "materials.rings.E",
                        "materials.rings.nu"):
                if key not in params:
                    raise InputError(key, "required for elastic rings in the condensed and fem models "
                                          "(or set materials.rings.rigid = true)")
    if params["bearing.rows"] > 1 and params["bearing.law"] != "iso16281":
        raise InputError("bearing.law", "several rows are solved with ISO/TS 16281 slices; allowed: iso16281")
    if params["load.axial"] > 0 and params["bearing.contact_angle"] == 0:
        raise InputError("load.axial", "a bearing with contact angle 0 carries no axial load in these models; "
                         "allowed: 0")
    if params["bearing.law"] == "plane_strain" or two_d:
        law = section(params).roller_law()
        q_lim = float(law.load(0.999 * law.max_deflection))
        if params["load.radial"] > q_lim:
            raise InputError("load.radial", f"{params['load.radial']:g} N could put more than the 2D roller law's "
                             f"range on one roller (contact widths not small against R); allowed: (0, {q_lim:.4g}] N")


def _quantities(psi, loads, interference, radial_load, delta_r, z, ca=1.0) -> tuple[dict, dict]:
    zone, eps = zone_from_profile(psi, interference)
    q = {"q_max": float(loads.max()), "radial_deflection": float(delta_r),
         "loaded_rollers": float(np.count_nonzero(loads > 0)), "load_zone_angle": zone,
         "load_zone_parameter": eps, "stribeck_factor": float(z * loads.max() / radial_load),
         "total_force": float(np.sum(loads * np.cos(psi)) * ca)}
    fields = {"roller_angle": np.asarray(psi, float), "roller_loads": np.asarray(loads, float),
              "roller_interference": np.asarray(interference, float)}
    return q, fields


def _hertz(law, q_max: float) -> dict[str, float]:
    """2D Hertz half-widths (m) and peak pressures (Pa) of the most loaded roller's two contacts (2D law only)."""
    if not isinstance(law, laws.PlaneStrainRoller):
        return {}
    a = law.half_widths(q_max)
    p = q_max / law.length
    return {"half_width_inner": float(a[0]), "half_width_outer": float(a[1]),
            "p_max_inner": float(2 * p / (np.pi * a[0])), "p_max_outer": float(2 * p / (np.pi * a[1]))}


def _rating(scene: Scene, slice_loads: np.ndarray) -> float:
    D, length = scene["geometry.roller_diameter"], scene["geometry.roller_length"]
    dpw = 0.5 * (scene["geometry.inner_raceway_diameter"] + scene["geometry.outer_raceway_diameter"])
    alpha, rows = scene["bearing.contact_angle"], scene["bearing.rows"]
    c = scene.get("bearing.dynamic_load_rating") or iso16281.dynamic_load_rating(
        scene["bearing.rollers"], D, dpw, length, alpha, rows)
    return iso16281.reference_rating_life(slice_loads, c, D, dpw, alpha, rows)


def rigid_ring(scene: Scene, progress=None) -> ModelResult:
    """Discrete rigid-ring distribution (single row: any law; ISO law: slices; several rows: 5 DOF)."""
    p = scene.params
    z, fr, pd = p["bearing.rollers"], p["load.radial"], clearance(p)
    if p["bearing.law"] == "iso16281":
        rows_n = p["bearing.rows"]
        alpha = p["bearing.contact_angle"]
        rows = iso16281.row_layout(rows_n, p["bearing.row_spacing"], p["bearing.row_arrangement"], alpha)
        D = p["geometry.roller_diameter"]
        sol = iso16281.sliced_equilibrium(rows, z, 0.25 * (p["geometry.inner_raceway_diameter"]
                                                           + p["geometry.outer_raceway_diameter"]),
                                          p["geometry.roller_length"], D, pd, p["bearing.slices"], fr,
                                          p["load.axial"], p["load.offset"], p["load.angle"], p["bearing.tilt"],
                                          p["bearing.crown"], tapered=alpha > 0)
        loads = sol.roller_loads.sum(axis=0) if rows_n == 1 else sol.roller_loads
        u = sol.equilibrium.u
        flat = sol.roller_loads[0] if rows_n == 1 else sol.roller_loads.max(axis=0)
        interference = sol.deflection[0].max(axis=1) if rows_n == 1 else sol.deflection.max(axis=(0, 2))
        q, fields = _quantities(sol.psi, flat, interference, fr, np.hypot(u[0], u[1]), z, np.cos(alpha))
        q["total_force"] = float(sol.row_radial.sum())
        stats = {"iterations": sol.equilibrium.iterations, "residual": sol.equilibrium.residual,
                 "dofs": list(sol.dofs), "displacement": u.tolist(), "slices": p["bearing.slices"]}
        if rows_n == 1:
            q["rating_life"] = _rating(scene, sol.slice_loads[0])
            fields["slice_loads"] = sol.slice_loads[0]
        else:
            shares = 100.0 * sol.row_radial / sol.row_radial.sum()
            for r, sh in enumerate(shares):
                q[f"row_share_{r + 1}"] = float(sh)
            fields["row_roller_loads"] = loads
            fields["row_shares"] = shares
            q.pop("load_zone_angle"), q.pop("load_zone_parameter"), q.pop("stribeck_factor")
            q["q_max"] = float(loads.max())
        return ModelResult("rigid_ring", quantities=q, stats=stats, fields=fields)
    law = roller_law(p)
    rr = rigid_ring_solve(z, pd, law, fr, p["load.angle"], p["load.axial"], p["bearing.contact_angle"])
    q, fields = _quantities(rr.psi, rr.loads, rr.deflection, fr, rr.radial_deflection, z,
                            np.cos(p["bearing.contact_angle"]))
    q["load_zone_angle"], q["load_zone_parameter"] = rr.load_zone_angle, rr.eps
    q.update(_hertz(law, rr.q_max))
    stats = {"iterations": rr.iterations, "residual": rr.residual, "law": getattr(law, "name", p["bearing.law"]),
             "displacement": rr.displacement.tolist(), "axial_reaction": rr.axial_reaction}
    return ModelResult("rigid_ring", quantities=q, stats=stats, fields=fields)


def integral(scene: Scene, progress=None) -> ModelResult:
    """Z -> infinity (Sjövall): the continuous distribution, sampled at the roller angles for the profile."""
    p = scene.params
    if p["bearing.rows"] > 1:
        return ModelResult("integral", "skipped", error="the integral model is single-row")
    law = roller_law(p)
    z, fr = p["bearing.rollers"], p["load.radial"]
    m = integral_model(z, clearance(p), law, fr, p["bearing.contact_angle"])
    psi = 2.0 * np.pi * np.arange(z) / z - p["load.angle"]
    psi = np.angle(np.exp(1j * psi))
    q = {"q_max": m.q_max, "radial_deflection": m.radial_deflection, "load_zone_angle": m.load_zone_angle,
         "load_zone_parameter": m.eps, "stribeck_factor": z * m.q_max / fr}
    stats = {"J_r": m.j_r, "J_a": m.j_a, "iterations": m.iterations, "residual": 0.0}
    if isinstance(law, laws.PowerLaw):
        stats["J_r_sjovall"], stats["J_a_sjovall"] = load_integrals(m.eps, law.exponent)
    interference = m.radial_deflection * np.cos(psi) - 0.5 * clearance(p)
    fields = {"roller_angle": psi, "roller_loads": m.load(psi, law), "roller_interference": interference}
    return ModelResult("integral", quantities=q, stats=stats, fields=fields)


def condensed(scene: Scene, progress=None) -> ModelResult:
    from ..bem.bearing_condensed import CondensedSettings, solve

    p = scene.params
    s = CondensedSettings(h_contact=p["numerics.condensed_h_contact"], roller=p["numerics.condensed_roller"])
    sec = section(p)
    r = solve(sec, s, progress)
    psi = np.angle(np.exp(1j * sec.angles))
    q, fields = _quantities(psi, r.loads, r.interference, p["load.radial"], np.hypot(*r.delta), sec.rollers)
    q.update(_hertz(sec.roller_law(), float(r.loads.max())))
    stats = {"iterations": r.newton_iterations, "width_iterations": r.width_iterations, "residual": r.residual,
             "b0": r.b0, "n_dofs": r.ring_dofs, "roller": s.roller, "delta": r.delta.tolist()}
    fields["half_width_inner"], fields["half_width_outer"] = r.widths
    return ModelResult("condensed", quantities=q, stats=stats, fields=fields)


def fem(scene: Scene, progress=None) -> ModelResult:
    from ..fem import bearing2d as fe

    p = scene.params
    s = fe.FESettings(levels=p["numerics.fem_levels"], ratio=p["numerics.fem_ratio"],
                      h_contact=p["numerics.fem_h_contact"], zone=p["numerics.fem_zone"],
                      grading=p["numerics.fem_grading"], h_max_ring=p["numerics.fem_h_max_ring"],
                      h_max_roller=p["numerics.fem_h_max_roller"], order=p["numerics.fem_order"],
                      method=p["numerics.fem_method"], penalty_factor=p["numerics.fem_penalty"],
                      similarity=p["numerics.fem_similarity"])
    sec = section(p)
    levels, certs = fe.solve(sec, s, progress)
    fine = levels[-1]
    psi = np.angle(np.exp(1j * sec.angles))
    q, fields = _quantities(psi, fine.roller_loads, fine.interference, p["load.radial"], fine.radial_deflection,
                            sec.rollers)
    q["load_zone_angle"], q["load_zone_parameter"] = fine.load_zone_angle, fine.load_zone_parameter
    finest = {k: q[k] for k in ("q_max", "radial_deflection", "load_zone_angle", "load_zone_parameter")}
    as_dict = {k: (v.as_dict() if hasattr(v, "as_dict") else v) for k, v in certs.items()}
    for k in finest:
        q[k] = as_dict[k]["value"]
    q["stribeck_factor"] = sec.rollers * q["q_max"] / p["load.radial"]
    as_dict["stribeck_factor"] = {**as_dict["q_max"], "value": q["stribeck_factor"],
                                  "finest": sec.rollers * finest["q_max"] / p["load.radial"]}
    for k in ("p_max_inner", "p_max_outer", "half_width_inner", "half_width_outer"):
        q[k] = fine.detail[k]
    fields.update(fine.detail["fields"])
    stats = {"certificates": as_dict, "finest": finest, "method": s.method, "similarity": s.similarity,
             "element_order": s.order, "iterations": fine.iterations, "residual": fine.residual,
             "levels": [{"h": lv.h, "h_over_b": lv.h / certs["roller_loads"]["b"], "n_dofs": lv.n_dofs,
                         "q_max": lv.q_max, "radial_deflection": lv.radial_deflection,
                         "load_zone_angle": lv.load_zone_angle, "loaded_rollers": lv.loaded_rollers,
                         "roller_loads": lv.roller_loads.tolist(), "iterations": lv.iterations,
                         "residual": lv.residual, "penetration": lv.penetration, "total_force": lv.total_force,
                         "included_rollers": [int(j) for j in lv.included], "time_s": lv.time_s} for lv in levels],
             "approach_reference": "shaft (tied bore) relative to the housing (clamped OD)"}
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)


def measured(scene: Scene, progress=None) -> ModelResult:
    """The row shares measured on the mill (seed 003 Table 3, ``paper.row_shares_measured``, %): a reference
    of measured data, not a model; skipped where the scene gives none."""
    shares = scene.get("paper.row_shares_measured")
    if not shares:
        return ModelResult("measured", "skipped", error="the scene gives no paper.row_shares_measured")
    if len(shares) != scene["bearing.rows"]:
        raise InputError("paper.row_shares_measured", f"{len(shares)} values for {scene['bearing.rows']} rows; "
                                                      "allowed: one share per row")
    return ModelResult("measured", quantities={f"row_share_{r + 1}": float(v) for r, v in enumerate(shares)},
                       stats={"source": "Yang et al. 2016, Table 3 (measured on the mill)"},
                       fields={"row_shares": np.asarray(shares, dtype=float)})


MODELS: dict[str, Callable[..., ModelResult]] = {"rigid_ring": rigid_ring, "integral": integral,
                                                 "condensed": condensed, "fem": fem,
                                                 "flexible_chock": flexible_chock, "condensed3d": condensed3d,
                                                 "coupled_slices": coupled_slices, "resolved": resolved,
                                                 "measured": measured}
STRESS_QUANTITIES = ("q_max", "roller_loads_max")


def load_of(scene: Scene) -> float:
    """The radial load (N) every model's ``total_force`` must balance."""
    return scene["load.radial"]


def profile_scale(scene: Scene) -> float:
    return 0.5 * scene["geometry.roller_diameter"]


def _with_clearance(params: dict[str, Any], pd: float) -> dict[str, Any]:
    return {"geometry.outer_raceway_diameter": params["geometry.inner_raceway_diameter"]
            + 2.0 * params["geometry.roller_diameter"] + pd}


def stress_cases(scene: Scene) -> list:
    """Extremes (spec §6.3): clearance from preload (P_d = -0.5 delta_r) to 20 delta_r (delta_r: the zero-clearance
    rigid-ring deflection), Z from 3 to 40 on the same pitch circle (roller diameter scaled to fit), the load line
    from a roller to midway between two, the load over seven decades (1e-6 to 10 x nominal), exponents 1, 10/9,
    3/2 (power law), and for elastic rings a housing arc down to 15 deg (condensed model). Every case runs the
    fast models; the generic checks catch lost equilibrium (|sum Q cos psi - F_r| > 1e-6 F_r) and negative loads."""
    from ..result import StressCase

    p = scene.params
    fast = {"models.run": ["rigid_ring", "integral"]}
    two_d = not p["materials.rings.rigid"] and "geometry.outside_diameter" in p
    # the condensed model (about 0.5 s) joins the cases that keep its geometry: clearance and load direction
    with_condensed = {"models.run": ["rigid_ring", "integral", "condensed"]} if two_d else fast
    law = roller_law({**p, **_with_clearance(p, 0.0)})
    dr0 = rigid_ring_solve(p["bearing.rollers"], 0.0, law, p["load.radial"]).radial_deflection
    cases = []
    for ratio in (-0.5, 0.0, 0.5, 1.0, 2.0, 5.0, 20.0):
        cases.append(StressCase(f"P_d/delta_r={ratio:g}", {**with_condensed, **_with_clearance(p, ratio * dr0)}))
    pitch = 0.5 * (p["geometry.inner_raceway_diameter"] + p["geometry.outer_raceway_diameter"])
    pd = clearance(p)
    for z in (3, 4, 6, 9, 20, 40):
        d = min(p["geometry.roller_diameter"], 0.8 * np.pi * pitch / z)
        cases.append(StressCase(f"Z={z}", {**fast, "bearing.rollers": z, "geometry.roller_diameter": d,
                                           "geometry.inner_raceway_diameter": pitch - d,
                                           "geometry.outer_raceway_diameter": pitch + d + pd}))
    for frac in (0.25, 0.5, 0.75, 1.0):
        cases.append(StressCase(f"load angle={frac:g} pi/Z",
                                {**with_condensed, "load.angle": frac * np.pi / p["bearing.rollers"]}))
    for factor in (1e-6, 1e-4, 1e-2, 1.0, 10.0):
        cases.append(StressCase(f"F_r={factor:g} x nominal", {**fast, "load.radial": factor * p["load.radial"]}))
    for n in (1.0, 10.0 / 9.0, 1.5):
        for frac in (0.0, 1.0):
            cases.append(StressCase(f"power n={n:.4g}, load angle={frac:g} pi/Z",
                                    {**fast, "bearing.law": "power", "bearing.load_exponent": n,
                                     "load.angle": frac * np.pi / p["bearing.rollers"]}))
    if two_d:
        for deg in (90.0, 60.0, 30.0, 15.0):
            cases.append(StressCase(f"housing arc {deg:g} deg", {"models.run": ["rigid_ring", "condensed"],
                                                                  "support.housing_half_angle": np.radians(deg)}))
        cases.append(StressCase("housing arc 15 deg, P_d/delta_r=-0.5",
                                {"models.run": ["rigid_ring", "condensed"], "support.housing_half_angle": np.radians(15.0),
                                 **_with_clearance(p, -0.5 * dr0)}))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """``femcheck bench``: rigid_ring and integral (no discretisation), the condensed model's patch-zone spacing
    (b_0 to b_0/8, FE ring compliances included), and single FE levels refined by the scene's ratio."""
    r = scene["numerics.fem_ratio"]
    h0, g0 = scene["numerics.fem_h_contact"], scene["numerics.fem_grading"]
    hr, hl = scene["numerics.fem_h_max_ring"], scene["numerics.fem_h_max_roller"]
    sweeps: dict[str, list[dict[str, Any]]] = {"rigid_ring": [{}], "integral": [{}]}
    if scene["bearing.rows"] == 1 and scene["bearing.contact_angle"] == 0:
        sweeps["condensed"] = [{"numerics.condensed_h_contact": h} for h in (1.0, 0.5, 0.25, 0.125)]
        sweeps["fem"] = [{"numerics.fem_levels": 1, "numerics.fem_h_contact": h0 / r**k,
                          "numerics.fem_grading": g0 / r**k, "numerics.fem_h_max_ring": hr / r**k,
                          "numerics.fem_h_max_roller": hl / r**k} for k in range(3)]
    return sweeps
