"""Fatigue life of a dented contact, lubricated against dry, at the operating point of seed 004 §4.3.1 (spec
ehl-life B.7 check 7).

    flock /tmp/femcheck-cpu.lock python benchmarks/ehl_life.py [--grids 129 257] [--out benchmarks/results]

Operating point (seed 004 §4.3.1, the tapered-roller example, circular equivalent): Rx = Ry = 5 mm, E' = 226 GPa
(steel, nu = 0.3), eta0 = 0.04 Pa s, alpha = 2e-8 1/Pa, Moes M = 350, L = 17 (femcheck derives the load and the
mean speed from M, L: p_H, b, u_m are reported next to the thesis' 2.2 GPa, 152 um, 5.9 m/s); Roelands viscosity,
Dowson-Higginson density, pure rolling. Indent (§4.3.1 medians): Phi = 0.56 b, D/Phi = 0.6, K = 4 (the thesis
prints no K for this example; K = 4 as in spec B.7.7). Life constants c = 8, e = 10/9, h = 0, window [-2b, 2b]^2,
24 depth planes to 2b, every window indented (f_d = 1).

- EHL: femcheck's transient EHL crossing (femcheck.ehl.model.crossing, NU2, time step = mesh size) on ``grid``
  nodes over [-2.5, 1.5] x [-2, 2] b, every step kept; the pressure of every step with the indent centre within
  |X_D| <= 1 + Phi fed to the full-transient stress history (femcheck.bem.stress_history.transient_history),
  beyond it the smooth EHL pressure; the pseudo-transient pass from the smooth and the centred solutions beside
  it (chi = 1 for |X_D| <= 1, contact form).
- dry: the BEM (femcheck.bem.halfspace) of the same ball at the same load, indent solved at every cell position
  |x_D| <= 1 + Phi, on ``grid`` x ``grid`` cells of the EHL mesh size h = 4 b/(grid - 1) (the contact centre on
  a cell centre: the BEM window is +/- 2.0 b plus half a cell).
- both through the same life model (femcheck.problems._life_output.indent_life: risk integrals I_S, I_D, life
  ratio L/L_S = (I_S/I_D)^(1/e) at f_d = 1).

Fatigue limit: tau_inf = 0.7 T_Smax (§4.3.1: T_inf/T_Smax ~ 0.7) with T_Smax of the dry (Hertz) smooth contact,
one material constant for both contacts; also tau_inf = 0.7 T_Smax of each contact's own smooth history, and no
limit. The thesis prints no risk-integral or life value for this example (Figs 4.10, 4.11 are missing); its
statement (§4.3.1) is that the pure-rolling EHL contact is less severe than the dry one: I-bar_D/I-bar_S(EHL) <
I-bar_D/I-bar_S(dry) (spec B.7.7).
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from femcheck.analytic import life
from femcheck.bem import halfspace
from femcheck.bem import stress_history as sh
from femcheck.ehl import adapter, model
from femcheck.geometry.profiles import indented, paraboloid
from femcheck.problems import _life_output as life_output
from femcheck.scene import load_scene

NU = 0.3
E_PRIME = 226e9
RADIUS = 5e-3
POINT = {"geometry.Rx": RADIUS, "geometry.Ry": RADIUS, "materials.body1.E": E_PRIME * (1 - NU**2),
         "materials.body2.E": E_PRIME * (1 - NU**2), "materials.body1.nu": NU, "materials.body2.nu": NU,
         "lubricant.viscosity": 0.04, "lubricant.pressure_viscosity": 2e-8, "ehl.M": 350.0, "ehl.L": 17.0,
         "kinematics.slide_roll": 0.0, "numerics.x_start": -2.5, "numerics.x_end": 1.5}
INDENT = {"diameter": 0.56, "slope": 0.6, "decay": 4.0}
THESIS = {"source": "seed 004 §4.3.1 (tapered-roller example)", "p_hertz": 2.2e9, "b": 152e-6, "u_s": 5.9,
          "M": 350, "L": 17, "alpha_bar": 44, "lambda_bar": 4.5e-3, "fatigue_limit_over_T_Smax": 0.7,
          "Phi": 0.56, "D_over_Phi": 0.6,
          "statement": "pure-rolling EHL contacts are less severe than dry contacts (Figs 4.10, 4.11 [figure only]; "
                       "no risk-integral or life value printed)"}
TAU_RATIO = 0.7
CHI = 1.0


def life_scene(fatigue_limit: float, e: float = 10.0 / 9.0):
    """indent-life's life keys (c = 8, h = 0, window 2, 24 planes to 2 b, f_d = 1) with ``fatigue_limit`` (Pa)."""
    return load_scene("indent-life", {"life.fatigue_limit": fatigue_limit, "life.e": e, "life.indent_fraction": 1.0,
                                      "life.window": 2.0, "numerics.life_depths": 24})


# ---------------------------------------------------------------------------------------------------------------
# the EHL crossing -> a pass of pressure frames in SI (what the life model takes)
# ---------------------------------------------------------------------------------------------------------------

def ehl_setup(grid: int):
    sc = load_scene("ehl-indent", {**POINT, "numerics.grid": grid})
    return adapter.setup(sc.params, grid)


def crossing_pass(x: np.ndarray, y: np.ndarray, smooth: np.ndarray, steps: list[tuple[float, np.ndarray]],
                  b: float, p_hertz: float, reach: float) -> dict:
    """Frames of a crossing for :func:`femcheck.bem.stress_history.transient_history`: ``x``, ``y`` the node
    coordinates (in b, uniform, equal spacing h, a node at x = 0), ``smooth`` and the step pressures P (in p_H) on
    them, ``steps`` the (X_D in b, P) of the crossing; the steps with |X_D| <= ``reach`` (in b) become frames
    keyed by the cell shift X_D/h (X_D must fall on nodes). Returns the smooth PressureMap (SI), the frames (Pa),
    the centre node and the frames' range in b."""
    h = float(x[1] - x[0])
    i0, j0 = int(np.argmin(np.abs(x))), int(np.argmin(np.abs(y)))
    frames = {}
    for xd, P in steps:
        if abs(xd) > reach + 1e-9:
            continue
        s = int(round(xd / h))
        if abs(xd / h - s) > 1e-6:
            raise ValueError(f"indent position {xd} b is not on a node (h = {h} b)")
        frames[s] = np.asarray(P, float) * p_hertz        # the indent at node i0 + s of the contact frame
    pm = sh.PressureMap(x * b, y * b, np.asarray(smooth, float) * p_hertz)
    return {"smooth": pm, "frames": frames, "centre": (i0, j0), "reach": [min(frames) * h, max(frames) * h]}


def life_numbers(hist: sh.StressHistory, b: float, p_hertz: float, fatigue_limit: float) -> dict:
    out = life_output.indent_life(hist, b, p_hertz, life_scene(fatigue_limit))
    q, s = out.quantities, out.stats
    return {"fatigue_limit": fatigue_limit, "risk_integral_smooth": q["risk_integral_smooth"],
            "risk_integral_dented": q["risk_integral"], "risk_ratio": s["risk_ratio"],
            "Ibar_ratio": s["risk_ratio"] ** (1.0 / s["c"]), "Ibar_smooth": s["risk_integral_bar_smooth"],
            "Ibar_dented": s["risk_integral_bar"], "life_ratio": q["life_ratio"], "stress_ratio": q["stress_ratio"],
            "T_Smax_over_pH": s["stress_history_max_smooth"] / p_hertz, "T_Dmax_over_pH": q["stress_history_max"] / p_hertz,
            "T_Dmax_at_over_b": {k: v / b for k, v in s["stress_history_max_at"].items()}}


def frame_extremes(ps: dict, b: float, p_hertz: float) -> dict:
    """Largest additional pressure max(P - P_S)/p_H over the fed frames and the indent position (in b) of it."""
    h = ps["smooth"].dx / b
    dp = {k: float((f - ps["smooth"].pressure).max()) / p_hertz for k, f in ps["frames"].items()}
    top = max(dp, key=dp.get)
    return {"dP_max_over_pH": dp[top], "dP_max_at_X_D": top * h,
            "p_max_over_pH": max(float(f.max()) for f in ps["frames"].values()) / p_hertz}


def t_smax(hist: sh.StressHistory) -> float:
    return float(sh.refined_max(hist.smooth, [hist.depths, hist.y])["value"])


def ehl_case(grid: int, indent: dict = INDENT) -> dict:
    s = ehl_setup(grid)
    g = s.g
    t0 = time.perf_counter()
    c = model.crossing(s, indent, 0.0, 1e-7, 1e-7, snapshots=100000)
    t_cross = time.perf_counter() - t0
    hist = c["history"]
    steps = [(hist.x_indent[k - 1], sn.P) for k, sn in zip(hist.kept_steps, hist.snapshots)]
    sm = c["smooth"]
    ps = crossing_pass(sm.x, sm.y, sm.P, steps, g.b, g.p_hertz, 1.0 + indent["diameter"])
    t1 = time.perf_counter()
    z, wz = life_output.depth_planes(life_scene(0.0), g.b)
    full = sh.transient_history(ps["smooth"], ps["frames"], ps["centre"], NU, z, wz, 2.0 * g.b)
    t_full = time.perf_counter() - t1
    pm_d = sh.PressureMap(ps["smooth"].x, ps["smooth"].y, c["centred"].P * g.p_hertz)
    pseudo = sh.pseudo_transient_history(ps["smooth"], pm_d, ps["centre"], NU, z, wz, 2.0 * g.b, CHI * g.b, "contact")
    dp = float((c["centred"].P - sm.P).max())
    return {"grid": grid, "groups": {"p_hertz": g.p_hertz, "b": g.b, "u_mean": g.u_mean, "u_s": 2 * g.u_mean,
                                     "load": g.load, "M": g.M, "L": g.L, "alpha_bar": g.alpha_bar, "lambda_bar": g.lam},
            "steps": c["steps"], "frames": len(ps["frames"]), "frame_reach_b": ps["reach"],
            "dP_centred_over_pH": dp, "crossing_extremes": frame_extremes(ps, g.b, g.p_hertz),
            "h_min_smooth_over_b2_Rx": float(sm.H[sm.P > 0].min()),
            "film_min_crossing": float(min(hist.h_min)), "load_error_max": float(max(np.abs(hist.load_error))),
            "time_crossing_s": t_cross, "time_history_s": t_full,
            "_hist": {"full": full, "pseudo": pseudo}, "_g": g}


# ---------------------------------------------------------------------------------------------------------------
# the dry contact at the same point (BEM)
# ---------------------------------------------------------------------------------------------------------------

class DryContact:
    """Ball Rx = Ry on the EHL point's load; ``cells`` (odd) cells of size ``h`` b, the centre cell on the
    origin."""

    def __init__(self, g, cells: int, h: float):
        self.b, self.p_hertz, self.load = g.b, g.p_hertz, g.load
        self.e_star = 0.5 * g.e_prime
        half = 0.5 * cells * h * g.b
        self.grid = halfspace.grid(half, half, cells, cells)
        self.c = (cells // 2, cells // 2)
        self.base = paraboloid(g.Rx, g.Ry)
        self.smooth = self._solve(self.base)
        self.rx = g.Rx

    def _solve(self, gap) -> np.ndarray:
        return halfspace.solve(self.grid, gap, self.e_star, self.load).result.pressure

    def dented(self, indent: dict, x0: float) -> np.ndarray:
        phi = indent["diameter"] * self.b
        depth = indent["slope"] * indent["diameter"] * self.b**2 / self.rx     # D = d Rx/b^2 (eq 2.16)
        return self._solve(indented(self.base, phi, depth, indent["decay"], x0=x0))

    def crossing(self, indent: dict) -> dict:
        """Frames at every cell position |x_D| <= (1 + Phi) b."""
        m = int(np.floor((1.0 + indent["diameter"]) * self.b / self.grid.dx + 1e-9))
        frames = {s: self.dented(indent, s * self.grid.dx) for s in range(-m, m + 1)}
        return {"smooth": sh.PressureMap.on_grid(self.grid, self.smooth), "frames": frames, "centre": self.c}


def dry_case(g, grid: int, indent: dict = INDENT) -> dict:
    h = 4.0 / (grid - 1)
    t0 = time.perf_counter()
    dc = DryContact(g, grid - 1 if (grid - 1) % 2 else grid, h)
    ps = dc.crossing(indent)
    t_solve = time.perf_counter() - t0
    z, wz = life_output.depth_planes(life_scene(0.0), g.b)
    t1 = time.perf_counter()
    full = sh.transient_history(ps["smooth"], ps["frames"], ps["centre"], NU, z, wz, 2.0 * g.b)
    t_hist = time.perf_counter() - t1
    pseudo = sh.pseudo_transient_history(ps["smooth"], sh.PressureMap.on_grid(dc.grid, ps["frames"][0]), dc.c, NU,
                                         z, wz, 2.0 * g.b, CHI * g.b, "contact")
    return {"cells": dc.grid.nx, "cell_over_b": dc.grid.dx / g.b, "frames": len(ps["frames"]),
            "dP_centred_over_pH": float((ps["frames"][0] - dc.smooth).max()) / g.p_hertz,
            "crossing_extremes": frame_extremes(ps, g.b, g.p_hertz),
            "time_bem_s": t_solve, "time_history_s": t_hist, "_hist": {"full": full, "pseudo": pseudo}}


# ---------------------------------------------------------------------------------------------------------------

def compare(grid: int) -> dict:
    ehl = ehl_case(grid)
    g = ehl.pop("_g")
    print(f"EHL {grid}: crossing {ehl['time_crossing_s']:.0f} s, history {ehl['time_history_s']:.0f} s", flush=True)
    dry = dry_case(g, grid)
    print(f"dry {dry['cells']}: BEM {dry['time_bem_s']:.0f} s, history {dry['time_history_s']:.0f} s", flush=True)
    he, hd = ehl.pop("_hist"), dry.pop("_hist")
    tau_dry = TAU_RATIO * t_smax(hd["full"])
    tau_ehl = TAU_RATIO * t_smax(he["full"])
    res = {"grid": grid, "ehl": ehl, "dry": dry, "fatigue_limit_material": tau_dry, "fatigue_limit_ehl_own": tau_ehl}
    for label, tau_e, tau_d in (("limit_0.7_dry", tau_dry, tau_dry), ("limit_0.7_own", tau_ehl, tau_dry),
                                ("no_limit", 0.0, 0.0)):
        row = {}
        for hist_kind in ("full", "pseudo"):
            e = life_numbers(he[hist_kind], g.b, g.p_hertz, tau_e)
            d = life_numbers(hd[hist_kind], g.b, g.p_hertz, tau_d)
            row[hist_kind] = {"ehl": e, "dry": d,
                              # the dented lubricated contact against the dented dry one (same p_H, b, window)
                              "life_ehl_over_dry": (d["risk_integral_dented"] / e["risk_integral_dented"]) ** (
                                  1.0 / life.LifeConstants().e) if e["risk_integral_dented"] > 0 else float("inf"),
                              "life_smooth_ehl_over_dry": (d["risk_integral_smooth"] / e["risk_integral_smooth"]) ** (
                                  1.0 / life.LifeConstants().e) if e["risk_integral_smooth"] > 0 else float("inf"),
                              "Ibar_ratio_ehl_over_dry": e["Ibar_ratio"] / d["Ibar_ratio"],
                              "check_7": e["Ibar_ratio"] < d["Ibar_ratio"]}
        res[label] = row
        f = row["full"]
        print(f"{label}: Ibar_D/Ibar_S EHL {f['ehl']['Ibar_ratio']:.4f} dry {f['dry']['Ibar_ratio']:.4f}; "
              f"L/L_S EHL {f['ehl']['life_ratio']:.4f} dry {f['dry']['life_ratio']:.4f}; "
              f"L_D(EHL)/L_D(dry) {f['life_ehl_over_dry']:.3f}", flush=True)
    return res


def markdown(res: dict) -> str:
    L = ["# Dented contact life, lubricated against dry, at seed 004 §4.3.1 (benchmarks/ehl_life.py)", "",
         "Operating point: Rx = Ry = 5 mm, E' = 226 GPa, eta0 = 0.04 Pa s, alpha = 2e-8 1/Pa, M = 350, L = 17 "
         "(Roelands, Dowson-Higginson), pure rolling; indent Phi = 0.56 b, D/Phi = 0.6, K = 4; c = 8, e = 10/9, "
         "h = 0, window [-2b, 2b]^2, 24 depth planes to 2b, f_d = 1. Thesis: " + THESIS["statement"] + ".", ""]
    for r in res["runs"]:
        e, d, gr = r["ehl"], r["dry"], r["ehl"]["groups"]
        L += [f"## EHL grid {r['grid']}^2 nodes, dry BEM {d['cells']}^2 cells (h = {d['cell_over_b']:.5f} b)", "",
              f"p_H = {gr['p_hertz'] / 1e9:.4f} GPa (thesis 2.2), b = {gr['b'] * 1e6:.2f} um (152), "
              f"u_s = 2 u_m = {gr['u_s']:.3f} m/s (5.9), alpha_bar = {gr['alpha_bar']:.2f} (44), "
              f"lambda_bar = {gr['lambda_bar']:.3e} (4.5e-3), load {gr['load']:.1f} N.", "",
              f"Centred additional pressure dP/p_H: EHL {e['dP_centred_over_pH']:.4f}, dry "
              f"{d['dP_centred_over_pH']:.4f}. EHL crossing {e['steps']} steps ({e['frames']} frames fed, X_D in "
              f"[{e['frame_reach_b'][0]:.3f}, {e['frame_reach_b'][1]:.3f}] b), {e['time_crossing_s']:.0f} s; dry "
              f"{d['frames']} BEM frames, {d['time_bem_s']:.0f} s. Stress histories {e['time_history_s']:.0f} s "
              f"(EHL), {d['time_history_s']:.0f} s (dry).", "",
              f"Over the fed frames, largest dP/p_H: EHL {e['crossing_extremes']['dP_max_over_pH']:.4f} at X_D = "
              f"{e['crossing_extremes']['dP_max_at_X_D']:.3f} b (largest P/p_H {e['crossing_extremes']['p_max_over_pH']:.4f}),"
              f" dry {d['crossing_extremes']['dP_max_over_pH']:.4f} at {d['crossing_extremes']['dP_max_at_X_D']:.3f} b "
              f"(P/p_H {d['crossing_extremes']['p_max_over_pH']:.4f}). T_Dmax (full, no limit) at depth, xi, y = "
              + ", ".join(f"{v:.3f}" for v in r['no_limit']['full']['ehl']['T_Dmax_at_over_b'].values()) + " b (EHL), "
              + ", ".join(f"{v:.3f}" for v in r['no_limit']['full']['dry']['T_Dmax_at_over_b'].values()) + " b (dry).", "",
              "| fatigue limit | history | T_Smax/p_H EHL, dry | T_D/T_S EHL | dry | Ibar_D/Ibar_S EHL | dry | "
              "L/L_S EHL | dry | L_D(EHL)/L_D(dry) | L_S(EHL)/L_S(dry) | check 7 |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for label, name in (("limit_0.7_dry", f"0.7 T_Smax(dry) = {r['fatigue_limit_material'] / 1e9:.4f} GPa"),
                            ("limit_0.7_own", "0.7 T_Smax of each"), ("no_limit", "0")):
            for hk in ("full", "pseudo"):
                x = r[label][hk]
                L.append(f"| {name} | {hk} | {x['ehl']['T_Smax_over_pH']:.4f}, {x['dry']['T_Smax_over_pH']:.4f} | "
                         f"{x['ehl']['stress_ratio']:.4f} | {x['dry']['stress_ratio']:.4f} | "
                         f"{x['ehl']['Ibar_ratio']:.4f} | {x['dry']['Ibar_ratio']:.4f} | {x['ehl']['life_ratio']:.4f} "
                         f"| {x['dry']['life_ratio']:.4f} | {x['life_ehl_over_dry']:.4g} | "
                         f"{x['life_smooth_ehl_over_dry']:.4g} | {'holds' if x['check_7'] else 'FAILS'} |")
        L.append("")
    if "grid_error" in res:
        L += ["## Discretisation (the coarse grid against the fine one, relative)", ""]
        for k, v in res["grid_error"].items():
            L.append(f"- {k}: {100 * v:+.2f} %")
        L.append("")
    return "\n".join(L) + "\n"


def grid_error(coarse: dict, fine: dict) -> dict:
    out = {}
    for label in ("limit_0.7_dry", "no_limit"):
        for who in ("ehl", "dry"):
            for q in ("Ibar_ratio", "life_ratio", "stress_ratio"):
                out[f"{label} full {who} {q}"] = coarse[label]["full"][who][q] / fine[label]["full"][who][q] - 1
        out[f"{label} full L_D(EHL)/L_D(dry)"] = (coarse[label]["full"]["life_ehl_over_dry"]
                                                 / fine[label]["full"]["life_ehl_over_dry"] - 1)
    out["dP_centred EHL"] = coarse["ehl"]["dP_centred_over_pH"] / fine["ehl"]["dP_centred_over_pH"] - 1
    out["dP_centred dry"] = coarse["dry"]["dP_centred_over_pH"] / fine["dry"]["dP_centred_over_pH"] - 1
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--grids", type=int, nargs="+", default=[129, 257])
    ap.add_argument("--out", default="benchmarks/results")
    args = ap.parse_args()
    t0 = time.perf_counter()
    res = {"thesis": THESIS, "indent": INDENT, "point": POINT, "runs": []}
    for grid in args.grids:
        res["runs"].append(compare(grid))
    if len(res["runs"]) >= 2:
        res["grid_error"] = grid_error(res["runs"][0], res["runs"][-1])
    res["elapsed_s"] = time.perf_counter() - t0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "ehl_life.json").write_text(json.dumps(res, indent=1, default=float))
    (out / "ehl_life.md").write_text(markdown(res))
    print(f"written {out}/ehl_life.json, .md ({res['elapsed_s']:.0f} s)")


if __name__ == "__main__":
    main()
