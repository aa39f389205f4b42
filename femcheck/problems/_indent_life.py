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


def transient(scene: Scene, solved: dict, solve_at: Callable[[float], np.ndarray], nu: float,
              domain: float) -> life_output.LifeOutput:
    """Full transient pass: the indent solved at every cell position x_D with |x_D| <= min(1 + Phi, domain -
    Phi/2) a (until its shoulders leave the contact, within the BEM domain); beyond, the smooth pressure. The
    additional pressure left at the end frames is reported (``end_frame_additional_pressure``)."""
    a, g = solved["a"], solved["grid"]
    phi = scene["indent.diameter"]
    reach = min(1.0 + phi, domain - 0.5 * phi) * a
    m = int(np.floor(reach / g.dx + 1e-9))
    pm_s, _, c = _maps(solved)
    frames, dp_max = {}, []
    for s in range(-m, m + 1):
        p = solved["dent"].pressure if s == 0 else solve_at(s * g.dx)
        frames[s] = p
        dp_max.append(float((p - pm_s.pressure).max()) / solved["p_hertz"])
    z, wz = life_output.depth_planes(scene, a)
    hist = sh.transient_history(pm_s, frames, c, nu, z, wz, scene["life.window"] * a)
    out = life_output.indent_life(hist, a, solved["p_hertz"], scene)
    end = max(float(np.abs(frames[s] - pm_s.pressure).max()) for s in (-m, m)) / solved["p_hertz"]
    inside = [d for s, d in zip(range(-m, m + 1), dp_max) if abs(s * g.dx) <= a]
    out.stats.update({"history": "transient", "frames": 2 * m + 1, "frame_reach": m * g.dx / a,
                      "end_frame_additional_pressure": end,
                      "additional_pressure_in_contact": {"centred": dp_max[m], "max": max(inside),
                                                         "min": min(inside)}})
    return out
