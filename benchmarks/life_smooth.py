"""Fatigue life of smooth Hertzian contacts (issue 15, spec ehl-life B.4/B.5/B.7.1/B.7.4): convergence of the
stress-amplitude history and of the risk integral, and the load-life exponents against Lundberg-Palmgren.

    flock /work/heavy.lock python benchmarks/life_smooth.py [--out benchmarks/results] [--quick]

Cases: hertz-point's ball (steel, R = 10 mm, E* = 115.4 GPa; 1 kN: p_H = 2.95 GPa, a = 0.402 mm), BEM over
+/- 1.25 a, window [-2a, 2a]^2, depth planes z = 2a (k/n)^2; hertz-line's cylinder (R = 10 mm, 1 MN/m:
p_H = 1.92 GPa, a = 0.332 mm), McEwen's closed form and the BEM strips, depth 4a.

1. Point contact: T_Smax against the closed form on the axis (Johnson eq 3.45), and the risk integral
   I-bar^c = I / (p_H^c a^3) at 65^2, 129^2, 257^2 cells and 24 / 48 depth planes, without fatigue limit and with
   tau_inf = 0.7 T_Smax (the issue: <= 1 % from 129^2 to 257^2 and from 24 to 48 planes).
2. Scaling every stress by lambda (the pressure, at a fixed grid) without fatigue limit: I(lambda) / I(1) against
   lambda^c.
3. Line contact: the BEM strips' risk integral against McEwen's, 256 ... 4096 strips.
4. Load-life exponents n = -d ln L / d ln Q (point: BEM 129^2; line: McEwen and BEM 1024 strips) over a factor 16
   in load, c = 8, h = 0 (defaults) and Lundberg-Palmgren's c = 31/3, h = 7/3, without and with a fatigue limit
   fixed in Pa (0.4 and 0.7 T_Smax at the middle load), against (c - h + 2)/(3e) and (c - h + 1)/(2e).
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from femcheck.analytic import hertz, life
from femcheck.analytic.stress import hertz_sphere_maxima
from femcheck.bem import halfspace
from femcheck.bem import stress_history as sh
from femcheck.bem.line import solve_line_contact
from femcheck.geometry.profiles import paraboloid

R, NU = 0.010, 0.3
E_STAR = 210e9 / (2 * (1 - NU**2))
W_POINT, W_LINE = 1000.0, 1e6


def point_history(W: float, n: int, planes: int):
    h = hertz.point_contact(W, R, E_STAR)
    a = h.semi_axis_x
    g = halfspace.grid(1.25 * a, 1.25 * a, n, n)
    t0 = time.perf_counter()
    r = halfspace.solve(g, paraboloid(R, R), E_STAR, W).result
    t1 = time.perf_counter()
    z, wz = life.depth_planes(2 * a, planes)
    hist = sh.smooth_history(sh.PressureMap.on_grid(g, r.pressure), NU, z, wz, 2 * a)
    return h, hist, {"solve_s": t1 - t0, "history_s": time.perf_counter() - t1}


def point_risk(hist, k: life.LifeConstants, a: float) -> float:
    """Risk per unit track length (Pa^c m^(2-h))."""
    zf = life.depth_weight(hist.depths, k.h, a)[:, None]
    return life.risk_integral(hist.smooth, hist.depth_weights[:, None] * hist.y_weights[None, :], k, zf)


def line_histories(W: float, planes: int, strips: int | None):
    h = hertz.line_contact(W, R, E_STAR)
    a = h.half_width
    z, wz = life.depth_planes(4 * a, planes)
    if strips is None:
        return h, z, wz, life.mcewen_history(a, h.p_max, NU, z)
    sol = solve_line_contact(lambda x: x * x / (2 * R), E_STAR, W, 1.25 * a, strips)
    return h, z, wz, sh.line_history(sol.result.pressure, sol.dx, NU, z)


def convergence(quick: bool) -> dict:
    out = {"point": [], "line": []}
    h = hertz.point_contact(W_POINT, R, E_STAR)
    closed = hertz_sphere_maxima(h.semi_axis_x, h.p_max, NU)
    t_inf = 0.7 * closed["von_mises_max"]
    for n in ((65, 129) if quick else (65, 129, 257)):
        for planes in (24, 48):
            h, hist, times = point_history(W_POINT, n, planes)
            a, p0 = h.semi_axis_x, h.p_max
            m = sh.refined_max(hist.smooth, [hist.depths, hist.y])
            row = {"cells": n, "planes": planes, "T_Smax_over_pH": m["value"] / p0,
                   "T_Smax_error": m["value"] / closed["von_mises_max"] - 1, "T_Smax_depth_over_a": m["position"][0] / a,
                   **times}
            for label, ti in (("no_limit", 0.0), ("limit_0.7", t_inf)):
                k = life.LifeConstants(fatigue_limit=ti)
                row[f"Ibar_c_{label}"] = point_risk(hist, k, a) * 4 * a / (p0**8 * a**3)
            out["point"].append(row)
            print("point", row, flush=True)
    # lambda scaling at fixed grid (pressure x lambda: every stress x lambda)
    h = hertz.point_contact(W_POINT, R, E_STAR)
    a = h.semi_axis_x
    g = halfspace.grid(1.25 * a, 1.25 * a, 65, 65)
    p = halfspace.solve(g, paraboloid(R, R), E_STAR, W_POINT).result.pressure
    z, wz = life.depth_planes(2 * a, 24)
    k = life.LifeConstants()
    I1 = point_risk(sh.smooth_history(sh.PressureMap.on_grid(g, p), NU, z, wz, 2 * a), k, a)
    scal = []
    for lam in (0.5, 1.7, 3.0):
        Il = point_risk(sh.smooth_history(sh.PressureMap.on_grid(g, lam * p), NU, z, wz, 2 * a), k, a)
        scal.append({"lambda": lam, "ratio_over_lambda_c": Il / I1 / lam**8 - 1})
    out["lambda_scaling"] = scal
    print("lambda", scal, flush=True)
    hl, z, wz, T_ref = line_histories(W_LINE, 24, None)
    for strips in (256, 512, 1024, 2048, 4096):
        _, _, _, T = line_histories(W_LINE, 24, strips)
        row = {"strips": strips}
        for label, ti in (("no_limit", 0.0), ("limit_0.7", 0.7 * T_ref.max())):
            k = life.LifeConstants(e=9 / 8, fatigue_limit=ti)
            row[f"risk_error_{label}"] = life.risk_integral(T, wz, k) / life.risk_integral(T_ref, wz, k) - 1
        row["T_Smax_error"] = T.max() / T_ref.max() - 1
        out["line"].append(row)
        print("line", row, flush=True)
    return out


def exponents(quick: bool) -> dict:
    loads_p = W_POINT * np.array([0.25, 0.5, 1.0, 2.0, 4.0])
    loads_l = W_LINE * np.array([0.25, 0.5, 1.0, 2.0, 4.0])
    constants = {"c=8,h=0": (8.0, 0.0), "LP c=31/3,h=7/3": (31 / 3, 7 / 3)}
    out = {}
    hist_p = [point_history(W, 65 if quick else 129, 24) for W in loads_p]
    t_inf_p = hist_p[2][1].smooth.max()            # T_Smax at the middle load; limits are fractions of it
    lines = {"mcewen": [line_histories(W, 48, None) for W in loads_l],
             "bem": [line_histories(W, 48, 1024) for W in loads_l]}
    t_inf_l = lines["mcewen"][2][3].max()
    for cname, (c, hexp) in constants.items():
        for label, f in (("no_limit", 0.0), ("limit 0.4", 0.4), ("limit 0.7", 0.7)):
            tp, tl = f * t_inf_p, f * t_inf_l
            kp = life.LifeConstants(c=c, e=10 / 9, h=hexp, fatigue_limit=tp)
            lives = [life.relative_life(point_risk(hh, kp, h.semi_axis_x), kp) for h, hh, _ in hist_p]
            out[f"point {cname} {label}"] = {
                "loads": loads_p.tolist(), "lives": lives, "local_exponents": life.local_exponents(loads_p, lives).tolist(),
                "lundberg_palmgren": life.load_life_exponent(c, hexp, 10 / 9, "point"),
                "fatigue_limit_Pa": tp}
            for model, rows in lines.items():
                kl = life.LifeConstants(c=c, e=9 / 8, h=hexp, fatigue_limit=tl)
                lives = [life.relative_life(life.risk_integral(T, wz, kl, life.depth_weight(z, hexp, h.half_width))
                                            * 1e-3, kl) for h, z, wz, T in rows]
                out[f"line ({model}) {cname} {label}"] = {
                    "loads": loads_l.tolist(), "lives": lives,
                    "local_exponents": life.local_exponents(loads_l, lives).tolist(),
                    "lundberg_palmgren": life.load_life_exponent(c, hexp, 9 / 8, "line"), "fatigue_limit_Pa": tl}
    for k, v in out.items():
        print(k, np.round(v["local_exponents"], 4), "LP", v["lundberg_palmgren"], flush=True)
    return out


def markdown(res: dict) -> str:
    L = ["# Fatigue life of smooth Hertzian contacts (benchmarks/life_smooth.py)", "",
         "Indicative timings (shared 2-core machine). I-bar^c = I / (p_H^c a^3) over the window [-2a, 2a]^2.", "",
         "## Point contact: history maximum and risk integral", "",
         "| cells | planes | T_Smax/p_H | error vs closed form | depth/a | I-bar^c (no limit) | I-bar^c (0.7 T_Smax) | history s |",
         "|---|---|---|---|---|---|---|---|"]
    for r in res["convergence"]["point"]:
        L.append(f"| {r['cells']} | {r['planes']} | {r['T_Smax_over_pH']:.5f} | {100 * r['T_Smax_error']:+.3f} % | "
                 f"{r['T_Smax_depth_over_a']:.4f} | {r['Ibar_c_no_limit']:.6e} | {r['Ibar_c_limit_0.7']:.6e} | "
                 f"{r['history_s']:.1f} |")
    pts = {(r["cells"], r["planes"]): r for r in res["convergence"]["point"]}
    cells = sorted({c for c, _ in pts})
    L += ["", "Changes of the risk integral:", ""]
    for lab in ("no_limit", "limit_0.7"):
        for c0, c1 in zip(cells[:-1], cells[1:]):
            d = pts[(c1, 24)][f"Ibar_c_{lab}"] / pts[(c0, 24)][f"Ibar_c_{lab}"] - 1
            L.append(f"- {lab}: {c0}^2 -> {c1}^2 (24 planes): {100 * d:+.3f} %")
        for c in cells:
            d = pts[(c, 48)][f"Ibar_c_{lab}"] / pts[(c, 24)][f"Ibar_c_{lab}"] - 1
            L.append(f"- {lab}: 24 -> 48 planes at {c}^2: {100 * d:+.4f} %")
    L += ["", "Stresses scaled by lambda (no fatigue limit): I(lambda)/I(1)/lambda^c - 1 = "
          + ", ".join(f"{r['lambda']:g}: {r['ratio_over_lambda_c']:.1e}" for r in res["convergence"]["lambda_scaling"]),
          "", "## Line contact: BEM strips against McEwen", "",
          "| strips | T_Smax error | risk error (no limit) | risk error (0.7 T_Smax) |", "|---|---|---|---|"]
    for r in res["convergence"]["line"]:
        L.append(f"| {r['strips']} | {100 * r['T_Smax_error']:+.4f} % | {100 * r['risk_error_no_limit']:+.3f} % | "
                 f"{100 * r['risk_error_limit_0.7']:+.3f} % |")
    L += ["", "## Load-life exponents n = -dlnL/dlnQ (local, between consecutive loads Q x 0.25 ... 4)", "",
          "| case | fatigue limit (GPa) | measured local exponents | Lundberg-Palmgren (no limit) |", "|---|---|---|---|"]
    for k, v in res["exponents"].items():
        ex = ", ".join("inf" if not np.isfinite(x) else f"{x:.4f}" for x in v["local_exponents"])
        L.append(f"| {k} | {v['fatigue_limit_Pa'] / 1e9:.3g} | {ex} | {v['lundberg_palmgren']:.4f} |")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="benchmarks/results")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    t0 = time.perf_counter()
    res = {"convergence": convergence(args.quick), "exponents": exponents(args.quick)}
    res["elapsed_s"] = time.perf_counter() - t0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    name = "life_smooth_quick" if args.quick else "life_smooth"
    (out / f"{name}.json").write_text(json.dumps(res, indent=1, default=float))
    (out / f"{name}.md").write_text(markdown(res))
    print(f"written {out}/{name}.json, .md ({res['elapsed_s']:.0f} s)")


if __name__ == "__main__":
    main()
