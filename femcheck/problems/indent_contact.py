"""Dry circular Hertz contact with a dent at its centre (indent-dry; seed 004 §3.2).

Indent keys are dimensionless as in the thesis: ``indent.diameter`` Phi (in the Hertz radius a),
``indent.slope`` D/Phi (D in a^2/R), ``indent.decay`` K. Models: ``analytic`` (zone A/B model, seed 004 eq 3.6,
coefficients calibrated on the BEM: ``femcheck calibrate indent-dry``), ``bem`` (half-space BEM, indented minus
smooth solution). Quantities: ``additional_pressure`` dP = max(p_indented - p_smooth) (Pa),
``indent_depth_ratio`` F = D_d/D_i (deformed over initial hole depth), ``p_max``, ``total_force``.
With ``outputs.life``: the life quantities of :mod:`femcheck.problems._life_output` (``bem``: pseudo-transient pass;
``bem_transient``: the indent solved at every position of the pass, :mod:`femcheck.problems._indent_life`).
"""
from __future__ import annotations

import time
from typing import Any, Callable

import numpy as np

from .. import __version__
from ..analytic import hertz, indent
from ..bem import halfspace
from ..errors import ConvergenceError, InputError
from ..geometry.profiles import indented, paraboloid
from ..materials import effective_modulus
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, material_keys, model_keys, tolerance_key
from . import _indent_life as indent_life, _life_output as life_output

MODEL_NAMES = ("analytic", "bem", "bem_transient")
DESIGN_QUANTITIES = ("life_ratio", "additional_pressure", "stress_ratio", "p_max")

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "ball radius R", lo=0.0),
    "load.normal": Key("float", "N", "normal load", lo=0.0),
    "indent.diameter": Key("float", "a", "indent diameter Phi / Hertz radius", lo=0.05, hi=1.0, lo_closed=True,
                           hi_closed=True),
    "indent.slope": Key("float", "-", "indent slope D/Phi (D in a^2/R; 0: smooth)", lo=0.0, hi=2.0,
                        lo_closed=True, hi_closed=True),
    "indent.decay": Key("float", "-", "shoulder decay K (3: high shoulders, 8: flat)", lo=2.0, hi=10.0,
                        lo_closed=True, hi_closed=True),
    **material_keys("body1"),
    **material_keys("body2"),
    **model_keys(MODEL_NAMES),
    "numerics.bem_cells": Key("int", "-", "BEM cells per side (odd)", lo=33, hi=1025, lo_closed=True,
                              hi_closed=True),
    "numerics.bem_domain": Key("float", "a", "BEM half-side / Hertz radius", lo=1.2, hi=5.0, hi_closed=True),
    "numerics.bem_tol": Key("float", "-", "BEM relative gap residual", lo=0.0, hi=1e-3, hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
    **life_output.keys(indent=True),
}
DEFAULTS: dict[str, Any] = {
    **life_output.defaults(10.0 / 9.0, indent=True),
    "materials.body1.rigid": False,
    "materials.body2.rigid": False,
    "models.run": ["analytic", "bem"],
    "models.references": ["bem"],
    "numerics.bem_cells": 193,
    "numerics.bem_domain": 1.6,
    "numerics.bem_tol": 1e-10,
}
REQUIRED = ("geometry.radius", "load.normal", "indent.diameter", "indent.slope", "indent.decay")
# the full transient (a BEM solve per indent position, minutes at 129^2) is cached and stored like an FE reference
DEPENDS: dict[str, dict] = {
    "bem_transient": {"params": ("geometry.", "load.", "materials.", "indent.", "life.", "outputs.life",
                                 "numerics.bem_", "numerics.life_"), "reference": True},
}


def _hertz(params: dict[str, Any]) -> hertz.EllipticContact:
    e_star = effective_modulus(elastic(params, "body1"), elastic(params, "body2"))
    return hertz.point_contact(params["load.normal"], params["geometry.radius"], e_star)


def validate(params: dict[str, Any]) -> None:
    check_body_pair(params, ("body1", "body2"))
    life_output.check_body(params, "body2")
    h = _hertz(params)
    if h.semi_axis_x / params["geometry.radius"] > 0.1:
        raise InputError("load.normal", f"{params['load.normal']:g} N gives a/R > 0.1 (half-space theory fails)")


def indent_size(params: dict[str, Any]) -> tuple[float, float]:
    """Physical indent diameter phi (m) and depth d (m) from the dimensionless keys."""
    h = _hertz(params)
    a, R = h.semi_axis_x, params["geometry.radius"]
    phi = params["indent.diameter"] * a
    return phi, params["indent.slope"] * params["indent.diameter"] * a * a / R


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Zone A/B model (seed 004 eq 3.6) with the calibrated coefficients."""
    c = indent.ZoneABCoefficients.load()
    h = _hertz(scene.params)
    S, K = scene["indent.slope"], scene["indent.decay"]
    dp = indent.additional_pressure(S, K, c) * h.p_max
    q = {"additional_pressure": dp, "indent_depth_ratio": indent.depth_ratio(S), "total_force": h.load}
    stats = {"zone": "A" if S <= indent.ZONE_B_SLOPE else "B", "nu": indent.nu(K), "zeta": indent.zeta(K),
             "coefficients": {"n": c.n, "m": c.m, "s": c.s, "omega": c.omega}, "calibration": c.provenance}
    return ModelResult("analytic", quantities=q, stats=stats)


def solve_indented(params: dict[str, Any], n: int | None = None) -> dict[str, Any]:
    """Smooth and indented BEM solutions on the same grid; dP, F, zone."""
    h = _hertz(params)
    a, R = h.semi_axis_x, params["geometry.radius"]
    n = n or params["numerics.bem_cells"]
    if n % 2 == 0:
        raise InputError("numerics.bem_cells", f"{n} is even; allowed: odd counts (a cell on the indent centre)")
    g = halfspace.grid(params["numerics.bem_domain"] * a, params["numerics.bem_domain"] * a, n, n)
    phi, d = indent_size(params)
    K = params["indent.decay"]
    smooth = halfspace.solve(g, paraboloid(R, R), h.modulus, h.load, tol=params["numerics.bem_tol"]).result
    dent = halfspace.solve(g, indented(paraboloid(R, R), phi, d, K), h.modulus, h.load,
                           tol=params["numerics.bem_tol"]).result
    c = n // 2
    if dent.contact[0, :].any() or dent.contact[-1, :].any() or dent.contact[:, 0].any() or dent.contact[:, -1].any():
        raise ConvergenceError("BEM indented contact", dent.iterations, dent.residual, params["numerics.bem_tol"],
                               "contact reaches the edge of the BEM domain; raise numerics.bem_domain")
    return {"grid": g, "smooth": smooth, "dent": dent, "dp": float((dent.pressure - smooth.pressure).max()),
            "F": float(dent.gap[c, c] / d) if d > 0 else 0.0, "p_centre": float(dent.pressure[c, c]),
            "p_hertz": h.p_max, "a": a, "phi": phi, "depth": d}


def bem(scene: Scene, progress=None) -> ModelResult:
    s = solve_indented(scene.params)
    g, dent = s["grid"], s["dent"]
    q = {"additional_pressure": s["dp"], "indent_depth_ratio": s["F"], "p_max": float(dent.pressure.max()),
         "total_force": dent.load}
    stats = {"zone": "A" if s["p_centre"] > 0 else "B", "iterations": dent.iterations, "residual": dent.residual,
             "smooth_iterations": s["smooth"].iterations, "nx": g.nx, "dx_over_a": g.dx / s["a"],
             "cells_per_indent_diameter": s["phi"] / g.dx, "additional_pressure_over_p_hertz": s["dp"] / s["p_hertz"]}
    j = g.ny // 2
    fields = {"x": g.x, "pressure": dent.pressure[:, j], "map_x": g.x, "map_y": g.y, "pressure_map": dent.pressure}
    if scene["outputs.life"]:
        out = indent_life.pseudo_transient(scene, s, scene["materials.body2.nu"])
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
        if scene["life.size_sweep"]:
            stats["life"]["size_sweep"] = indent_life.size_sweep(scene, solve_indented, scene["materials.body2.nu"])
    return ModelResult("bem", quantities=q, stats=stats, fields=fields)


def bem_transient(scene: Scene, progress=None) -> ModelResult:
    """Life quantities of the full transient pass: the indented contact solved by the BEM at every cell position
    of the indent (:func:`femcheck.problems._indent_life.transient`); the reference of the pseudo-transient."""
    if not scene["outputs.life"]:
        raise InputError("models.run", "bem_transient only computes the life; set outputs.life = true")
    p = scene.params
    s = solve_indented(p)
    h = _hertz(p)
    R, K = p["geometry.radius"], p["indent.decay"]
    solves = [s["smooth"], s["dent"]]

    def solve_at(x0: float) -> np.ndarray:
        gap = indented(paraboloid(R, R), s["phi"], s["depth"], K, x0=x0)
        r = halfspace.solve(s["grid"], gap, h.modulus, h.load, tol=p["numerics.bem_tol"]).result
        if r.contact[0, :].any() or r.contact[-1, :].any():
            raise ConvergenceError("BEM indented contact", r.iterations, r.residual, p["numerics.bem_tol"],
                                   "contact reaches the edge of the BEM domain; raise numerics.bem_domain")
        solves.append(r)
        return r.pressure

    out = indent_life.transient(scene, s, solve_at, p["materials.body2.nu"], p["numerics.bem_domain"])
    stats = {"iterations": sum(r.iterations for r in solves), "residual": max(r.residual for r in solves),
             "bem_solves": len(solves), "life": out.stats}
    return ModelResult("bem_transient", quantities=out.quantities, stats=stats, fields=out.fields)


MODELS: dict[str, Callable[..., ModelResult]] = {"analytic": analytic, "bem": bem, "bem_transient": bem_transient}
CALIBRATION_FILE = indent.COEFFS        # where `femcheck calibrate` stores the zone A/B coefficients

# Calibration grid: zone A (S <= 1/4) for n, m and zone B for s, omega, at Phi = 0.5 over the thesis' K range.
CALIBRATION_K = (3.0, 4.0, 5.0, 6.0, 8.0)
CALIBRATION_SLOPES = (0.05, 0.1, 0.15, 0.2, 0.4, 0.75, 1.0, 1.5, 2.0)


def calibrate(scene: Scene, progress=None) -> dict:
    """Fit the zone A/B coefficients on BEM solutions (seed 004 App. B procedure); returns the JSON written."""
    t0 = time.perf_counter()
    samples = []
    for K in CALIBRATION_K:
        for S in CALIBRATION_SLOPES:
            if progress:
                progress(f"K={K:g} D/Phi={S:g}")
            params = {**scene.params, "indent.decay": K, "indent.slope": S, "indent.diameter": 0.5}
            s = solve_indented(params)
            samples.append((S, K, s["dp"] / s["p_hertz"]))
    n, m, s_, omega = indent.calibrate(samples)
    c = indent.ZoneABCoefficients(n, m, s_, omega, {})
    resid = [indent.additional_pressure(S, K, c) - dp for S, K, dp in samples]
    rel = [abs(r) / dp for r, (_, _, dp) in zip(resid, samples)]
    return {"n": n, "m": m, "s": s_, "omega": omega,
            "provenance": {"femcheck_version": __version__, "scene": scene.name, "indent.diameter": 0.5,
                           "K": list(CALIBRATION_K), "slopes": list(CALIBRATION_SLOPES),
                           "bem_cells": scene["numerics.bem_cells"], "bem_domain": scene["numerics.bem_domain"],
                           "samples": [list(x) for x in samples], "max_rel_misfit": max(rel),
                           "rms_rel_misfit": float(np.sqrt(np.mean(np.square(rel)))),
                           "time_s": time.perf_counter() - t0}}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return _hertz(scene.params).semi_axis_x


def stress_cases(scene: Scene) -> list:
    from ..result import StressCase

    return [StressCase(f"K={K:g}, D/Phi={S:g}, Phi={P:g}", {"indent.decay": K, "indent.slope": S,
                                                           "indent.diameter": P})
            for K in (3.0, 8.0) for S in (0.01, 0.25, 2.0) for P in (0.25, 1.0)]


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    return {"bem": [{"numerics.bem_cells": n} for n in (65, 97, 129, 193, 257, 385)]}
