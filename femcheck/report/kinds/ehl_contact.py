"""Report section of the ``ehl_contact`` kind: film table against the classical formulas, centre-line pressure
and film with the Hertz pressure, pressure and film maps, and with an indent its pressure history while it
crosses the contact and the EHL additional pressure against the dry one."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ...result import RunResult  # noqa: E402
from ..plots import save_figure  # noqa: E402
from . import Figure, KindSection, Table  # noqa: E402

FILM = ("h_central", "h_min", "H_central_moes", "H_min_moes", "p_max")


def _film_table(run: RunResult) -> Table | None:
    e = run.models.get("ehl")
    if e is None or e.status != "ok":
        return None
    certs = e.stats.get("certificates", {})
    rows = []
    for q in FILM:
        if q not in e.quantities:
            continue
        c = certs.get(q, {})
        row = [q, e.quantities[q], c.get("order"), c.get("error_estimate"), "yes" if c.get("certified") else "no"]
        for name in ("moes", "hamrock_dowson", "dry"):
            m = run.models.get(name)
            v = m.quantities.get(q) if m is not None and m.status == "ok" else None
            row.append(None if v is None else v / e.quantities[q] - 1.0)
        rows.append(row)
    s = e.stats
    note = (f"M = {s['M']:.4g}, L = {s['L']:.4g} (Moes, sum speed); alpha_bar = {s['alpha_bar']:.4g}, lambda_bar = "
            f"{s['lambda_bar']:.4g}; b = {s['b'] * 1e6:.4g} um, p_H = {s['p_hertz'] / 1e9:.4g} GPa; finest grid "
            f"{s['grid']}^2 nodes. EHL values are Richardson-extrapolated where certified. The formula columns are "
            "relative differences (formula/EHL - 1): Hamrock-Dowson is a +-20 % / +-30 % sanity band, "
            "Nijenbanning-Venner-Moes fits Barus/incompressible solutions.")
    return Table("EHL film and pressure against the classical formulas",
                 ["quantity", "EHL (SI)", "observed order", "error estimate", "certified", "Moes", "Hamrock-Dowson",
                  "dry"], rows, note)


def _lines(run: RunResult, path: Path) -> str:
    f = run.models["ehl"].fields
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for ax, (xk, pk, hk, hz, lab) in zip(axes, (("line_x", "line_pressure", "line_film", "line_hertz", "x (Y = 0)"),
                                                 ("cross_y", "cross_pressure", "cross_film", "cross_hertz",
                                                  "y (X = 0)"))):
        x = f[xk] * 1e3
        ax.plot(x, f[pk] / 1e9, "tab:blue", label="EHL pressure")
        ax.plot(x, f[hz] / 1e9, "k--", lw=0.9, label="Hertz")
        if xk == "line_x" and "smooth_line_pressure" in f:
            ax.plot(x, f["smooth_line_pressure"] / 1e9, color="tab:gray", lw=0.8, label="smooth EHL")
        ax.set_xlabel(f"{lab} (mm)")
        ax.set_ylabel("p (GPa)")
        ax2 = ax.twinx()
        ax2.plot(x, f[hk] * 1e9, "tab:red", lw=1.0, label="film")
        ax2.set_ylabel("h (nm)", color="tab:red")
        h = f[hk]
        ax2.set_ylim(0, 4 * np.nanmin(h[h > 0]) * 1e9 if (h > 0).any() else None)
        ax.legend(loc="upper left", fontsize=8)
    fig.suptitle(f"{run.scene}: pressure and film along the centre lines")
    return save_figure(fig, path)


def _maps(run: RunResult, path: Path) -> str:
    f = run.models["ehl"].fields
    x, y = f["map_x"] * 1e3, f["map_y"] * 1e3
    items = [("pressure_map", 1e-9, "p (GPa)"), ("film_map", 1e9, "h (nm)")]
    if "dp_map" in f:
        items.append(("dp_map", 1e-9, "p - p_smooth (GPa)"))
    fig, axes = plt.subplots(1, len(items), figsize=(4.2 * len(items), 3.7))
    for ax, (k, s, lab) in zip(axes, items):
        v = f[k] * s
        if k == "film_map":
            v = np.minimum(v, 4 * np.nanmin(v[f["pressure_map"] > 0]))
        im = ax.pcolormesh(x, y, v.T, shading="auto", cmap="RdBu_r" if k == "dp_map" else "viridis")
        fig.colorbar(im, ax=ax, label=lab)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
    fig.suptitle(f"{run.scene}: maps (rolling along +x)")
    return save_figure(fig, path)


def _history(run: RunResult, path: Path) -> str:
    f = run.models["ehl"].fields
    b = run.models["ehl"].stats["b"]
    xd = f["history_x_indent"] / b
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for k, c in (("rear", "tab:blue"), ("front", "tab:orange"), ("lateral", "tab:green"), ("centre", "tab:purple")):
        ax.plot(xd, f[f"history_dp_{k}"] / 1e9, color=c, label=f"dP {k}")
    dry = run.models.get("dry")
    if dry is not None and dry.status == "ok" and "additional_pressure" in dry.quantities:
        ax.axhline(dry.quantities["additional_pressure"] / 1e9, color="k", ls="--", lw=0.9, label="dry (BEM)")
    ax.set_xlabel("indent centre X_D / b")
    ax.set_ylabel("additional pressure (GPa)")
    ax.set_title(f"{run.scene}: additional pressure while the indent crosses")
    ax.legend(fontsize=8)
    return save_figure(fig, path)


def _dp_table(run: RunResult) -> Table:
    e = run.models["ehl"]
    dry = run.models.get("dry")
    d = dry.quantities.get("additional_pressure") if dry is not None and dry.status == "ok" else None
    rows = []
    for k in ("rear", "front", "lateral", "centre"):
        v = e.quantities[f"additional_pressure_{k}"]
        rows.append([k, v, v / e.stats["p_hertz"], v / (0.2 * e.stats["p_hertz"]), d, None if d is None else v / d])
    return Table("Additional pressure of the indent at X_D = 0: EHL against dry",
                 ["position", "dP EHL (Pa)", "dP/p_H", "dP/P_REF", "dP dry (Pa)", "EHL/dry"], rows,
                 "P_REF = 0.200 p_H (femcheck's fit of seed 004 Table 3.3). Rear: upstream shoulder, front: downstream, "
                 "lateral: sides, centre: minimum in the hole. The dry contact under the same load is the upper bound "
                 "of the lubricated amplitude (seed 004 §3.3.1).")


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    sec = KindSection()
    e = run.models.get("ehl")
    t = _film_table(run)
    if t is not None:
        sec.tables.append(t)
    if e is None or e.status != "ok" or "line_x" not in e.fields:
        return sec
    sec.figures.append(Figure(_lines(run, outdir / f"{prefix}-ehl-lines.png"),
                              "Pressure (GPa) and film (nm) along the rolling centre line and across it, with the "
                              "Hertz pressure of the same load; the outlet spike and constriction are the EHL "
                              "signature."))
    sec.figures.append(Figure(_maps(run, outdir / f"{prefix}-ehl-maps.png"),
                              "Pressure and film maps on the finest grid (film clipped at 4 h_min)."))
    if "history_x_indent" in e.fields:
        sec.tables.append(_dp_table(run))
        sec.figures.append(Figure(_history(run, outdir / f"{prefix}-ehl-history.png"),
                                  "Additional pressure amplitudes against the indent position as it crosses the "
                                  "contact (pure rolling, NU2 time step = mesh size), with the dry BEM value."))
    return sec
