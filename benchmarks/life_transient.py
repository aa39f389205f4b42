"""Pseudo-transient superposition against the full transient, dry indented ball contact (issue 15 item 2; spec
ehl-life B.7.2, B.7.3), and the life ratio against the indent size.

    flock /work/heavy.lock python benchmarks/life_transient.py [--cells 129] [--linearity] [--out benchmarks/results]

Contact: indent-dry's ball (steel, R = 10 mm, 1 kN: p_H = 2.95 GPa, a = 0.402 mm), BEM over +/- 1.6 a, depth
planes z = 2a (k/24)^2, window [-2a, 2a]^2. Per indent (Phi, K, D/Phi):

- full transient: the indented contact solved by the BEM at every cell position |x_D| <= min(1 + Phi, 1.6 -
  Phi/2) a, the history the max of the von Mises stress of each frame in the material frame;
- pseudo-transient, contact form (femcheck's default) and linear form (eq 4.5 as printed), chi = 1 for
  |x_D| <= X_chi = 1 a, and the contact form with X_chi = 0.5 a (sensitivity to the choice the thesis leaves open).

Reported: T_Dmax/T_Smax, I-bar_D / I-bar_S and the life ratio L/L_S (f_d = 1) without fatigue limit and with
tau_inf = 0.7 T_Smax, the relative differences pseudo/full, and the additional pressure during the crossing
(seed 004 Table 3.1 assumes it constant). ``--linearity``: T_Dmax/T_Smax against dP/P_REF (P_REF = 0.200 p_H,
femcheck's Table 3.3 fit) over 18 indents (Phi 0.25-1, D/Phi 0.25-2, K 3, 8), pseudo-transient (B.7.3: R^2).
Life ratio against Phi (0.25, 0.5, 0.75, 1) at D/Phi = 1, K = 3 and 4.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from femcheck.analytic import hertz, life
from femcheck.bem import halfspace
from femcheck.bem import stress_history as sh
from femcheck.geometry.profiles import indented, paraboloid

R, NU, W = 0.010, 0.3, 1000.0
E_STAR = 210e9 / (2 * (1 - NU**2))
H = hertz.point_contact(W, R, E_STAR)
A, P0 = H.semi_axis_x, H.p_max
DOMAIN, WINDOW, P_REF = 1.6, 2.0, 0.200
CASES = [(0.5, 3.0, 1.0), (0.5, 4.0, 0.5), (0.25, 3.0, 1.0), (0.5, 8.0, 2.0), (0.5, 4.0, 0.2), (1.0, 4.0, 1.0)]


class Contact:
    def __init__(self, n: int, planes: int):
        self.g = halfspace.grid(DOMAIN * A, DOMAIN * A, n, n)
        self.c = (n // 2, n // 2)
        self.smooth = halfspace.solve(self.g, paraboloid(R, R), E_STAR, W).result.pressure
        self.pm_s = sh.PressureMap.on_grid(self.g, self.smooth)
        self.z, self.wz = life.depth_planes(2 * A, planes)

    def dented(self, phi, K, S, x0=0.0):
        gap = indented(paraboloid(R, R), phi * A, S * phi * A * A / R, K, x0=x0)
        return halfspace.solve(self.g, gap, E_STAR, W).result.pressure

    def metrics(self, hist, t_inf: float) -> dict:
        w = hist.depth_weights[:, None, None] * hist.xi_weights[None, :, None] * hist.y_weights[None, None, :]
        k = life.LifeConstants(fatigue_limit=t_inf)
        I_S = life.risk_integral(np.broadcast_to(hist.smooth[:, None, :], hist.amplitude.shape), w, k)
        I_D = life.risk_integral(hist.amplitude, w, k)
        ts = sh.refined_max(hist.smooth, [hist.depths, hist.y])["value"]
        td = sh.refined_max(hist.amplitude, [hist.depths, hist.xi, hist.y])
        ratio = life.risk_ratio(I_D, I_S)
        return {"T_ratio": td["value"] / ts, "T_Dmax_at_over_a": [p / A for p in td["position"]],
                "Ibar_ratio": ratio ** (1 / 8), "risk_ratio": ratio,
                "life_ratio": life.dented_life_ratio(ratio, 1.0, k.e), "T_Smax": ts}

    def pseudo(self, phi, K, S, mode="contact", chi=1.0, p_d=None):
        p_d = self.dented(phi, K, S) if p_d is None else p_d
        return sh.pseudo_transient_history(self.pm_s, sh.PressureMap.on_grid(self.g, p_d), self.c, NU, self.z,
                                           self.wz, WINDOW * A, chi * A, mode)

    def transient(self, phi, K, S):
        m = int(np.floor(min(1.0 + phi, DOMAIN - 0.5 * phi) * A / self.g.dx))
        frames, dps = {}, []
        for s in range(-m, m + 1):
            frames[s] = self.dented(phi, K, S, s * self.g.dx)
            dps.append((s * self.g.dx / A, float((frames[s] - self.smooth).max()) / P0))
        return sh.transient_history(self.pm_s, frames, self.c, NU, self.z, self.wz, WINDOW * A), dps


def compare(ct: Contact, cases) -> list[dict]:
    rows = []
    for phi, K, S in cases:
        t0 = time.perf_counter()
        p_d = ct.dented(phi, K, S)
        dp = float((p_d - ct.smooth).max()) / P0
        full, dps = ct.transient(phi, K, S)
        t_full = time.perf_counter() - t0
        t1 = time.perf_counter()
        variants = {"contact": ct.pseudo(phi, K, S, "contact", 1.0, p_d)}
        t_pseudo = time.perf_counter() - t1
        variants["linear"] = ct.pseudo(phi, K, S, "linear", 1.0, p_d)
        variants["contact chi=0.5"] = ct.pseudo(phi, K, S, "contact", 0.5, p_d)
        t_smax = ct.metrics(full, 0.0)["T_Smax"]
        row = {"Phi": phi, "K": K, "slope": S, "dP_over_pH": dp, "time_full_s": t_full, "time_pseudo_s": t_pseudo,
               "dP_crossing": {"centred": dp, "max_in_contact": max(d for x, d in dps if abs(x) <= 1.0),
                               "min_in_contact": min(d for x, d in dps if abs(x) <= 1.0), "end_frames": dps[-1][1]}}
        for label, t_inf in (("no_limit", 0.0), ("limit_0.7", 0.7 * t_smax)):
            ref = ct.metrics(full, t_inf)
            row[label] = {"full": ref}
            for name, hist in variants.items():
                m = ct.metrics(hist, t_inf)
                m["T_ratio_error"] = m["T_ratio"] / ref["T_ratio"] - 1
                m["Ibar_ratio_error"] = m["Ibar_ratio"] / ref["Ibar_ratio"] - 1
                m["life_ratio_error"] = m["life_ratio"] / ref["life_ratio"] - 1 if ref["life_ratio"] > 0 else None
                row[label][name] = m
        rows.append(row)
        print(json.dumps({k: row[k] for k in ("Phi", "K", "slope", "dP_over_pH", "time_full_s", "time_pseudo_s")}),
              {name: round(row["no_limit"][name]["T_ratio_error"], 4) for name in variants},
              {name: round(row["limit_0.7"][name]["Ibar_ratio_error"], 4) for name in variants}, flush=True)
    return rows


def linearity(ct: Contact) -> dict:
    pts = []
    for phi in (0.25, 0.5, 1.0):
        for S in (0.25, 1.0, 2.0):
            for K in (3.0, 8.0):
                p_d = ct.dented(phi, K, S)
                m = ct.metrics(ct.pseudo(phi, K, S, p_d=p_d), 0.0)
                pts.append({"Phi": phi, "slope": S, "K": K, "dP_over_PREF": float((p_d - ct.smooth).max()) / P0 / P_REF,
                            "T_ratio": m["T_ratio"]})
                print(pts[-1], flush=True)
    x, y = np.array([p["dP_over_PREF"] for p in pts]), np.array([p["T_ratio"] for p in pts])
    slope, icpt = np.polyfit(x, y, 1)
    r2 = 1 - np.sum((y - (slope * x + icpt)) ** 2) / np.sum((y - y.mean()) ** 2)
    return {"points": pts, "fit": {"slope": slope, "intercept": icpt, "R2": r2}}


def size_sweep(ct: Contact) -> list[dict]:
    rows = []
    for K in (3.0, 4.0):
        for phi in (0.25, 0.5, 0.75, 1.0):
            hist = ct.pseudo(phi, K, 1.0)
            t_smax = sh.refined_max(hist.smooth, [hist.depths, hist.y])["value"]
            row = {"K": K, "Phi": phi, "slope": 1.0}
            for label, f in (("no_limit", 0.0), ("limit_0.5", 0.5), ("limit_0.7", 0.7)):
                m = ct.metrics(hist, f * t_smax)
                row[label] = {"life_ratio": m["life_ratio"], "Ibar_ratio": m["Ibar_ratio"], "T_ratio": m["T_ratio"]}
            rows.append(row)
            print(row, flush=True)
    return rows


def markdown(res: dict) -> str:
    L = ["# Pseudo-transient against full transient, dry indented ball contact (benchmarks/life_transient.py)", "",
         f"{res['cells']}^2 cells over +/- {DOMAIN} a, {res['planes']} depth planes to 2a, window [-2a, 2a]^2, c = 8, "
         "e = 10/9, h = 0. Errors are pseudo / full - 1. Times indicative (shared machine).", ""]
    for label in ("no_limit", "limit_0.7"):
        L += [f"## {label.replace('_', ' ')}", "",
              "| Phi | K | D/Phi | dP/p_H | T_D/T_S full | contact | linear | contact chi=0.5 | Ibar_D/Ibar_S full "
              "| contact | linear | L/L_S full | L/L_S contact |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in res["compare"]:
            d = r[label]

            def pc(v):
                return "-" if v is None else f"{100 * v:+.2f} %"
            L.append(f"| {r['Phi']} | {r['K']:g} | {r['slope']} | {r['dP_over_pH']:.3f} | {d['full']['T_ratio']:.4f} "
                     f"| {pc(d['contact']['T_ratio_error'])} | {pc(d['linear']['T_ratio_error'])} "
                     f"| {pc(d['contact chi=0.5']['T_ratio_error'])} | {d['full']['Ibar_ratio']:.4f} "
                     f"| {pc(d['contact']['Ibar_ratio_error'])} | {pc(d['linear']['Ibar_ratio_error'])} "
                     f"| {d['full']['life_ratio']:.4f} | {d['contact']['life_ratio']:.4f} |")
        L.append("")
    L += ["## Additional pressure during the crossing (full transient)", "",
          "| Phi | K | D/Phi | dP/p_H centred | min, max with the indent centre in the contact | at the end frames |"
          " time full (s) | time pseudo (s) |", "|---|---|---|---|---|---|---|---|"]
    for r in res["compare"]:
        c = r["dP_crossing"]
        L.append(f"| {r['Phi']} | {r['K']:g} | {r['slope']} | {c['centred']:.4f} | {c['min_in_contact']:.4f}, "
                 f"{c['max_in_contact']:.4f} | {c['end_frames']:.4f} | {r['time_full_s']:.0f} | {r['time_pseudo_s']:.0f} |")
    if "linearity" in res:
        f = res["linearity"]["fit"]
        L += ["", f"## Linearity of T_Dmax/T_Smax in dP/P_REF (18 indents): slope {f['slope']:.4f}, intercept "
              f"{f['intercept']:.4f}, R^2 = {f['R2']:.4f}", ""]
    L += ["", "## Life ratio against indent size (D/Phi = 1, pseudo-transient, contact form)", "",
          "| K | Phi | T_D/T_S | L/L_S no limit | L/L_S tau_inf = 0.5 T_Smax | L/L_S tau_inf = 0.7 T_Smax |",
          "|---|---|---|---|---|---|"]
    for r in res["size_sweep"]:
        L.append(f"| {r['K']:g} | {r['Phi']} | {r['no_limit']['T_ratio']:.4f} | {r['no_limit']['life_ratio']:.4f} | "
                 f"{r['limit_0.5']['life_ratio']:.4f} | {r['limit_0.7']['life_ratio']:.4f} |")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", type=int, default=129)
    ap.add_argument("--planes", type=int, default=24)
    ap.add_argument("--cases", type=int, default=len(CASES))
    ap.add_argument("--linearity", action="store_true")
    ap.add_argument("--out", default="benchmarks/results")
    args = ap.parse_args()
    t0 = time.perf_counter()
    ct = Contact(args.cells, args.planes)
    res = {"cells": args.cells, "planes": args.planes, "compare": compare(ct, CASES[:args.cases])}
    if args.linearity:
        res["linearity"] = linearity(ct)
    res["size_sweep"] = size_sweep(ct)
    res["elapsed_s"] = time.perf_counter() - t0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    name = f"life_transient_{args.cells}"
    (out / f"{name}.json").write_text(json.dumps(res, indent=1, default=float))
    (out / f"{name}.md").write_text(markdown(res))
    print(f"written {out}/{name}.json, .md ({res['elapsed_s']:.0f} s)")


if __name__ == "__main__":
    main()
