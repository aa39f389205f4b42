"""Report section of the ``life`` output (seed 004 ch. 4): a table of the life quantities per model, the stressed
volume in a section view (the stress-amplitude history over the fatigue limit), and for indents the life ratio
against the indent size. Used by the kinds' report modules (:mod:`femcheck.report.kinds`); reads stats and fields
only (it never runs a model)."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..result import RunResult  # noqa: E402
from .kinds import Figure, KindSection, Table  # noqa: E402
from .plots import save_figure  # noqa: E402


def _models(run: RunResult) -> dict:
    return {k: m for k, m in run.models.items() if m.status == "ok" and "life" in m.stats}


def _a(st: dict) -> float:
    """Hertz semi-axis x from the window: track_window_length = 2 w a."""
    return st["track_window_length"] / (2.0 * st["window"])


def _table(models: dict) -> Table:
    rows = []
    for name, m in models.items():
        st, q = m.stats["life"], m.quantities
        rows.append([name, st["c"], st["e"], st["h"], st["fatigue_limit"] / 1e9,
                     st["fatigue_limit_over_max"] if st["fatigue_limit_over_max"] is not None else "-",
                     q["stress_history_max"] / 1e9, q["stress_history_max"] / st["p_hertz"],
                     q["risk_integral"], st.get("risk_integral_bar", "-"), q["fatigue_life"],
                     q.get("stress_ratio", "-"), q.get("life_ratio", "-")])
    return Table("Rolling-contact fatigue life (seed 004 ch. 4)",
                 ["model", "c", "e", "h", "tau_inf (GPa)", "tau_inf / T_max", "T_max (GPa)", "T_max / p_H",
                  "risk integral I (SI)", "I-bar", "relative life", "T_Dmax / T_Smax", "L / L_S"], rows,
                 "T = stress-amplitude history (largest von Mises stress over a pass, smooth: T_Smax). I = sum of "
                 "max(T - tau_inf, 0)^c over the window (Pa^c m^(3-h); line contacts per metre of line), I-bar = "
                 "(I / (p_H^c b^(3-h)))^(1/c). Relative life: life of 1 mm of track, (R / (1 GPa)^c (1 mm)^(2-h))^(-1/e), "
                 "R the risk per unit track length; inf: nothing exceeds the fatigue limit. Indents: L/L_S = "
                 "[1 + f_d (I_D/I_S - 1)]^(-1/e).")


def _section_figure(run: RunResult, models: dict, path: Path) -> str | None:
    maps = {k: m for k, m in models.items() if "life_section" in m.fields}
    profiles = {k: m for k, m in models.items() if "life_profile" in m.fields}
    if not maps and not profiles:
        return None
    n = len(maps) + (1 if profiles else 0)
    fig, axes = plt.subplots(1, n, figsize=(5.6 * n, 3.8), squeeze=False)
    for ax, (name, m) in zip(axes[0], maps.items()):
        st = m.stats["life"]
        a, p0 = _a(st), st["p_hertz"]
        T = m.fields["life_section"] / p0
        h, z = m.fields["life_section_h"] / a, m.fields["life_section_z"] / a
        pc = ax.pcolormesh(h, z, T, shading="nearest", cmap="viridis")
        fig.colorbar(pc, ax=ax, label="T / p_H")
        if 0 < st["fatigue_limit"] / p0 < T.max():
            ax.contour(h, z, T, levels=[st["fatigue_limit"] / p0], colors="w", linewidths=1.2)
            ax.contourf(h, z, T, levels=[st["fatigue_limit"] / p0, T.max() * 1.01], colors="none",
                        hatches=["///"])
        ax.invert_yaxis()
        ax.set_xlabel("xi / a (from the indent)" if "xi" in st.get("stress_history_max_at", {}) else "y / a")
        ax.set_ylabel("z / a")
        ax.set_title(f"{name}: stress-amplitude history" + (f", hatched T > {st['fatigue_limit'] / 1e9:.3g} GPa"
                                                           if st["fatigue_limit"] > 0 else ""), fontsize=9)
    if profiles:
        ax = axes[0][-1]
        for name, m in profiles.items():
            st = m.stats["life"]
            a, p0 = _a(st), st["p_hertz"]
            ax.plot(m.fields["life_profile"] / p0, m.fields["life_profile_z"] / a, label=name)
        if st["fatigue_limit"] > 0:
            ax.axvline(st["fatigue_limit"] / p0, color="k", ls=":", label="fatigue limit")
        ax.invert_yaxis()
        ax.set_xlabel("T_S / p_H")
        ax.set_ylabel("z / a")
        ax.set_title("line contact: history T_S(z) (stressed where right of the limit)", fontsize=9)
        ax.legend(fontsize=8)
    fig.suptitle(run.scene, fontsize=10)
    return save_figure(fig, path)


def _sweep(models: dict, path: Path) -> tuple[Table | None, str | None]:
    rows, curves = [], {}
    for name, m in models.items():
        sw = m.stats["life"].get("size_sweep")
        if not sw:
            continue
        curves[name] = sw
        rows += [[name, r["diameter"], r["additional_pressure_over_p_hertz"], r["stress_ratio"], r["risk_ratio"],
                  r["life_ratio"]] for r in sw]
    if not rows:
        return None, None
    fig, ax = plt.subplots(figsize=(5.6, 3.6))
    for name, sw in curves.items():
        ax.plot([r["diameter"] for r in sw], [r["life_ratio"] for r in sw], "o-", label=f"{name}: L/L_S")
        ax.plot([r["diameter"] for r in sw], [1.0 / r["stress_ratio"] for r in sw], "s--", label=f"{name}: T_Smax/T_Dmax")
    ax.set_xlabel("indent diameter Phi / a")
    ax.set_ylabel("ratio")
    ax.set_ylim(0, 1.05)
    ax.legend(fontsize=8)
    ax.set_title("life ratio against indent size (same slope D/Phi and K)", fontsize=9)
    save_figure(fig, path)
    return Table("Life ratio against indent size", ["model", "Phi / a", "dP / p_H", "T_Dmax / T_Smax", "I_D / I_S",
                                                   "L / L_S"], rows,
                 "Pseudo-transient pass, the scene's slope, decay, life constants and window."), path.name


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    models = _models(run)
    if not models:
        return KindSection()
    sec = KindSection([_table(models)])
    name = _section_figure(run, models, outdir / f"{prefix}-life-section.png")
    if name:
        sec.figures.append(Figure(name, "Stress-amplitude history T (largest von Mises stress a material point sees "
                                  "in a pass) in a section: across the track for smooth contacts, along the "
                                  "rolling direction through the indent for dented ones; hatched: the stressed "
                                  "volume T > fatigue limit."))
    table, fig = _sweep(models, outdir / f"{prefix}-life-size.png")
    if table:
        sec.tables.append(table)
        sec.figures.append(Figure(fig, "Life ratio L/L_S of a dented track against the indent diameter."))
    for name, m in models.items():
        st = m.stats["life"]
        if "additional_pressure_in_contact" in st:
            d = st["additional_pressure_in_contact"]
            sec.tables.append(Table(f"{name}: full transient pass", ["frames", "reach / a", "dP/p_H centred",
                                                                    "dP/p_H min in contact", "dP/p_H max in contact",
                                                                    "max at x_D / a", "inner shoulder centred",
                                                                    "inner shoulder max", "Table 3.1 measure",
                                                                    "dP/p_H end frames"],
                                    [[st["frames"], st["frame_reach"], d["centred"], d["min"], d["max"],
                                      d.get("max_at", float("nan")), d.get("inner_centred", float("nan")),
                                      d.get("inner_max", float("nan")), d.get("table_3_1_difference", float("nan")),
                                      st["end_frame_additional_pressure"]]],
                                    "Additional pressure of the indent solved at every position of the pass with "
                                    "its centre in the contact: max(p - p_S) over the grid, which rises when a "
                                    "shoulder reaches the contact edge, and the amplitude of the shoulder on the "
                                    "contact-centre side, which seed 004 Table 3.1 finds constant "
                                    "(|centred - max|/max)."))
    return sec
