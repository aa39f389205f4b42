"""Seed 004 eq 4.6 fitted to femcheck's own risk integrals, and how well it predicts runs left out of the fit.

    flock /tmp/femcheck-cpu.lock python benchmarks/life_eq46.py [--cells 129] [--out benchmarks/results]
    python benchmarks/life_eq46.py --report --out benchmarks/results        # re-fit and md + png from the JSON

Samples (dry, the ``indent-life`` scene: steel ball R = 10 mm, 1 kN, BEM over +-1.6 a on ``cells``^2 cells, 24
depth planes to 2 a, window [-2a, 2a]^2, c = 8, e = 10/9, h = 0): every indent Phi = 0.25, 0.5, 0.75, 1 a,
D/Phi = 0.25, 0.5, 1, 2, K = 3, 4, 8 (eq 2.16), its pseudo-transient stress history (seed 004 eq 4.5, contact form:
femcheck.bem.stress_history.pseudo_transient_history, what ``indent-life``'s ``bem`` model runs) computed once,
and I_D/I_S (eq 4.3 over the same window) at the fatigue limits T_inf/T_Smax = 0, 0.3, 0.5, 0.7 (T_Smax of the
smooth contact; seed 004 Fig 4.7's range 0.3-0.7). 48 indents x 4 limits = 192 samples.

Fit (femcheck.analytic.indent_risk.fit_eq46): ln(I_D/I_S - 1) - ln(Phi^3 [(T_Dmax/T_Smax - t)/(1 - t)]^c) =
ln q_K(K) + ln q_Tinf(t), least squares, q_Tinf(0) = 1, T_Dmax/T_Smax each sample's own (as the thesis uses it in
eq 4.6). Held out: (1) leave one indent out (its four limits), fit on the other 47; (2) whole slices: Phi = 0.75
(interpolation), Phi = 1 (extrapolation), D/Phi = 0.5, K = 4 (q_K interpolated linearly in K in its log between
the fitted K = 3 and 8), t = 0.5 (q_Tinf interpolated in t). Errors on I_D/I_S, on I-bar_D/I-bar_S = (I_D/I_S)^(1/c)
and on the life ratio L/L_S = (I_D/I_S)^(-1/e) (f_d = 1). (3) The thesis' route of Fig 4.4: T_Dmax/T_Smax
not computed but read off a straight line in the centred additional pressure dP/p_H (fitted per K on the other
indents), then eq 4.6.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from femcheck.analytic import indent_risk
from femcheck.bem import stress_history as sh
from femcheck.problems import _indent_life, _life_output as life_output
from femcheck.problems.indent_contact import solve_indented
from femcheck.scene import load_scene

PHIS = (0.25, 0.5, 0.75, 1.0)
SLOPES = (0.25, 0.5, 1.0, 2.0)
KS = (3.0, 4.0, 8.0)
LIMITS = (0.0, 0.3, 0.5, 0.7)
NU = 0.3


def scene(cells: int, phi: float = 0.5, slope: float = 1.0, K: float = 3.0, fatigue_limit: float = 0.0):
    return load_scene("indent-life", {"numerics.bem_cells": cells, "indent.diameter": phi, "indent.slope": slope,
                                      "indent.decay": K, "life.fatigue_limit": fatigue_limit,
                                      "life.indent_fraction": 1.0})


def indent_samples(phi: float, slope: float, K: float, cells: int, limits=LIMITS) -> dict:
    """One indent: the pseudo-transient history (as ``indent-life``'s bem model computes it) and, per fatigue limit
    t T_Smax, I_D/I_S and T_Dmax/T_Smax (dimensionless), plus dP/p_H of the centred indent."""
    t0 = time.perf_counter()
    sc = scene(cells, phi, slope, K)
    s = solve_indented(sc.params)
    a = s["a"]
    pm_s, pm_d, c = _indent_life._maps(s)
    z, wz = life_output.depth_planes(sc, a)
    hist = sh.pseudo_transient_history(pm_s, pm_d, c, NU, z, wz, sc["life.window"] * a, sc["life.chi_extent"] * a,
                                       sc["life.superposition"])
    t_smax = float(sh.refined_max(hist.smooth, [hist.depths, hist.y])["value"])
    rows = []
    for t in limits:
        out = life_output.indent_life(hist, a, s["p_hertz"], sc.with_overrides({"life.fatigue_limit": t * t_smax}))
        rows.append({"limit_ratio": t, "risk_ratio": out.stats["risk_ratio"],
                     "stress_ratio": out.quantities["stress_ratio"], "life_ratio": out.quantities["life_ratio"]})
    return {"phi": phi, "slope": slope, "K": K, "cells": cells, "T_Smax_over_pH": t_smax / s["p_hertz"],
            "dP_over_pH": s["dp"] / s["p_hertz"], "samples": rows, "time_s": time.perf_counter() - t0}


def flatten(indents: list[dict]) -> dict[str, np.ndarray]:
    cols = {k: [] for k in ("phi", "slope", "K", "limit_ratio", "stress_ratio", "risk_ratio", "indent")}
    for i, d in enumerate(indents):
        for r in d["samples"]:
            for k in ("phi", "slope", "K"):
                cols[k].append(d[k])
            for k in ("limit_ratio", "stress_ratio", "risk_ratio"):
                cols[k].append(r[k])
            cols["indent"].append(i)
    return {k: np.array(v, float) for k, v in cols.items()}


def _interp_log(table: dict[float, float], x: float) -> float:
    xs = np.array(sorted(table))
    return float(np.exp(np.interp(x, xs, np.log([table[v] for v in xs]))))


def predict(fit: indent_risk.Eq46Fit, S: dict[str, np.ndarray], sel: np.ndarray) -> np.ndarray:
    """eq 4.6 at the selected samples; a K or t the fit did not see gets q interpolated in its log."""
    qk = np.array([fit.q_k.get(k, None) or _interp_log(fit.q_k, k) for k in S["K"][sel]])
    qt = np.array([fit.q_t.get(t, None) or _interp_log(fit.q_t, t) for t in S["limit_ratio"][sel]])
    return indent_risk.eq46_risk_ratio(S["phi"][sel], S["stress_ratio"][sel], S["limit_ratio"][sel], fit.c, qk, qt)


def errors(pred: np.ndarray, true: np.ndarray, c: float, e: float) -> dict:
    """Relative errors of I_D/I_S, I-bar_D/I-bar_S and L/L_S (f_d = 1) over the samples with a prediction."""
    ok = np.isfinite(pred)
    p, t = pred[ok], true[ok]
    out = {"n": int(ok.sum()), "n_without_prediction": int((~ok).sum())}
    for name, f in (("risk_ratio", lambda x: x), ("Ibar_ratio", lambda x: x ** (1.0 / c)),
                    ("life_ratio", lambda x: x ** (-1.0 / e))):
        rel = f(p) / f(t) - 1.0
        out[name] = {"median_abs": float(np.median(np.abs(rel))), "p90_abs": float(np.quantile(np.abs(rel), 0.9)),
                     "max_abs": float(np.abs(rel).max()), "rms": float(np.sqrt(np.mean(rel ** 2)))}
    return out


def analyse(indents: list[dict], c: float = 8.0, e: float = 10.0 / 9.0) -> dict:
    S = flatten(indents)
    fit = indent_risk.fit_eq46(S["phi"], S["K"], S["limit_ratio"], S["stress_ratio"], S["risk_ratio"], c)
    allsel = np.ones(S["phi"].size, bool)
    res = {"fit": {"q_K": fit.q_k, "q_Tinf": fit.q_t, "used": fit.used, "samples": int(S["phi"].size),
                   "rms_log": fit.rms_log, "max_log": fit.max_log},
           "in_sample": errors(predict(fit, S, allsel), S["risk_ratio"], c, e)}
    # (1) leave one indent out
    pred = np.full(S["phi"].size, np.nan)
    for i in range(len(indents)):
        out = S["indent"] == i
        keep = ~out
        f = indent_risk.fit_eq46(S["phi"][keep], S["K"][keep], S["limit_ratio"][keep], S["stress_ratio"][keep],
                                 S["risk_ratio"][keep], c)
        pred[out] = predict(f, S, out)
    res["leave_one_indent_out"] = errors(pred, S["risk_ratio"], c, e)
    big = S["risk_ratio"] >= 1.1
    res["leave_one_indent_out_risk_ratio_above_1.1"] = errors(pred[big], S["risk_ratio"][big], c, e)
    res["below_smooth"] = {"n": int((S["risk_ratio"] < 1.0).sum()), "min": float(S["risk_ratio"].min())}
    res["leave_one_indent_out_by_limit"] = {
        str(t): errors(pred[S["limit_ratio"] == t], S["risk_ratio"][S["limit_ratio"] == t], c, e) for t in LIMITS}
    # (1b) the thesis' route (Fig 4.4): T_Dmax/T_Smax not computed but read off a straight line in the centred
    # additional pressure dP/p_H (fitted per K on the other indents), then eq 4.6
    dP = np.array([indents[int(i)]["dP_over_pH"] for i in S["indent"]])
    pred_dp = np.full(S["phi"].size, np.nan)
    lines = {}
    for i in range(len(indents)):
        out = S["indent"] == i
        keep = ~out
        same_k = keep & (S["K"] == indents[i]["K"])
        a, b0 = np.polyfit(dP[same_k], S["stress_ratio"][same_k], 1)
        f = indent_risk.fit_eq46(S["phi"][keep], S["K"][keep], S["limit_ratio"][keep], S["stress_ratio"][keep],
                                 S["risk_ratio"][keep], c)
        S2 = dict(S)
        S2["stress_ratio"] = np.where(out, a * dP + b0, S["stress_ratio"])
        pred_dp[out] = predict(f, S2, out)
    for K in KS:
        sel = S["K"] == K
        a, b0 = np.polyfit(dP[sel], S["stress_ratio"][sel], 1)
        r = S["stress_ratio"][sel] - (a * dP[sel] + b0)
        lines[str(K)] = {"slope": float(a), "intercept": float(b0),
                         "R2": float(1 - np.sum(r ** 2) / np.sum((S["stress_ratio"][sel] - S["stress_ratio"][sel].mean()) ** 2))}
    res["leave_one_indent_out_stress_ratio_from_dP"] = {**errors(pred_dp, S["risk_ratio"], c, e), "lines": lines}
    # (2) whole slices
    res["slices"] = {}
    for name, key, val in (("Phi = 0.75 (interpolation)", "phi", 0.75), ("Phi = 1 (extrapolation)", "phi", 1.0),
                           ("D/Phi = 0.5", "slope", 0.5), ("K = 4 (q_K interpolated)", "K", 4.0),
                           ("t = 0.5 (q_Tinf interpolated)", "limit_ratio", 0.5)):
        out = S[key] == val
        keep = ~out
        f = indent_risk.fit_eq46(S["phi"][keep], S["K"][keep], S["limit_ratio"][keep], S["stress_ratio"][keep],
                                 S["risk_ratio"][keep], c)
        res["slices"][name] = {**errors(predict(f, S, out), S["risk_ratio"][out], c, e),
                               "q_K": f.q_k, "q_Tinf": f.q_t}
    res["table"] = [{"phi": float(S["phi"][i]), "slope": float(S["slope"][i]), "K": float(S["K"][i]),
                     "t": float(S["limit_ratio"][i]), "stress_ratio": float(S["stress_ratio"][i]),
                     "risk_ratio": float(S["risk_ratio"][i]), "fit": float(predict(fit, S, np.arange(S["phi"].size) == i)[0]),
                     "leave_one_out": float(pred[i])} for i in range(S["phi"].size)]
    return res


def plot(doc: dict, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tab = doc["analysis"]["table"]
    fig, ax = plt.subplots(figsize=(6.2, 5.2))
    for t, m in zip(LIMITS, ("o", "s", "^", "D")):
        rows = [r for r in tab if r["t"] == t]
        ax.loglog([r["risk_ratio"] - 1 for r in rows], [r["leave_one_out"] - 1 for r in rows], m, ms=4, mfc="none",
                  label=f"T_inf/T_Smax = {t:g}")
    lim = [1e-3, 3e4]
    ax.plot(lim, lim, "k-", lw=0.8)
    ax.set_xlim(lim)
    ax.set_ylim(lim)
    ax.set_xlabel("femcheck I_D/I_S - 1 (dry BEM, pseudo-transient)")
    ax.set_ylabel("eq 4.6, leave-one-indent-out prediction - 1")
    f = doc["analysis"]["fit"]
    ax.set_title("seed 004 eq 4.6: q_K " + ", ".join(f"{k:g}: {v:.3g}" for k, v in f["q_K"].items()), fontsize=8)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _pct(x):
    return f"{100 * x:.1f} %"


def write_md(doc: dict, path: Path) -> None:
    a = doc["analysis"]
    f = a["fit"]
    L = ["# Seed 004 eq 4.6 fitted to femcheck's risk integrals (benchmarks/life_eq46.py)", "",
         f"Dry BEM ({doc['cells']}^2 cells over +-1.6 a), pseudo-transient history, c = 8, e = 10/9, window "
         f"[-2a, 2a]^2; {len(doc['indents'])} indents (Phi {PHIS}, D/Phi {SLOPES}, K {KS}) x limits {LIMITS}: "
         f"{f['samples']} samples, {f['used']} used by the fit (I_D/I_S - 1 > 1e-3 and a positive bracket). "
         f"Case time {sum(d['time_s'] for d in doc['indents']):.0f} s.", "",
         "q_K: " + ", ".join(f"K = {k:g}: {v:.4g}" for k, v in f["q_K"].items()) + "; q_Tinf: "
         + ", ".join(f"t = {k:g}: {v:.4g}" for k, v in f["q_Tinf"].items())
         + f"; misfit of ln(I_D/I_S - 1): rms {f['rms_log']:.3f}, max {f['max_log']:.3f}.", "",
         "| prediction | samples | I_D/I_S: median / p90 / max abs error | I-bar_D/I-bar_S | L/L_S (f_d = 1) |",
         "|---|---|---|---|---|"]

    def row(name, e):
        return (f"| {name} | {e['n']} | " + " | ".join(
            f"{_pct(e[q]['median_abs'])} / {_pct(e[q]['p90_abs'])} / {_pct(e[q]['max_abs'])}"
            for q in ("risk_ratio", "Ibar_ratio", "life_ratio")) + " |")

    L.append(row("in sample (all samples fitted)", a["in_sample"]))
    L.append(row("leave one indent out", a["leave_one_indent_out"]))
    L.append(row("leave one indent out, samples with I_D/I_S >= 1.1", a["leave_one_indent_out_risk_ratio_above_1.1"]))
    L.append(row("leave one indent out, T_Dmax/T_Smax from a line in dP/p_H (Fig 4.4 route)",
                 a["leave_one_indent_out_stress_ratio_from_dP"]))
    for t, e in a["leave_one_indent_out_by_limit"].items():
        L.append(row(f"leave one indent out, t = {t}", e))
    for name, e in a["slices"].items():
        L.append(row(f"slice held out: {name}", e))
    L += ["", "Fig 4.4 route: T_Dmax/T_Smax = slope x dP/p_H + intercept per K (all indents): " + "; ".join(
        f"K = {float(k):g}: {v['slope']:.3f} dP/p_H + {v['intercept']:.3f}, R^2 = {v['R2']:.3f}"
        for k, v in a["leave_one_indent_out_stress_ratio_from_dP"]["lines"].items()) + "."]
    L += ["", f"{a['below_smooth']['n']} samples have I_D/I_S < 1 (down to {a['below_smooth']['min']:.4f}: a shallow "
          "or flat-shouldered indent that lowers the stresses under its hole more than its shoulders raise them); "
          "eq 4.6 is >= 1 by construction and cannot represent them.",
          "", "Plot: `life_eq46.png` (leave-one-indent-out predictions against femcheck's values).", ""]
    path.write_text("\n".join(L))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", type=int, default=129)
    ap.add_argument("--out", default="benchmarks/results")
    ap.add_argument("--report", action="store_true")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "life_eq46.json"
    if args.report:
        doc = json.loads(path.read_text())
    else:
        doc = json.loads(path.read_text()) if path.exists() else {"cells": args.cells, "indents": []}
        if doc["cells"] != args.cells:
            doc = {"cells": args.cells, "indents": []}
        done = {(d["phi"], d["slope"], d["K"]) for d in doc["indents"]}
        for K in KS:
            for phi in PHIS:
                for slope in SLOPES:
                    if (phi, slope, K) in done:
                        continue
                    d = indent_samples(phi, slope, K, args.cells)
                    doc["indents"].append(d)
                    path.write_text(json.dumps(doc, indent=1, default=float))       # resumable
                    r = {s["limit_ratio"]: s["risk_ratio"] for s in d["samples"]}
                    print(f"Phi {phi} D/Phi {slope} K {K}: T_D/T_S {d['samples'][0]['stress_ratio']:.4f}, "
                          f"I_D/I_S {r[0.0]:.4g} (t 0) {r[0.7]:.4g} (t 0.7), {d['time_s']:.1f} s", flush=True)
    doc["analysis"] = analyse(doc["indents"])
    path.write_text(json.dumps(doc, indent=1, default=float))
    write_md(doc, out / "life_eq46.md")
    plot(doc, out / "life_eq46.png")
    print((out / "life_eq46.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
