"""3D point / elliptical contact of two bodies with principal relative radii Rx, Ry (hertz-point, hertz-elliptic).

x is the rolling direction. Models: ``analytic`` (exact elliptic Hertz), ``bem`` (half-space boundary
integral: Love rectangles, DC-FFT or MLMI, preconditioned Polonsky-Keer CG, coarse-to-fine warm start), ``fem``
(3D FE reference: rigid indenter on a quarter block of the equivalent material, P1 tetrahedra, active set with
AMG-CG, Richardson over mesh levels; :mod:`femcheck.fem.point_contact`), ``fem_p2`` (the same with quadratic
tetrahedra and a mortar contact pressure; :mod:`femcheck.fem.point_contact_p2`).
"""
from __future__ import annotations

from importlib import import_module
from typing import Any, Callable

import numpy as np

from ..analytic import hertz
from ..analytic import stress as stress_closed_form
from ..bem import halfspace
from ..bem import stress as bem_stress
from ..errors import ConvergenceError, InputError
from ..fem import point_contact as fem_point
from ..materials import effective_modulus
from ..qoi import semi_axes
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, fem_mesh_keys, material_keys, model_keys, tolerance_key
from . import _life_output as life_output

MODEL_NAMES = ("analytic", "bem", "fem", "fem_p2", "calculix")
# a sphere radius or the two radii of curvature: the one given last (an override) wins
ALTERNATIVES = (("geometry.radius", ("geometry.Rx", "geometry.Ry")),)
MAX_A_OVER_R = 0.1

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "sphere radius R (sets Rx = Ry = R)", lo=0.0),
    "geometry.Rx": Key("float", "m", "relative radius of curvature in the rolling direction x", lo=0.0),
    "geometry.Ry": Key("float", "m", "relative radius of curvature across, y", lo=0.0),
    "geometry.profile": Key("str", "-", "gap: Hertz paraboloid, or the exact sphere (radius only)",
                            choices=("paraboloid", "sphere")),
    "load.normal": Key("float", "N", "normal load", lo=0.0),
    **material_keys("body1"),
    **material_keys("body2"),
    "outputs.subsurface_stress": Key("bool", "-", "compute sub-surface stresses (BEM field; analytic: sphere "
                                     "axis closed form)"),
    **model_keys(MODEL_NAMES),
    "numerics.bem_cells": Key("int", "-", "BEM cells per side (odd: a cell sits on the centre)", lo=9,
                              hi=4097, lo_closed=True, hi_closed=True),
    "numerics.bem_domain": Key("float", "a_H", "BEM half-side / Hertz semi-axis (each direction)", lo=1.05,
                               hi=10.0, hi_closed=True),
    "numerics.bem_tol": Key("float", "-", "BEM relative gap residual", lo=0.0, hi=1e-3, hi_closed=True),
    "numerics.bem_convolution": Key("str", "-", "influence-coefficient sum: exact DC-FFT or multilevel "
                                    "multi-integration (mlmi; needs cells with dy/dx <= 2)",
                                    choices=halfspace.CONVOLUTIONS),
    "numerics.bem_warm_levels": Key("int", "-", "coarser grids solved first as a warm start", lo=0, hi=8,
                                    lo_closed=True, hi_closed=True),
    **fem_mesh_keys(5, 0.005, 0.5, 20.0, "FEM contact candidate zone / Hertz semi-axes", 3.0, "a_H",
                    "FEM block side and depth / long Hertz semi-axis", 5.0, 200.0),
    "numerics.fem_method": Key("str", "-", "FEM contact algorithm", choices=("active_set", "penalty")),
    "numerics.fem_solver": Key("str", "-", "FEM linear solver (auto: LU up to 3000 DOFs, AMG-CG above)",
                               choices=("auto", "direct", "amg")),
    "numerics.fem_penalty": Key("float", "-", "penalty stiffness / (E' tributary area / element size)", lo=1.0,
                                hi=1e8, lo_closed=True, hi_closed=True),
    "numerics.fem_finite_size_check": Key("bool", "-", "solve the coarsest FEM level again on a block twice as "
                                          "large and report the change"),
    "numerics.p2_levels": Key("int", "-", "FEM P2 mesh levels", lo=1, hi=5, lo_closed=True, hi_closed=True),
    "numerics.p2_ratio": Key("float", "-", "FEM P2 refinement ratio between levels", lo=1.2, hi=2.0,
                             lo_closed=True, hi_closed=True),
    "numerics.p2_h_contact": Key("float", "a_H", "FEM P2 element size in the contact at the coarsest level / "
                                 "short Hertz semi-axis", lo=0.02, hi=0.5, lo_closed=True, hi_closed=True),
    "numerics.p2_zone": Key("float", "a_H", "FEM P2 structured zone (cubes of the contact element size) / Hertz "
                            "semi-axes, along x and y", lo=1.3, hi=3.0, lo_closed=True, hi_closed=True),
    "numerics.p2_zone_depth": Key("float", "a_H", "FEM P2 structured zone depth / short Hertz semi-axis", lo=0.1,
                                  hi=3.0, lo_closed=True, hi_closed=True),
    "numerics.stress_depths": Key("int", "-", "depth levels of the stress field", lo=4, hi=400,
                                  lo_closed=True, hi_closed=True),
    "numerics.stress_depth_max": Key("float", "a_H", "deepest level / Hertz semi-axis x", lo=0.0, hi=20.0,
                                     hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
    **life_output.keys(),
}
DEFAULTS: dict[str, Any] = {
    **life_output.defaults(10.0 / 9.0),
    "geometry.profile": "paraboloid",
    "materials.body1.rigid": False,
    "materials.body2.rigid": False,
    "models.run": ["analytic", "bem"],
    "models.references": ["analytic"],
    "numerics.bem_cells": 65,
    "numerics.bem_domain": 1.25,
    "numerics.bem_tol": 1e-10,
    "numerics.bem_convolution": "dcfft",
    "numerics.bem_warm_levels": 0,
    "outputs.subsurface_stress": False,
    "numerics.fem_levels": 3,
    "numerics.fem_ratio": 2.0,
    "numerics.fem_h_contact": 0.125,
    "numerics.fem_grading": 0.25,
    "numerics.fem_h_max": 2.0,
    "numerics.fem_contact_zone": 1.3,
    "numerics.fem_block": 20.0,
    "numerics.fem_finite_size_check": True,
    "numerics.fem_method": "active_set",
    "numerics.fem_solver": "auto",
    "numerics.fem_penalty": 1e3,
    "numerics.p2_levels": 3,
    "numerics.p2_ratio": 1.5,
    "numerics.p2_h_contact": 0.125,
    "numerics.p2_zone": 1.5,
    "numerics.p2_zone_depth": 0.5,
    "numerics.stress_depths": 40,
    "numerics.stress_depth_max": 1.5,
}
REQUIRED = ("load.normal",)
DEPENDS: dict[str, dict] = {
    "fem": {"params": ("geometry.", "load.", "materials.", "numerics.fem_"),
            "reference": True,
            # the coarsest level alone (femcheck.reference_check re-solves it against the stored reference)
            "coarse": {"numerics.fem_levels": 1, "numerics.fem_finite_size_check": False}},
    "fem_p2": {"params": ("geometry.", "load.", "materials.", "numerics.fem_", "numerics.p2_"),
               "reference": True,
               "coarse": {"numerics.p2_levels": 1, "numerics.fem_finite_size_check": False}},
}


def radii(params: dict[str, Any]) -> tuple[float, float]:
    if "geometry.radius" in params:
        return params["geometry.radius"], params["geometry.radius"]
    return params["geometry.Rx"], params["geometry.Ry"]


def _hertz(params: dict[str, Any]) -> hertz.EllipticContact:
    rx, ry = radii(params)
    e_star = effective_modulus(elastic(params, "body1"), elastic(params, "body2"))
    return hertz.elliptic_contact(params["load.normal"], rx, ry, e_star)


def validate(params: dict[str, Any]) -> None:
    """Exactly one of radius or (Rx, Ry); elastic bodies need E and nu, one must be elastic; small a/R."""
    has_r, has_xy = "geometry.radius" in params, ("geometry.Rx" in params, "geometry.Ry" in params)
    if has_r and any(has_xy):
        raise InputError("geometry.radius", "give either geometry.radius or geometry.Rx and geometry.Ry")
    if not has_r and not all(has_xy):
        missing = "geometry.Rx" if not has_xy[0] else "geometry.Ry"
        raise InputError(missing, "required (or give geometry.radius for a sphere)")
    if params["geometry.profile"] == "sphere" and not has_r:
        raise InputError("geometry.profile", "'sphere' needs geometry.radius; allowed for Rx, Ry: paraboloid")
    check_body_pair(params, ("body1", "body2"))
    life_output.check_body(params, "body2")
    h = _hertz(params)
    rx, ry = radii(params)
    aspect = h.semi_axis_y / h.semi_axis_x     # the BEM cell aspect ratio: the grid follows the ellipse
    if params["numerics.bem_convolution"] == "mlmi" and not 0.5 <= aspect <= 2.0:
        raise InputError("numerics.bem_convolution", f"mlmi needs BEM cells with dy/dx in [0.5, 2]; this contact "
                         f"gives {aspect:.3g}; allowed here: dcfft")
    ratio = max(h.semi_axis_x / rx, h.semi_axis_y / ry)
    if ratio > MAX_A_OVER_R:
        w_max = params["load.normal"] * (MAX_A_OVER_R / ratio) ** 3       # a ~ W^(1/3)
        raise InputError("load.normal", f"{params['load.normal']:g} N gives Hertz semi-axes up to a/R = {ratio:.3g} "
                         f"> {MAX_A_OVER_R} (half-space and small-strain assumptions fail); allowed (0, {w_max:.4g}] N "
                         "for these radii and materials")


def gap_function(params: dict[str, Any]) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    rx, ry = radii(params)
    if params["geometry.profile"] == "sphere":
        return lambda X, Y: rx - np.sqrt(np.clip(rx * rx - X * X - Y * Y, 0.0, None))
    return lambda X, Y: X * X / (2.0 * rx) + Y * Y / (2.0 * ry)


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Exact elliptic Hertz (Johnson 1985 §4.2; sphere: eq. 4.22)."""
    h = _hertz(scene.params)
    x = np.linspace(-1.5 * h.semi_axis_x, 1.5 * h.semi_axis_x, 601)
    q = {"p_max": h.p_max, "semi_axis_x": h.semi_axis_x, "semi_axis_y": h.semi_axis_y,
         "contact_area": h.contact_area, "approach": h.approach, "total_force": h.load}
    stats = {"E_star": h.modulus, "ellipticity": h.semi_axis_y / h.semi_axis_x}
    rx, ry = radii(scene.params)
    if scene["outputs.subsurface_stress"] and rx == ry:
        # closed form on the axis of a sphere contact (Johnson eq 3.45), in body 2 (the flat)
        q.update(stress_closed_form.hertz_sphere_maxima(h.semi_axis_x, h.p_max, scene["materials.body2.nu"]))
        stats["stress_body"] = "body2"
    if scene["outputs.life"] and rx == ry:
        # smooth contact: the history's maximum is the field's, on the axis (Johnson eq 3.45)
        q["stress_history_max"] = stress_closed_form.hertz_sphere_maxima(
            h.semi_axis_x, h.p_max, scene["materials.body2.nu"])["von_mises_max"]
    return ModelResult("analytic", quantities=q, stats=stats, fields={"x": x, "pressure": h.pressure(x, 0 * x)})


def grid_semi_axes(g: halfspace.Grid, pressure: np.ndarray) -> tuple[dict[str, float], dict[str, dict]]:
    """Semi-axes (m) of a contact centred on the grid: :func:`femcheck.qoi.semi_axes` (power-law edges with the
    exponent fitted, in strips along both axes: no Hertzian shape assumed); also each edge's exponent and misfit."""
    X, Y = g.mesh()
    ax, ay, fits = semi_axes(X, Y, pressure)
    return ({"semi_axis_x": ax, "semi_axis_y": ay},
            {k: {"exponent": e.exponent, "misfit": e.misfit} for k, e in fits.items()})


def bem(scene: Scene, progress=None) -> ModelResult:
    """Half-space BEM on an n x n grid over +/- bem_domain Hertz semi-axes (dy/dx follows the ellipse)."""
    h = _hertz(scene.params)
    n, dom = scene["numerics.bem_cells"], scene["numerics.bem_domain"]
    g = halfspace.grid(dom * h.semi_axis_x, dom * h.semi_axis_y, n, n)
    sol = halfspace.solve(g, gap_function(scene.params), h.modulus, scene["load.normal"], tol=scene["numerics.bem_tol"],
                          warm_levels=scene["numerics.bem_warm_levels"],
                          convolution=scene["numerics.bem_convolution"])
    r = sol.result
    c = r.contact
    if c[0, :].any() or c[-1, :].any() or c[:, 0].any() or c[:, -1].any():
        raise ConvergenceError("BEM half-space contact", r.iterations, r.residual, scene["numerics.bem_tol"],
                               "contact reaches the edge of the BEM domain; raise numerics.bem_domain")
    semi, fits = grid_semi_axes(g, r.pressure)
    q = {"p_max": float(r.pressure.max()), **semi,
         "contact_area": float(np.pi * semi["semi_axis_x"] * semi["semi_axis_y"]), "approach": r.approach,
         "total_force": r.load}
    stats = {**sol.stats, "residual": r.residual, "nx": g.nx, "ny": g.ny, "dx": g.dx, "dy": g.dy,
             "a_over_dx": h.semi_axis_x / g.dx, "contact_cells": int(c.sum()), "edges": fits,
             "solver": "polonsky_keer",
             "convolution": scene["numerics.bem_convolution"], "preconditioner": "circulant"}
    j = g.ny // 2
    fields = {"x": g.x, "pressure": r.pressure[:, j], "pressure_map": r.pressure, "map_x": g.x, "map_y": g.y}
    if scene["outputs.subsurface_stress"]:
        if scene["materials.body2.rigid"]:
            raise InputError("outputs.subsurface_stress", "stresses are computed in body2, which is rigid")
        depths = bem_stress.graded_depths(scene["numerics.stress_depth_max"] * h.semi_axis_x,
                                          scene["numerics.stress_depths"])
        f = bem_stress.subsurface_stresses(r.pressure, g, depths, scene["materials.body2.nu"])
        vm, tr = f.von_mises(), f.tresca()
        m_vm, m_tr = bem_stress.maximum(vm, depths, g), bem_stress.maximum(tr, depths, g)
        m_xz = bem_stress.maximum(np.abs(f.components["tau_xz"]), depths, g)
        q.update({"von_mises_max": m_vm["value"], "von_mises_max_depth": m_vm["depth"],
                  "tau_max": m_tr["value"], "tau_max_depth": m_tr["depth"], "tau_xz_max": m_xz["value"]})
        stats["stress"] = {"depths": int(depths.size), "depth_max": float(depths[-1]), "body": "body2",
                           "von_mises_max_at": m_vm, "tau_xz_max_at": m_xz}
        fields.update({"stress_x": g.x, "stress_z": depths, "von_mises": vm[:, :, j].copy(),
                       "tau_xz": f.components["tau_xz"][:, :, j].copy()})
    if scene["outputs.life"]:
        out = life_output.point_life(scene, g, r.pressure, h.semi_axis_x, h.semi_axis_y, h.p_max,
                                     scene["materials.body2.nu"])
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
    return ModelResult("bem", quantities=q, stats=stats, fields=fields)


def fem(scene: Scene, progress=None) -> ModelResult:
    """3D FE reference, :func:`femcheck.fem.point_contact.model` (kept there whole, so that the stored
    references depend on the FE code only)."""
    return fem_point.model(scene.params, progress)


def _by_name(module: str, on_params: bool, doc: str) -> Callable[..., ModelResult]:
    """A model kept in another module and imported only when it runs. Referenced by module name so that the
    stored references of this kind's other models are not keyed on its code (their keys cover this module and
    what it imports); its own key is (:func:`femcheck.runner.model_modules` takes the function's module)."""
    def run(scene: Scene, progress=None) -> ModelResult:
        m = import_module(module)
        return m.model(scene.params if on_params else scene, progress)

    run.__module__, run.__doc__ = module, doc
    return run


fem_p2 = _by_name("femcheck.fem.point_contact_p2", True, "3D FE reference with quadratic tetrahedra and a mortar "
                  "pressure (:mod:`femcheck.fem.point_contact_p2`).")
calculix = _by_name("femcheck.export.calculix_model", False, "CalculiX (``ccx``) on the scene's exported deck at "
                    "each mesh level, an independent FE (:mod:`femcheck.export.calculix_model`); skipped where ccx "
                    "is not installed. Selected with --models.")


MODELS: dict[str, Callable[..., ModelResult]] = {"analytic": analytic, "bem": bem, "fem": fem, "fem_p2": fem_p2,
                                                 "calculix": calculix}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return _hertz(scene.params).semi_axis_x


def stress_cases(scene: Scene) -> list:
    """Ellipticity up to Ry/Rx = 500, Poisson's ratio to 0.4999, load over six decades, rigid bodies."""
    from ..result import StressCase

    rx, ry = radii(scene.params)
    base = {k: v for k, v in scene.params.items() if k.startswith("geometry.") and k != "geometry.profile"}
    drop = {k: None for k in base}
    cases = [StressCase(f"nu={nu:g}", {"materials.body1.nu": nu, "materials.body2.nu": nu})
             for nu in (0.0, 0.3, 0.49, 0.4999)]
    for ratio in (1.0, 10.0, 100.0, 500.0):
        cases.append(StressCase(f"Ry/Rx={ratio:g}", {**drop, "geometry.Rx": rx, "geometry.Ry": rx * ratio,
                                                     "geometry.profile": "paraboloid"}))
    w_max = max_load(scene.params)
    for k in range(6, -1, -1):
        cases.append(StressCase(f"load={w_max * 10.0**-k:.3g} N", {"load.normal": w_max * 10.0**-k}))
    cases.append(StressCase("rigid body1", {"materials.body1.rigid": True}))
    return cases


def max_load(params: dict[str, Any]) -> float:
    h = _hertz(params)
    rx, ry = radii(params)
    ratio = max(h.semi_axis_x / rx, h.semi_axis_y / ry)
    return params["load.normal"] * (MAX_A_OVER_R / ratio) ** 3


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    dcfft = [{"numerics.bem_cells": n} for n in (17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513)]
    mlmi = [{"numerics.bem_cells": n, "numerics.bem_convolution": "mlmi"} for n in (17, 33, 65, 129, 257)]
    h = _hertz(scene.params)
    if 0.5 <= h.semi_axis_y / h.semi_axis_x <= 2.0:
        return {"bem": dcfft, "bem:mlmi": mlmi}
    return {"bem": dcfft}
