"""Elastohydrodynamically lubricated point / elliptical contact, smooth or with a passing indent (seed 004
§2.3, §2.6, ch. 3; spec ehl-life.md part A).

Inputs: physical (``geometry.Rx``, ``geometry.Ry``, ``load.normal``, materials, ``lubricant.*``,
``kinematics.mean_speed``) or the Moes groups ``ehl.M``, ``ehl.L``, which then replace the speed and the load
(the radii, the moduli and the lubricant stay). With ``indent.*`` keys the indent (seed 004 eq 2.16; Phi in the
Hertz semi-axis b along the rolling direction, D/Phi with D in b^2/Rx, decay K) enters at the inlet and is
marched with the surface at u_D = u_m (1 + slide_roll) through the centre of the contact, where the additional
pressures are taken, and out through the exit (X_D = 1 + 1.5 Phi; :func:`femcheck.ehl.model.crossing_steps`).

Models: ``ehl`` (FAS/FMG multigrid, NU2 transient; :mod:`femcheck.ehl`), ``moes`` (Nijenbanning-Venner-Moes
central film), ``hamrock_dowson`` (central and minimum film), ``dry`` (half-space BEM: Hertz p_max, and with an
indent its additional pressure, the upper bound of the lubricated one).
Quantities: ``h_central``, ``h_min`` (m), ``p_max`` (Pa), ``H_central_moes``, ``H_min_moes`` (h/Rx U_M^-1/2, U_M on
the sum speed), ``load_error``; with an indent ``additional_pressure`` (the largest dP on the indent's shoulders,
Pa), ``additional_pressure_rear|front|lateral|centre`` (Pa) and, for the record, ``additional_pressure_disc_max``
(max dP within 1.5 Phi, which for large indents also reads the outlet spike; :mod:`femcheck.ehl.outputs`).
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from ..ehl import formulas
from ..ehl.adapter import INDENT_KEYS, has_indent, operating_point
from ..ehl.lubricant import DENSITY_LAWS, VISCOSITY_LAWS, roelands_z
from ..ehl.model import default_y_half
from ..errors import InputError
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, material_keys, model_keys, tolerance_key

MODEL_NAMES = ("ehl", "moes", "hamrock_dowson", "dry")
# What a designer reads first: the minimum film (lambda ratio, wear), then the central film, the dent's
# additional pressure (life), the peak pressure
DESIGN_QUANTITIES = ("h_min", "H_min_moes", "h_central", "H_central_moes", "additional_pressure", "p_max")
# The Moes groups replace the load and the speed: the ones given last (an override over the scene file) win
ALTERNATIVES = ((("load.normal", "kinematics.mean_speed"), ("ehl.M", "ehl.L")),)
M_RANGE = (5.0, 2000.0)          # Moes M the solver is tested on (thesis range 100-1200, 1000 at L = 2)
L_RANGE = (1.0, 25.0)

SCHEMA: dict[str, Key] = {
    "geometry.Rx": Key("float", "m", "relative radius of curvature in the rolling direction x", lo=0.0),
    "geometry.Ry": Key("float", "m", "relative radius of curvature across (Ry >= Rx)", lo=0.0),
    "load.normal": Key("float", "N", "normal load (replaced by ehl.M, ehl.L when given)", lo=0.0),
    **material_keys("body1"),
    **material_keys("body2"),
    "lubricant.viscosity": Key("float", "Pa s", "ambient dynamic viscosity eta0", lo=0.0),
    "lubricant.pressure_viscosity": Key("float", "1/Pa", "pressure-viscosity coefficient alpha", lo=0.0,
                                        hi=1e-7, hi_closed=True),
    "lubricant.viscosity_law": Key("str", "-", "eta(p)", choices=VISCOSITY_LAWS),
    "lubricant.density_law": Key("str", "-", "rho(p)", choices=DENSITY_LAWS),
    "kinematics.mean_speed": Key("float", "m/s", "mean rolling speed u_m = (u1 + u2)/2", lo=0.0),
    "kinematics.slide_roll": Key("float", "-", "slide-to-roll ratio of the indented surface, u_D = u_m (1 + s)",
                                 lo=-0.5, hi=0.5, lo_closed=True, hi_closed=True),
    "ehl.M": Key("float", "-", "Moes load parameter M = W U^-3/4 (with ehl.L: replaces load and speed)",
                 lo=M_RANGE[0], hi=M_RANGE[1], lo_closed=True, hi_closed=True),
    "ehl.L": Key("float", "-", "Moes lubricant parameter L = G U^1/4", lo=L_RANGE[0], hi=L_RANGE[1],
                 lo_closed=True, hi_closed=True),
    "indent.diameter": Key("float", "b", "indent diameter Phi / Hertz semi-axis b", lo=0.1, hi=1.0,
                           lo_closed=True, hi_closed=True),
    "indent.slope": Key("float", "-", "indent slope D/Phi (D in b^2/Rx)", lo=0.0, hi=2.0, hi_closed=True),
    "indent.decay": Key("float", "-", "shoulder decay K", lo=2.0, hi=10.0, lo_closed=True, hi_closed=True),
    "numerics.grid": Key("int", "-", "nodes per side of the finest grid (2^k + 1)", lo=33, hi=1025,
                         lo_closed=True, hi_closed=True),
    "numerics.levels": Key("int", "-", "multigrid levels (default: coarsest grid of 17^2 nodes)", lo=2, hi=8,
                           lo_closed=True, hi_closed=True),
    "numerics.refinements": Key("int", "-", "grids solved for the convergence certificate (finest, /2, /4 ...; a "
                                "coarse grid that does not resolve the contact is left out and said so)", lo=1, hi=4,
                                lo_closed=True, hi_closed=True),
    "numerics.x_start": Key("float", "b", "inlet end of the domain / b", lo=-10.0, hi=-1.5, lo_closed=True,
                            hi_closed=True),
    "numerics.x_end": Key("float", "b", "outlet end of the domain / b", lo=1.2, hi=4.0,
                          lo_closed=True, hi_closed=True),
    "numerics.y_half": Key("float", "b", "half-width of the domain across / b (default: (x_end - x_start)/2 for a "
                           "circle, (x_end - x_start)/(2 kappa) for an ellipse, kappa = b/a)", lo=0.5, hi=40.0,
                           lo_closed=True, hi_closed=True),
    "numerics.snapshots": Key("int", "-", "pressure fields kept per crossing (evenly spaced steps over the whole "
                              "crossing, plus the centred X_D = 0 and the last)", lo=1, hi=10000, lo_closed=True,
                              hi_closed=True),
    "numerics.tol": Key("float", "-", "mean scaled residual per solve", lo=0.0, hi=1e-4, hi_closed=True),
    "numerics.load_tol": Key("float", "-", "relative load error per solve (and per time step)", lo=0.0,
                             hi=1e-6, hi_closed=True),
    "numerics.bem_cells": Key("int", "-", "dry BEM cells per side (odd)", lo=33, hi=1025, lo_closed=True,
                              hi_closed=True),
    **model_keys(MODEL_NAMES),
    "tolerances.*.*": tolerance_key("relative tolerance (or band, for contrasts) of model.quantity"),
}
DEFAULTS: dict[str, Any] = {
    "materials.body1.rigid": False,
    "materials.body2.rigid": False,
    "lubricant.viscosity_law": "roelands",
    "lubricant.density_law": "dowson_higginson",
    "kinematics.slide_roll": 0.0,
    "models.run": list(MODEL_NAMES),
    "models.references": ["ehl"],
    "models.contrast": ["moes", "hamrock_dowson", "dry"],
    "numerics.grid": 129,
    "numerics.refinements": 1,
    "numerics.x_start": -4.5,
    "numerics.x_end": 1.5,
    "numerics.tol": 1e-7,
    "numerics.snapshots": 16,
    "numerics.load_tol": 1e-7,
    "numerics.bem_cells": 193,
}
REQUIRED = ("geometry.Rx", "geometry.Ry", "lubricant.viscosity", "lubricant.pressure_viscosity")
DEPENDS: dict[str, dict] = {
    "ehl": {"params": ("geometry.", "load.", "materials.", "lubricant.", "kinematics.", "ehl.", "indent.",
                       "numerics.grid", "numerics.levels", "numerics.refinements", "numerics.x_", "numerics.y_half", "numerics.tol",
                       "numerics.snapshots",
                       "numerics.load_tol"),
            "reference": True},
}


def validate(params: dict[str, Any]) -> None:
    check_body_pair(params, ("body1", "body2"))
    if ("ehl.M" in params) != ("ehl.L" in params):
        raise InputError("ehl.L" if "ehl.M" in params else "ehl.M", "give both ehl.M and ehl.L (or neither)")
    if "ehl.M" not in params:
        for k in ("load.normal", "kinematics.mean_speed"):
            if k not in params:
                raise InputError(k, "required (or give the Moes groups ehl.M and ehl.L)")
    if has_indent(params) and not all(k in params for k in INDENT_KEYS):
        missing = next(k for k in INDENT_KEYS if k not in params)
        raise InputError(missing, "an indent needs indent.diameter, indent.slope and indent.decay")
    if params["geometry.Rx"] > params["geometry.Ry"]:
        raise InputError("geometry.Ry", f"{params['geometry.Ry']:g} m < Rx; allowed: Ry >= Rx (x is the rolling "
                         "direction, across which the contact is narrow)")
    n = params["numerics.grid"] - 1
    if n & (n - 1):
        raise InputError("numerics.grid", f"{n + 1} is not 2^k + 1; allowed: 33, 65, 129, 257, 513, 1025")
    levels = params.get("numerics.levels")
    if levels is not None and n >> (levels - 1) < 8:
        raise InputError("numerics.levels", f"{levels} levels on a {n + 1}^2 grid leave fewer than 8 intervals on "
                         f"the coarsest; allowed: 2 .. {int(np.log2(n)) - 2}")
    if (n >> (params["numerics.refinements"] - 1)) < 16:
        raise InputError("numerics.refinements", f"{params['numerics.refinements']} grids below {n + 1}^2 go under "
                         "17^2 nodes; allowed here: up to " + str(int(np.log2(n)) - 3))
    if params["lubricant.viscosity_law"] == "roelands":
        try:
            roelands_z(params["lubricant.viscosity"], params["lubricant.pressure_viscosity"])
        except ValueError:
            raise InputError("lubricant.viscosity", f"{params['lubricant.viscosity']:g} Pa s is below the Roelands "
                             "limit; allowed: (6.31e-5, inf) Pa s") from None
    g = operating_point(params)
    if "ehl.M" not in params:      # given Moes groups are checked against the same ranges by the schema
        for name, v, (lo, hi) in (("M", g.M, M_RANGE), ("L", g.L, L_RANGE)):
            if not lo <= v <= hi:
                key = "load.normal" if name == "M" else "kinematics.mean_speed"
                raise InputError(key, f"gives Moes {name} = {v:.4g}; allowed: {name} in [{lo:g}, {hi:g}] (the range "
                                 "the EHL solver supports)")
    if g.b / g.Rx > 0.1:
        raise InputError("load.normal", f"gives b/Rx = {g.b / g.Rx:.3g} > 0.1 (half-space theory fails)")
    half = params.get("numerics.y_half") or default_y_half(g, params["numerics.x_start"], params["numerics.x_end"])
    if half is None:
        half = 0.5 * (params["numerics.x_end"] - params["numerics.x_start"])
    if half < 1.2 / g.kappa:
        key = "numerics.y_half" if "numerics.y_half" in params else "numerics.x_start"
        raise InputError(key, f"the domain's half-width across {half:g} b does not hold the contact "
                         f"(a/b = {1 / g.kappa:.3g}); allowed: >= {1.2 / g.kappa:.3g} b")


def ehl(scene: Scene, progress=None) -> ModelResult:
    from ..ehl.adapter import run

    return run(scene.params, progress)


def moes(scene: Scene, progress=None) -> ModelResult:
    """Nijenbanning, Venner & Moes (1994) central film (Barus, incompressible; spec §A.8)."""
    g = operating_point(scene.params)
    H = formulas.moes_central(g.M, g.L, g.Rx / g.Ry)
    return ModelResult("moes", quantities={"H_central_moes": H, "h_central": H * np.sqrt(g.U_moes) * g.Rx},
                       stats={"M": g.M, "L": g.L, "D": g.Rx / g.Ry})


def hamrock_dowson(scene: Scene, progress=None) -> ModelResult:
    """Hamrock & Dowson (1977) central and minimum film, mean speed (spec §A.8)."""
    g = operating_point(scene.params)
    hc, hm = formulas.hamrock_dowson(g.U_hd, g.G, g.W, g.a / g.b)
    s = np.sqrt(g.U_moes)
    return ModelResult("hamrock_dowson", quantities={"h_central": hc * g.Rx, "h_min": hm * g.Rx,
                                                     "H_central_moes": hc / s, "H_min_moes": hm / s},
                       stats={"U": g.U_hd, "G": g.G, "W": g.W, "k": g.a / g.b})


def dry(scene: Scene, progress=None) -> ModelResult:
    """Dry contact under the same load: Hertz p_max by the half-space BEM and, with an indent, the dry additional
    pressure (femcheck's ``indent-dry`` BEM, circular contacts)."""
    from . import indent_contact

    p = scene.params
    g = operating_point(p)
    if not has_indent(p):
        from ..analytic import hertz

        h = hertz.elliptic_contact(g.load, g.Rx, g.Ry, 0.5 * g.e_prime)
        return ModelResult("dry", quantities={"p_max": h.p_max}, stats={"model": "Hertz"})
    if g.Rx != g.Ry:
        return ModelResult("dry", status="skipped", error="the dry indent BEM (indent-dry) is for circular contacts")
    keys = {"geometry.radius": g.Rx, "load.normal": g.load, "numerics.bem_cells": p["numerics.bem_cells"],
            "numerics.bem_domain": 1.6, "numerics.bem_tol": 1e-10,
            **{k: v for k, v in p.items() if k.startswith("materials.")},
            **{k: p[k] for k in INDENT_KEYS}}
    s = indent_contact.solve_indented(keys)
    return ModelResult("dry", quantities={"additional_pressure": s["dp"]},
                       stats={"iterations": s["dent"].iterations, "residual": s["dent"].residual,
                              "additional_pressure_over_p_hertz": s["dp"] / s["p_hertz"],
                              "cells_per_indent_diameter": s["phi"] / s["grid"].dx,
                              "p_max_indented": float(s["dent"].pressure.max())})


MODELS: dict[str, Callable[..., ModelResult]] = {"ehl": ehl, "moes": moes, "hamrock_dowson": hamrock_dowson,
                                                  "dry": dry}


def load_of(scene: Scene) -> float:
    return operating_point(scene.params).load


def profile_scale(scene: Scene) -> float:
    return operating_point(scene.params).b


def stress_cases(scene: Scene) -> list:
    """The thesis range M = 100-1200, L = 3-19 (corners) and high M / low L (1000, 2), smooth contact."""
    from ..result import StressCase

    drop = {k: None for k in INDENT_KEYS}
    return [StressCase(f"M={M:g}, L={L:g}", {"ehl.M": M, "ehl.L": L, "numerics.grid": 257, **drop})
            for M, L in ((100, 3), (100, 19), (1200, 3), (1200, 19), (1000, 2))]


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """Steady: 65^2 - 257^2 (257^2 under 60 s); indent crossing: 65^2 and 129^2 (under 2 min)."""
    grids = (65, 129) if has_indent(scene.params) else (65, 129, 257)
    return {"ehl": [{"numerics.grid": n, "numerics.refinements": 1} for n in grids]}
