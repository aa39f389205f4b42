"""The ``life`` output of the contact kinds (point, line, roller, indent): scene keys and the step from a
pressure solution to the life quantities (seed 004 ch. 4; :mod:`femcheck.analytic.life`,
:mod:`femcheck.bem.stress_history`).

Keys: ``outputs.life`` (computed only when true), ``life.c``, ``life.e``, ``life.h``, ``life.fatigue_limit`` (Pa),
``life.window`` w, ``numerics.life_depths``, ``numerics.life_depth_max``; indents add ``life.indent_fraction``,
``life.chi_extent``, ``life.superposition`` and ``life.size_sweep``.

Integration window (the thesis leaves it open; its dry runs use [-2, 2] x [-2, 2] b): [-w a_x, w a_x] along the
rolling direction x and [-w a_y, w a_y] across (a_x, a_y: the Hertz semi-axes; a roller: its whole length across,
a line contact: per unit length), depth (0, life_depth_max a_x]. Default w = 2. A smooth contact's history does not
depend on x, so there the window along x only sets the track length l_w = 2 w a_x the risk integral belongs to;
an indent's risk integral depends on the window (the smooth part grows with its area; spec B.2).

Quantities (SI): ``risk_integral`` I over the window (Pa^c m^(3-h); line contacts per unit length,
Pa^c m^(2-h)), ``fatigue_life`` the relative life of 1 mm of track (:func:`femcheck.analytic.life.relative_life`;
+inf when nothing exceeds the fatigue limit), ``stress_history_max`` T_max (Pa); indents also
``risk_integral_smooth`` I_S, ``life_ratio`` L/L_S = [1 + f_d (I_D/I_S - 1)]^(-1/e) and ``stress_ratio``
T_Dmax/T_Smax.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..analytic import life
from ..bem import stress_history as sh
from ..errors import InputError
from ..scene import Key, Scene

DEFAULT_WINDOW = 2.0
DEFAULT_DEPTHS = 24
DEFAULT_DEPTH_MAX = 2.0
LINE_DEPTH_MAX = 4.0
SIZE_SWEEP = (0.25, 0.5, 0.75, 1.0)      # indent diameters Phi (a) of the life-ratio-vs-size sweep


def keys(indent: bool = False) -> dict[str, Key]:
    """The ``life`` keys of a kind (indent kinds get the three indent keys too)."""
    k = {
        "outputs.life": Key("bool", "-", "rolling-contact fatigue life: risk integral of the von Mises amplitude "
                            "history, Weibull life (seed 004 ch. 4)"),
        "life.c": Key("float", "-", "stress exponent c of the risk integral (LP 31/3; thesis 6.3-11.3)", lo=1.0,
                      hi=life.C_MAX, lo_closed=True, hi_closed=True),
        "life.e": Key("float", "-", "Weibull slope e (LP: 10/9 point, 9/8 line)", lo=0.0, hi=10.0, hi_closed=True),
        "life.h": Key("float", "-", "depth exponent h (0: no depth weight; LP 7/3)", lo=0.0, hi=10.0,
                      lo_closed=True, hi_closed=True),
        "life.fatigue_limit": Key("float", "Pa", "fatigue limit tau_inf of the von Mises amplitude", lo=0.0,
                                  lo_closed=True),
        "life.window": Key("float", "a_H", "integration window half-side w: [-w a_x, w a_x] along x, [-w a_y, w a_y] "
                           "across (roller: its whole length)", lo=1.0, hi=4.0, lo_closed=True, hi_closed=True),
        "numerics.life_depths": Key("int", "-", "depth planes of the life stress field (graded to the surface)",
                                    lo=4, hi=200, lo_closed=True, hi_closed=True),
        "numerics.life_depth_max": Key("float", "a_H", "deepest life stress plane / Hertz semi-axis x", lo=0.5,
                                       hi=10.0, lo_closed=True, hi_closed=True),
    }
    if indent:
        k.update({
            "life.indent_fraction": Key("float", "-", "fraction f_d of the track's windows that hold an indent", lo=0.0,
                                        hi=1.0, lo_closed=True, hi_closed=True),
            "life.chi_extent": Key("float", "a", "pseudo-transient: the indent's extra stress counts while its "
                                   "centre is within this distance of the contact centre", lo=0.05, hi=2.0,
                                   lo_closed=True, hi_closed=True),
            "life.size_sweep": Key("bool", "-", f"also compute the life ratio for Phi = {SIZE_SWEEP} (same slope "
                                   "and K)"),
            "life.superposition": Key("str", "-", "pseudo-transient: contact (emulated pressure kept >= 0, default) "
                                      "or linear (seed 004 eq 4.5 as printed)", choices=sh.SUPERPOSITIONS),
        })
    return k


def defaults(e: float, indent: bool = False, depth_max: float = DEFAULT_DEPTH_MAX) -> dict[str, Any]:
    """Default life keys. ``depth_max`` (a_H): 2 for point contacts (the history at 2a is below 0.3 p_H: the risk
    integral without fatigue limit changes by 7e-5 from 2a to 4a), 4 for line contacts (their stresses decay
    like a/z: 2a misses 2 % of it, 4a 0.03 %)."""
    d = {"outputs.life": False, "life.c": 8.0, "life.e": e, "life.h": 0.0, "life.fatigue_limit": 0.0,
         "life.window": DEFAULT_WINDOW, "numerics.life_depths": DEFAULT_DEPTHS,
         "numerics.life_depth_max": depth_max}
    if indent:
        d.update({"life.indent_fraction": 1.0, "life.chi_extent": 1.0, "life.size_sweep": False,
                  "life.superposition": "contact"})
    return d


def constants(params: dict[str, Any]) -> life.LifeConstants:
    return life.LifeConstants(params["life.c"], params["life.e"], params["life.h"], params["life.fatigue_limit"])


def check_body(params: dict[str, Any], body: str) -> None:
    if params.get("outputs.life") and params.get(f"materials.{body}.rigid", False):
        raise InputError("outputs.life", f"the life is computed from the stresses in {body}, which is rigid")


def depth_planes(scene: Scene, a: float) -> tuple[np.ndarray, np.ndarray]:
    return life.depth_planes(scene["numerics.life_depth_max"] * a, scene["numerics.life_depths"])


@dataclass
class LifeOutput:
    quantities: dict[str, float]
    stats: dict[str, Any]
    fields: dict[str, np.ndarray] = field(default_factory=dict)


def _common_stats(c: life.LifeConstants, window: float, depths: np.ndarray, p_hertz: float, t_max: float) -> dict:
    return {"c": c.c, "e": c.e, "h": c.h, "fatigue_limit": c.fatigue_limit, "window": window,
            "depth_planes": int(depths.size), "depth_max": float(depths[-1]), "p_hertz": p_hertz,
            "fatigue_limit_over_max": c.fatigue_limit / t_max if t_max > 0 else None,
            "depth_weight_floor": life.Z_FLOOR}


def _life_of(risk_per_length: float, c: life.LifeConstants) -> float:
    return life.relative_life(risk_per_length, c)


def surface_life(hist: sh.StressHistory, a_x: float, p_hertz: float, scene: Scene) -> LifeOutput:
    """Life of a smooth 3D contact from its history T_S(y, z): the window along x is the track length
    l_w = 2 w a_x; risk per track length R = sum T-density wz wy."""
    c = constants(scene.params)
    w = scene["life.window"]
    zf = life.depth_weight(hist.depths, c.h, a_x)[:, None]
    weights = hist.depth_weights[:, None] * hist.y_weights[None, :]
    per_length = life.risk_integral(hist.smooth, weights, c, zf)
    track = 2.0 * w * a_x
    m = sh.refined_max(hist.smooth, [hist.depths, hist.y])
    q = {"risk_integral": per_length * track, "fatigue_life": _life_of(per_length, c), "stress_history_max": m["value"]}
    stats = {**_common_stats(c, w, hist.depths, p_hertz, m["value"]), "track_window_length": track,
             "risk_per_track_length": per_length,
             "stress_history_max_at": {"depth": m["position"][0], "y": m["position"][1]},
             "stressed_area": float(np.sum(weights * (hist.smooth > c.fatigue_limit))),
             "risk_integral_bar": life.dimensionless_risk(per_length * track, p_hertz, a_x, c),
             "infinite_life": per_length == 0.0, **hist.stats}
    f = {"life_section": hist.smooth, "life_section_h": hist.y, "life_section_z": hist.depths}
    return LifeOutput(q, stats, f)


def line_life(T: np.ndarray, depths: np.ndarray, depth_weights: np.ndarray, a: float, p_hertz: float,
              scene: Scene, length: float | None = None) -> LifeOutput:
    """Life of a line contact from T_S(z): per unit length (``length`` None) or for a roller of ``length`` (m).
    Risk per track length per unit length R' = sum T-density wz; the life is that of 1 mm of track of a 1 mm
    slice (line) or of the whole roller."""
    c = constants(scene.params)
    w = scene["life.window"]
    per = life.risk_integral(T, depth_weights, c, life.depth_weight(depths, c.h, a))
    span = length if length is not None else life.REFERENCE_LENGTH
    track = 2.0 * w * a
    m = sh.refined_max(T, [depths])
    q = {"risk_integral": per * track * (length if length is not None else 1.0),
         "fatigue_life": _life_of(per * span, c), "stress_history_max": m["value"]}
    stats = {**_common_stats(c, w, depths, p_hertz, m["value"]), "track_window_length": track,
             "risk_per_track_length": per * (length if length is not None else 1.0),
             "per_unit_length": length is None, "stress_history_max_at": {"depth": m["position"][0]},
             "stressed_depth": float(np.sum(depth_weights * (T > c.fatigue_limit))), "infinite_life": per == 0.0}
    return LifeOutput(q, stats, {"life_profile": T, "life_profile_z": depths})


def indent_life(hist: sh.StressHistory, a: float, p_hertz: float, scene: Scene) -> LifeOutput:
    """Life of an indented contact from a pass history (pseudo-transient or transient): I_S and I_D over the same
    window with the same weights (a depth-0 indent gives I_D = I_S bit for bit, life ratio exactly 1)."""
    c = constants(scene.params)
    w, fd = scene["life.window"], scene["life.indent_fraction"]
    weights = hist.depth_weights[:, None, None] * hist.xi_weights[None, :, None] * hist.y_weights[None, None, :]
    zf = life.depth_weight(hist.depths, c.h, a)[:, None, None]
    smooth = np.broadcast_to(hist.smooth[:, None, :], hist.amplitude.shape)
    I_S = life.risk_integral(smooth, weights, c, zf)
    I_D = life.risk_integral(hist.amplitude, weights, c, zf)
    ratio = life.risk_ratio(I_D, I_S)
    track = float(np.sum(hist.xi_weights))
    per_length = (I_S + fd * (I_D - I_S)) / track
    ts = sh.refined_max(hist.smooth, [hist.depths, hist.y])
    td = sh.refined_max(hist.amplitude, [hist.depths, hist.xi, hist.y])
    q = {"risk_integral": I_D, "risk_integral_smooth": I_S,
         "fatigue_life": _life_of(max(per_length, 0.0), c),
         "life_ratio": life.dented_life_ratio(ratio, fd, c.e),
         "stress_ratio": td["value"] / ts["value"], "stress_history_max": td["value"]}
    j = hist.y.size // 2          # the window across is centred on the indent's track
    stats = {**_common_stats(c, w, hist.depths, p_hertz, ts["value"]), "indent_fraction": fd,
             "risk_ratio": ratio, "track_window_length": track,
             "stress_history_max_smooth": ts["value"],
             "stress_history_max_at": {"depth": td["position"][0], "xi": td["position"][1], "y": td["position"][2]},
             "risk_integral_bar": life.dimensionless_risk(I_D, p_hertz, a, c),
             "risk_integral_bar_smooth": life.dimensionless_risk(I_S, p_hertz, a, c),
             "stressed_volume": float(np.sum(weights * (hist.amplitude > c.fatigue_limit))),
             "stressed_volume_smooth": float(np.sum(weights * (smooth > c.fatigue_limit))),
             "infinite_life": per_length == 0.0, **hist.stats}
    f = {"life_section": hist.amplitude[:, :, j], "life_section_h": hist.xi, "life_section_z": hist.depths,
         "life_smooth_profile": hist.smooth[:, j]}
    return LifeOutput(q, stats, f)


# ---------------------------------------------------------------------------------------------------------------
# one call per kind (the adapters' hunks stay small)
# ---------------------------------------------------------------------------------------------------------------

def point_life(scene: Scene, grid, pressure: np.ndarray, a_x: float, a_y: float, p_hertz: float,
               nu: float) -> LifeOutput:
    """Smooth point / elliptical contact: history across [-w a_y, w a_y], the track window 2 w a_x."""
    z, wz = depth_planes(scene, a_x)
    hist = sh.smooth_history(sh.PressureMap.on_grid(grid, pressure), nu, z, wz, scene["life.window"] * a_y)
    return surface_life(hist, a_x, p_hertz, scene)


def roller_life(scene: Scene, grid, pressure: np.ndarray, a: float, p_hertz: float, nu: float) -> LifeOutput:
    """Finite roller: history over the whole grid across (the roller and its margins)."""
    z, wz = depth_planes(scene, a)
    hist = sh.smooth_history(sh.PressureMap.on_grid(grid, pressure), nu, z, wz, None)
    return surface_life(hist, a, p_hertz, scene)


def line_life_closed_form(scene: Scene, a: float, p_hertz: float, nu: float,
                          length: float | None = None) -> LifeOutput:
    """Hertz line contact, McEwen's stresses (:func:`femcheck.analytic.life.mcewen_history`)."""
    z, wz = depth_planes(scene, a)
    return line_life(life.mcewen_history(a, p_hertz, nu, z), z, wz, a, p_hertz, scene, length)


def line_life_strips(scene: Scene, pressure: np.ndarray, dx: float, a: float, p_hertz: float,
                     nu: float) -> LifeOutput:
    """Plane-strain BEM pressure on strips (:func:`femcheck.bem.stress_history.line_history`)."""
    z, wz = depth_planes(scene, a)
    return line_life(sh.line_history(pressure, dx, nu, z), z, wz, a, p_hertz, scene)
