"""Seed 004 Figs 4.10-4.11: the risk of a population of indents, dry and lubricated, at the §4.3.1 operating point.

    flock /tmp/femcheck-cpu.lock python benchmarks/life_population.py [--grid 129] [--out benchmarks/results]
        [--diameter 0.56:1.5] [--slope 0.6:1.5] [--fractions 0.01 0.1 1]
    python benchmarks/life_population.py --report [--diameter M:GSD] [--slope M:GSD]   # population from the maps
    python benchmarks/life_population.py --report --store    # also store it for femcheck's report

``--store`` writes the maps and the population under references/indent_population/, keyed on the inputs and on the
code of this script, of benchmarks/ehl_life.py and of the femcheck modules they import (femcheck.population_map):
the indent-life scene's report shows them while that key is current.

Maps (the expensive part, cached case by case in the JSON, resumable): I_D/I_S over the indent diameter
Phi = 0.25, 0.4, 0.56, 0.8, 1 b and slope D/Phi = 0.3, 0.6, 1.2 at K = 4, for
- EHL: the §4.3.1 point of benchmarks/ehl_life.py (Rx = Ry = 5 mm, E' = 226 GPa, eta0 = 0.04 Pa s,
  alpha = 2e-8 1/Pa, M = 350, L = 17, Roelands + Dowson-Higginson, pure rolling, [-2.5, 1.5] x [-2, 2] b on
  ``grid``^2 nodes): the smooth steady solution, the indent marched from the inlet to the centre (NU2, time step =
  mesh size; femcheck.ehl.transient.march, as benchmarks/ehl_master_curves.py does), the pseudo-transient stress
  history of the smooth and the centred pressures (seed 004 eq 4.5, contact form);
- dry: the BEM of the same ball at the same load (benchmarks/ehl_life.py's DryContact, cells of the EHL mesh
  size), the same pseudo-transient history.
Both through the same life model (c = 8, e = 10/9, h = 0, window [-2b, 2b]^2, 24 planes to 2b), fatigue limit
0.7 T_Smax of the dry smooth contact (one material constant, §4.3.1's T_inf/T_Smax ~ 0.7) and 0.

Population (seed 004 §4.3: indents of a standard pollution test; spec B.6: median dimensionless diameter 0.56 and
slope 0.6): diameter and slope independent and log-normal, given as median:geometric standard deviation (default
0.56:1.5 and 0.6:1.5; the thesis prints the medians only, the spreads are an input); E[I_D/I_S] by
femcheck.analytic.indent_risk.map_population_mean over the map (bilinear in the logs, the edge value held beyond
it; Gauss-Legendre between the map's nodes;
the probability mass outside the map is reported; an EHL cell refused on the grid (negative film over steep
shoulders) takes the dry cell's value when every computed cell has EHL <= max(dry, 1), and the EHL mean is then
reported as an upper bound), and the life ratio of a track whose windows hold an indent
with probability f_d, L/L_S = [1 + f_d (E[I_D/I_S] - 1)]^(-1/e) (eq 4.10, spec B.3).
"""
from __future__ import annotations

import argparse
import copy
import dataclasses
import importlib.util
import json
import sys
import time
from pathlib import Path

import numpy as np

from femcheck import population_map
from femcheck.analytic import indent_risk
from femcheck.bem import stress_history as sh
from femcheck.ehl import model, transient
from femcheck.ehl.film import Indent
from femcheck.problems import _life_output as life_output

PHIS = (0.25, 0.4, 0.56, 0.8, 1.0)
SLOPES = (0.3, 0.6, 1.2)
K = 4.0
TOL = 1e-7
TAU_RATIO = 0.7


def _ehl_life():
    path = Path(__file__).resolve().parent / "ehl_life.py"
    spec = importlib.util.spec_from_file_location("ehl_life_for_population", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


EL = _ehl_life()


class Point:
    """The §4.3.1 EHL point on ``grid``^2 nodes: its smooth solution and multigrid (solved once), the dry BEM of
    the same ball (smooth solved once), the depth planes and the dry T_Smax."""

    def __init__(self, grid: int):
        self.grid = grid
        self.s = EL.ehl_setup(grid)
        self.g = self.s.g
        self.smooth, self.mg = model.solve_smooth(self.s, TOL, TOL)
        h = 4.0 / (grid - 1)
        self.dry = EL.DryContact(self.g, grid - 1 if (grid - 1) % 2 else grid, h)
        self.z, self.wz = life_output.depth_planes(EL.life_scene(0.0), self.g.b)
        ps = EL.crossing_pass(self.smooth.x, self.smooth.y, self.smooth.P, [(0.0, self.smooth.P)], self.g.b,
                              self.g.p_hertz, 1.0)
        self.ehl_smooth, self.centre = ps["smooth"], ps["centre"]
        hist = sh.smooth_history(sh.PressureMap.on_grid(self.dry.grid, self.dry.smooth), EL.NU, self.z, self.wz,
                                 2.0 * self.g.b)
        self.t_smax_dry = float(sh.refined_max(hist.smooth, [hist.depths, hist.y])["value"])

    def ehl_centred(self, phi: float, slope: float) -> np.ndarray:
        mg = copy.deepcopy(self.mg)
        h = mg.fine.h
        centre, _ = model.crossing_steps(phi, self.s.prob.x_start, h, 1.0)
        ind = Indent(phi, slope * phi, K, x0=-centre * h, speed_ratio=1.0)
        mg.prob = dataclasses.replace(self.s.prob, indent=ind)
        mg.set_time(0.0)
        transient.start(mg)
        hist = transient.march(mg, centre, tol=TOL, load_tol=TOL, keep=lambda k, T: k == centre, base=self.smooth.P)
        assert abs(ind.centre(mg.T)) < 1e-9
        return hist.snapshots[-1].P, hist

    def case(self, phi: float, slope: float) -> dict:
        g = self.g
        t0 = time.perf_counter()
        out = {"phi": phi, "slope": slope, "K": K}
        try:
            P, hist = self.ehl_centred(phi, slope)
            t1 = time.perf_counter()
            pm_d = sh.PressureMap(self.ehl_smooth.x, self.ehl_smooth.y, P * g.p_hertz)
            ph = sh.pseudo_transient_history(self.ehl_smooth, pm_d, self.centre, EL.NU, self.z, self.wz, 2.0 * g.b,
                                             EL.CHI * g.b, "contact")
            out["ehl"] = {"dP_over_pH": float((P - self.smooth.P).max()), "film_min": float(min(hist.h_min)),
                          "steps": len(hist.T), "time_march_s": t1 - t0,
                          **{lab: EL.life_numbers(ph, g.b, g.p_hertz, tau) for lab, tau in
                             (("limit_0.7", TAU_RATIO * self.t_smax_dry), ("no_limit", 0.0))}}
        except Exception as err:       # noqa: BLE001 - a refused EHL case (negative film) is a result
            out["ehl"] = {"status": "refused", "error": f"{type(err).__name__}: {str(err)[:300]}"}
        t2 = time.perf_counter()
        dc = self.dry
        p = dc.dented({"diameter": phi, "slope": slope, "decay": K}, 0.0)
        pd = sh.pseudo_transient_history(sh.PressureMap.on_grid(dc.grid, dc.smooth), sh.PressureMap.on_grid(dc.grid, p),
                                         dc.c, EL.NU, self.z, self.wz, 2.0 * g.b, EL.CHI * g.b, "contact")
        out["dry"] = {"dP_over_pH": float((p - dc.smooth).max()) / g.p_hertz,
                      **{lab: EL.life_numbers(pd, g.b, g.p_hertz, tau) for lab, tau in
                         (("limit_0.7", TAU_RATIO * self.t_smax_dry), ("no_limit", 0.0))}}
        out["time_dry_s"] = time.perf_counter() - t2
        out["time_s"] = time.perf_counter() - t0
        return out


def maps(doc: dict) -> dict:
    """ratio[i, j] (I_D/I_S) at PHIS[i] x SLOPES[j] per contact and fatigue limit; NaN where refused. An EHL cell
    refused on the map's grid and solved on a finer one (``refined``, --refine-refused) takes the finer grid's
    value (each grid's dented window against its own smooth one)."""
    out = {}
    for who in ("ehl", "dry"):
        for lab in ("limit_0.7", "no_limit"):
            R = np.full((len(doc["phis"]), len(doc["slopes"])), np.nan)
            for c in doc["cases"]:
                d = c.get(who, {})
                if who == "ehl" and lab not in d and lab in c.get("refined", {}).get("ehl", {}):
                    d = c["refined"]["ehl"]
                if lab in d:
                    R[doc["phis"].index(c["phi"]), doc["slopes"].index(c["slope"])] = d[lab]["risk_ratio"]
            out[f"{who} {lab}"] = R
    return out


def population(doc: dict, diameter: tuple[float, float], slope: tuple[float, float], fractions, e=10.0 / 9.0) -> dict:
    res = {"diameter": {"median": diameter[0], "gsd": diameter[1]}, "slope": {"median": slope[0], "gsd": slope[1]},
           "mass_outside_map": {
               "diameter": indent_risk.mass_outside(doc["phis"][0], doc["phis"][-1], *diameter),
               "slope": indent_risk.mass_outside(doc["slopes"][0], doc["slopes"][-1], *slope)}}
    m = maps(doc)
    for name, R in m.items():
        extra = {}
        if not np.isfinite(R).all():
            dry = m[name.replace("ehl", "dry")]
            both = np.isfinite(R)
            if (not name.startswith("ehl") or not np.all(R[both] <= np.maximum(dry[both], 1.0))
                    or not np.isfinite(dry).all()):
                res[name] = {"status": f"map incomplete ({int((~both).sum())} refused cells)"}
                continue
            # the EHL cells refused (negative film on this grid) take the dry value: an upper bound where every
            # computed cell has EHL <= dry or both below 1 (checked above; seed 004 §4.3.1: EHL less severe than
            # dry)
            R = np.where(both, R, dry)
            extra = {"upper_bound": True, "refused_cells_at_dry_value": [
                [doc["phis"][i], doc["slopes"][j]] for i, j in zip(*np.nonzero(~both))]}
        f = indent_risk.map_interpolant(doc["phis"], doc["slopes"], R)
        mean = indent_risk.map_population_mean(doc["phis"], doc["slopes"], R, diameter, slope)
        median = float(f(np.array([diameter[0]]), np.array([slope[0]]))[0])
        res[name] = {**extra, "mean_risk_ratio": mean, "median_indent_risk_ratio": median,
                     "life_ratio": {str(fd): indent_risk.population_life_ratio(mean, fd, e) for fd in fractions},
                     "life_ratio_median_indent": {str(fd): indent_risk.population_life_ratio(median, fd, e)
                                                  for fd in fractions}}
    return res


def plot(doc: dict, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    m = maps(doc)
    pop = doc["population"]
    fig, axes = plt.subplots(2, 2, figsize=(9, 7.2), sharex=True, sharey=True)
    P, S = np.meshgrid(doc["phis"], doc["slopes"], indexing="ij")
    for ax, name in zip(axes.ravel(), ("dry limit_0.7", "ehl limit_0.7", "dry no_limit", "ehl no_limit")):
        R = m[name]
        from matplotlib.colors import TwoSlopeNorm
        cs = ax.contourf(P, S, np.log10(R), levels=np.concatenate([np.linspace(-0.02, 0, 5)[:-1],
                                                                    np.linspace(0, 2, 21)]),
                         cmap="RdBu_r", norm=TwoSlopeNorm(0.0, -0.02, 2.0), extend="both")
        for i, p in enumerate(doc["phis"]):
            for j, s in enumerate(doc["slopes"]):
                ax.text(p, s, f"{R[i, j]:.3g}" if np.isfinite(R[i, j]) else "refused", fontsize=7, ha="center",
                        va="center", color="k")
        # the population: 1 and 2 geometric standard deviations around the medians
        dm, dg = pop["diameter"]["median"], pop["diameter"]["gsd"]
        sm, sg = pop["slope"]["median"], pop["slope"]["gsd"]
        th = np.linspace(0, 2 * np.pi, 200)
        for k in (1, 2):
            ax.plot(dm * dg ** (k * np.cos(th)), sm * sg ** (k * np.sin(th)), "k--", lw=0.7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(doc["phis"], [f"{v:g}" for v in doc["phis"]])
        ax.set_yticks(doc["slopes"], [f"{v:g}" for v in doc["slopes"]])
        ax.minorticks_off()
        q = pop.get(name, {})
        tail = (f"; E {'<=' if q.get('upper_bound') else '='} {q['mean_risk_ratio']:.4g}"
                if "mean_risk_ratio" in q else "")
        ax.set_title(f"{name}: I_D/I_S{tail}", fontsize=9)
        fig.colorbar(cs, ax=ax, label="log10(I_D/I_S)")
    for ax in axes[-1]:
        ax.set_xlabel("Phi (indent diameter / b)")
    for ax in axes[:, 0]:
        ax.set_ylabel("D/Phi (slope)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_md(doc: dict, path: Path) -> None:
    m = maps(doc)
    pop = doc["population"]
    L = ["# Risk of indent populations, dry and lubricated, at seed 004 §4.3.1 (benchmarks/life_population.py)", "",
         f"EHL {doc['grid']}^2 nodes (M = 350, L = 17), dry BEM of the same ball and load with cells of the same "
         "size; K = 4, pseudo-transient histories, c = 8, e = 10/9, window [-2b, 2b]^2. I_D/I_S "
         "(= (I-bar_D/I-bar_S)^c) per indent; fatigue limit 0.7 T_Smax(dry) "
         f"= {doc['tau_inf_over_pH']:.4f} p_H and 0. Case time {sum(c['time_s'] for c in doc['cases']):.0f} s.", ""]
    fine = {(c["phi"], c["slope"]): c["refined"] for c in doc["cases"] if "refined" in c}

    def cell(name, i, j, v):
        if not np.isfinite(v):
            return "refused"
        r = fine.get((doc["phis"][i], doc["slopes"][j]))
        if r and name.startswith("ehl"):
            return f"{v:.5g} ({r['grid']}^2; refused on {doc['grid']}^2)"
        return f"{v:.5g}"

    for name, R in m.items():
        L += [f"## {name}", "", "| Phi \\ D/Phi | " + " | ".join(f"{s:g}" for s in doc["slopes"]) + " |",
              "|---|" + "---|" * len(doc["slopes"])]
        for i, p in enumerate(doc["phis"]):
            L.append(f"| {p:g} | " + " | ".join(cell(name, i, j, R[i, j]) for j in range(len(doc["slopes"]))) + " |")
        L.append("")
    for (p, sl), r in fine.items():
        L.append(f"Refined cell Phi = {p:g}, D/Phi = {sl:g} on {r['grid']}^2 ({r['time_s']:.0f} s): dry there "
                 f"{r['dry']['limit_0.7']['risk_ratio']:.5g} (0.7) and {r['dry']['no_limit']['risk_ratio']:.5g} (no "
                 f"limit); EHL film minimum {r['ehl'].get('film_min', float('nan')):.3g} b^2/Rx.")
    if fine:
        L.append("")
    L += ["## Population", "",
          f"Diameter log-normal, median {pop['diameter']['median']:g} b, gsd {pop['diameter']['gsd']:g}; slope "
          f"median {pop['slope']['median']:g}, gsd {pop['slope']['gsd']:g}. Probability outside the map: diameter "
          f"{100 * pop['mass_outside_map']['diameter']:.1f} %, slope {100 * pop['mass_outside_map']['slope']:.1f} % "
          "(given the edge value).", "",
          "| contact, limit | E[I_D/I_S] | median indent's I_D/I_S | L/L_S at f_d = " + ", ".join(doc["fractions"])
          + " | median indent only |", "|---|---|---|---|---|"]
    for name in m:
        q = pop[name]
        if "mean_risk_ratio" not in q:
            L.append(f"| {name} | {q['status']} | | | |")
            continue
        ub = " (upper bound: refused cells at the dry value)" if q.get("upper_bound") else ""
        L.append(f"| {name}{ub} | {q['mean_risk_ratio']:.5g} | {q['median_indent_risk_ratio']:.5g} | "
                 + ", ".join(f"{v:.4f}" for v in q["life_ratio"].values()) + " | "
                 + ", ".join(f"{v:.4f}" for v in q["life_ratio_median_indent"].values()) + " |")
    L += ["", "Plot: `life_population.png` (log10(I_D/I_S) over the map, blue below 1; dashed: the population's 1 and 2 "
          "geometric standard deviations).", ""]
    path.write_text("\n".join(L))


def store_inputs(doc: dict) -> dict:
    """What the stored map depends on besides code: the EHL scene at the operating point and grid, the life
    constants, the map's axes and tolerances, the refined cells' grid and the population."""
    from femcheck.result import _jsonable
    ehl = EL.load_scene("ehl-indent", {**EL.POINT, "numerics.grid": doc["grid"]}).params
    lifep = EL.life_scene(0.0).params
    return _jsonable({"grid": doc["grid"], "phis": doc["phis"], "slopes": doc["slopes"], "K": doc["K"], "tol": TOL,
                      "tau_ratio": TAU_RATIO, "chi": EL.CHI, "nu": EL.NU,
                      "ehl_scene": {k: v for k, v in ehl.items() if not k.startswith(("models.", "tolerances."))},
                      "life": {k: v for k, v in lifep.items() if k.startswith(("life.", "numerics.life_"))
                               and k != "life.fatigue_limit"},
                      "refined": sorted({c["refined"]["grid"] for c in doc["cases"] if "refined" in c}),
                      "population": {k: doc["population"][k] for k in ("diameter", "slope")},
                      "fractions": doc["fractions"]})


def store_result(doc: dict) -> dict:
    """The stored part: maps (null where refused), refined cells, population numbers, fatigue limit, case time."""
    from femcheck.result import _jsonable
    return _jsonable({"grid": doc["grid"], "phis": doc["phis"], "slopes": doc["slopes"], "K": doc["K"],
                      "tau_inf_over_pH": doc["tau_inf_over_pH"], "T_Smax_dry_over_pH": doc["T_Smax_dry_over_pH"],
                      "maps": maps(doc), "fractions": doc["fractions"], "population": doc["population"],
                      "refined": [[c["phi"], c["slope"], c["refined"]["grid"]] for c in doc["cases"] if "refined" in c],
                      "case_time_s": sum(c["time_s"] for c in doc["cases"])
                      + sum(c["refined"]["time_s"] for c in doc["cases"] if "refined" in c)})


def _pair(text: str) -> tuple[float, float]:
    a, b = text.split(":")
    return float(a), float(b)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--grid", type=int, default=129)
    ap.add_argument("--out", default="benchmarks/results")
    ap.add_argument("--diameter", default="0.56:1.5", help="median:gsd of Phi")
    ap.add_argument("--slope", default="0.6:1.5", help="median:gsd of D/Phi")
    ap.add_argument("--fractions", nargs="*", default=["0.01", "0.1", "1"])
    ap.add_argument("--report", action="store_true")
    ap.add_argument("--store", action="store_true", help="store the maps for femcheck's report (references/)")
    ap.add_argument("--refine-refused", type=int, default=None, metavar="GRID",
                    help="solve the EHL cells refused on --grid again on GRID^2 nodes (e.g. 257)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "life_population.json"
    doc = json.loads(path.read_text()) if path.exists() else None
    if doc is None or doc["grid"] != args.grid:
        doc = {"grid": args.grid, "phis": list(PHIS), "slopes": list(SLOPES), "K": K, "cases": []}
    if not args.report and not args.refine_refused:
        pt = Point(args.grid)
        doc["tau_inf_over_pH"] = TAU_RATIO * pt.t_smax_dry / pt.g.p_hertz
        doc["T_Smax_dry_over_pH"] = pt.t_smax_dry / pt.g.p_hertz
        done = {(c["phi"], c["slope"]) for c in doc["cases"]}
        for phi in PHIS:
            for slope in SLOPES:
                if (phi, slope) in done:
                    continue
                c = pt.case(phi, slope)
                doc["cases"].append(c)
                path.write_text(json.dumps(doc, indent=1, default=float))
                e = c["ehl"].get("limit_0.7", {}).get("risk_ratio", float("nan"))
                print(f"Phi {phi} D/Phi {slope}: I_D/I_S (0.7) EHL {e:.5g} dry {c['dry']['limit_0.7']['risk_ratio']:.5g}"
                      f" ({c['time_s']:.0f} s) {c['ehl'].get('error', '')[:120]}", flush=True)
    if args.refine_refused:
        todo = [c for c in doc["cases"] if "limit_0.7" not in c["ehl"] and "refined" not in c]
        if todo:
            fine = Point(args.refine_refused)
            for c in todo:
                r = fine.case(c["phi"], c["slope"])
                c["refined"] = {"grid": args.refine_refused, "ehl": r["ehl"], "dry": r["dry"], "time_s": r["time_s"]}
                path.write_text(json.dumps(doc, indent=1, default=float))
                e = r["ehl"].get("limit_0.7", {}).get("risk_ratio", float("nan"))
                print(f"refined {args.refine_refused}^2 Phi {c['phi']} D/Phi {c['slope']}: I_D/I_S (0.7) EHL {e:.5g} "
                      f"dry {r['dry']['limit_0.7']['risk_ratio']:.5g} ({r['time_s']:.0f} s) "
                      f"{r['ehl'].get('error', '')[:120]}", flush=True)
    doc["fractions"] = args.fractions
    doc["population"] = population(doc, _pair(args.diameter), _pair(args.slope), [float(f) for f in args.fractions])
    path.write_text(json.dumps(doc, indent=1, default=float))
    write_md(doc, out / "life_population.md")
    plot(doc, out / "life_population.png")
    if args.store:
        res = store_result(doc)
        print("stored:", population_map.store(res, store_inputs(doc), run_time_s=res["case_time_s"]))
    print((out / "life_population.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
