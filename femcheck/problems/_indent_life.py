"""Life of a dented dry contact (indent-dry, indent-life): the pseudo-transient pass of the ``bem`` model, the full
transient of the ``bem_transient`` model (the indent's pressure solved by the BEM at every position of the pass)
and the life ratio against the indent size (seed 004 §4.2.2-4.3; :mod:`femcheck.problems._life_output`).

The solutions come from the indent kind's adapter (:mod:`femcheck.problems.indent_contact`), passed in as arguments
or callables, so this module does not import the adapter.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from ..bem import stress_history as sh
from ..ehl.outputs import additional_pressure as shoulder_amplitudes
from ..scene import Scene
from . import _life_output as life_output


def _maps(solved: dict) -> tuple[sh.PressureMap, sh.PressureMap, tuple[int, int]]:
    g = solved["grid"]
    c = (g.nx // 2, g.ny // 2)
    return (sh.PressureMap.on_grid(g, solved["smooth"].pressure), sh.PressureMap.on_grid(g, solved["dent"].pressure),
            c)


def pseudo_transient(scene: Scene, solved: dict, nu: float) -> life_output.LifeOutput:
    """Life quantities of the pass emulated from the smooth and the centred-indent solutions (``solved``: the
    dict of ``indent_contact.solve_indented``)."""
    a = solved["a"]
    pm_s, pm_d, c = _maps(solved)
    z, wz = life_output.depth_planes(scene, a)
    hist = sh.pseudo_transient_history(pm_s, pm_d, c, nu, z, wz, scene["life.window"] * a,
                                       scene["life.chi_extent"] * a, scene["life.superposition"])
    out = life_output.indent_life(hist, a, solved["p_hertz"], scene)
    out.stats["history"] = "pseudo_transient"
    return out


def size_sweep(scene: Scene, solve: Callable[[dict], dict], nu: float) -> list[dict[str, Any]]:
    """Life ratio, stress ratio and risk ratio for the diameters ``life_output.SIZE_SWEEP`` at the scene's slope
    D/Phi and decay K (each a pair of BEM solves and a pseudo-transient pass)."""
    rows = []
    for phi in life_output.SIZE_SWEEP:
        params = {**scene.params, "indent.diameter": phi}
        s = solve(params)
        out = pseudo_transient(scene.with_overrides({"indent.diameter": phi}), s, nu)
        rows.append({"diameter": phi, "life_ratio": out.quantities["life_ratio"],
                     "stress_ratio": out.quantities["stress_ratio"], "risk_ratio": out.stats["risk_ratio"],
                     "additional_pressure_over_p_hertz": s["dp"] / s["p_hertz"]})
    return rows


def crossing_additional_pressure(x: np.ndarray, y: np.ndarray, smooth: np.ndarray, frames: dict[float, np.ndarray],
                                 phi: float) -> dict[str, Any]:
    """Additional pressure dP = P - P_S (dimensionless, P = p/p_H on a grid x, y in the Hertz radius a) of an
    indent of diameter ``phi`` (in a) at the positions x_D = keys of ``frames`` (in a, on the line y = 0), two
    measures (seed 004 §3.2.1, Table 3.1):

    - ``max``/``min``/``centred``: max over the grid of dP per frame. Once a shoulder of the indent reaches the
      edge of the Hertz contact (|x_D| + 0.6 Phi ~ a, where P_S ~ 0) the shoulder there carries its own contact
      pressure and this maximum rises: measured (BEM, 129^2 and 257^2 over +-2 a, K = 4) +2.5 % (Phi = 0.5,
      D/Phi = 2) to +47 % (Phi = 1, D/Phi = 1) above the centred value, +46 % at Phi = 0.5, D/Phi = 0.5;
      ``max_at`` is the x_D of that maximum.
    - ``inner_*``: the amplitude of the shoulder on the contact-centre side of the indent (the front sector,
      downstream, while the indent enters, x_D < 0; the rear one while it leaves; the larger at x_D = 0), read as
      femcheck's EHL shoulder amplitudes (:func:`femcheck.ehl.outputs.additional_pressure`). That shoulder stays
      inside the contact over the crossing; its amplitude is the one seed 004 finds constant:
      ``table_3_1_difference`` = |dP_inner(x_D = 0) - max dP_inner|/max dP_inner, the measure of Table 3.1
      (thesis: < 1 %, < 1 %, < 1 %, 2 % for Phi = 0.5, 1 and D/Phi = 1, 2 at K = 4; femcheck 129^2:
      0.2, 0.1, 1.2, 3.5 %)."""
    dp = {xd: f - smooth for xd, f in frames.items()}
    glob = {xd: float(d.max()) for xd, d in dp.items()}
    inner = {}
    for xd, d in dp.items():
        a = shoulder_amplitudes(x, y, d, xd, 0.0, phi)
        side = [a["front"]] if xd < 0 else [a["rear"]] if xd > 0 else [a["front"], a["rear"]]
        side = [v for v in side if np.isfinite(v)]
        if side:
            inner[xd] = max(side)
    centre = min(frames, key=abs)
    at = max(glob, key=glob.get)
    out = {"centred": glob[centre], "max": glob[at], "min": min(glob.values()), "max_at": at}
    if inner:
        top = max(inner.values())
        out.update({"inner_centred": inner.get(centre, float("nan")), "inner_max": top,
                    "inner_min": min(inner.values()),
                    "table_3_1_difference": abs(inner.get(centre, float("nan")) - top) / top})
    return out


def transient(scene: Scene, solved: dict, solve_at: Callable[[float], np.ndarray], nu: float,
              domain: float) -> life_output.LifeOutput:
    """Full transient pass: the indent solved at every cell position x_D with |x_D| <= min(1 + Phi, domain -
    Phi/2) a (until its shoulders leave the contact, within the BEM domain); beyond, the smooth pressure. The
    additional pressure left at the end frames is reported (``end_frame_additional_pressure``), and the additional
    pressure over the frames with the indent centre in the contact, |x_D| <= a, by the two measures of
    :func:`crossing_additional_pressure` (``additional_pressure_in_contact``, in p_H)."""
    a, g = solved["a"], solved["grid"]
    phi = scene["indent.diameter"]
    reach = min(1.0 + phi, domain - 0.5 * phi) * a
    m = int(np.floor(reach / g.dx + 1e-9))
    pm_s, _, c = _maps(solved)
    frames = {}
    for s in range(-m, m + 1):
        frames[s] = solved["dent"].pressure if s == 0 else solve_at(s * g.dx)
    z, wz = life_output.depth_planes(scene, a)
    hist = sh.transient_history(pm_s, frames, c, nu, z, wz, scene["life.window"] * a)
    out = life_output.indent_life(hist, a, solved["p_hertz"], scene)
    end = max(float(np.abs(frames[s] - pm_s.pressure).max()) for s in (-m, m)) / solved["p_hertz"]
    ph = solved["p_hertz"]
    inside = {s * g.dx / a: frames[s] / ph for s in frames if abs(s * g.dx) <= a}
    dp = crossing_additional_pressure(g.x / a, g.y / a, pm_s.pressure / ph, inside, phi)
    out.stats.update({"history": "transient", "frames": 2 * m + 1, "frame_reach": m * g.dx / a,
                      "end_frame_additional_pressure": end, "additional_pressure_in_contact": dp})
    return out
