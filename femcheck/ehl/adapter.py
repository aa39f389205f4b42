"""Scene parameters -> EHL runs -> :class:`ModelResult` (SI quantities, certificates, fields for the report and
for the fatigue-life model: the smooth and the centred-indent pressure for a pseudo-transient pass, kept steps of
the whole crossing for a transient one). Kept apart from the problem kind so that the stored ``ehl`` references
hash the EHL code only."""
from __future__ import annotations

import time
from typing import Any

import numpy as np

from ..materials import effective_modulus
from ..result import ModelResult
from ..scene import elastic
from ..errors import ConvergenceError
from ..solvers.convergence import certify
from . import failures, groups, model

INDENT_KEYS = ("indent.diameter", "indent.slope", "indent.decay")
FILM_QUANTITIES = ("h_central", "h_min", "p_max", "H_central_moes", "H_min_moes")
DP_NAMES = ("rear", "front", "lateral", "centre")


def e_prime(params: dict[str, Any]) -> float:
    """E' = 2 E* (seed 004 eq 2.3)."""
    return 2.0 * effective_modulus(elastic(params, "body1"), elastic(params, "body2"))


def operating_point(params: dict[str, Any]) -> groups.Groups:
    """Groups from the physical keys, or from ehl.M, ehl.L (which replace load and speed)."""
    rx, ry = params["geometry.Rx"], params["geometry.Ry"]
    eta0, alpha = params["lubricant.viscosity"], params["lubricant.pressure_viscosity"]
    if "ehl.M" in params:
        return groups.from_moes(params["ehl.M"], params["ehl.L"], rx, ry, e_prime(params), eta0, alpha)
    return groups.from_physical(rx, ry, e_prime(params), params["load.normal"], eta0, alpha,
                                params["kinematics.mean_speed"])


def has_indent(params: dict[str, Any]) -> bool:
    return any(k in params for k in INDENT_KEYS)


def setup(params: dict[str, Any], grid: int) -> model.Setup:
    g = operating_point(params)
    return model.make_setup(g, params["lubricant.viscosity_law"], params["lubricant.density_law"], grid,
                            params.get("numerics.levels"), params["numerics.x_start"], params["numerics.x_end"],
                            y_half=params.get("numerics.y_half"))


def _levels_grids(params: dict[str, Any]) -> list[int]:
    n = params["numerics.grid"] - 1
    return [(n >> k) + 1 for k in range(params["numerics.refinements"] - 1, -1, -1)]


def _line_fields(s: model.Setup, sol) -> dict[str, np.ndarray]:
    g = s.g
    j0, i0 = int(np.argmin(np.abs(sol.y))), int(np.argmin(np.abs(sol.x)))
    x = sol.x * g.b
    hertz = g.p_hertz * np.sqrt(np.clip(1.0 - sol.x**2, 0.0, None))
    return {"line_x": x, "line_pressure": sol.P[:, j0] * g.p_hertz, "line_film": g.film_to_m(sol.H[:, j0]),
            "line_hertz": hertz, "cross_y": sol.y * g.b, "cross_pressure": sol.P[i0, :] * g.p_hertz,
            "cross_film": g.film_to_m(sol.H[i0, :]),
            "cross_hertz": g.p_hertz * np.sqrt(np.clip(1.0 - (g.kappa * sol.y) ** 2, 0.0, None)),
            "map_x": x, "map_y": sol.y * g.b, "pressure_map": sol.P * g.p_hertz, "film_map": g.film_to_m(sol.H)}


def _solve_level(params: dict[str, Any], s: model.Setup, indent: bool, tol: float, load_tol: float):
    """One grid of the certificate: the smooth steady solution, or the indent's crossing; (level record, solution
    whose fields are reported, quantities, crossing or None)."""
    grid = s.n + 1
    if indent:
        c = model.crossing(s, {"diameter": params["indent.diameter"], "slope": params["indent.slope"],
                               "decay": params["indent.decay"]}, params["kinematics.slide_roll"], tol, load_tol,
                           snapshots=params["numerics.snapshots"])
        sol = c["centred"]
        # film quantities of the smooth contact; the indent's effect is in the additional pressures at X_D = 0
        q = model.film_quantities(s, c["smooth"])
        q["p_max_indented"] = float(sol.P.max()) * s.g.p_hertz
        amps = {k: v[c["centre_step"] - 1] for k, v in c["amplitudes"].items()}
        q.update({f"additional_pressure_{k}": amps[k] * s.g.p_hertz for k in DP_NAMES})
        q["additional_pressure"] = amps["amplitude"] * s.g.p_hertz
        # max dP over r <= 1.5 Phi, beyond the shoulders too (outlet spike): for the record, not an amplitude
        q["additional_pressure_disc_max"] = amps["disc_max"] * s.g.p_hertz
        hist = c["history"]
        q["load_error"] = max(hist.load_error)
        info = {"grid": grid, "cycles": int(sum(hist.cycles)), "steps": c["steps"], "centre_step": c["centre_step"],
                "cycles_per_step_max": int(max(hist.cycles)), "residual": float(max(hist.residual)),
                "film_min_over_steps": float(np.nanmin(hist.h_min)), "smooth_cycles": c["smooth"].cycles}
        return info, sol, q, c
    sol, _ = model.solve_smooth(s, tol, load_tol)
    q = model.film_quantities(s, sol)
    info = {"grid": grid, "cycles": sol.cycles, "residual": sol.residual, "residual_history": sol.history,
            "work_sweeps": sol.work}
    return info, sol, q, None


def _certificate_level_error(err: ConvergenceError, params: dict[str, Any], grids: list[int], i: int) -> None:
    """A coarse level of the certificate that failed: say which, and which key leaves it out."""
    r = params["numerics.refinements"]
    err.args = (f"{err.args[0]} [this is the {grids[i]}^2 level, {i + 1} of {len(grids)} of the grid certificate "
                f"(numerics.refinements = {r} below numerics.grid = {grids[-1]}); numerics.refinements = "
                f"{len(grids) - i - 1} starts the certificate at {grids[i + 1]}^2]",) + err.args[1:]


def run(params: dict[str, Any], progress=None) -> ModelResult:
    """Smooth steady solutions on the refinement grids (coarse to fine), certificates of the film quantities;
    with an indent, the full crossing on each grid and certificates of the additional pressures at X_D = 0.

    A coarse grid that converges to a negative film (:class:`~femcheck.ehl.failures.UnderResolvedFilm`: it does
    not resolve the contact at this M, L) is left out: the certificate starts at the coarsest grid that resolves
    the contact, its note names the grids used and the ones refused, and with fewer than three grids left no order
    is claimed (uncertified; the value is the finest grid's). A refusal on the finest grid, or on a grid finer
    than one that resolved the contact, and any other failure end the run; a failure on a coarse grid says which
    level it was and which ``numerics.refinements`` leaves it out."""
    t0 = time.perf_counter()
    grids = _levels_grids(params)
    tol, load_tol = params["numerics.tol"], params["numerics.load_tol"]
    indent = has_indent(params)
    per_level: list[dict[str, Any]] = []
    refused: list[dict[str, Any]] = []
    last = None
    for i, grid in enumerate(grids):
        s = setup(params, grid)
        if progress:
            progress(f"EHL {'crossing' if indent else 'steady'} on {grid}^2 nodes")
        tl = time.perf_counter()
        try:
            info, sol, q, c = _solve_level(params, s, indent, tol, load_tol)
        except failures.UnderResolvedFilm as err:
            if i == len(grids) - 1 or per_level:
                if i < len(grids) - 1:
                    _certificate_level_error(err, params, grids, i)
                raise
            refused.append({"grid": grid, "film_min": err.h_min, "message": str(err),
                            "time_s": time.perf_counter() - tl})
            continue
        except ConvergenceError as err:
            if i < len(grids) - 1:
                _certificate_level_error(err, params, grids, i)
            raise
        info.update({"time_s": time.perf_counter() - tl, "levels": s.levels, **q})
        per_level.append(info)
        last = (s, sol, q, c)
    s, sol, q, c = last
    g = s.g
    used = [lv["grid"] for lv in per_level]
    hs = [(params["numerics.x_end"] - params["numerics.x_start"]) / (n - 1) for n in used]
    names = list(FILM_QUANTITIES) + ([f"additional_pressure_{k}" for k in DP_NAMES] + ["additional_pressure"]
                                     if indent else [])
    certs = {k: certify(hs, [lv[k] for lv in per_level], expected_order=2.0).as_dict() for k in names}
    if refused:
        why = (", ".join(f"{r_['grid']}^2" for r_ in refused) + " refused (negative film: does not resolve the "
               f"contact at M = {g.M:.4g}, L = {g.L:.4g}); certificate over " + ", ".join(f"{n}^2" for n in used)
               + ": ")
        for cert in certs.values():
            cert["note"] = why + cert["note"]
    quantities = dict(q)
    for k in names:
        quantities[k] = certs[k]["value"]
    stats = {"iterations": per_level[-1]["cycles"], "residual": per_level[-1]["residual"],
             "load_error": q["load_error"], "levels": per_level, "certificates": certs,
             "finest": {k: q[k] for k in names}, "grid": grids[-1], "multigrid_levels": s.levels,
             "M": g.M, "L": g.L, "alpha_bar": g.alpha_bar, "lambda_bar": g.lam, "b": g.b, "a": g.a,
             "p_hertz": g.p_hertz, "kappa": g.kappa, "load": g.load, "u_mean": g.u_mean,
             "U_moes": g.U_moes, "G": g.G, "W": g.W, "domain": [params["numerics.x_start"], params["numerics.x_end"]],
             "domain_y_half": float(sol.y[-1]),
             "certificate_grids": used, "refused_grids": refused}
    fields = _line_fields(s, sol)
    if c is not None:
        hist = c["history"]
        ind = c["indent"]
        t_scale = g.b / g.u_mean
        fields.update({
            "history_time": np.array(hist.T) * t_scale, "history_x_indent": np.array(hist.x_indent) * g.b,
            **{f"history_dp_{k}": np.array(c["amplitudes"][k]) * g.p_hertz for k in DP_NAMES},
            "history_load_error": np.array(hist.load_error), "history_cycles": np.array(hist.cycles),
            "pressure_steps": np.array([sn.P for sn in hist.snapshots]) * g.p_hertz,
            "steps_time": np.array([sn.T for sn in hist.snapshots]) * t_scale,
            "steps_x_indent": np.array([ind.centre(sn.T) for sn in hist.snapshots]) * g.b,
            "steps_index": np.array(hist.kept_steps), "history_film_min": g.film_to_m(np.array(hist.h_min)),
            "smooth_pressure_map": c["smooth"].P * g.p_hertz,
            "dp_map": (sol.P - c["smooth"].P) * g.p_hertz,
            "smooth_line_pressure": c["smooth"].P[:, int(np.argmin(np.abs(sol.y)))] * g.p_hertz})
        end = c["final"]
        stats.update({"steps": c["steps"], "centre_step": c["centre_step"],
                      "crossing": {"x_indent_start_b": hist.x_indent[0], "x_indent_centre_b":
                                   hist.x_indent[c["centre_step"] - 1], "x_indent_end_b": hist.x_indent[-1],
                                   "film_min_over_steps_m": g.film_to_m(float(np.nanmin(hist.h_min))),
                                   "additional_pressure_max_over_crossing": {
                                       k: float(np.nanmax(c["amplitudes"][k])) * g.p_hertz
                                       for k in ("rear", "front", "lateral")},
                                   "end_additional_pressure_over_p_hertz":
                                       float(np.abs(end.P - c["smooth"].P).max())},
                      "indent_diameter_m": params["indent.diameter"] * g.b,
                      "indent_depth_m": g.film_to_m(ind.depth), "indent_speed_ratio": ind.speed_ratio,
                      "max_load_error_over_steps": float(max(hist.load_error)),
                      "cycles_per_step_mean": float(np.mean(hist.cycles)),
                      "additional_pressure_over_p_ref": {k: q[f"additional_pressure_{k}"] / (0.2 * g.p_hertz)
                                                         for k in DP_NAMES}})
    stats["time_s"] = time.perf_counter() - t0
    return ModelResult("ehl", quantities=quantities, stats=stats, fields=fields)
