"""Layered (coated) contact: a rigid cylinder (line, plane strain) or sphere (point) pressed on a layer
(E1, nu1, thickness h) perfectly bonded to an elastic substrate (E2, nu2) or to a rigid base (layer-line,
layer-point, coated-roller).

The contact is line contact when the scene gives ``load.per_length`` (N/m) and point contact when it gives
``load.normal`` (N). The layer is given either dimensionally (``layer.E``, ``layer.thickness``) or by the
dimensionless ``layer.E_ratio`` = E1 / E2 and ``layer.h_over_a`` = h / a_H, a_H the Hertz half-width (line) or
contact radius (point) of the rigid indenter on the uncoated substrate; exactly one of each pair.
:func:`resolve_layer` turns them into ``layer.E`` and ``layer.thickness`` once, for every model.

Several coatings in one scene (coated-roller): sections ``[coatings.<name>]`` with ``E``, ``nu``, ``thickness``
instead of ``[layer]``; every model then runs each coating and reports its quantities with the suffix
``_<name>`` (as srb_contact does with ``_inner`` / ``_outer``).

Models:
  ``bem``         layered half-space boundary-integral model (:mod:`femcheck.bem.layered`: Chen / O'Sullivan &
                  King frequency response, DC-FFT, preconditioned Polonsky-Keer CG); the reference for now.
  ``thin_layer``  Johnson's thin layer on a rigid base (:mod:`femcheck.analytic.thin_layer`; compressible for
                  nu1 <= 0.499, squeeze-film form with a frictionless top above): ignores the substrate's
                  compliance, valid for h << a on a substrate much stiffer than the layer.
  ``analytic``    homogeneous Hertz of the uncoated substrate (for contrast: what the coating changes).
  ``fem``         layered FE reference (:mod:`femcheck.fem.layered_line`: 2D plane strain, P2 / mixed u-p
                  where nu > 0.45; :mod:`femcheck.fem.layered_point`: 3D quarter block, P1, nu <= 0.45):
                  conforming structured layer, bonded interface, rigid indenter, active set, Richardson over
                  mesh levels; stored in references/ and re-solved only when its inputs or code change.

Quantities (SI): line ``p_max`` (Pa), ``half_width`` (m), ``total_force`` (N/m); point ``p_max``,
``semi_axis_x``, ``semi_axis_y`` (m), ``total_force`` (N). The bem model's stats carry ``edge_estimates``
(:func:`edge_estimates`): the fitted edge beside the contact cells' own measure (strip count or area radius), and a
``note`` when they differ by more than a cell plus the fit's bias bound.

The module is above 500 lines because it adapts both geometries (line and point) for every model of the kind,
with the layered BEM's two edge estimates.
"""
from __future__ import annotations

from importlib import import_module
from typing import Any, Callable

import numpy as np

from ..analytic import hertz, thin_layer
from ..bem import layered
from ..bem.halfspace import grid as bem_grid
from ..fem import layered_line, layered_point
from ..errors import ConvergenceError, InputError
from ..qoi import Edge, edges, semi_axes
from ..result import ModelResult
from ..scene import Key, Scene, model_keys, tolerance_key

MODEL_NAMES = ("bem", "thin_layer", "analytic", "fem", "fem_p2", "fem_axisym")


def _wider(a: Key | None, b: Key | None) -> Key:
    """One schema entry for a numerics.fem_* key that the 2D and 3D FE models may both have (each model's own
    range is checked again in ``validate``, and its own default applies when the scene does not set the key)."""
    if a is None or b is None:
        return a or b
    if a.kind in ("int", "float"):
        lo, hi = min(a.lo, b.lo), max(a.hi, b.hi)
        return Key(a.kind, a.unit, a.doc.replace("(2D", "(2D/3D"), lo=lo, hi=hi, lo_closed=True, hi_closed=True)
    return a
MAX_A_OVER_R = 0.1            # half-space and small-strain assumptions of every model here

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "radius R of the rigid cylinder (line) or sphere (point)", lo=0.0),
    "load.per_length": Key("float", "N/m", "normal load per unit length W' (line contact)", lo=0.0),
    "load.normal": Key("float", "N", "normal load P (point contact)", lo=0.0),
    "layer.E": Key("float", "Pa", "Young's modulus of the layer E1", lo=0.0),
    "layer.E_ratio": Key("float", "-", "E1 / E2 (instead of layer.E; elastic substrate only)", lo=0.0),
    "layer.nu": Key("float", "-", "Poisson's ratio of the layer", lo=-1.0, hi=0.5, hi_closed=True),
    "layer.thickness": Key("float", "m", "layer thickness h", lo=0.0),
    "layer.h_over_a": Key("float", "-", "h / Hertz half-width or radius on the uncoated substrate (instead of "
                          "layer.thickness; elastic substrate only)", lo=0.0),
    "coatings.*.E": Key("float", "Pa", "Young's modulus of a coating (multi-coating scenes)", lo=0.0),
    "coatings.*.nu": Key("float", "-", "Poisson's ratio of a coating", lo=-1.0, hi=0.5, hi_closed=True),
    "coatings.*.thickness": Key("float", "m", "thickness of a coating", lo=0.0),
    "materials.substrate.E": Key("float", "Pa", "Young's modulus of the substrate E2", lo=0.0),
    "materials.substrate.nu": Key("float", "-", "Poisson's ratio of the substrate", lo=-1.0, hi=0.5),
    "materials.substrate.rigid": Key("bool", "-", "rigid base under the layer (E2, nu2 ignored)"),
    **model_keys(MODEL_NAMES),
    "numerics.bem_elements": Key("int", "-", "BEM strips over the domain (line)", lo=32, hi=2**18,
                                 lo_closed=True, hi_closed=True),
    "numerics.bem_cells": Key("int", "-", "BEM cells per side (point; odd puts a cell on the centre)", lo=9,
                              hi=1025, lo_closed=True, hi_closed=True),
    "numerics.bem_domain": Key("float", "a", "BEM domain half-size / contact size found by a coarse pre-solve",
                               lo=1.05, hi=10.0, hi_closed=True),
    "numerics.bem_tol": Key("float", "-", "BEM relative gap residual", lo=0.0, hi=1e-3, hi_closed=True),
    "outputs.subsurface_stress": Key("bool", "-", "sub-surface stresses of the bem model in layer and substrate "
                                     "(femcheck.bem.layered_stress), interface both sides"),
    **{k: _wider(layered_line.FEM_SCHEMA.get(k), layered_point.FEM_SCHEMA.get(k))
       for k in {**layered_line.FEM_SCHEMA, **layered_point.FEM_SCHEMA}},
    "numerics.p2_levels": Key("int", "-", "FEM P2 mesh levels (ratio sqrt 2; point contact)", lo=1, hi=4,
                              lo_closed=True, hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
}
DEFAULTS: dict[str, Any] = {
    "materials.substrate.rigid": False,
    "models.run": ["bem", "thin_layer", "analytic", "fem"],     # fem_p2 (3D point contact) when asked for
    "models.references": ["bem"],
    "numerics.bem_elements": 1024,
    "numerics.bem_cells": 65,
    "numerics.bem_domain": 1.25,
    "numerics.bem_tol": 1e-10,
    "outputs.subsurface_stress": False,
}
REQUIRED = ("geometry.radius",)
DEPENDS: dict[str, dict] = {
    "fem": {"params": ("geometry.", "load.", "layer.", "coatings.", "materials.", "numerics.fem_"),
            "reference": True, "coarse": {"numerics.fem_levels": 1}},
    "fem_p2": {"params": ("geometry.", "load.", "layer.", "coatings.", "materials.", "numerics.fem_", "numerics.p2_"),
               "reference": True, "coarse": {"numerics.p2_levels": 1}},
    "fem_axisym": {"params": ("geometry.", "load.", "layer.", "coatings.", "materials.", "numerics.fem_"),
                   "reference": True, "coarse": {"numerics.fem_levels": 1}},
}

LAYER_KEYS = ("layer.E", "layer.E_ratio", "layer.nu", "layer.thickness", "layer.h_over_a")
# setting one key of a pair (--set, a map axis) replaces the other (femcheck.scene._apply_overrides)
ALTERNATIVES = (("layer.thickness", "layer.h_over_a"), ("layer.E", "layer.E_ratio"))


# ---------------------------------------------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------------------------------------------

def geometry_of(params: dict[str, Any]) -> str:
    """"line" (load.per_length given) or "point" (load.normal given)."""
    return "line" if "load.per_length" in params else "point"


def load_value(params: dict[str, Any]) -> float:
    return float(params["load.per_length"] if geometry_of(params) == "line" else params["load.normal"])


def coating_names(params: dict[str, Any]) -> list[str]:
    """Names of the ``[coatings.<name>]`` sections, in the order of the scene."""
    names: list[str] = []
    for k in params:
        if k.startswith("coatings."):
            name = k.split(".")[1]
            if name not in names:
                names.append(name)
    return names


def _substrate_modulus(params: dict[str, Any]) -> float:
    """E2* = E2 / (1 - nu2^2) (Pa) of the substrate (the indenter is rigid)."""
    return params["materials.substrate.E"] / (1.0 - params["materials.substrate.nu"] ** 2)


def substrate_hertz(params: dict[str, Any]):
    """Hertz contact of the rigid indenter on the uncoated substrate (line or circular), SI."""
    R, w = params["geometry.radius"], load_value(params)
    if geometry_of(params) == "line":
        return hertz.line_contact(w, R, _substrate_modulus(params))
    return hertz.elliptic_contact(w, R, R, _substrate_modulus(params))


def _hertz_size(h) -> float:
    return h.half_width if isinstance(h, hertz.LineContact) else h.semi_axis_x


def resolve_layer(params: dict[str, Any]) -> dict[str, Any]:
    """A copy of ``params`` in which the layer is given by ``layer.E`` and ``layer.thickness`` (the keys every
    model reads): ``layer.E = layer.E_ratio * E2`` and ``layer.thickness = layer.h_over_a * a_H`` with a_H the
    Hertz half-width (line) or contact radius (point) of the rigid indenter on the uncoated substrate. The
    dimensionless keys are dropped. Raises InputError unless exactly one key of each pair is given."""
    out = dict(params)
    for dim, rel, what in (("layer.E", "layer.E_ratio", "E_substrate"),
                           ("layer.thickness", "layer.h_over_a", "Hertz size on the substrate")):
        if (dim in params) == (rel in params):
            raise InputError(dim, f"give exactly one of {dim} and {rel} ({rel} = {dim} / {what})")
        if rel in params and params.get("materials.substrate.rigid", False):
            raise InputError(rel, "needs an elastic substrate (no Hertz solution or E ratio on a rigid base); "
                             f"give {dim} instead")
    if "layer.E_ratio" in out:
        out["layer.E"] = out.pop("layer.E_ratio") * params["materials.substrate.E"]
    if "layer.h_over_a" in out:
        out["layer.thickness"] = out.pop("layer.h_over_a") * _hertz_size(substrate_hertz(params))
    return out


def layer_params(params: dict[str, Any], coating: str | None = None) -> dict[str, Any]:
    """The single-layer parameters of one coating (``coating`` given) or of the ``[layer]`` section, resolved."""
    if coating is None:
        return resolve_layer(params)
    out = {k: v for k, v in params.items() if not k.startswith("coatings.")}
    for key in ("E", "nu", "thickness"):
        out[f"layer.{key}"] = params[f"coatings.{coating}.{key}"]
    return out


def solid_of(params: dict[str, Any]) -> layered.LayeredSolid:
    """The :class:`LayeredSolid` of resolved single-layer parameters."""
    rigid = bool(params.get("materials.substrate.rigid", False))
    return layered.LayeredSolid(params["layer.E"], params["layer.nu"], params["layer.thickness"],
                                params.get("materials.substrate.E", 1.0), params.get("materials.substrate.nu", 0.0),
                                rigid)


def validate(params: dict[str, Any]) -> None:
    """Exactly one load key; an elastic substrate needs E and nu; either [layer] or [coatings.*]; a/R small."""
    if ("load.per_length" in params) == ("load.normal" in params):
        raise InputError("load.per_length", "give exactly one of load.per_length (line contact) and load.normal "
                         "(point contact)")
    rigid = params.get("materials.substrate.rigid", False)
    if not rigid:
        for k in ("materials.substrate.E", "materials.substrate.nu"):
            if k not in params:
                raise InputError(k, "required for an elastic substrate (or set materials.substrate.rigid = true)")
    names = coating_names(params)
    if names:
        if any(k in params for k in LAYER_KEYS):
            raise InputError("layer", "give either a [layer] section or [coatings.<name>] sections, not both")
        for name in names:
            for key in ("E", "nu", "thickness"):
                if f"coatings.{name}.{key}" not in params:
                    raise InputError(f"coatings.{name}.{key}", "required for every coating")
        layers = [layer_params(params, n) for n in names]
    else:
        if "layer.nu" not in params:
            raise InputError("layer.nu", "required")
        layers = [resolve_layer(params)]
    for lp in layers:
        solid_of(lp)                     # range checks with the key names
        if "analytic" in params.get("models.run", ()) and rigid:
            raise InputError("models.run", "analytic (Hertz of the uncoated substrate) needs an elastic substrate; "
                             "drop it from models.run")
    if "fem" in params.get("models.run", ()) or "fem" in params.get("models.references", ()):
        fem_schema = (layered_line if geometry_of(params) == "line" else layered_point).FEM_SCHEMA
        for k, v in params.items():
            if k.startswith("numerics.fem_"):
                if k not in fem_schema:
                    raise InputError(k, f"not a key of the {geometry_of(params)}-contact FE model; allowed: "
                                     + ", ".join(sorted(fem_schema)))
                fem_schema[k].coerce(k, v)
        if geometry_of(params) == "point":
            for lp in layers:
                if lp["layer.nu"] > 0.45:
                    raise InputError("layer.nu", f"{lp['layer.nu']:g}: the 3D FE model (P1, no mixed form) allows "
                                     "(-1, 0.45]; drop fem from models.run for a nearly incompressible layer")
    # small contact against the radius: the largest contact is the softer of the layer and substrate half-spaces
    for lp in layers:
        a_max = _size_bound(lp)
        if a_max / params["geometry.radius"] > MAX_A_OVER_R:
            raise InputError(next(k for k in ("load.per_length", "load.normal") if k in params),
                             f"{load_value(params):g} gives a contact size up to a/R = {a_max / params['geometry.radius']:.3g}"
                             f" > {MAX_A_OVER_R} (half-space and small-strain assumptions fail); lower the load")


def _size_bound(lp: dict[str, Any]) -> float:
    """An upper estimate (m) of the contact size: the Hertz size of the softer of the layer and the substrate
    as half-spaces (a layered solid's compliance lies between the two at every wavenumber)."""
    solid = solid_of(lp)
    e = min(solid.modulus_layer, solid.modulus_substrate)
    R, w = lp["geometry.radius"], load_value(lp)
    if geometry_of(lp) == "line":
        return hertz.line_contact(w, R, e).half_width
    return hertz.elliptic_contact(w, R, R, e).semi_axis_x


# ---------------------------------------------------------------------------------------------------------------
# Contact edges
# ---------------------------------------------------------------------------------------------------------------

def _half_width(x: np.ndarray, p: np.ndarray) -> float:
    """Half-width (m) of a profile centred on x = 0: :func:`femcheck.qoi.half_width`, a power-law edge with its
    exponent fitted (square-root on a half-space or a thick layer, linear on Johnson's thin compressible layer,
    quadratic on an incompressible one: no shape is assumed)."""
    right, left = edges(x, p, 0.0)
    return right.position if left is None else 0.5 * (right.position + left.position)


def edge_estimates(fits: list[Edge], fitted: float, counted: float, cell: float) -> dict[str, Any]:
    """Both estimates of a BEM contact's size (m), and whether they disagree.

    ``fitted``: the power-law edge (:func:`femcheck.qoi.edge`, band adapted to the exponent's drift); ``counted``:
    the contact cells' own measure, half their number of strips times the strip width (line) or the radius of
    their total area sqrt(N dx dy / pi) (point), known to within one cell ``cell``: half a cell because the edge
    lies anywhere between the last loaded and the first unloaded collocation point, and up to half a cell more
    because the BEM's own contact set is that far off near the edge (measured on layer-rigid at 1024 strips: the
    count 1.3 half cells beyond the Fourier solution's edge, docs/notes/layered-edge.md). On a thin layer the two
    estimates differed by 1.4-2 % whatever the grid while the fit's band was wider than the layer's edge
    boundary layer. ``disagree``: |fitted - counted| > cell + the fit's bias bound (its change over the last band
    halving) + twice its standard error; ``note`` then says so (shown in the report)."""
    bias = max(e.bias for e in fits)
    std = float(np.sqrt(np.mean([e.std**2 for e in fits]))) if all(np.isfinite(e.std) for e in fits) else 0.0
    allowed = cell + bias + 2.0 * std
    out = {"fitted": float(fitted), "counted": float(counted), "cell": float(cell),
           "difference": (fitted - counted) / counted, "allowed": float(allowed / counted),
           "fit_band": min(e.band for e in fits), "fit_exponent": float(np.mean([e.exponent for e in fits])),
           "fit_drift": max(e.drift for e in fits), "fit_bias": bias, "fit_std": std,
           "disagree": bool(abs(fitted - counted) > allowed)}
    if out["disagree"]:
        out["note"] = (f"the fitted edge {fitted:.6g} m and the contact cells' {counted:.6g} m differ by "
                       f"{100 * out['difference']:+.2f} %, more than a cell plus the fit's bias bound "
                       f"({100 * out['allowed']:.2f} %): the edge's power law is not resolved on this grid")
    return out


# ---------------------------------------------------------------------------------------------------------------
# Models on one layer
# ---------------------------------------------------------------------------------------------------------------

COARSE = {"line": 256, "point": 33}


def _bem_one(lp: dict[str, Any], progress=None) -> ModelResult:
    """Layered BEM for one layer: a coarse pre-solve over 1.5 x the size bound finds the contact size a_c, then
    the final grid covers numerics.bem_domain x (a_c + one coarse cell)."""
    solid = solid_of(lp)
    R, w, geo = lp["geometry.radius"], load_value(lp), geometry_of(lp)
    tol = lp["numerics.bem_tol"]

    def run(half: float, n: int, tol_: float):
        if geo == "line":
            sol = layered.solve_line(solid, lambda x: x * x / (2.0 * R), w, half, n, tol=tol_)
            return sol, sol.x, sol.result.pressure
        g = bem_grid(half, half, n, n)
        sol = layered.solve_point(solid, g, lambda X, Y: (X * X + Y * Y) / (2.0 * R), w, tol=tol_)
        return sol, sol.x, sol.result.pressure[:, n // 2]

    half = 1.5 * _size_bound(lp)
    for _ in range(4):
        coarse, xc, pc = run(half, COARSE[geo], max(tol, 1e-8))
        if not layered.touches_edge(coarse.result.contact):
            break
        half *= 2.0                  # the size bound was not one: widen and try again
    else:
        raise ConvergenceError("layered BEM", coarse.result.iterations, coarse.result.residual, tol,
                               "contact reaches the domain edge even on a domain 8x the Hertz bound")
    a_c = _half_width(xc, pc) + (xc[1] - xc[0])
    half = lp["numerics.bem_domain"] * a_c
    n = lp["numerics.bem_elements"] if geo == "line" else lp["numerics.bem_cells"]
    sol, x, pline = run(half, n, tol)
    r = sol.result
    if layered.touches_edge(r.contact):
        raise ConvergenceError("layered BEM", r.iterations, r.residual, tol,
                               "contact reaches the edge of the BEM domain; raise numerics.bem_domain")
    stats = {**sol.stats, "domain_half_length": half, "cells": n, "spacing": list(sol.spacing),
             "coarse_iterations": coarse.result.iterations, "contact_cells": int(r.contact.sum()),
             "h_over_dx": solid.thickness / sol.spacing[0], "solver": "polonsky_keer", "convolution": "dcfft"}
    if geo == "line":
        right, left = edges(x, r.pressure, 0.0)
        a_fit = 0.5 * (right.position + left.position)
        q = {"p_max": float(r.pressure.max()), "half_width": a_fit, "total_force": r.load}
        fields = {"x": x, "pressure": r.pressure}
        stats["edge_estimates"] = edge_estimates([right, left], a_fit, 0.5 * int(r.contact.sum()) * sol.spacing[0],
                                                 sol.spacing[0])
    else:
        y = sol.y
        # the estimator of the 3D FE reference (strips along both axes, femcheck.qoi.semi_axes): one definition
        # of the edge for every model of the scene
        ax, ay, fits = semi_axes(*np.meshgrid(x, y, indexing="ij"), r.pressure)
        q = {"p_max": float(r.pressure.max()), "semi_axis_x": ax, "semi_axis_y": ay, "total_force": r.load}
        fields = {"x": x, "pressure": pline, "pressure_map": r.pressure, "map_x": x, "map_y": y}
        area = int(r.contact.sum()) * sol.spacing[0] * sol.spacing[1]
        stats["edge_estimates"] = edge_estimates(list(fits.values()), float(np.sqrt(ax * ay)),
                                                 float(np.sqrt(area / np.pi)), max(sol.spacing))
    if lp.get("outputs.subsurface_stress", False):
        _bem_stress(solid, sol, max(v for k, v in q.items() if k in ("half_width", "semi_axis_x", "semi_axis_y")),
                    q, stats, fields)
    return ModelResult("bem", quantities=q, stats=stats, fields=fields)


def _bem_stress(solid: layered.LayeredSolid, sol: layered.LayeredContactSolution, size: float, q: dict,
                stats: dict, fields: dict) -> None:
    """Sub-surface stresses of the layered BEM pressure (:mod:`femcheck.bem.layered_stress`): depth planes graded
    down to 3 x the contact ``size`` (m), 7 more across the layer, the interface on both sides. Adds the maxima
    (von_mises_max and its depth, tau_max, tau_xz_max, interface_shear_max, interface_normal_max, Pa / m) to
    ``q`` and the (x, z) section (3D: the plane y = 0) to ``fields`` under the names line_contact uses."""
    from ..bem import layered_stress
    from ..bem.halfspace import Grid

    depths = layered_stress.default_depths(solid, size)
    r = sol.result
    if sol.y is None:
        f = layered_stress.line_stresses(r.pressure, sol.spacing[0], solid, depths, x=sol.x)
        vm, tr, txz = f.von_mises(), f.tresca(), f.components["tau_xz"]
    else:
        g = Grid(sol.x.size, sol.y.size, *sol.spacing)
        f = layered_stress.point_stresses(r.pressure, g, solid, depths)
        j = g.ny // 2
        vm, tr, txz = f.von_mises()[:, :, j], f.tresca()[:, :, j], f.components["tau_xz"][:, :, j]
    m = f.maxima()
    q.update({k: m[k] for k in ("von_mises_max", "von_mises_max_depth", "tau_max", "tau_xz_max",
                                "interface_shear_max", "interface_normal_max") if k in m})
    stats["stress"] = {**f.stats, "maxima": m, "depth_max": float(f.depths[-1]),
                       "von_mises_max_in": "layer" if m["von_mises_max_depth"] <= solid.thickness else "substrate"}
    fields.update({"stress_x": f.x, "stress_z": f.depths, "von_mises": vm, "tresca": tr, "tau_xz": txz})


def _thin_one(lp: dict[str, Any], progress=None) -> ModelResult:
    """Johnson's thin layer on a rigid base (the substrate's compliance is ignored by this model)."""
    geo = "line" if geometry_of(lp) == "line" else "circular"
    E, nu, b, R, w = lp["layer.E"], lp["layer.nu"], lp["layer.thickness"], lp["geometry.radius"], load_value(lp)
    if nu <= thin_layer.NU_COMPRESSIBLE_MAX:
        c = thin_layer.compressible(E, nu, b, R, w, geo)
    else:
        c = thin_layer.incompressible(E, b, R, w, geo, top="frictionless")
    x = np.linspace(-1.5 * c.a, 1.5 * c.a, 601)
    q = {"p_max": c.p_max, "total_force": w}
    q.update({"half_width": c.a} if geo == "line" else {"semi_axis_x": c.a, "semi_axis_y": c.a})
    stats = {"form": c.model, "h_over_a": b / c.a, "substrate": "rigid (model assumption)"}
    return ModelResult("thin_layer", quantities=q, stats=stats, fields={"x": x, "pressure": c.pressure(x)})


def _analytic_one(lp: dict[str, Any], progress=None) -> ModelResult:
    """Hertz of the rigid indenter on the uncoated substrate."""
    h = substrate_hertz(lp)
    a = _hertz_size(h)
    x = np.linspace(-1.5 * a, 1.5 * a, 601)
    if isinstance(h, hertz.LineContact):
        q = {"p_max": h.p_max, "half_width": h.half_width, "total_force": h.load}
        p = h.pressure(x)
    else:
        q = {"p_max": h.p_max, "semi_axis_x": h.semi_axis_x, "semi_axis_y": h.semi_axis_y, "total_force": h.load}
        p = h.pressure(x, 0 * x)
    return ModelResult("analytic", quantities=q, stats={"E_star": h.modulus}, fields={"x": x, "pressure": p})


def _fem_one(lp: dict[str, Any], progress=None) -> ModelResult:
    """Layered FE reference: 2D plane strain (line) or 3D quarter block (point)."""
    return (layered_line if geometry_of(lp) == "line" else layered_point).model(lp, progress)


# Imported by name when they run, so that the stored references of the other models are not keyed on their code
# (a key covers the adapter and what it imports); their own keys cover it through the module name that
# MODELS[name] carries (femcheck.runner.model_modules).
BY_NAME = {"fem_p2": "femcheck.fem.layered_point_p2", "fem_axisym": "femcheck.fem.layered_axisym"}


def _point_only(name: str, what: str) -> Callable[..., ModelResult]:
    """The point-contact model ``name`` (``what`` it is), imported by name when it runs; refused for a line
    contact."""
    def run(lp: dict[str, Any], progress=None) -> ModelResult:
        if geometry_of(lp) == "line":
            raise InputError("models.run", f"{name} is the {what} model; allowed for a line contact: fem")
        return import_module(BY_NAME[name]).model(lp, progress)

    run.__doc__ = f"Layered FE reference, {what} (:mod:`{BY_NAME[name]}`)."
    return run


SINGLE: dict[str, Callable[..., ModelResult]] = {"bem": _bem_one, "thin_layer": _thin_one, "analytic": _analytic_one,
                                                 "fem": _fem_one,
                                                 "fem_p2": _point_only("fem_p2", "3D point-contact"),
                                                 "fem_axisym": _point_only("fem_axisym", "axisymmetric point-contact")}


def _model(name: str) -> Callable[..., ModelResult]:
    def run(scene: Scene, progress=None) -> ModelResult:
        names = coating_names(scene.params)
        if not names:
            res = SINGLE[name](resolve_layer(scene.params), progress)
            res.stats.setdefault("layer", {"E": resolve_layer(scene.params)["layer.E"],
                                           "thickness": resolve_layer(scene.params)["layer.thickness"]})
            return res
        q, stats, fields = {}, {}, {}
        for c in names:
            if progress:
                progress(f"{name}: {c}")
            res = SINGLE[name](layer_params(scene.params, c), progress)
            q.update({f"{k}_{c}": v for k, v in res.quantities.items() if k != "total_force"})
            stats[c] = res.stats
            for k in ("x", "pressure"):
                fields[k if c == names[0] else f"{k}_{c}"] = res.fields[k]
            if abs(res.quantities["total_force"] / load_value(scene.params) - 1.0) > 1e-6:
                raise RuntimeError(f"{c}: total force {res.quantities['total_force']:.6g} != applied load")
        q["total_force"] = load_value(scene.params)     # every coating checked just above
        return ModelResult(name, quantities=q, stats=stats, fields=fields)

    run.__doc__ = SINGLE[name].__doc__
    if name in BY_NAME:
        run.__module__ = BY_NAME[name]
    return run


MODELS: dict[str, Callable[..., ModelResult]] = {n: _model(n) for n in MODEL_NAMES}


def load_of(scene: Scene) -> float:
    return load_value(scene.params)


def profile_scale(scene: Scene) -> float:
    """Hertz size of the stiffest reading: the smallest of the substrate Hertz and the layers' size bounds."""
    names = coating_names(scene.params)
    layers = [layer_params(scene.params, c) for c in names] if names else [resolve_layer(scene.params)]
    return min(_size_bound(lp) for lp in layers)


def stress_cases(scene: Scene) -> list:
    """Very thin (h/a = 1e-3) and very thick (h/a = 100) layers, E1/E2 from 0.01 to 100, nu -> 0.5 in the
    layer and the substrate, an incompressible layer on a rigid base, and their corners."""
    from ..result import StressCase

    if coating_names(scene.params):
        w = load_value(scene.params)
        key = "load.per_length" if geometry_of(scene.params) == "line" else "load.normal"
        return [StressCase(f"load={w * f:.3g}", {key: w * f}) for f in (1e-3, 1e-2, 0.1, 1.0)]
    drop = {k: None for k in LAYER_KEYS if k != "layer.nu"}
    cases = []
    rigid = scene.params.get("materials.substrate.rigid", False)
    if not rigid:
        lp = resolve_layer(scene.params)
        ratio0 = lp["layer.E"] / scene["materials.substrate.E"]
        h0 = lp["layer.thickness"] / _hertz_size(substrate_hertz(scene.params))
        for hr in (1e-3, 1e-2, 10.0, 100.0):
            cases.append(StressCase(f"h/a={hr:g}", {**drop, "layer.h_over_a": hr, "layer.E_ratio": ratio0}))
        for er in (0.01, 0.1, 10.0, 100.0):
            cases.append(StressCase(f"E1/E2={er:g}", {**drop, "layer.h_over_a": h0, "layer.E_ratio": er}))
        for hr, er in ((1e-3, 100.0), (1e-3, 0.01), (100.0, 0.01), (100.0, 100.0)):
            cases.append(StressCase(f"h/a={hr:g}, E1/E2={er:g}", {**drop, "layer.h_over_a": hr, "layer.E_ratio": er}))
        for nu in (0.49, 0.4999, 0.5):
            cases.append(StressCase(f"layer nu={nu:g}", {"layer.nu": nu}))
        cases.append(StressCase("substrate nu=0.4999", {"materials.substrate.nu": 0.4999}))
        cases.append(StressCase("rigid substrate", {"materials.substrate.rigid": True,
                                                   **drop, "layer.E": lp["layer.E"],
                                                   "layer.thickness": lp["layer.thickness"],
                                                   "models.run": ["bem", "thin_layer"]}))
    else:
        lp = resolve_layer(scene.params)
        for f in (1e-3, 1e-2, 10.0, 100.0):
            cases.append(StressCase(f"h x {f:g}", {"layer.thickness": lp["layer.thickness"] * f}))
        for nu in (0.49, 0.4999, 0.5):
            cases.append(StressCase(f"layer nu={nu:g}", {"layer.nu": nu}))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    if geometry_of(scene.params) == "line":
        return {"bem": [{"numerics.bem_elements": n} for n in (64, 128, 256, 512, 1024, 2048, 4096, 8192)]}
    return {"bem": [{"numerics.bem_cells": n} for n in (17, 33, 49, 65, 97, 129, 193, 257)]}
