"""Report section of the bearing_load kind: roller-load polar plot of every model over the FE, roller-load table
with each model's departure from the reference, load-zone angles, the FE's deformed rings, and for the seed-003
four-row bearing its Table 3 with the recomputed errors and a per-row plot."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ...result import RunResult
from ..plots import plt, save_figure
from . import Figure, KindSection, Table

COLOURS = {"fem": "tab:red", "condensed": "tab:blue", "rigid_ring": "k", "integral": "tab:green",
           "flexible_chock": "tab:purple", "resolved": "tab:red", "condensed3d": "tab:blue",
           "coupled_slices": "tab:green"}
MARKERS = {"fem": "o", "condensed": "x", "rigid_ring": "+", "integral": ".", "flexible_chock": "s",
           "resolved": "o", "condensed3d": "x", "coupled_slices": "d"}
# several rows: the models that give row shares, as Table 3 names them
MULTI_ROW_MODELS = {"rigid_ring": "rigid rings, ISO slices (femcheck)",
                    "flexible_chock": "elastic chock + roll, ISO slices (femcheck)"}
ROW_COLOURS = {"rigid_ring": "k", "flexible_chock": "tab:purple"}
ROW_STYLES = {"rigid_ring": "--", "flexible_chock": "-"}


def _ok(run: RunResult) -> dict:
    return {k: m for k, m in run.models.items() if m.status == "ok" and "roller_loads" in m.fields
            and np.ndim(m.fields["roller_loads"]) == 1}


def _polar(run: RunResult, path: Path) -> str | None:
    models = _ok(run)
    if not models:
        return None
    fig = plt.figure(figsize=(5.8, 5.4))
    ax = fig.add_subplot(projection="polar")
    ax.set_theta_zero_location("S")           # the load line points down
    for name, m in models.items():
        psi = np.asarray(m.fields["roller_angle"])
        q = np.asarray(m.fields["roller_loads"])
        order = np.argsort(psi)
        closed = np.r_[order, order[:1]]
        if name in run.params.get("models.references", ()) and name in ("fem", "resolved"):
            ax.bar(psi, q, width=0.6 * 2 * np.pi / len(psi), color=COLOURS[name], alpha=0.3,
                   label=f"{name} (reference)")
        else:
            ax.plot(psi[closed], q[closed], marker=MARKERS.get(name, "."), color=COLOURS.get(name), lw=0.8,
                    label=name)
        zone = m.quantities.get("load_zone_angle")
        if zone is not None and np.isfinite(zone):
            for s in (-1, 1):
                ax.plot([s * zone] * 2, [0, q.max()], color=COLOURS.get(name), ls=":", lw=0.8)
    ax.set_title("roller loads (N); dotted: load-zone half-angles")
    ax.legend(loc="upper right", fontsize=7, bbox_to_anchor=(1.15, 1.1))
    return save_figure(fig, path)


def _rings(run: RunResult, path: Path) -> str | None:
    """The rings' elastic deformation (the inner ring relative to the shaft it is tied to), magnified."""
    m = run.models.get("fem")
    if m is None or m.status != "ok" or "ring_outer_raceway_xy" not in m.fields:
        return None
    f = m.fields
    shaft = np.asarray(f.get("shaft_delta", np.zeros(2)))[:, None]
    elastic = {}
    for name in ("inner", "outer"):
        for surf in ("raceway", "back"):
            key = f"ring_{name}_{surf}_xy"
            if key in f:
                u = np.asarray(f[f"ring_{name}_{surf}_u"]) - (shaft if name == "inner" else 0.0)
                elastic[key] = (np.asarray(f[key]), u)
    radius = np.hypot(*f["ring_outer_back_xy"]).max()
    scale = 0.06 * radius / max(max(np.abs(u).max() for _, u in elastic.values()), 1e-30)
    rot = np.array([[0.0, 1.0], [-1.0, 0.0]])          # the load (+x) points down
    fig, ax = plt.subplots(figsize=(5.8, 5.8))
    for key, (xy, u) in elastic.items():
        a, b = rot @ xy, rot @ (xy + scale * u)
        ax.plot(*(1e3 * np.c_[a, a[:, :1]]), color="0.7", lw=0.6)
        ax.plot(*(1e3 * np.c_[b, b[:, :1]]), color="tab:red" if "outer" in key else "tab:blue", lw=1.0)
    psi = np.asarray(f["roller_angle"])
    loads = np.asarray(f["roller_loads"])
    r_c = 0.5 * (np.hypot(*f["ring_inner_raceway_xy"]).max() + np.hypot(*f["ring_outer_raceway_xy"]).min())
    rad = 0.5 * (np.hypot(*f["ring_outer_raceway_xy"]).min() - np.hypot(*f["ring_inner_raceway_xy"]).max())
    t = np.linspace(0, 2 * np.pi, 60)
    for j, p in enumerate(psi):
        c = np.array([np.sin(p), -np.cos(p)]) * r_c
        ax.fill(1e3 * (c[0] + rad * np.cos(t)), 1e3 * (c[1] + rad * np.sin(t)), color="tab:orange",
                alpha=float(0.1 + 0.8 * loads[j] / loads.max()), lw=0)
    ax.set_aspect("equal")
    ax.set_xlabel("mm")
    ax.set_title(f"FE ring deformation x {scale:.3g} (load downwards)")
    return save_figure(fig, path)


def _load_table(run: RunResult) -> Table | None:
    models = _ok(run)
    if not models:
        return None
    ref_name = "fem" if "fem" in models else next(iter(models))
    ref = models[ref_name]
    psi = np.asarray(ref.fields["roller_angle"])
    qref = np.asarray(ref.fields["roller_loads"])
    names = list(models)
    header = ["roller", "psi (deg)"] + [f"{n} Q (N)" for n in names] + \
             [f"{n} - {ref_name} (% of Q_max)" for n in names if n != ref_name]
    rows = []
    for j in np.argsort(np.abs(psi)):
        row = [int(j), float(np.degrees(psi[j]))] + [float(models[n].fields["roller_loads"][j]) for n in names]
        row += [float(100 * (models[n].fields["roller_loads"][j] - qref[j]) / qref.max()) for n in names if n != ref_name]
        rows.append(row)
    # the load-zone half-angle of a single row (several rows: each row has its own, not reported)
    if any("load_zone_angle" in models[n].quantities for n in names):
        rows.append(["load-zone half-angle (deg)", ""] +
                    [float(np.degrees(models[n].quantities["load_zone_angle"])) if "load_zone_angle" in
                     models[n].quantities else "" for n in names] + ["" for n in names if n != ref_name])
    rows_note = " Several rows: each roller position's largest load over the rows." if \
        any("row_shares" in m.fields for m in models.values()) else ""
    against = ("where rigid-ring theory departs from the FE (rings' compliance, housing support) shows here"
               if ref_name == "fem" else f"no FE reference in this scene; {ref_name} is the first model shown")
    return Table("Roller loads by model", header, rows,
                 f"Rollers sorted by their angle psi from the load line. Differences relative to the {ref_name} "
                 f"Q_max: {against}." + rows_note)


def _table3(run: RunResult) -> Table | None:
    p = run.params
    if "paper.row_shares_measured" not in p:
        return None
    meas = np.asarray(p["paper.row_shares_measured"], float)
    rows_out = []
    sources = [("GSC-BBEM (seed 003)", p.get("paper.row_shares_gsc")), ("T-BBEM (seed 003)", p.get("paper.row_shares_tbbem"))]
    for name, label in MULTI_ROW_MODELS.items():
        m = run.models.get(name)
        if m is not None and m.status == "ok" and "row_shares" in m.fields:
            sources.append((label, list(m.fields["row_shares"])))
    rows_out.append(["experiment"] + [float(v) for v in meas] + [""])
    for label, shares in sources:
        if shares is None:
            continue
        sh = np.asarray(shares, float)
        err = 100 * np.abs(sh - meas) / meas
        rows_out.append([label] + [float(v) for v in sh] + [float(err.max())])
        rows_out.append(["  error |sim - exp|/exp (%)"] + [float(v) for v in err] + [""])
    header = ["row share (%)"] + [f"row {r + 1}" for r in range(meas.size)] + ["max error (%)"]
    return Table("Seed 003 Table 3: row shares of the work-side radial load", header, rows_out,
                 "Errors recomputed from the printed shares (the paper prints 9.73 % for GSC row 4; "
                 "|29.85 - 32.67|/32.67 = 8.63 %). The femcheck rows share the reconstructed geometry and the load "
                 "offset and axial load fitted for rigid rings; no rigid model reproduces row 3 > row 4. The "
                 "flexible chock's geometry, pad and seat are assumptions (scene file); both are contrasts.")


def _rows(run: RunResult, path: Path) -> str | None:
    """Row shares of the paper's models, the experiment and femcheck's, and each row's roller loads."""
    p = run.params
    models = {n: run.models[n] for n in MULTI_ROW_MODELS if n in run.models and run.models[n].status == "ok"
              and "row_shares" in run.models[n].fields}
    if not models:
        return None
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10.5, 4.0))
    bars = [("experiment", p.get("paper.row_shares_measured"), "0.3"),
            ("GSC-BBEM", p.get("paper.row_shares_gsc"), "0.6"), ("T-BBEM", p.get("paper.row_shares_tbbem"), "0.8")]
    bars += [(n, list(m.fields["row_shares"]), ROW_COLOURS[n]) for n, m in models.items()]
    bars = [b for b in bars if b[1] is not None]
    n_rows = len(bars[0][1])
    w = 0.8 / len(bars)
    for i, (label, sh, colour) in enumerate(bars):
        a1.bar(np.arange(n_rows) + (i - 0.5 * (len(bars) - 1)) * w, sh, w, label=label, color=colour)
    a1.set_xticks(np.arange(n_rows), [f"row {r + 1}" for r in range(n_rows)])
    a1.set_ylabel("share of the radial load (%)")
    a1.set_title("row shares (row 1: operating side)")
    a1.legend(fontsize=7)
    for n, m in models.items():
        psi = np.degrees(np.asarray(m.fields["roller_angle"]))
        order = np.argsort(psi)
        for r, q in enumerate(np.asarray(m.fields["row_roller_loads"])):
            a2.plot(psi[order], q[order], color=f"C{r}", ls=ROW_STYLES[n], marker=".", lw=0.9,
                    label=f"row {r + 1}, {n}")
    a2.set_xlabel("roller angle psi from the load line (deg)")
    a2.set_ylabel("roller load Q (N)")
    a2.set_title("roller loads per row")
    a2.legend(fontsize=6, ncol=2)
    return save_figure(fig, path)


def _slices(run: RunResult, path: Path) -> str | None:
    """Slice loads along the two most loaded rollers of every model with ISO slices (the reference's with the
    error estimates of its certificate as bars)."""
    models = {n: m for n, m in run.models.items() if m.status == "ok" and np.ndim(m.fields.get("slice_loads")) == 2}
    if not models:
        return None
    ref = next((n for n in run.params.get("models.references", ()) if n in models), None)
    order = np.argsort(-np.asarray((models[ref] if ref else next(iter(models.values()))).fields["roller_loads"]))
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 3.8), sharey=True)
    for ax, j in zip(axes, order[:2]):
        for n, m in models.items():
            q = np.asarray(m.fields["slice_loads"])[j]
            k = np.arange(q.size) + 1
            err = m.fields.get("slice_load_estimates")
            if err is not None:
                ax.errorbar(k, q, yerr=np.asarray(err)[j], color=COLOURS.get(n), marker=MARKERS.get(n, "."),
                            lw=0.9, capsize=2, label=f"{n} (reference)" if n == ref else n)
            else:
                ax.plot(k, q, color=COLOURS.get(n), marker=MARKERS.get(n, "."), lw=0.9, label=n)
        psi = np.degrees(float(np.asarray(models[ref or n].fields["roller_angle"])[j]))
        ax.set_title(f"roller at psi = {psi:.0f} deg")
        ax.set_xlabel("slice (1 .. n_s along the roller)")
    axes[0].set_ylabel("slice load q (N)")
    axes[0].legend(fontsize=7)
    return save_figure(fig, path)


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    out = KindSection()
    fe = "fem" in run.models
    for name, fn, caption in (
            ("polar", _polar, "Roller loads (N) of every model around the bearing" +
             (", the FE reference as bars" if fe else "") + "; dotted lines mark each model's load-zone "
             "half-angle."),
            ("rings", _rings, "FE finest level: elastic deformation of the inner (blue, relative to the shaft it "
                              "is tied to) and outer ring (red, in the housing) over the undeformed rings (grey), "
                              "magnified; rollers shaded by their load."),
            ("slices", _slices, "Slice loads (N) along the two most loaded rollers: each model's ISO/TS 16281 "
                                "slices, the reference's with its certificate's error estimates."),
            ("rows", _rows, "Several rows: each row's share of the radial load (seed 003 Table 3's experiment "
                            "and models beside femcheck's) and the roller loads of every row.")):
        f = fn(run, outdir / f"{prefix}-{name}.png")
        if f:
            out.figures.append(Figure(f, caption))
    for t in (_load_table(run), _table3(run)):
        if t is not None:
            out.tables.append(t)
    # the FE's certificates are in the report's generic FE table (not repeated here)
    return out
