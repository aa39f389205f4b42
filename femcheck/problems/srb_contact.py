"""Frictionless normal contact of a spherical-roller-bearing roller with its inner and outer raceways
(srb-normal; seed 000, Table 1 and eq 1).

Local geometry at the nominal contact points (pitch radius with the minus sign seed 000's eq 1 lost, rolling
radii, relative radii of curvature): :mod:`femcheck.geometry.srb`.

Both contacts carry the roller's normal load N (radial equilibrium of one roller without centrifugal force,
as in the frictionless normal problem). Each contact is then a point-contact problem with these radii, solved by
the point-contact models (:mod:`femcheck.problems.point_contact`): ``analytic`` (elliptic Hertz), ``bem``
(half-space BEM), ``fem`` (3D FE reference with the equivalent paraboloid on a flat block: the half-space
geometry of Hertz and the BEM). ``fem_conformal`` is the conformal sub-model: the barrel-roller segment and
each raceway segment meshed with their real curvatures, two-body node-to-surface contact
(:mod:`femcheck.fem.srb_conformal`). ``calculix`` (selected with --models) solves the same conformal meshes
in CalculiX (:mod:`femcheck.export.calculix_model`). ``cect`` is the conformal half-space normal problem (the exact
gap of the real surfaces on the developed grid, Kalker's developed half-space coefficients) and ``fem_finite_body``
the same problem with finite-body influence coefficients (the whole roller and two ring segments by FE, certified
in three parts: :mod:`femcheck.problems._srb_normal_fb`). Quantities carry the suffix ``_inner`` / ``_outer``.
"""
from __future__ import annotations

from typing import Any, Callable

from ..fem import srb_conformal
from ..geometry.srb import radii
from ..result import ModelResult
from ..scene import Key, Scene, build_scene, check_body_pair, material_keys, model_keys, tolerance_key
from . import _srb_normal_fb, point_contact

CONTACTS = ("inner", "outer")
MODEL_NAMES = ("analytic", "bem", "fem", "fem_conformal", "calculix", "cect", "fem_finite_body")

SCHEMA: dict[str, Key] = {
    "geometry.roller_diameter": Key("float", "m", "roller nominal diameter D", lo=0.0),
    "geometry.crown_radius": Key("float", "m", "roller crown radius R", lo=0.0),
    "geometry.groove_radius_inner": Key("float", "m", "inner-race groove curvature radius r_I (> R)", lo=0.0),
    "geometry.groove_radius_outer": Key("float", "m", "outer-race groove curvature radius r_E (> R)", lo=0.0),
    "geometry.contact_angle": Key("float", "rad", "nominal contact angle alpha", lo=0.0, hi=0.8, lo_closed=True,
                                  hi_closed=True),
    "load.normal": Key("float", "N", "roller normal load N on each raceway", lo=0.0),
    **material_keys("roller"),
    **material_keys("ring"),
    **model_keys(MODEL_NAMES),
    **{k: v for k, v in point_contact.SCHEMA.items() if k.startswith("numerics.") and "stress" not in k},
    **srb_conformal.FEM_SCHEMA,
    **_srb_normal_fb.SCHEMA,
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
}
DEFAULTS: dict[str, Any] = {
    "materials.roller.rigid": False,
    "materials.ring.rigid": False,
    "models.run": ["analytic", "bem"],
    "models.references": ["analytic"],
    **{k: v for k, v in point_contact.DEFAULTS.items() if k.startswith("numerics.") and "stress" not in k},
    **srb_conformal.FEM_DEFAULTS,
    **_srb_normal_fb.DEFAULTS,
}
REQUIRED = ("geometry.roller_diameter", "geometry.crown_radius", "geometry.groove_radius_inner",
            "geometry.groove_radius_outer", "geometry.contact_angle", "load.normal")
DEPENDS = {"fem": {"params": ("geometry.", "load.", "materials.", "numerics.fem_"),
                   "reference": True, "coarse": {"numerics.fem_levels": 1, "numerics.fem_finite_size_check": False}},
           "fem_conformal": {"params": ("geometry.", "load.", "materials.", "numerics.conformal_"),
                             "reference": True, "coarse": {"numerics.conformal_levels": 1}},
           "fem_finite_body": {"params": ("geometry.", "load.", "materials.", "numerics.fb_", "numerics.cect_"),
                               "reference": True, "coarse": _srb_normal_fb.COARSE}}


def validate(params: dict[str, Any]) -> None:
    from ..errors import InputError

    check_body_pair(params, ("roller", "ring"))
    R = params["geometry.crown_radius"]
    for c in CONTACTS:
        if params[f"geometry.groove_radius_{c}"] <= R:
            raise InputError(f"geometry.groove_radius_{c}", f"must exceed the crown radius {R:g} m (a groove "
                             f"conforming to a barrel roller); allowed ({R:g}, inf) m")
    if params["geometry.groove_radius_outer"] <= params["geometry.roller_diameter"]:
        raise InputError("geometry.groove_radius_outer", "must exceed the roller diameter")
    for c in CONTACTS:
        point_contact.validate(_contact_params(params, c))


def _contact_params(params: dict[str, Any], contact: str) -> dict[str, Any]:
    rx, ry = radii(params)[contact]
    out = {k: v for k, v in params.items() if k.startswith(("numerics.", "load."))
           and not k.startswith(("numerics.conformal_", "numerics.cect_", "numerics.fb_"))}
    out.update({"geometry.Rx": float(rx), "geometry.Ry": float(ry), "geometry.profile": "paraboloid",
                "outputs.subsurface_stress": False, "models.run": ["analytic"], "models.references": ["analytic"]})
    for body, src in (("body1", "roller"), ("body2", "ring")):
        for k in ("E", "nu", "rigid"):
            if f"materials.{src}.{k}" in params:
                out[f"materials.{body}.{k}"] = params[f"materials.{src}.{k}"]
    return out


def contact_scene(scene: Scene, contact: str) -> Scene:
    """The point-contact scene of one raceway contact."""
    return build_scene(f"{scene.name}:{contact}", "point_contact", scene.description, [],
                       _contact_params(scene.params, contact))


def _both(name: str) -> Callable[..., ModelResult]:
    def run(scene: Scene, progress=None) -> ModelResult:
        q, stats, fields = {}, {}, {}
        for c in CONTACTS:
            if progress:
                progress(f"{name}: {c} raceway")
            res = point_contact.MODELS[name](contact_scene(scene, c), progress)
            if res.status != "ok":
                raise RuntimeError(f"{c} raceway: {res.error}")
            q.update({f"{k}_{c}": v for k, v in res.quantities.items()})
            stats[c] = res.stats
            for k in ("x", "pressure"):
                if k in res.fields:
                    fields[k if c == "inner" else f"{k}_{c}"] = res.fields[k]
            if c == "inner":
                fields.update({k: v for k, v in res.fields.items() if k.startswith("view_")})
            if "richardson" in res.stats or "finest" in res.stats:
                stats.setdefault("finest", {}).update({f"{k}_{c}": v for k, v in res.stats.get("finest", {}).items()})
            if "certificates" in res.stats:
                stats.setdefault("certificates", {}).update(
                    {f"{k}_{c}": v for k, v in res.stats["certificates"].items()})
        if any("levels" in stats[c] for c in CONTACTS):
            stats["levels"] = [{**lv, "contact": c, "level": k} for c in CONTACTS
                               for k, lv in enumerate(stats[c].get("levels", []))]
            stats["level_quantities"] = list(stats[CONTACTS[0]].get("finest", {}))
        rx = radii(scene.params)
        stats["radii"] = {c: {"Rx": rx[c][0], "Ry": rx[c][1], "Ry_over_Rx": rx[c][1] / rx[c][0]} for c in CONTACTS}
        # each raceway carries N: the runner checks the inner one as total_force, the outer one is checked here
        q["total_force"] = q["total_force_inner"]
        if abs(q["total_force_outer"] / scene["load.normal"] - 1.0) > 1e-6:
            raise RuntimeError(f"outer raceway load {q['total_force_outer']:.6g} N != {scene['load.normal']:g} N")
        return ModelResult(name, quantities=q, stats=stats, fields=fields)

    run.__doc__ = f"The point-contact ``{name}`` model on the inner and the outer raceway contact."
    return run


def fem_conformal(scene: Scene, progress=None) -> ModelResult:
    """Conformal FE sub-model: the roller segment and each raceway segment meshed, two-body node-to-surface
    contact (:mod:`femcheck.fem.srb_conformal`)."""
    return srb_conformal.model(scene.params, progress)


calculix = point_contact._by_name(
    "femcheck.export.calculix_model", False, "CalculiX (``ccx``) on the conformal sub-model's meshes, both raceway "
    "contacts, an independent FE (:mod:`femcheck.export.calculix_model`); skipped where ccx is not installed.")

def cect(scene: Scene, progress=None) -> ModelResult:
    """The conformal half-space normal contact of both raceways (:func:`femcheck.problems._srb_normal_fb.cect`)."""
    return _srb_normal_fb.cect(scene.params, progress)


def fem_finite_body(scene: Scene, progress=None) -> ModelResult:
    """The finite-body normal contact of both raceways, certified in three parts
    (:func:`femcheck.problems._srb_normal_fb.finite_body`)."""
    return _srb_normal_fb.finite_body(scene.params, progress)


MODELS: dict[str, Callable[..., ModelResult]] = {
    **{n: _both(n) for n in ("analytic", "bem", "fem")},
    "fem_conformal": fem_conformal, "calculix": calculix, "cect": cect, "fem_finite_body": fem_finite_body}


def load_of(scene: Scene) -> float:
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return point_contact.profile_scale(contact_scene(scene, "inner"))


def stress_cases(scene: Scene) -> list:
    from ..result import StressCase

    n = scene["load.normal"]
    return [StressCase(f"load={n * f:.3g} N", {"load.normal": n * f}) for f in (1e-3, 1e-2, 0.1, 1.0)]


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    return {"bem": [{"numerics.bem_cells": n} for n in (17, 33, 65, 129)]}
