"""Plane-strain line contact: a cylinder (elastic or rigid) pressed on a flat elastic block (hertz-line).

Models: ``analytic`` (Hertz + McEwen stresses), ``bem`` (half-plane boundary integral), ``fem`` (Gmsh +
scikit-fem, mesh levels with Richardson extrapolation), ``calculix`` (CalculiX on the exported deck, an independent
FE; selected with --models, skipped where ccx is not installed).
"""
from __future__ import annotations

from importlib import import_module
from typing import Any, Callable

import numpy as np

from ..analytic import hertz
from ..analytic.stress import line_contact_field
from ..bem.line import solve_line_contact
from ..errors import ConvergenceError, InputError
from ..fem.line_contact import FEMLineSettings, solve_level
from ..solvers.convergence import certificate_stats, certify_levels
from ..materials import effective_modulus
from ..qoi import half_width
from ..result import ModelResult
from ..scene import (Key, Scene, check_body_pair, elastic, fem_line_mesh_keys, material_keys, model_keys,
                     tolerance_key)
from . import _life_output as life_output

MODEL_NAMES = ("analytic", "bem", "fem", "calculix")
MAX_A_OVER_R = 0.1   # beyond this the half-space and small-strain assumptions of every model here fail

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "cylinder radius R", lo=0.0),
    "load.per_length": Key("float", "N/m", "normal load per unit length W'", lo=0.0),
    **material_keys("cylinder"),
    **{k: v for k, v in material_keys("block").items() if not k.endswith("rigid")},
    "outputs.subsurface_stress": Key("bool", "-", "compute the sub-surface stress field (analytic)"),
    **model_keys(MODEL_NAMES),
    "numerics.bem_elements": Key("int", "-", "BEM strips over the domain", lo=16, hi=2**20, lo_closed=True,
                                 hi_closed=True),
    "numerics.bem_domain": Key("float", "a_H", "BEM domain half-length / Hertz half-width", lo=1.05, hi=20.0,
                               hi_closed=True),
    "numerics.bem_tol": Key("float", "-", "BEM relative gap residual", lo=0.0, hi=1e-3, hi_closed=True),
    **fem_line_mesh_keys(),
    "numerics.fem_method": Key("str", "-", "contact algorithm", choices=("active_set", "penalty")),
    "numerics.fem_penalty": Key("float", "-", "penalty stiffness / (E* / h)", lo=1.0, hi=1e9, hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
    **life_output.keys(),
}

_FEM = FEMLineSettings()
DEFAULTS: dict[str, Any] = {
    **life_output.defaults(9.0 / 8.0, depth_max=life_output.LINE_DEPTH_MAX),
    "materials.cylinder.rigid": False,
    "outputs.subsurface_stress": False,
    "models.run": ["analytic", "bem", "fem"],      # calculix: selectable (--models), minutes of ccx
    "models.references": ["analytic", "fem"],
    "numerics.bem_elements": 1024,
    "numerics.bem_domain": 1.25,
    "numerics.bem_tol": 1e-10,
    "numerics.fem_levels": _FEM.levels,
    "numerics.fem_h_contact": _FEM.h_contact,
    "numerics.fem_grading": _FEM.grading,
    "numerics.fem_contact_zone": _FEM.contact_zone,
    "numerics.fem_block_width": _FEM.block_width,
    "numerics.fem_block_depth": _FEM.block_depth,
    "numerics.fem_order": _FEM.order,
    "numerics.fem_formulation": _FEM.formulation,
    "numerics.fem_method": _FEM.method,
    "numerics.fem_penalty": _FEM.penalty_factor,
}
REQUIRED = ("geometry.radius", "load.per_length", "materials.block.E", "materials.block.nu")

# Parameters that determine each cached model's result; the code is found from the imports (femcheck.provenance).
DEPENDS = {
    "fem": {"params": ("geometry.", "load.", "materials.", "numerics.fem_")},
}


def _hertz(params: dict[str, Any]) -> hertz.LineContact:
    e_star = effective_modulus(elastic(params, "cylinder"), elastic(params, "block"))
    return hertz.line_contact(params["load.per_length"], params["geometry.radius"], e_star)


def validate(params: dict[str, Any]) -> None:
    """Cross-key checks: an elastic cylinder needs E and nu; the contact must stay small against R."""
    check_body_pair(params, ("cylinder", "block"))
    h = _hertz(params)
    ratio = h.half_width / params["geometry.radius"]
    if ratio > MAX_A_OVER_R:
        w_max = params["load.per_length"] * (MAX_A_OVER_R / ratio) ** 2
        raise InputError("load.per_length", f"{params['load.per_length']:g} N/m gives a Hertz half-width a/R = "
                         f"{ratio:.3g} > {MAX_A_OVER_R} (half-space and small-strain assumptions fail); "
                         f"allowed (0, {w_max:.4g}] N/m for this radius and these materials")


def _profile_gap(radius: float) -> Callable[[np.ndarray], np.ndarray]:
    """Initial gap of a circular cylinder over a flat, exact (not the parabolic Hertz approximation)."""
    return lambda x: radius - np.sqrt(np.clip(radius**2 - x**2, 0.0, None))


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Hertz line contact (seed 001 eqs 1-5); sub-surface stresses (McEwen) only when the scene asks."""
    h = _hertz(scene.params)
    x = np.linspace(-1.5 * h.half_width, 1.5 * h.half_width, 601)
    q = {"p_max": h.p_max, "half_width": h.half_width, "total_force": h.load}
    fields = {"x": x, "pressure": h.pressure(x)}
    stats: dict[str, Any] = {"E_star": h.modulus, "a_over_R": h.half_width / h.radius}
    if scene["outputs.subsurface_stress"]:
        f = line_contact_field(h, scene["materials.block.nu"])
        q.update({k: f.maxima[k] for k in ("von_mises_max", "von_mises_max_depth", "tau_max", "tau_xz_max")})
        stats["stress_maxima"] = f.maxima
        stats["stress_body"] = "block"
        fields.update({"stress_x": f.x, "stress_z": f.z, "von_mises": f.von_mises, "tresca": f.tresca,
                       "tau_xz": f.components["tau_xz"]})
    if scene["outputs.life"]:
        out = life_output.line_life_closed_form(scene, h.half_width, h.p_max, scene["materials.block.nu"])
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
    return ModelResult("analytic", quantities=q, stats=stats, fields=fields)


def bem(scene: Scene, progress=None) -> ModelResult:
    """Half-plane BEM: uniform strips, exact influence coefficients, DC-FFT, Polonsky-Keer CG."""
    h = _hertz(scene.params)
    half_domain = scene["numerics.bem_domain"] * h.half_width
    sol = solve_line_contact(_profile_gap(scene["geometry.radius"]), h.modulus, scene["load.per_length"],
                             half_domain, scene["numerics.bem_elements"], tol=scene["numerics.bem_tol"])
    r = sol.result
    if r.contact[0] or r.contact[-1]:
        raise ConvergenceError("BEM line contact", r.iterations, r.residual, scene["numerics.bem_tol"],
                               "contact reaches the edge of the BEM domain; raise numerics.bem_domain")
    q = {"p_max": float(r.pressure.max()), "half_width": half_width(sol.x, r.pressure), "total_force": r.load}
    stats = {"iterations": r.iterations, "residual": r.residual, "n_elements": sol.x.size, "dx": sol.dx,
             "domain_half_length": half_domain, "solver": "polonsky_keer", "convolution": "dcfft",
             "contact_cells": int(r.contact.sum())}
    fields = {"x": sol.x, "pressure": r.pressure}
    if scene["outputs.life"]:
        out = life_output.line_life_strips(scene, r.pressure, sol.dx, h.half_width, h.p_max,
                                           scene["materials.block.nu"])
        q.update(out.quantities)
        stats["life"] = out.stats
        fields.update(out.fields)
    return ModelResult("bem", quantities=q, stats=stats, fields=fields)


def fem_settings(scene: Scene) -> FEMLineSettings:
    n = scene.section("numerics")
    return FEMLineSettings(levels=n["fem_levels"], h_contact=n["fem_h_contact"], grading=n["fem_grading"],
                           contact_zone=n["fem_contact_zone"], block_width=n["fem_block_width"],
                           block_depth=n["fem_block_depth"], order=n["fem_order"],
                           formulation=n["fem_formulation"], method=n["fem_method"],
                           penalty_factor=n["fem_penalty"])


def _crop(mesh, a: float, extent: float = 3.0) -> dict[str, np.ndarray]:
    """The part of a mesh within ``extent`` a of the contact, for the report picture."""
    inside = (mesh.points[0] <= extent * a) & (np.abs(mesh.points[1]) <= extent * a)
    keep = inside[mesh.triangles].all(axis=0)
    return {"points": mesh.points, "triangles": mesh.triangles[:, keep]}


def fem(scene: Scene, progress=None) -> ModelResult:
    """2D plane-strain FEM on ``numerics.fem_levels`` meshes; per quantity a convergence certificate
    (stats["certificates"]: Richardson-extrapolated when the levels are in the asymptotic range, else the finest
    level with a two-level bound); stats carry every level and the finest values."""
    h = _hertz(scene.params)
    s = fem_settings(scene)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        levels.append(solve_level(scene["geometry.radius"], scene.material("cylinder"),
                                  scene.material("block"), scene["load.per_length"], h.half_width, k, s))
    fine = levels[-1]
    finest = {"p_max": fine.p_max, "half_width": fine.half_width}
    stats: dict[str, Any] = {
        "method": s.method, "element_order": s.order, "formulation": fine.formulations, "finest": finest,
        "levels": [{"h": lv.h, "h_over_a": lv.h / h.half_width, "n_dofs": lv.n_dofs,
                    "n_elements": lv.n_elements, "p_max": lv.p_max, "half_width": lv.half_width, **lv.std,
                    "iterations": lv.iterations, "residual": lv.residual, "penetration": lv.penetration,
                    "total_force": lv.total_force, "time_s": lv.time_s} for lv in levels],
        "block": {"width": s.block_width * h.half_width, "depth": s.block_depth * h.half_width},
    }
    certs = certify_levels(stats["levels"], ("p_max", "half_width"))
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    q["total_force"] = fine.total_force
    fields = {"x": fine.x, "pressure": fine.p}
    for body, mesh in fine.meshes.items():
        crop = _crop(mesh, h.half_width)
        fields[f"mesh_{body}_points"] = crop["points"]
        fields[f"mesh_{body}_triangles"] = crop["triangles"]
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)


def calculix(scene: Scene, progress=None) -> ModelResult:
    """CalculiX (``ccx``) on the scene's exported deck at each mesh level, an independent FE
    (:mod:`femcheck.export.calculix_model`); skipped where ccx is not installed. Imported by name when it runs,
    so that the stored references of the other models are not keyed on the export code (see
    :func:`femcheck.problems.point_contact._by_name`)."""
    return import_module("femcheck.export.calculix_model").model(scene, progress)


calculix.__module__ = "femcheck.export.calculix_model"      # its key covers the export code


MODELS: dict[str, Callable[..., ModelResult]] = {"analytic": analytic, "bem": bem, "fem": fem, "calculix": calculix}


def load_of(scene: Scene) -> float:
    """Applied load (N/m) against which every model's ``total_force`` is checked."""
    return scene["load.per_length"]


def profile_scale(scene: Scene) -> float:
    """Length (m) that sets the common grid of pressure-profile comparisons."""
    return _hertz(scene.params).half_width


def max_load(params: dict[str, Any]) -> float:
    """Largest admissible load per length (N/m): the one giving a/R = MAX_A_OVER_R."""
    h = _hertz(params)
    return params["load.per_length"] * (MAX_A_OVER_R * params["geometry.radius"] / h.half_width) ** 2


def stress_cases(scene: Scene) -> list:
    """Extremes: nu from 0 to 0.4999 (both bodies), E_cylinder/E_block from 1e-2 to 1e2, load over six decades
    up to the largest admissible one, a rigid cylinder, and the corners nu = 0.4999 x E ratio 1e-2 / 1e2.
    When the moduli change, the load is scaled with E* so that a/R stays that of the scene (a softer pair at
    the same load would only leave the admissible range, which is tested by the load sweep)."""
    from ..result import StressCase

    e_block = scene["materials.block.E"]
    e_star0 = _hertz(scene.params).modulus

    def same_size(over: dict[str, Any]) -> dict[str, Any]:
        e_star = _hertz({**scene.params, **over}).modulus
        return {**over, "load.per_length": scene["load.per_length"] * e_star / e_star0}

    cases = []
    for nu in (0.0, 0.25, 0.45, 0.49, 0.499, 0.4999):
        cases.append(StressCase(f"nu={nu:g}", {"materials.cylinder.nu": nu, "materials.block.nu": nu}))
    for ratio in (1e-2, 1e-1, 1e1, 1e2):
        cases.append(StressCase(f"E_cyl/E_block={ratio:g}", same_size({"materials.cylinder.E": ratio * e_block})))
    w_max = max_load(scene.params)
    for k in range(6, -1, -1):
        w = w_max * 10.0**-k
        cases.append(StressCase(f"load={w:.3g} N/m", {"load.per_length": w}))
    cases.append(StressCase("rigid cylinder", {"materials.cylinder.rigid": True}))
    cases.append(StressCase("rigid cylinder, nu=0.4999", {"materials.cylinder.rigid": True,
                                                          "materials.block.nu": 0.4999}))
    for ratio in (1e-2, 1e2):
        cases.append(StressCase(f"nu=0.4999, E_cyl/E_block={ratio:g}",
                                same_size({"materials.cylinder.nu": 0.4999, "materials.block.nu": 0.4999,
                                           "materials.cylinder.E": ratio * e_block})))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """Discretisation sweeps for ``femcheck bench``: BEM strip count; FEM single mesh levels refined uniformly
    (element size on the contact and grading halved together)."""
    h0, g0 = scene["numerics.fem_h_contact"], scene["numerics.fem_grading"]
    return {
        "bem": [{"numerics.bem_elements": n} for n in (32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384)],
        "fem": [{"numerics.fem_levels": 1, "numerics.fem_h_contact": h0 / 2**k, "numerics.fem_grading": g0 / 2**k}
                for k in range(5)],
    }
