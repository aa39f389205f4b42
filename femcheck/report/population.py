"""Report section: the risk of an indent population, dry and lubricated (seed 004 §4.3, Figs 4.10-4.11), from the
stored map (:mod:`femcheck.population_map`; it never computes one).

Per indent (diameter Phi = phi/b, slope D/Phi, K = 4) the map holds I_D/I_S, the dented window's risk integral
over the smooth one (seed 004 eqs 4.2-4.3, c = 8, h = 0), dry (BEM) and lubricated (transient EHL, pure rolling)
at the §4.3.1 operating point, with the fatigue limit 0.7 T_Smax of the dry smooth contact and without one.
Over a log-normal population (median and geometric standard deviation of each, independent) the mean E[I_D/I_S]
gives the life ratio of a track whose windows hold an indent with probability f_d (eq 4.10):
L/L_S = [1 + f_d (E[I_D/I_S] - 1)]^(-1/e), e = 10/9. Dimensionless throughout.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402

from .. import population_map  # noqa: E402
from .kinds import Figure, KindSection, Table  # noqa: E402
from .plots import save_figure  # noqa: E402

PANELS = ("dry limit_0.7", "ehl limit_0.7", "dry no_limit", "ehl no_limit")


def _label(name: str) -> str:
    who, lim = name.split()
    return f"{'EHL' if who == 'ehl' else 'dry'}, " + ("tau_inf = 0.7 T_Smax" if lim == "limit_0.7" else "no limit")


def maps_figure(res: dict, path: Path) -> str:
    """2 x 2 maps of log10(I_D/I_S) over (Phi, D/Phi), the cell values printed, the population's 1 and 2
    geometric-standard-deviation ellipses dashed."""
    phis, slopes, pop = res["phis"], res["slopes"], res["population"]
    P, S = np.meshgrid(phis, slopes, indexing="ij")
    fig, axes = plt.subplots(2, 2, figsize=(9, 7.2), sharex=True, sharey=True)
    levels = np.concatenate([np.linspace(-0.02, 0, 5)[:-1], np.linspace(0, 2, 21)])
    th = np.linspace(0, 2 * np.pi, 200)
    for ax, name in zip(axes.ravel(), PANELS):
        R = np.array([[np.nan if v is None else v for v in row] for row in res["maps"][name]], dtype=float)
        cs = ax.contourf(P, S, np.log10(R), levels=levels, cmap="RdBu_r", norm=TwoSlopeNorm(0.0, -0.02, 2.0),
                         extend="both")
        for i, p in enumerate(phis):
            for j, s in enumerate(slopes):
                ax.text(p, s, f"{R[i, j]:.3g}" if np.isfinite(R[i, j]) else "refused", fontsize=7, ha="center",
                        va="center")
        dm, dg = pop["diameter"]["median"], pop["diameter"]["gsd"]
        sm, sg = pop["slope"]["median"], pop["slope"]["gsd"]
        for k in (1, 2):
            ax.plot(dm * dg ** (k * np.cos(th)), sm * sg ** (k * np.sin(th)), "k--", lw=0.7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(phis, [f"{v:g}" for v in phis])
        ax.set_yticks(slopes, [f"{v:g}" for v in slopes])
        ax.minorticks_off()
        q = pop.get(name, {})
        tail = (f"; E[I_D/I_S] {'<=' if q.get('upper_bound') else '='} {q['mean_risk_ratio']:.4g}"
                if "mean_risk_ratio" in q else "")
        ax.set_title(f"{_label(name)}{tail}", fontsize=9)
        fig.colorbar(cs, ax=ax, label="log10(I_D/I_S)")
    for ax in axes[-1]:
        ax.set_xlabel("Phi (indent diameter / b)")
    for ax in axes[:, 0]:
        ax.set_ylabel("D/Phi (slope)")
    fig.suptitle(f"Indent population risk maps, seed 004 §4.3.1 point, {res['grid']}^2 nodes", fontsize=10)
    return save_figure(fig, path)


def table(res: dict, key: str, created: str) -> Table:
    pop = res["population"]
    fr = res["fractions"]
    rows = []
    for name in PANELS:
        q = pop[name]
        if "mean_risk_ratio" not in q:
            rows.append([_label(name), q.get("status", "-")] + ["-"] * (1 + 2 * len(fr)))
            continue
        rows.append([_label(name) + (" (upper bound)" if q.get("upper_bound") else ""), q["mean_risk_ratio"],
                     q["median_indent_risk_ratio"]] + [q["life_ratio"][f] for f in sorted(q["life_ratio"], key=float)]
                    + [q["life_ratio_median_indent"][f] for f in sorted(q["life_ratio_median_indent"], key=float)])
    fs = sorted(pop[PANELS[0]].get("life_ratio", {}), key=float) or fr
    refined = "; ".join(f"Phi {p:g}, D/Phi {s:g} on {g}^2" for p, s, g in res.get("refined", []))
    return Table("Indent population (seed 004 §4.3, Figs 4.10-4.11): stored map",
                 ["contact, fatigue limit", "E[I_D/I_S]", "median indent I_D/I_S"]
                 + [f"L/L_S, f_d = {f}" for f in fs] + [f"median indent only, f_d = {f}" for f in fs], rows,
                 f"Diameter Phi log-normal, median {pop['diameter']['median']:g} b, geometric standard deviation "
                 f"{pop['diameter']['gsd']:g}; slope D/Phi median {pop['slope']['median']:g}, gsd "
                 f"{pop['slope']['gsd']:g} (the thesis' medians; the spreads are an input). Probability outside the "
                 f"map (given the edge value): diameter {100 * pop['mass_outside_map']['diameter']:.1f} %, slope "
                 f"{100 * pop['mass_outside_map']['slope']:.1f} %. Fatigue limit 0.7 T_Smax(dry) = "
                 f"{res['tau_inf_over_pH']:.4f} p_H. Cells refused on {res['grid']}^2 (negative film) and solved "
                 f"finer: {refined or 'none'}. Operating point of seed 004 §4.3.1 (Rx = Ry = 5 mm, M = 350, L = 17), "
                 f"not this scene's contact. Computed by benchmarks/life_population.py (case time "
                 f"{res['case_time_s']:.0f} s), stored {created} under key {key[:16]}, which matches today's code.")


def section(outdir: Path, prefix: str, refs: Path | None = None, root: Path | None = None) -> KindSection:
    """The stored population map as a table and a figure when it is current; a one-line table saying why not
    otherwise (missing, stale, or not checkable without the benchmark scripts)."""
    doc, status = population_map.load_current(refs, root)
    if doc is None:
        why = {"missing": "none stored", "stale": "the stored map was computed by other code than today's",
               "unchecked": "the benchmark scripts are not installed, so its key cannot be checked"}[status]
        return KindSection([Table("Indent population (seed 004 §4.3): not shown", ["status", "why", "to make it"],
                                  [[status, why, "flock /tmp/femcheck-cpu.lock python benchmarks/life_population.py "
                                    "&& python benchmarks/life_population.py --report --store"]])])
    res, prov = doc["result"], doc["provenance"]
    name = maps_figure(res, outdir / f"{prefix}-population.png")
    return KindSection([table(res, prov["key"], prov["created"])],
                       [Figure(name, "I_D/I_S per indent over diameter Phi = phi/b and slope D/Phi (K = 4), dry BEM and "
                               "transient EHL at seed 004 §4.3.1 (stored map; log colour scale, blue below 1); "
                               "dashed: the population's 1 and 2 geometric standard deviations.")])
