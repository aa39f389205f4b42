"""Finite roller on a raceway (roller-finite, roller-crowned): flat-ended or crowned, aligned or tilted.

x = rolling direction, y = roller axis. Models: ``analytic`` (infinite-line Hertz with W' = W/L, and seed 001
eq 7 for the approach of a finite line), ``bem`` (3D half-space BEM; cells beyond the roller ends excluded).
Quantities: ``p_max`` (global maximum; at a sharp roller edge the pressure is singular, so this value depends
on the grid), ``p_centre`` (at x = y = 0), ``half_width`` (at the roller centre), ``edge_peak_y`` (distance
from the roller centre of the largest pressure on the centre line x = 0), ``approach``, ``total_force``.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .. import geometry
from ..analytic import hertz
from ..bem import finite_line as finite_line_method
from ..bem import halfspace
from ..errors import ConvergenceError, InputError
from ..fem import roller_contact as fem_roller
from ..materials import effective_modulus
from ..qoi import edge
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, fem_mesh_keys, material_keys, model_keys, tolerance_key
from . import _life_output as life_output

MODEL_NAMES = ("analytic", "bem", "finite_line", "fem")

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "roller radius", lo=0.0),
    "geometry.length": Key("float", "m", "roller effective length L", lo=0.0),
    "geometry.race_radius": Key("float", "m", "raceway radius (+ convex inner ring, - concave outer; "
                                "omit for a flat)"),
    "geometry.crown": Key("str", "-", "roller profile", choices=("none", "circular", "log")),
    "geometry.crown_radius": Key("float", "m", "radius of a circular crown", lo=0.0),
    "geometry.flat_length": Key("float", "m", "straight central part of a circular crown", lo=0.0,
                                lo_closed=True),
    "geometry.crown_design_load": Key("float", "N", "design load of a logarithmic crown", lo=0.0),
    "geometry.tilt": Key("float", "rad", "misalignment about the rolling direction", lo=-0.01, hi=0.01,
                         lo_closed=True, hi_closed=True),
    "load.normal": Key("float", "N", "roller load W", lo=0.0),
    **material_keys("roller"),
    **material_keys("race"),
    **model_keys(MODEL_NAMES),
    "numerics.bem_nx": Key("int", "-", "BEM cells across (odd)", lo=9, hi=2049, lo_closed=True,
                           hi_closed=True),
    "numerics.bem_ny": Key("int", "-", "BEM cells along the roller length (odd)", lo=9, hi=4097,
                           lo_closed=True, hi_closed=True),
    "numerics.bem_domain_x": Key("float", "a_H", "BEM half-width / Hertz half-width", lo=1.05, hi=10.0,
                                 hi_closed=True),
    "numerics.bem_margin_y": Key("float", "L", "BEM margin beyond each roller end / L", lo=0.0, hi=0.5,
                                 lo_closed=True, hi_closed=True),
    "numerics.bem_tol": Key("float", "-", "BEM relative gap residual", lo=0.0, hi=1e-3, hi_closed=True),
    "numerics.finite_line_elements": Key("int", "-", "finite-line elements along the roller (even)", lo=4,
                                         hi=1024, lo_closed=True, hi_closed=True),
    **fem_mesh_keys(4, 0.02, 1.0, 500.0, "FEM candidate zone across / Hertz half-width", 5.0, "L",
                    "FEM block beyond the footprint / roller length", 0.5, 20.0),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
    **life_output.keys(),
}
DEFAULTS: dict[str, Any] = {
    **life_output.defaults(9.0 / 8.0, depth_max=life_output.LINE_DEPTH_MAX),
    "geometry.crown": "none",
    "geometry.flat_length": 0.0,
    "geometry.tilt": 0.0,
    "materials.roller.rigid": False,
    "materials.race.rigid": False,
    "models.run": ["analytic", "bem", "finite_line"],
    "models.references": ["bem"],
    "numerics.bem_nx": 33,
    "numerics.bem_ny": 129,
    "numerics.bem_domain_x": 1.6,
    "numerics.bem_margin_y": 0.05,
    "numerics.bem_tol": 1e-10,
    "numerics.finite_line_elements": 64,
    # three levels a/4, a/(4 sqrt 2), a/8: Richardson for the cost of two halvings (a/16 over a 90a-long
    # footprint would not fit the 5-minute, 8-GB budget)
    "numerics.fem_levels": 3,
    "numerics.fem_ratio": 2.0**0.5,
    "numerics.fem_h_contact": 0.25,
    "numerics.fem_grading": 0.25,
    "numerics.fem_h_max": 40.0,
    "numerics.fem_contact_zone": 1.8,      # the footprint widens at sharp roller ends (dog-bone)
    "numerics.fem_block": 2.0,
}
REQUIRED = ("geometry.radius", "geometry.length", "load.normal")
DEPENDS: dict[str, dict] = {
    "fem": {"params": ("geometry.", "load.", "materials.", "numerics.fem_"),
            "reference": True, "coarse": {"numerics.fem_levels": 1}},
}


def modulus(params: dict[str, Any]) -> float:
    return effective_modulus(elastic(params, "roller"), elastic(params, "race"))


def reduced_radius(params: dict[str, Any]) -> float:
    return hertz.reduced_radius(params["geometry.radius"], params.get("geometry.race_radius", np.inf))


def _hertz(params: dict[str, Any]) -> hertz.LineContact:
    return hertz.line_contact(params["load.normal"] / params["geometry.length"], reduced_radius(params),
                              modulus(params))


def validate(params: dict[str, Any]) -> None:
    check_body_pair(params, ("roller", "race"))
    life_output.check_body(params, "race")
    rr = params.get("geometry.race_radius")
    if rr is not None and rr < 0 and -rr <= params["geometry.radius"]:
        raise InputError("geometry.race_radius", f"a concave raceway must be larger than the roller: allowed "
                         f"(-inf, -{params['geometry.radius']:g}) or (0, inf) m")
    if rr == 0:
        raise InputError("geometry.race_radius", "0 is not allowed; allowed: nonzero (m)")
    crown = params["geometry.crown"]
    if crown == "circular" and "geometry.crown_radius" not in params:
        raise InputError("geometry.crown_radius", "required for a circular crown; allowed (0, inf) m")
    if crown == "log" and "geometry.crown_design_load" not in params:
        raise InputError("geometry.crown_design_load", "required for a logarithmic crown; allowed (0, inf) N")
    if params["geometry.flat_length"] >= params["geometry.length"]:
        raise InputError("geometry.flat_length", f"must be shorter than the roller; allowed [0, "
                         f"{params['geometry.length']:g}) m")
    h = _hertz(params)
    if h.half_width / reduced_radius(params) > 0.1:
        raise InputError("load.normal", f"{params['load.normal']:g} N gives a/R = "
                         f"{h.half_width / reduced_radius(params):.3g} > 0.1 (half-space theory fails)")


def gap_function(params: dict[str, Any]) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    return geometry.roller(params["geometry.radius"], params["geometry.length"], params["geometry.crown"],
                           params.get("geometry.crown_radius"), params["geometry.flat_length"],
                           params.get("geometry.crown_design_load"), modulus(params),
                           params.get("geometry.race_radius", np.inf), params["geometry.tilt"])


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Infinite-line Hertz with the mean load per length W/L (seed 001 eqs 1-5), and the centre approach of a
    line of elliptical pressure of length L: delta = a p0 / E* (ln(2L/a) + 1/2).

    Seed 001 eq 7 prints a p0 / (pi E*) (...): integrating its own eq 6 gives
    (2 p0 / (pi E*)) int_-a^a sqrt(1 - x^2/a^2) ln(L/|x|) dx = (a p0 / E*)(ln(2L/a) + 1/2), using
    int_-1^1 sqrt(1 - t^2) ln|t| dt = -(pi/2)(ln 2 + 1/2); the printed 1/pi is a slip (it makes delta 3.1x
    too small against the BEM). For a flat-ended roller the BEM centre pressure is 4.9 % below this Hertz
    value (the end peaks carry load): this model is a contrast, not a reference, for finite rollers.
    """
    h = _hertz(scene.params)
    L = scene["geometry.length"]
    x = np.linspace(-1.5 * h.half_width, 1.5 * h.half_width, 601)
    delta = h.half_width * h.p_max / h.modulus * (np.log(2 * L / h.half_width) + 0.5)
    q = {"p_centre": h.p_max, "half_width": h.half_width, "approach": delta, "total_force": scene["load.normal"]}
    stats: dict[str, Any] = {"E_star": h.modulus, "R": h.radius}
    fields = {"x": x, "pressure": h.pressure(x)}
    if scene["outputs.life"]:      # the infinite line's life per unit length times L (a contrast, like the rest)
        out = life_output.line_life_closed_form(scene, h.half_width, h.p_max, scene["materials.race.nu"], L)
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
    return ModelResult("analytic", quantities=q, stats=stats, fields=fields)


def bem_grid(scene: Scene) -> halfspace.Grid:
    """Cells across x over +/- bem_domain_x a_H; along y ``bem_ny`` cells exactly over the roller length (cell
    edges on the roller ends) plus margin cells beyond each end."""
    h = _hertz(scene.params)
    L, ny = scene["geometry.length"], scene["numerics.bem_ny"]
    dy = L / ny
    margin = int(np.ceil(scene["numerics.bem_margin_y"] * L / dy))
    nx = scene["numerics.bem_nx"]
    return halfspace.Grid(nx, ny + 2 * margin, 2 * scene["numerics.bem_domain_x"] * h.half_width / nx, dy)


def centre_half_width(g: halfspace.Grid, pressure: np.ndarray, length: float) -> float:
    """Half-width (m) at the roller centre: the edges of the cells within L/8 of the centre across
    (:func:`femcheck.qoi.edge`, power law with its exponent fitted, band 0.5, the local y^2 term), averaged over
    both sides -- the estimator of the FE reference (:func:`femcheck.fem.roller_contact.centre_quantities`)."""
    X, Y = g.mesh()
    strip = np.abs(Y) < length / 8.0
    sides = [edge(s * X[strip & (s * X >= 0)], pressure[strip & (s * X >= 0)], band=0.5, min_points=8,
                  transverse=Y[strip & (s * X >= 0)]).position for s in (1.0, -1.0)]
    return float(np.mean(sides))


def bem(scene: Scene, progress=None) -> ModelResult:
    """3D half-space BEM (Love rectangles, DC-FFT, Polonsky-Keer) over the roller footprint."""
    for k in ("numerics.bem_nx", "numerics.bem_ny"):
        if scene[k] % 2 == 0:
            raise InputError(k, f"{scene[k]} is even; allowed: odd counts (a cell on the roller centre)")
    g = bem_grid(scene)
    sol = halfspace.solve(g, gap_function(scene.params), modulus(scene.params), scene["load.normal"],
                          tol=scene["numerics.bem_tol"])
    r = sol.result
    if r.contact[0, :].any() or r.contact[-1, :].any():
        raise ConvergenceError("BEM roller contact", r.iterations, r.residual, scene["numerics.bem_tol"],
                               "contact reaches the edge of the BEM domain across; raise numerics.bem_domain_x")
    ic, jc = g.nx // 2, g.ny // 2
    centre_line = r.pressure[ic, :]
    jp = int(np.argmax(np.where(g.y >= 0, centre_line, -1.0)))
    q = {"p_max": float(r.pressure.max()), "p_centre": float(r.pressure[ic, jc]),
         "half_width": centre_half_width(g, r.pressure, scene["geometry.length"]), "edge_peak_y": float(g.y[jp]),
         "approach": r.approach, "total_force": r.load}
    stats = {**sol.stats, "residual": r.residual, "nx": g.nx, "ny": g.ny, "dx": g.dx, "dy": g.dy,
             "contact_cells": int(r.contact.sum()), "solver": "polonsky_keer", "convolution": "dcfft"}
    fields = {"x": g.x, "pressure": r.pressure[:, jc], "y": g.y, "pressure_axial": centre_line,
              "map_x": g.x, "map_y": g.y, "pressure_map": r.pressure}
    if scene["outputs.life"]:
        hz = _hertz(scene.params)
        out = life_output.roller_life(scene, g, r.pressure, hz.half_width, hz.p_max, scene["materials.race.nu"])
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
    return ModelResult("bem", quantities=q, stats=stats, fields=fields)


def finite_line(scene: Scene, progress=None) -> ModelResult:
    """Seed 001's overlapping-element method (eqs 8-17), locally Hertzian half-widths."""
    n = scene["numerics.finite_line_elements"]
    if n % 2:
        raise InputError("numerics.finite_line_elements", f"{n} is odd; allowed: even counts (a station on "
                         "the roller centre)")
    gap = gap_function(scene.params)
    r = finite_line_method.solve(lambda y: gap(np.zeros_like(y), y), reduced_radius(scene.params),
                                 scene["geometry.length"], modulus(scene.params), scene["load.normal"], n)
    jc = n // 2
    jp = int(np.argmax(np.where(r.y >= 0, r.p_m, -1.0)))
    hz = _hertz(scene.params)
    x = np.linspace(-1.6 * hz.half_width, 1.6 * hz.half_width, 321)
    q = {"p_max": float(r.p_m.max()), "p_centre": float(r.p_m[jc]), "half_width": float(r.a[jc]),
         "edge_peak_y": float(r.y[jp]), "approach": r.approach, "total_force": r.load}
    stats = {"iterations": r.iterations, "residual": r.residual, "n_elements": n,
             "element_length": scene["geometry.length"] / n, "half_width_rule": "a = 2 R p_m / E*"}
    return ModelResult("finite_line", quantities=q, stats=stats,
                       fields={"x": x, "pressure": r.pressure(x, np.zeros_like(x)), "y": r.y,
                               "pressure_axial": r.p_m})


def fem(scene: Scene, progress=None) -> ModelResult:
    """3D FE reference, :func:`femcheck.fem.roller_contact.model`."""
    return fem_roller.model(scene.params, progress)


MODELS: dict[str, Callable[..., ModelResult]] = {"analytic": analytic, "bem": bem, "finite_line": finite_line,
                                                "fem": fem}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return _hertz(scene.params).half_width


def singular_quantities(scene: Scene) -> tuple[str, ...]:
    """Quantities that grow with refinement by nature, left out of the comparisons (femcheck.compare): the
    global ``p_max`` of a roller with sharp ends (no crown), where the footprint has corners and the pressure
    is unbounded, as at the edge of a flat punch; every grid gives its own finite value. ``edge_peak_y`` (the
    peak's position) converges and is compared instead. A logarithmic crown loaded beyond its design load
    reaches the ends too. (A circular crown may, at a high enough load; that is not known before the solve.)"""
    crown = scene["geometry.crown"]
    overloaded = crown == "log" and scene["load.normal"] > scene["geometry.crown_design_load"]
    return ("p_max",) if crown == "none" or overloaded else ()


def stress_cases(scene: Scene) -> list:
    """Load over four decades, Poisson's ratio to 0.4999, misalignment, and each crown type."""
    from ..result import StressCase

    W = scene["load.normal"]
    cases = [StressCase(f"load={W * f:.3g} N", {"load.normal": W * f}) for f in (1e-3, 1e-2, 1e-1, 1.0, 3.0)]
    cases += [StressCase(f"nu={nu:g}", {"materials.roller.nu": nu, "materials.race.nu": nu}) for nu in (0.0, 0.4999)]
    cases += [StressCase(f"tilt={t:g} rad", {"geometry.tilt": t}) for t in (1e-4, 5e-4)]
    cases += [StressCase("circular crown", {"geometry.crown": "circular", "geometry.crown_radius": 1.0}),
              StressCase("log crown", {"geometry.crown": "log", "geometry.crown_design_load": W})]
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    return {"bem": [{"numerics.bem_nx": nx, "numerics.bem_ny": ny}
                    for nx, ny in ((17, 65), (25, 97), (33, 129), (49, 193), (65, 257), (97, 385))]}
