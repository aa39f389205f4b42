"""A crowned body of revolution rolling freely in a grooved ring or on a straight grooved rail:
the one-contact core of the spherical roller bearing of seed 000, with Coulomb friction.

Geometry and frame: :mod:`femcheck.geometry.groove` (X rolling, Y along both axes, Z the nominal normal into the
crowned body; ring_curvature > 0 convex ring, < 0 concave ring, 0 straight rail). The ring's surface speed V is
given; free rolling: the body's rolling speed is the unknown that makes the rolling-direction force vanish.

Models (:mod:`femcheck.cect.groove_contact`):
- ``cect``: Kalker's exact theory on the conformal contact (:mod:`femcheck.cect.conformal`): exact gap between
  the crown and the groove on the developed (x, s) grid along the groove, 3D rigid slip of the two bodies of
  revolution (rolling radii varying across the patch), variable rolling step kappa(s), developed half-space (or
  angle-corrected) influence coefficients. The reference. Applicable up to a solved contact half-angle of
  50 deg on the groove (:func:`validate`; FE-checked to 45 deg, the deepest contact the FE meshes: the developed
  half-space within 0.5 % on the half-angle, 0.8 % on p_max and 2.8 % on the frictional power; the angle-corrected
  coefficients are not closer, so there is no automatic switch to them).
- ``planar``: today's planar exact theory (:mod:`femcheck.cect.exact`) with the Hertz quadratic gap and Kalker's
  creepages at the nominal point: the contrast that shows what conformity changes. With parallel axes it has
  neither spin nor a varying rolling radius, so it rolls freely at zero creepage with full adhesion and no
  frictional power; its normal problem differs from the conformal one by the quadratic gap and the flat
  contact plane only.
- ``fem``: the frictional finite-element reference (:mod:`femcheck.fem.groove_rolling`): FE
  compliances of the whole crowned body and a ring segment (Gmsh layered P2 meshes, scikit-fem, one
  factorisation per body) condensed onto the contact cells, steady rolling solved by the FE side's own semi-smooth
  Newton (:mod:`femcheck.solvers.coulomb3d`), free rolling and load control; levels refining grid and mesh
  together with certificates. A stored reference (``references/groove_rolling/``); elastic bodies only.
- ``fem_finite_body``: the exact theory with finite-body influence coefficients (the developed half-space plus the
  FE correction of the same bodies, :mod:`._groove_fb`) on the exact theory's fine grids, certified in two
  parts (the correction's FE levels, the contact grid with lattice-phase means). A stored reference.

Quantities (SI): ``approach`` (m), ``p_max`` (Pa), ``contact_half_length_s`` (m), ``angle_span`` (rad),
``adhesion_fraction``, ``creepage_x`` (free-rolling longitudinal creepage w_x/V at the nominal point, Kalker's
sign), ``spin_moment`` (N m, about the normal at the nominal point; zero by symmetry in this scene, reported as 0
when below the solver's tolerance), ``friction_power`` (W), ``total_force`` (N, the pressure resultant along
the nominal normal = load.normal).
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np
from scipy.optimize import brentq

from ..analytic.hertz import elliptic_contact
from ..cect.conformal import GridTooSmall
from ..cect.groove_contact import GridSpec, solve_groove_cect, solve_groove_planar
from ..cect.groove_extent import CHECK_GRID, NormalExtent, normal_extent
from ..cect.influence import combined_constants
from ..cect.influence_conformal import INFLUENCE_OPTIONS
from ..errors import ConvergenceError, InputError
from ..fem.groove_rolling import FEM_DEFAULTS, FEM_SCHEMA
from ..geometry.groove import GrooveRolling
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, material_keys, model_keys, tolerance_key
from ._finite_body_keys import FINITE_BODY_COARSE, FINITE_BODY_DEFAULTS, FINITE_BODY_KEYS

MODEL_NAMES = ("cect", "planar", "fem", "fem_finite_body")
DESIGN_QUANTITIES = ("creepage_x", "friction_power", "p_max")     # the conformal contact's rolling loss first
QUANTITIES = ("approach", "p_max", "contact_half_length_s", "angle_span", "adhesion_fraction", "creepage_x",
              "spin_moment", "friction_power")
MAX_HALF_ANGLE = np.radians(50.0)     # solved contact half-angle on the groove beyond which it is not applicable
MAX_A_OVER_R = 0.1                    # solved half-length along x / body rolling radius (half-space along x)
MAX_B_OVER_CROWN = 0.8                # solved axial half-width / axial half extent of the crown arc
CROWN_END = "the check grid reaches past the end of the crown, where no ray from the groove meets the body"

SCHEMA: dict[str, Key] = {
    "geometry.rolling_radius": Key("float", "m", "nominal rolling radius r of the crowned body", lo=0.0),
    "geometry.crown_radius": Key("float", "m", "lateral profile (crown) radius R of the crowned body", lo=0.0),
    "geometry.groove_radius": Key("float", "m", "groove profile radius r_g of the ring (> crown radius)", lo=0.0),
    "geometry.ring_curvature": Key("float", "1/m", "longitudinal curvature k of the grooved ring at the contact: > 0 "
                                   "convex (like an inner raceway), < 0 concave (outer raceway), 0 straight rail"),
    "load.normal": Key("float", "N", "normal load along the nominal contact normal", lo=0.0),
    "friction.mu": Key("float", "-", "Coulomb friction coefficient", lo=0.0, hi=10.0, hi_closed=True),
    **material_keys("body1"),
    **material_keys("body2"),
    "kinematics.speed": Key("float", "m/s", "rolling speed V (the ring's surface speed at the nominal point)",
                            lo=0.0),
    **model_keys(MODEL_NAMES),
    "numerics.conformal_cells_x": Key("int", "-", "elements along the rolling direction (both models)", lo=9,
                                      hi=401, lo_closed=True, hi_closed=True),
    "numerics.conformal_cells_s": Key("int", "-", "elements across, along the groove (both models)", lo=9, hi=801,
                                      lo_closed=True, hi_closed=True),
    "numerics.conformal_domain_x": Key("float", "a_H", "grid half-length along x / Hertz semi-axis (enlarged "
                                       "automatically when the contact reaches it)", lo=1.02, hi=3.0,
                                       hi_closed=True),
    "numerics.conformal_domain_s": Key("float", "b_H", "grid half-width along s / Hertz semi-axis (enlarged "
                                       "automatically)", lo=1.02, hi=3.0, hi_closed=True),
    "numerics.conformal_influence": Key("str", "-", "cect influence coefficients: halfspace (developed half-space), "
                                        "blanco or rotated_response (angle-corrected, CONTACT variants 1 and 3)",
                                        choices=INFLUENCE_OPTIONS),
    "numerics.conformal_solver": Key("str", "-", "tangential solver: dense, fft or auto (fft above 300 contact "
                                     "elements)", choices=("auto", "dense", "fft")),
    "numerics.conformal_tol": Key("float", "-", "Coulomb residual / max(mu p)", lo=0.0, hi=1e-4, hi_closed=True),
    "numerics.variable_dq": Key("bool", "-", "cect: variable rolling step kappa(s) = V(s)/V_ref (seed 000 eq 21)"),
    "tolerances.*.*": tolerance_key("relative tolerance (or contrast band) of model.quantity against the "
                                    "references"),
    **FEM_SCHEMA,
    "numerics.fb_correction_levels": Key("int", "-", "fem_finite_body: correction levels (FE mesh and correction "
                                         "grid refined together, as fem's levels)", lo=1, hi=4, lo_closed=True,
                                         hi_closed=True),
    **FINITE_BODY_KEYS,
}
DEFAULTS: dict[str, Any] = {
    "materials.body1.rigid": False,
    "materials.body2.rigid": False,
    "models.run": ["cect", "planar"],
    "models.references": ["cect"],
    "models.contrast": ["planar"],
    "numerics.conformal_cells_x": 41,
    "numerics.conformal_cells_s": 81,
    "numerics.conformal_domain_x": 1.35,
    "numerics.conformal_domain_s": 1.25,
    "numerics.conformal_influence": "halfspace",
    "numerics.conformal_solver": "auto",
    "numerics.conformal_tol": 1e-9,
    "numerics.variable_dq": True,
    **FEM_DEFAULTS,
    "numerics.fb_correction_levels": 3,
    **FINITE_BODY_DEFAULTS,
}
REQUIRED = ("geometry.rolling_radius", "geometry.crown_radius", "geometry.groove_radius",
            "geometry.ring_curvature", "load.normal", "friction.mu", "kinematics.speed")
# fem: a stored reference, keyed on every input it reads (the cect/planar numerics do not enter it)
DEPENDS: dict[str, dict] = {"fem": {"params": ("geometry.", "load.", "friction.", "materials.", "kinematics.",
                                               "numerics.fem_"), "reference": True,
                                    "coarse": {"numerics.fem_levels": 1}},
                            # fem_finite_body: its coarse re-solve is the coarsest correction on the scene's grid
                            "fem_finite_body": {"params": ("geometry.", "load.", "friction.", "materials.",
                                                           "kinematics.", "numerics."), "reference": True,
                                                "coarse": FINITE_BODY_COARSE}}


def geometry(params: dict[str, Any]) -> GrooveRolling:
    return GrooveRolling(params["geometry.rolling_radius"], params["geometry.crown_radius"],
                         params["geometry.groove_radius"], params["geometry.ring_curvature"])


def _constants(params: dict[str, Any]):
    return combined_constants(elastic(params, "body1"), elastic(params, "body2"))


def _extent(params: dict[str, Any], load: float) -> NormalExtent | None:
    """The frictionless conformal normal contact of ``load`` on the coarse check grid over the scene's domain
    (:func:`femcheck.cect.groove_extent.normal_extent`); None when its grid reaches past the end of the crown
    (no ray meets the body) or the contact outgrows every enlargement."""
    spec = GridSpec(CHECK_GRID.cells_x, CHECK_GRID.cells_s, params["numerics.conformal_domain_x"],
                    params["numerics.conformal_domain_s"])
    try:
        return normal_extent(geometry(params), load, _constants(params), spec)
    except (ConvergenceError, GridTooSmall):
        return None


def _ratios(params: dict[str, Any], e: NormalExtent | None) -> dict[str, float]:
    """Each applicability measure of the solved contact over its limit (> 1: refused)."""
    if e is None:
        return {CROWN_END: np.inf}
    g = geometry(params)
    return {f"solved contact half-angle on the groove {np.degrees(e.half_angle):.3g} deg / "
            f"{np.degrees(MAX_HALF_ANGLE):g} deg": e.half_angle / MAX_HALF_ANGLE,
            f"solved a / rolling radius / {MAX_A_OVER_R}": e.half_length_x / g.rolling_radius / MAX_A_OVER_R,
            f"solved axial half-width / crown half extent / {MAX_B_OVER_CROWN}":
                e.axial_half_width / g.crown_half_extent / MAX_B_OVER_CROWN}


def _largest_load(params: dict[str, Any], load: float) -> float:
    """The largest load (N) whose solved contact meets every limit (root of max ratio - 1 in log N by Brent's
    method, to 1e-7; every ratio grows with the load). ``load`` is refused."""
    # a root find, not Hertz's N^(1/3) scaling: the conformal patch grows more slowly (N^0.28 near 45 deg), and a
    # grid past the crown's end has no ratio (capped at 10 for the bracket)
    def excess(log_n: float) -> float:
        return min(max(_ratios(params, _extent(params, float(np.exp(log_n)))).values()), 10.0) - 1.0

    hi = np.log(load)
    lo = hi - np.log(8.0)
    for _ in range(20):
        if excess(lo) <= 0:
            return float(np.exp(brentq(excess, lo, hi, xtol=1e-7, rtol=1e-12)))
        hi, lo = lo, lo - np.log(8.0)
    return 0.0


def validate(params: dict[str, Any]) -> None:
    """Groove wider than the crown; a concave ring larger than the body; mu > 0; a load whose solved contact
    stays within the model: half-angle on the groove <= 50 deg, a/r <= 0.1, axial half-width <= 0.8 of the crown's
    half extent, all measured on the frictionless conformal normal contact (:mod:`femcheck.cect.groove_extent`,
    21 x 41 cells, ~0.02 s), not on Hertz's estimate, which overstates the half-angle of deep grooves (14 % at a
    solved 45 deg, groove/crown 1.002) and understates a (up to 20 %). A refused load names the largest one
    allowed (Brent's method on the same solve, ~0.3 s)."""
    check_body_pair(params, ("body1", "body2"))
    R, rg, r = params["geometry.crown_radius"], params["geometry.groove_radius"], params["geometry.rolling_radius"]
    if rg <= R:
        raise InputError("geometry.groove_radius", f"{rg:g} m is not allowed; allowed: ({R:g}, inf) m (larger than "
                         "geometry.crown_radius: a groove conforming to the crown)")
    k = params["geometry.ring_curvature"]
    if k <= -1.0 / r:
        raise InputError("geometry.ring_curvature", f"{k:g} 1/m is not allowed; allowed: ({-1.0 / r:.6g}, inf) 1/m "
                         "(a concave ring must be larger than the body it carries)")
    if params["friction.mu"] <= 0:
        raise InputError("friction.mu", f"{params['friction.mu']:g} is not allowed; allowed: (0, 10]")
    N = params["load.normal"]
    ratios = _ratios(params, _extent(params, N))
    worst = max(ratios, key=ratios.get)
    if ratios[worst] > 1.0:
        why = worst if worst == CROWN_END else f"{worst} = {ratios[worst]:.3g}"
        raise InputError("load.normal", f"{N:g} N cannot be carried by this contact model ({why}); allowed: "
                         f"(0, {_largest_load(params, N):.6g}] N for this geometry")


def _spec(p: dict[str, Any]) -> GridSpec:
    return GridSpec(p["numerics.conformal_cells_x"], p["numerics.conformal_cells_s"], p["numerics.conformal_domain_x"],
                    p["numerics.conformal_domain_s"])


def _quantities(q: dict[str, float]) -> dict[str, float]:
    out = {k: float(q[k]) for k in ("approach", "p_max", "angle_span", "adhesion_fraction", "creepage_x",
                                    "spin_moment", "friction_power", "total_force")}
    out["contact_half_length_s"] = float(q["half_length_s"])
    return out


def _weights(p: dict[str, Any]) -> tuple[float, float]:
    """E8: the rolling speeds of the two bodies weighted by their compliances (1 - nu^2)/E (0 when rigid)."""
    return tuple(0.0 if p[f"materials.{b}.rigid"] else (1.0 - p[f"materials.{b}.nu"] ** 2) / p[f"materials.{b}.E"]
                 for b in ("body1", "body2"))


def cect(scene: Scene, progress=None) -> ModelResult:
    """Free rolling by the conformal exact theory (reference)."""
    p = scene.params
    if progress:
        progress("cect: conformal exact theory, free rolling")
    sol = solve_groove_cect(geometry(p), p["load.normal"], p["friction.mu"], _constants(p), p["kinematics.speed"],
                            _spec(p), p["numerics.conformal_influence"], p["numerics.variable_dq"],
                            p["numerics.conformal_solver"], p["numerics.conformal_tol"], _weights(p))
    r, dg = sol.result, sol.grid
    stats = {**sol.stats, "n_elements": r.grid.nx * r.grid.ny,
             "solver": "conformal CECT: semi-smooth Newton ("
                       + ("matrix-free FGMRES" if sol.stats["tangential_solver"] == "fft" else "dense LU")
                       + ") + Polonsky-Keer CG, secant on the body speed"}
    fields = {"map_x": dg.x, "map_y": dg.s, "pressure_map": r.pressure, "adhesion_map": r.adhesion.astype(float),
              "px_map": r.px, "py_map": r.ps, "slip_x_map": r.slip_x, "slip_y_map": r.slip_s,
              "power_density_map": r.power_density, "s": dg.s, "lateral_normal": r.lateral_normal,
              "lateral_fx": r.lateral_fx, "lateral_fs": r.lateral_fs, "kappa": r.kappa}
    return ModelResult("cect", quantities=_quantities(sol.quantities), stats=stats, fields=fields)


def planar(scene: Scene, progress=None) -> ModelResult:
    """Free rolling by the planar exact theory with the Hertz quadratic gap (contrast)."""
    p = scene.params
    if progress:
        progress("planar: planar exact theory, free rolling")
    sol = solve_groove_planar(geometry(p), p["load.normal"], p["friction.mu"], _constants(p), p["kinematics.speed"],
                              _spec(p), p["numerics.conformal_solver"], p["numerics.conformal_tol"])
    r = sol.result
    g = r.grid
    fields = {"map_x": g.x, "map_y": g.y, "pressure_map": r.pressure, "adhesion_map": r.adhesion.astype(float),
              "s": g.y, "lateral_normal": r.pressure.sum(axis=0) * g.dx, "lateral_fx": r.px.sum(axis=0) * g.dx}
    stats = {**sol.stats, "n_elements": g.nx * g.ny,
             "solver": "planar exact theory: semi-smooth Newton + Polonsky-Keer CG, secant on the creepage"}
    return ModelResult("planar", quantities=_quantities(sol.quantities), stats=stats, fields=fields)


def fem(scene: Scene, progress=None) -> ModelResult:
    """Free rolling by the frictional FE reference (levels with certificates; :mod:`femcheck.fem.groove_rolling`)."""
    from ..fem import groove_rolling as fe

    _elastic_only(scene.params, "fem")
    return fe.model(scene, progress)


def _elastic_only(p: dict[str, Any], model: str) -> None:
    for b in ("body1", "body2"):
        if p[f"materials.{b}.rigid"]:
            raise InputError(f"materials.{b}.rigid", f"true is not allowed with the {model} model (it meshes two "
                                                    "elastic bodies); allowed: false")


def fem_finite_body(scene: Scene, progress=None) -> ModelResult:
    """Free rolling with finite-body influence coefficients (half-space + FE correction) on fine contact grids,
    certified in two parts: the correction's FE mesh and grid, and the contact grid with the lattice-phase mean
    (:mod:`._groove_fb`)."""
    from . import _groove_fb

    p = scene.params
    _elastic_only(p, "fem_finite_body")
    if p["numerics.conformal_influence"] != "halfspace":
        raise InputError("numerics.conformal_influence", f"{p['numerics.conformal_influence']} is not allowed with "
                         "fem_finite_body (its correction is taken against the developed half-space); allowed: "
                         "halfspace")
    args = {"variable_dq": p["numerics.variable_dq"], "solver": p["numerics.conformal_solver"],
            "tol": p["numerics.conformal_tol"], "compliance_weights": _weights(p)}
    return _groove_fb.finite_body({**FEM_DEFAULTS, **p}, geometry(p), _constants(p), _spec(p), args, progress)


MODELS: dict[str, Callable[..., ModelResult]] = {"cect": cect, "planar": planar, "fem": fem,
                                                 "fem_finite_body": fem_finite_body}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    p = scene.params
    rx, ry = geometry(p).hertz_radii
    return elliptic_contact(p["load.normal"], rx, ry, _constants(p).contact_modulus).semi_axis_x


def stress_cases(scene: Scene) -> list:
    """Conformity from 1.002 to 1.05 (groove / crown radius), straight rail and concave ring, friction 0.01-1,
    loads down to 1e-3 of the scene's."""
    from ..result import StressCase

    p = scene.params
    R = p["geometry.crown_radius"]
    cases = [StressCase(f"groove/crown={q:g}", {"geometry.groove_radius": R * q}) for q in (1.002, 1.005, 1.01, 1.05)]
    cases.append(StressCase("straight rail", {"geometry.ring_curvature": 0.0}))
    cases.append(StressCase("concave ring", {"geometry.ring_curvature": -0.8 / p["geometry.rolling_radius"]}))
    cases += [StressCase(f"mu={mu:g}", {"friction.mu": mu}) for mu in (0.01, 1.0)]
    cases += [StressCase(f"load x {f:g}", {"load.normal": p["load.normal"] * f}) for f in (1e-3, 0.1)]
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """Grid refinement of the conformal solver (cells along x, across: 1:2)."""
    return {"cect": [{"numerics.conformal_cells_x": n, "numerics.conformal_cells_s": 2 * n - 1}
                     for n in (21, 31, 41, 61, 81)]}
