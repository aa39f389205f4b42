"""The roller of seed 000's spherical roller bearing in steady rolling with Coulomb friction (spec
srb-rolling §3, §6, §7): its equilibrium between the two raceways (six unknowns: the centre offsets d_Y, d_Z, tilt,
skew, cage speed omega_m, roller spin omega_R) with both contacts solved by Kalker's exact theory on the conformal
surfaces, and seed 000 Table 2.

Models:
- ``cect``: the roller equilibrium with conformal CECT contacts (:mod:`femcheck.cect.roller_equilibrium`): exact
  conformal gaps, 3D rigid slip, variable rolling step kappa(s), developed half-space influence coefficients; the
  inner ring's approach along e_z solved so that the inner normal force is ``load.normal``. Configuration 1 from
  the nominal pose; configuration 2 (``equilibrium.configuration``) found from skewed starts at
  ``equilibrium.branch_start_load`` (2 kN, the low end of Fig. 17) and followed in N up to the load
  (:func:`femcheck.cect.roller_sweep.configuration_2`); a configuration that does not exist at the load (or whose
  branch folds below it) is reported as skipped with the reason (status 2), not replaced by the other.
- ``paper``: seed 000 Table 2's CECT column (mu = 0.1 or 0.3 at 5.5 kN; skipped otherwise): the reference every
  model is compared against, together with ``cect``.
- ``strip`` / ``strip_s0``: strip theory H+C with the 2-unknown speed iteration (:mod:`femcheck.cect.strip_bearing`)
  at the nominal contact centres / at the CECT pressure-centre offset s0 (spec §4.1, check 12): contrasts.
- ``full_slip``: Table 2's full-slip column: p_t = -mu p_n w/|w| with the CECT pressure and rigid slip at the CECT
  equilibrium (spec §4.4): a contrast (not an equilibrium).
- ``fem``: the frictional FE of :mod:`femcheck.fem.srb_rolling` at the CECT pose with the speeds re-balanced for
  free rolling and each contact held at N (not a full FE equilibrium: the lateral, radial and tilt/skew residuals
  at the CECT pose are reported), three levels (9 x 17 -> 19 x 35 cells per contact, meshes refined with them)
  with certificates; stored in ``references/srb_rolling/``. A contrast with bands: the paper's own FEM differs
  from its CECT by +14 / +17 % in sum f_lat.

Quantities (Table 2's signs and normalisation, :mod:`femcheck.problems._srb_rolling_out`): ``f_x_inner``,
``f_x_outer``, ``f_lat_inner``, ``f_lat_outer``, ``f_lat_sum`` (-, F/(mu N)), ``d_y`` (m), ``tilt``, ``skew``
(rad; skew = gamma_p = -gamma), ``friction_power_inner|outer`` (W), ``adhesion_fraction_inner|outer``,
``omega_m_deviation``, ``omega_R_deviation`` (-: omega / omega_kinematic - 1, seed 000 eqs 2-3; the raw speeds in
rad/s are in ``stats["speeds"]``).
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .. import replay
from ..cect.conformal import resultants
from ..cect.full_slip import full_slip_tractions
from ..cect.influence import combined_constants
from ..cect.influence_conformal import INFLUENCE_OPTIONS
from ..cect.roller_equilibrium import EquilibriumResult, equilibrium, require_converged
from ..cect.roller_state import Numerics, RollerProblem
from ..cect.roller_sweep import configuration_2
from ..cect.strip_bearing import strip_bearing
from ..errors import InputError
from ..geometry import srb_bearing as sb
from ..result import ModelResult
from ..scene import Key, Scene, elastic, material_keys, model_keys, tolerance_key
from . import _srb_rolling_out as out
from ._finite_body_keys import SRB_COARSE, SRB_DEFAULTS, SRB_KEYS

MODEL_NAMES = ("cect", "paper", "strip", "strip_s0", "full_slip", "fem", "fem_finite_body", "paper_fem")
# seed 000's question: the lateral forces (their sum loads the cage and flanges), then the rolling-direction ones
DESIGN_QUANTITIES = ("f_lat_sum", "f_lat", "f_x", "d_y")
# Table 2's normalisation: forces divided by mu N
UNITS = {"f_x": "- (F / mu N)", "f_lat": "- (F / mu N)", "d_y": "m", "tilt": "rad", "skew": "rad",
         "omega_m_deviation": "- (omega_m / omega_m,o - 1)", "omega_R_deviation": "- (omega_R / omega_R,o - 1)"}
TABLE_2_QUANTITIES = ("f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "f_lat_sum", "d_y")

SCHEMA: dict[str, Key] = {
    "geometry.roller_diameter": Key("float", "m", "roller nominal diameter D", lo=0.0),
    "geometry.crown_radius": Key("float", "m", "roller crown radius R", lo=0.0),
    "geometry.groove_radius_inner": Key("float", "m", "inner-race groove radius r_I (> R)", lo=0.0),
    "geometry.groove_radius_outer": Key("float", "m", "outer-race groove radius r_E (> R)", lo=0.0),
    "geometry.contact_angle": Key("float", "rad", "nominal contact angle alpha", lo=0.0, hi=0.8, lo_closed=True),
    "geometry.roller_length": Key("float", "m", "roller length L_R (not in the paper: 27 mm from the mass)", lo=0.0),
    **material_keys("roller"),
    **material_keys("ring"),
    "load.normal": Key("float", "N", "normal load N held on the inner contact (the ring approach is solved for it)",
                       lo=0.0),
    "friction.mu": Key("float", "-", "Coulomb friction coefficient", lo=0.0, hi=10.0, hi_closed=True),
    "kinematics.inner_ring_speed": Key("float", "rad/s", "inner ring speed omega_I about the ring axis"),
    "kinematics.outer_ring_speed": Key("float", "rad/s", "outer ring speed omega_E about the ring axis"),
    "roller.mass": Key("float", "kg", "roller mass m_R (centrifugal force)", lo=0.0, lo_closed=True),
    "roller.inertia": Key("float", "kg m^2", "roller inertia about its spin axis I_R (gyroscopic moment; E9)",
                          lo=0.0, lo_closed=True),
    "equilibrium.configuration": Key("int", "-", "1: from the nominal pose; 2: from skewed starts (seed 000 §4.3)",
                                     lo=1, hi=2, lo_closed=True, hi_closed=True),
    "equilibrium.branch_start_load": Key("float", "N", "configuration 2: found from skewed starts at this load "
                                         "(or the scene's load if lower) and followed in N up to the scene's load",
                                         lo=0.0),
    "equilibrium.branch_step": Key("float", "N", "configuration 2: load step of the continuation (halved at "
                                   "failure down to 62.5 N)", lo=62.5, lo_closed=True),
    **model_keys(MODEL_NAMES),
    "numerics.conformal_cells_x": Key("int", "-", "elements along the rolling direction per contact", lo=9, hi=401,
                                      lo_closed=True, hi_closed=True),
    "numerics.conformal_cells_s": Key("int", "-", "elements along the profile per contact", lo=9, hi=801,
                                      lo_closed=True, hi_closed=True),
    "numerics.conformal_domain_x": Key("float", "a_H", "window half-length along x / Hertz semi-axis", lo=1.02,
                                       hi=3.0, hi_closed=True),
    "numerics.conformal_domain_s": Key("float", "b_H", "window half-width along s / Hertz semi-axis", lo=1.02,
                                       hi=3.0, hi_closed=True),
    "numerics.conformal_influence": Key("str", "-", "influence coefficients: halfspace (developed), blanco, "
                                        "rotated_response", choices=INFLUENCE_OPTIONS),
    "numerics.variable_dq": Key("bool", "-", "variable rolling step kappa(s) (seed 000 eq 21)"),
    "numerics.equilibrium_tol": Key("float", "-", "tol_F / (mu N) (tol_M = tol_F D/2)", lo=0.0, hi=1e-2,
                                    hi_closed=True),
    "numerics.strip_count": Key("int", "-", "strips of the H+C models", lo=10, hi=5000, lo_closed=True,
                                hi_closed=True),
    "numerics.fem_cells_x": Key("int", "-", "fem: cells along x per contact on the coarsest level (common dx)", lo=5,
                                hi=61, lo_closed=True, hi_closed=True),
    "numerics.fem_cells_s": Key("int", "-", "fem: cells along s per contact on the coarsest level (common ds)", lo=5,
                                hi=121, lo_closed=True, hi_closed=True),
    "numerics.fem_levels": Key("int", "-", "fem: levels (cells and meshes refined together)", lo=1, hi=3,
                               lo_closed=True, hi_closed=True),
    "numerics.fem_ratio": Key("float", "-", "fem: refinement ratio of dx between levels", lo=1.1, hi=2.0,
                              lo_closed=True, hi_closed=True),
    "numerics.fem_h_contact": Key("float", "dx", "fem: element size at the contact line / dx", lo=0.1, hi=2.0,
                                  hi_closed=True),
    "numerics.fem_grading": Key("float", "-", "fem: mesh grading away from the contact", lo=0.05, hi=1.0,
                                hi_closed=True),
    **SRB_KEYS,
    "tolerances.*.*": tolerance_key("relative tolerance (or contrast band) of model.quantity against the "
                                    "references"),
}
DEFAULTS: dict[str, Any] = {
    "materials.roller.rigid": False,
    "materials.ring.rigid": False,
    "geometry.roller_length": 0.027,
    "friction.mu": 0.1,
    "kinematics.outer_ring_speed": 0.0,
    "roller.mass": 0.0656,
    "roller.inertia": 5.87e-6,
    "equilibrium.configuration": 1,
    "equilibrium.branch_start_load": 2000.0,
    "equilibrium.branch_step": 250.0,
    "models.run": ["cect", "paper", "strip", "strip_s0", "full_slip"],
    "models.references": ["paper", "cect"],
    "models.contrast": ["strip", "strip_s0", "full_slip"],
    "numerics.conformal_cells_x": 41,
    "numerics.conformal_cells_s": 81,
    "numerics.conformal_domain_x": 1.35,
    "numerics.conformal_domain_s": 1.25,
    "numerics.conformal_influence": "halfspace",
    "numerics.variable_dq": True,
    "numerics.equilibrium_tol": 1e-5,
    "numerics.strip_count": 400,
    "numerics.fem_cells_x": 9,
    "numerics.fem_cells_s": 17,
    "numerics.fem_levels": 3,
    "numerics.fem_ratio": 1.4142135623730951,
    "numerics.fem_h_contact": 0.7,
    "numerics.fem_grading": 0.4,
    **SRB_DEFAULTS,
}
REQUIRED = ("geometry.roller_diameter", "geometry.crown_radius", "geometry.groove_radius_inner",
            "geometry.groove_radius_outer", "geometry.contact_angle", "load.normal", "kinematics.inner_ring_speed")
# fem: a stored reference (three levels with certificates; the CECT pose it is solved at is part of its inputs)
DEPENDS: dict[str, dict] = {"fem": {"params": ("geometry.", "materials.", "load.", "friction.", "kinematics.",
                                               "roller.", "equilibrium.", "numerics."), "reference": True,
                                    "coarse": {"numerics.fem_levels": 1}},
                            # fem_finite_body: its coarse re-solve is the coarsest correction on the scene's grid
                            "fem_finite_body": {"params": ("geometry.", "materials.", "load.", "friction.",
                                                           "kinematics.", "roller.", "equilibrium.", "numerics."),
                                                "reference": True,
                                                "coarse": SRB_COARSE}}


def bearing(p: dict[str, Any]) -> sb.BearingGeometry:
    return sb.BearingGeometry.from_params(p)


def problem_of(p: dict[str, Any]) -> RollerProblem:
    c = combined_constants(elastic(p, "roller"), elastic(p, "ring"))
    return RollerProblem(bearing(p), c, float(p["friction.mu"]), float(p["kinematics.inner_ring_speed"]),
                         float(p["kinematics.outer_ring_speed"]), float(p["load.normal"]))


def numerics_of(p: dict[str, Any]) -> Numerics:
    return Numerics(nx=p["numerics.conformal_cells_x"], ns=p["numerics.conformal_cells_s"],
                    domain_x=p["numerics.conformal_domain_x"], domain_s=p["numerics.conformal_domain_s"],
                    variable_dq=p["numerics.variable_dq"], influence=p["numerics.conformal_influence"],
                    tol_scale=p["numerics.equilibrium_tol"])


def validate(params: dict[str, Any]) -> None:
    """Elastic steel-like bodies, grooves wider than the crown, mu > 0, rolling rings, and a load whose contacts
    stay on the roller (Hertz lateral semi-axis b_H <= L_R/2 on both raceways)."""
    for body in ("roller", "ring"):
        if params.get(f"materials.{body}.rigid", False):
            raise InputError(f"materials.{body}.rigid", "true is not allowed; allowed: false (elastic bodies)")
        for k in (f"materials.{body}.E", f"materials.{body}.nu"):
            if k not in params:
                raise InputError(k, "required; allowed: an elastic constant")
    R = params["geometry.crown_radius"]
    for k in ("geometry.groove_radius_inner", "geometry.groove_radius_outer"):
        if params[k] <= R:
            raise InputError(k, f"{params[k]:g} m is not allowed; allowed: ({R:g}, inf) m (larger than the crown)")
    if not params["friction.mu"] > 0:
        raise InputError("friction.mu", f"{params['friction.mu']:g} is not allowed; allowed: (0, 10]")
    if params["kinematics.inner_ring_speed"] == params["kinematics.outer_ring_speed"]:
        raise InputError("kinematics.inner_ring_speed", "equal to the outer ring speed; allowed: a different speed "
                         "(the roller must roll)")
    pr = problem_of(params)
    hz = pr.hertz()
    half = 0.5 * params["geometry.roller_length"]
    worst = max(hz[c].semi_axis_y for c in sb.CONTACTS)
    if worst > half:
        N = params["load.normal"]
        raise InputError("load.normal", f"{N:g} N cannot be carried (the contact would be {2 * worst * 1e3:.3g} mm "
                         f"wide on a {2 * half * 1e3:.3g} mm roller); allowed: (0, {N * (half / worst) ** 3:.4g}] N")


_SOLVED: dict[tuple, EquilibriumResult] = {}


def solved(p: dict[str, Any], configuration: int | None = None) -> EquilibriumResult:
    """The CECT equilibrium of the scene's parameters (memoised: full_slip and strip_s0 need the same state)."""
    cfg = p["equilibrium.configuration"] if configuration is None else configuration
    key = tuple(sorted((k, str(v)) for k, v in p.items() if not k.startswith(("models.", "tolerances."))))
    key += (("configuration", cfg),)
    if key not in _SOLVED:
        if len(_SOLVED) > 8:
            _SOLVED.clear()
        if cfg == 2:
            _SOLVED[key] = configuration_2(problem_of(p), numerics_of(p), p["equilibrium.branch_start_load"],
                                           p["equilibrium.branch_step"])
        else:
            _SOLVED[key] = equilibrium(problem_of(p), numerics_of(p), configuration=1)
    return _SOLVED[key]


def _not_found(name: str, r: EquilibriumResult) -> ModelResult:
    return ModelResult(name, "skipped", error=f"configuration {r.configuration}: {r.message}")


def cect(scene: Scene, progress=None) -> ModelResult:
    """The roller equilibrium with conformal CECT contacts."""
    p = scene.params
    if progress:
        progress("cect: roller equilibrium (pose, speeds, approach), conformal CECT on both contacts")
    r = solved(p)
    if r.status == 2:
        return _not_found("cect", r)
    require_converged(r)
    pr = problem_of(p)
    q = out.quantities(pr, r)
    stats = {"iterations": r.nit, "jacobians": r.njev, "evaluations": r.nfev,
             "residual": float(np.max(np.abs(r.scaled_residual))), "residual_components": r.residual_by_name(),
             "tolerance": "tol_F = %.3g N, tol_M = %.3g N m" % (p["numerics.equilibrium_tol"] * pr.mu * pr.load,
                                                                   p["numerics.equilibrium_tol"] * pr.mu * pr.load
                                                                   * 0.5 * pr.bearing.roller_diameter),
             "approach": r.approach, "configuration": r.configuration, "state": r.unknowns(),
             "state_changes_in_jacobian": r.state_changes, "checks": out.checks(pr, r, q),
             "grid": [p["numerics.conformal_cells_x"], p["numerics.conformal_cells_s"]],
             "n_elements": 2 * p["numerics.conformal_cells_x"] * p["numerics.conformal_cells_s"],
             "normal_forces": {c: r.state.contacts[c].result.normal_force for c in sb.CONTACTS},
             "time_s": r.time_s,
             "speeds": out.speeds(pr.bearing, pr.omega_inner, pr.omega_outer, float(r.x[4]), float(r.x[5])),
             "solver": "damped Newton/Broyden (FD Jacobian) on 7 unknowns (pose, speeds, ring approach); "
                       "conformal CECT per contact"}
    return ModelResult("cect", quantities=q, stats=stats, fields=out.fields(r.state))


def _table_2_column(scene: Scene, name: str, column: str) -> ModelResult:
    p = scene.params
    cols = out.table_2(p["friction.mu"], p["load.normal"])
    if cols is None or p["equilibrium.configuration"] != 1:
        return ModelResult(name, "skipped", error="seed 000 Table 2 gives configuration 1 at 5.5 kN, mu 0.1 or 0.3 "
                                                  "only")
    stats = {"source": f"Blanco-Lorenzo et al. 2022 (seed 000) Table 2, {column.upper()} column"}
    if column == "cect":
        stats.update({"full_slip": cols["full_slip"], "fem": cols["fem"]})
    return ModelResult(name, quantities=dict(cols[column]), stats=stats)


def paper(scene: Scene, progress=None) -> ModelResult:
    """Seed 000 Table 2, CECT column (mu 0.1 / 0.3 at 5.5 kN)."""
    return _table_2_column(scene, "paper", "cect")


def _strip(scene: Scene, name: str, s0: float) -> ModelResult:
    p = scene.params
    pr = problem_of(p)
    hc = strip_bearing(pr.bearing, pr.load, pr.mu, p["materials.roller.E"], p["materials.roller.nu"],
                       pr.omega_inner, pr.omega_outer, s0=s0, n_strips=p["numerics.strip_count"])
    q = {f"f_x_{c}": float(hc.f_x[c]) for c in sb.CONTACTS}
    for c in sb.CONTACTS:
        q[f"friction_power_{c}"] = float(hc.contacts[c].frictional_power)
        q[f"adhesion_fraction_{c}"] = float(hc.contacts[c].adhesion_fraction)
    q.update(out.speed_deviations(pr, float(hc.omega_m), float(hc.omega_R)))
    fields = {}
    for c in sb.CONTACTS:
        sc = hc.contacts[c]
        fields.update({f"{c}_y": sc.y, f"{c}_lateral_normal": sc.normal_per_width, f"{c}_lateral_fx":
                       sc.force_per_width})
    return ModelResult(name, quantities=q, fields=fields,
                       stats={"iterations": hc.iterations, "residual": hc.residual, "s0": s0,
                              "speeds": out.speeds(pr.bearing, pr.omega_inner, pr.omega_outer, float(hc.omega_m),
                                                  float(hc.omega_R)),
                              "zero_slip": {c: hc.contacts[c].zero_slip for c in sb.CONTACTS},
                              "solver": "strip theory H+C, Newton on (omega_m, omega_R)"})


def strip(scene: Scene, progress=None) -> ModelResult:
    """H+C at the nominal contact centres (s0 = 0)."""
    return _strip(scene, "strip", 0.0)


def strip_s0(scene: Scene, progress=None) -> ModelResult:
    """H+C with the contact centres at the CECT pressure-centre offset (mean of both contacts)."""
    r = solved(scene.params)
    if r.status != 0:
        return _not_found("strip_s0", r)
    s0 = float(np.mean([r.state.contacts[c].result.pressure_centre for c in sb.CONTACTS]))
    return _strip(scene, "strip_s0", s0)


def full_slip(scene: Scene, progress=None) -> ModelResult:
    """Full slip with the CECT pressure and rigid slip at the CECT equilibrium (Table 2's first columns)."""
    p = scene.params
    r = solved(p)
    if r.status != 0:
        return _not_found("full_slip", r)
    pr = problem_of(p)
    muN = pr.mu * pr.load
    xp = out.x_p(pr)
    q = {}
    for c in sb.CONTACTS:
        cs = r.state.contacts[c]
        res, ci = cs.result, cs.inputs
        px, ps = full_slip_tractions(res.pressure, ci.slip.wx, ci.slip.ws, pr.mu)
        F = resultants(res, ci.grid, r.state.centre, tractions=(px, ps, res.pressure)).force
        q[f"f_x_{c}"] = float(F @ xp / muN)
        q[f"f_lat_{c}"] = float(ps.sum() * res.cell_area / muN)
        q[f"friction_power_{c}"] = float(-(px * ci.slip.wx + ps * ci.slip.ws).sum() * res.cell_area)
    q["f_lat_sum"] = q["f_lat_inner"] + q["f_lat_outer"]
    return ModelResult("full_slip", quantities=q, stats={"solver": "full slip on the CECT pressure and rigid slip",
                                                         "iterations": 0, "residual": 0.0})


def fem(scene: Scene, progress=None) -> ModelResult:
    """The frictional FE (FE compliances of the whole roller and two ring segments, the FE side's own Coulomb
    solver) at the CECT equilibrium's pose, speeds re-balanced for free rolling (:mod:`._srb_rolling_fem`), on
    ``numerics.fem_levels`` levels that refine the cells and the meshes together by ``numerics.fem_ratio`` (dx
    exactly; the counts rounded up to odd numbers, the window widened by the rounding), with certificates."""
    from ..fem.contact_grid import refined_count
    from ..fem.rolling_compliance import MeshSettings
    from ..solvers.convergence import certify
    from . import _srb_rolling_fem

    p = scene.params

    def pose() -> dict:
        r = solved(p)
        return _srb_rolling_fem.cect_pose(r) if r.status == 0 else {"not_found": _not_found("fem", r).error}

    # the pose is an input of the FE that the CECT solve fixes only to its tolerance: recorded with the reference
    cp = replay.derived("srb_rolling.fem.cect_pose", pose)
    if "not_found" in cp:
        return ModelResult("fem", "skipped", error=cp["not_found"])
    levels = []
    for k in range(p["numerics.fem_levels"]):
        f = p["numerics.fem_ratio"] ** k
        nx0 = p["numerics.fem_cells_x"]
        nx, ns = refined_count(nx0, f), refined_count(p["numerics.fem_cells_s"], f)
        if progress:
            progress(f"fem: level {k + 1}/{p['numerics.fem_levels']} ({nx} x {ns} cells per contact)")
        mesh = MeshSettings(p["numerics.fem_h_contact"], p["numerics.fem_grading"] / f, 2e-3, 1, 2)
        o = _srb_rolling_fem.at_cect_pose(p, cp, nx, ns, mesh, progress, half_x=1.35 * nx / (nx0 * f))
        levels.append({"level": k, "nx": nx, "ns": ns, "h": o["stats"]["dx"], **o["quantities"],
                       **{key: o["stats"][key] for key in ("ds", "n_dofs", "iterations", "residual", "omega_m",
                                                          "omega_R", "speed_iterations", "speed_residual",
                                                          "equilibrium_residual_force_N")}})
    names = list(o["quantities"])
    certs = {q: certify([lv["h"] for lv in levels], [lv[q] for lv in levels]) for q in names}
    quantities = {q: c.value for q, c in certs.items()}
    fine = {q: levels[-1][q] for q in names}
    stats = {**o["stats"], "solver": "FE compliances (P2, PARDISO/LU) + 3D Coulomb semi-smooth Newton "
                                     "(solvers/coulomb3d), speeds by Newton",
             "levels": levels, "level_quantities": names, "finest": fine, "cect_pose": cp,
             "certificates": {q: c.as_dict() for q, c in certs.items()}}
    return ModelResult("fem", quantities=quantities, stats=stats)


def fem_finite_body(scene: Scene, progress=None) -> ModelResult:
    """The roller's own equilibrium with finite-body influence coefficients (half-space + FE correction) on fine
    contact grids, certified in two parts: the correction's FE mesh and grid, and the contact grid with the
    lattice-phase mean (:mod:`._srb_rolling_fb`). Configuration 1 only."""
    from . import _srb_rolling_fb

    p = scene.params
    if p["equilibrium.configuration"] != 1:
        return ModelResult("fem_finite_body", "skipped", error="configuration 1 only (configuration 2 with the "
                           "finite-body coefficients is not implemented)")
    r = solved(p)
    if r.status != 0:
        return _not_found("fem_finite_body", r)
    if progress:
        progress("fem_finite_body: the roller equilibrium with the FE finite-body correction")
    pr = problem_of(p)
    return _srb_rolling_fb.finite_body(p, pr, numerics_of(p), pr.constants, r, progress)


def paper_fem(scene: Scene, progress=None) -> ModelResult:
    """Seed 000 Table 2, FEM column (Abaqus, mu 0.1 / 0.3 at 5.5 kN; no error estimate published)."""
    return _table_2_column(scene, "paper_fem", "fem")


MODELS: dict[str, Callable[..., ModelResult]] = {"cect": cect, "paper": paper, "strip": strip,
                                                 "strip_s0": strip_s0, "full_slip": full_slip, "fem": fem,
                                                 "fem_finite_body": fem_finite_body, "paper_fem": paper_fem}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return problem_of(scene.params).hertz()["inner"].semi_axis_x


def stress_cases(scene: Scene) -> list:
    """Friction from 0.01 to 1, loads from 1 to 10 kN, configuration 2."""
    from ..result import StressCase

    cases = [StressCase(f"mu={mu:g}", {"friction.mu": mu}) for mu in (0.01, 1.0)]
    cases += [StressCase(f"N={n:g}", {"load.normal": n}) for n in (1000.0, 10000.0)]
    cases.append(StressCase("configuration 2", {"equilibrium.configuration": 2}))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """The grid study of spec §10.1 item 10: 41 x 81, 61 x 121, 81 x 161."""
    return {"cect": [{"numerics.conformal_cells_x": nx, "numerics.conformal_cells_s": ns}
                     for nx, ns in ((41, 81), (61, 121), (81, 161))]}
