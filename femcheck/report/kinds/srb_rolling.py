"""Report section of the srb_rolling kind: seed 000 Table 2 laid out as in the paper (full slip, CECT, FE, with
the paper's values beside ours), the lateral distributions of normal and tangential load of both contacts (Figs
8-9), the adhesion/slip maps of both contacts (Figs 10-11) and, when the sweep has been run
(``benchmarks/srb_fig17.py`` -> ``benchmarks/results/srb_fig17.json``), the Fig. 17 curves with both branches."""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ...result import RunResult  # noqa: E402
from ..plots import save_figure  # noqa: E402
from . import Figure, KindSection, Table  # noqa: E402

ROWS = (("f_x_inner", "f_x,i", 1.0), ("f_x_outer", "f_x,e", 1.0), ("f_lat_inner", "f_lat,i", 1.0),
        ("f_lat_outer", "f_lat,e", 1.0), ("f_lat_sum", "sum f_lat", 1.0), ("d_y", "d_y (um)", 1e6),
        ("tilt", "tilt beta (mrad)", 1e3), ("skew", "skew gamma_p (mrad)", 1e3),
        ("friction_power_inner", "P_fric,i (W)", 1.0), ("friction_power_outer", "P_fric,e (W)", 1.0),
        ("adhesion_fraction_inner", "adhesion fraction i", 1.0), ("adhesion_fraction_outer", "adhesion fraction e",
                                                                   1.0),
        ("omega_m_deviation", "cage speed omega_m / omega_m,o - 1", 1.0),
        ("omega_R_deviation", "roller speed omega_R / omega_R,o - 1", 1.0))
SWEEP = Path(__file__).resolve().parents[3] / "benchmarks" / "results" / "srb_fig17.json"
CONTACTS = ("inner", "outer")


def _q(run: RunResult, model: str) -> dict:
    m = run.models.get(model)
    return m.quantities if m is not None and m.status == "ok" else {}


def _table(run: RunResult) -> Table:
    paper = run.models.get("paper")
    pst = paper.stats if paper is not None and paper.status == "ok" else {}
    cols = [("full slip", _q(run, "full_slip")), ("full slip (paper)", pst.get("full_slip", {})),
            ("CECT", _q(run, "cect")), ("CECT (paper)", _q(run, "paper")), ("FE at the CECT pose", _q(run, "fem")),
            ("FEM (paper)", pst.get("fem", {})),
            ("H+C s0 = 0", _q(run, "strip")), ("H+C s0 = s0_CECT", _q(run, "strip_s0"))]
    rows = []
    for key, label, scale in ROWS:
        rows.append([label] + [("" if key not in q else q[key] * scale) for _, q in cols])
    mu = run.params.get("friction.mu")
    note = (f"mu = {mu:g}, N = {run.params.get('load.normal', 0) / 1e3:g} kN, configuration "
            f"{run.params.get('equilibrium.configuration', 1)}. f = F/(mu N): f_x along the roller's motion relative "
            "to the inner ring, f_lat towards the bearing mid-plane; d_y the friction-induced axial offset (seed 000 "
            "Table 2's conventions, spec srb-rolling E10/E11). Full slip: p_t = -mu p_n w/|w| with the CECT pressure "
            "and rigid slip at the CECT equilibrium (not an equilibrium). FE at the CECT pose: femcheck's FE compliances and "
            "Coulomb solver at the CECT tilt, skew and offset, speeds re-balanced, three levels (no d_y: not an FE "
            "equilibrium). Speeds as deviations from the rigid-kinematics speeds omega_m,o, omega_R,o (seed 000 eqs "
            "2-3). The cage's deviation is 0.55 x the difference of the two contacts' free-rolling creepages (inner "
            "minus outer, each about 5e-3): a 1 % difference between two models in either creepage moves it by "
            "2.8e-5, three times its CECT value; the FE's is not a check of the CECT's at that accuracy. (Its "
            "former -1.5e-3 came from the inner slip taken on the undisplaced inner groove, 25 um from the ring.) "
            "Blank: not given / not computed.")
    return Table("Seed 000 Table 2: full slip, CECT and FEM", ["quantity"] + [c for c, _ in cols], rows, note)


def _lateral(run: RunResult, path: Path) -> str | None:
    m = run.models.get("cect")
    if m is None or m.status != "ok" or "inner_lateral_normal" not in m.fields:
        return None
    fig, axes = plt.subplots(3, 2, figsize=(9.0, 7.0), sharex="col")
    for j, c in enumerate(CONTACTS):
        s = m.fields[f"{c}_s"] * 1e3
        axes[0, j].plot(s, m.fields[f"{c}_lateral_normal"] / 1e3, label="CECT")
        axes[1, j].plot(s, m.fields[f"{c}_lateral_fx"] / 1e3, label="CECT")
        axes[2, j].plot(s, m.fields[f"{c}_lateral_fs"] / 1e3, label="CECT")
        for name in ("strip", "strip_s0"):
            h = run.models.get(name)
            if h is not None and h.status == "ok" and f"{c}_y" in h.fields:
                sign = -1.0 if c == "inner" else 1.0       # H+C gives F_X along X; CECT's p_x is along x_j
                axes[0, j].plot(h.fields[f"{c}_y"] * 1e3, h.fields[f"{c}_lateral_normal"] / 1e3, "--", label=name)
                axes[1, j].plot(h.fields[f"{c}_y"] * 1e3, sign * h.fields[f"{c}_lateral_fx"] / 1e3, "--",
                                label=name)
        axes[0, j].set_title(f"{c} contact")
        axes[2, j].set_xlabel("s along the groove (mm)")
    axes[0, 0].set_ylabel("N* (N/mm)")
    axes[1, 0].set_ylabel("F_x* (N/mm)")
    axes[2, 0].set_ylabel("F_s* (N/mm)")
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    return save_figure(fig, path)


def _maps(run: RunResult, path: Path) -> str | None:
    m = run.models.get("cect")
    if m is None or m.status != "ok" or "inner_adhesion_map" not in m.fields:
        return None
    cmap = matplotlib.colors.ListedColormap(["white", "tab:orange", "tab:blue"])
    fig, axes = plt.subplots(2, 1, figsize=(8.0, 5.0))
    for ax, c in zip(axes, CONTACTS):
        x, s, p = m.fields[f"{c}_x"], m.fields[f"{c}_s"], m.fields[f"{c}_pressure_map"]
        state = np.where(p > 0, 1.0 + m.fields[f"{c}_adhesion_map"], 0.0)
        ax.pcolormesh(s * 1e3, x * 1e3, state, shading="nearest", cmap=cmap, vmin=-0.5, vmax=2.5)
        ax.contour(s * 1e3, x * 1e3, p / 1e9, levels=5, colors="k", linewidths=0.5)
        ax.set_ylabel("x, rolling (mm)")
        ax.set_title(f"{c} contact: adhesion (blue) / slip (orange), pressure contours", fontsize=9)
    axes[-1].set_xlabel("s along the groove (mm)")
    return save_figure(fig, path)


def _fig17(path: Path) -> str | None:
    if not SWEEP.exists():
        return None
    data = json.loads(SWEEP.read_text())
    panels = (("d_y", "d_y (um)", 1e6), ("f_x_outer", "f_x,e = -f_x,i", 1.0), ("friction_power", "P_fric (W)", 1.0),
              ("power_ratio_outer_inner", "P_fric,e / P_fric,i", 1.0), ("tilt", "tilt (mrad)", 1e3),
              ("skew", "skew gamma_p (mrad)", 1e3))
    fig, axes = plt.subplots(3, 2, figsize=(9.0, 8.0), sharex=True)
    colours = {}
    for br in data["branches"]:
        pts = br["points"]
        if not pts:
            continue
        col = colours.setdefault(br["mu"], f"C{len(colours)}")
        N = np.array([p["load"] for p in pts]) / 1e3
        order = np.argsort(N)
        for ax, (k, label, sc) in zip(axes.ravel(), panels):
            v = np.array([p[k] for p in pts]) * sc
            ax.plot(N[order], v[order], "-o" if br["configuration"] == 1 else "--s", color=col, ms=3,
                    label=f"mu {br['mu']:g}, config. {br['configuration']}")
            ax.set_ylabel(label)
    for ax in axes[-1]:
        ax.set_xlabel("N (kN)")
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    return save_figure(fig, path)


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    out = KindSection(tables=[_table(run)])
    for fn, suffix, caption in (
            (_lateral, "lateral", "Lateral distributions of both contacts (seed 000 Figs 8-9): N*(s) = sum_x p_n dx, "
                                  "F_x*(s) = sum_x p_x dx along each contact's rolling direction, F_s*(s) along the "
                                  "groove (N/mm), CECT at the equilibrium and H+C (dashed) at its strips."),
            (_maps, "maps", "Adhesion (blue) and slip (orange) areas of both contacts at the CECT equilibrium with "
                            "pressure contours (seed 000 Figs 10-11); x along the rolling direction (leading edge "
                            "at +x).")):
        name = fn(run, Path(outdir) / f"{prefix}-srb-{suffix}.png")
        if name:
            out.figures.append(Figure(name, caption))
    name = _fig17(Path(outdir) / f"{prefix}-srb-fig17.png")
    if name:
        out.figures.append(Figure(name, "Seed 000 Fig. 17 from benchmarks/results/srb_fig17.json (41 x 81 per "
                                        "contact): configuration 1 (solid) traced from 7 kN down, configuration 2 "
                                        "(dashed) from 2 kN up, each to the load where its branch ends."))
    return out
