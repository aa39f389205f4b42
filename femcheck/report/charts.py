"""Charts across scenes and runs (PNG): the dashboard's cost against error of every model of every scene, the
benchmark's run time against error, and the validity map's heat maps."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .plots import plt, save_figure

VERDICT_COLOUR = {"valid": "tab:green", "contrast": "0.55", "not valid here": "tab:red",
                  "reference uncertified": "tab:orange", "ungraded": "tab:purple"}


TIME_FLOOR = 1e-4          # s: the chart's left edge


def cost_error(rows, path: Path) -> str | None:
    """Run time (s) against the largest relative error on a scalar quantity, one point per scene and model
    (dashboard rows with a comparison), coloured by verdict, hollow for contrasts. A stored reference's time is
    the time it was solved in; times below TIME_FLOOR are drawn there as left-pointing triangles (not measured
    there: faster)."""
    pts = [r for r in rows if r.max_rel_error is not None]
    if not pts:
        return None
    fig, ax = plt.subplots(figsize=(11.0, 6.2))
    placed: list[tuple[float, float]] = []          # label positions (log10 t, log10 e + offset) already used
    step = 0.11                                     # label spacing in decades of error (8-point labels)
    floored = False
    right = np.log10(max(max(r.time_s for r in pts), TIME_FLOOR))      # labels of the right-most points go left
    for r in sorted(pts, key=lambda r: (r.time_s, r.max_rel_error)):
        colour = VERDICT_COLOUR.get(r.verdict, "k")
        below = r.time_s < TIME_FLOOR
        floored |= below
        t, e = max(r.time_s, TIME_FLOOR), max(r.max_rel_error, 1e-7)
        # a time below the floor is not a measurement at the floor: drawn as a left-pointing triangle
        ax.loglog(t, e, "<" if below else "o", ms=7, color=colour, mfc="none" if r.role == "contrast" else colour)
        lt, le = np.log10(t), np.log10(e)
        while any(abs(lt - pt) < 1.1 and abs(le - pe) < step for pt, pe in placed):
            le -= step                                  # move the label down until it does not cover another
        placed.append((lt, le))
        left = lt > right - 0.5
        ax.annotate(f"{r.scene}:{r.model}", (t, e), xytext=(t / 1.2 if left else t * 1.2, 10**le), fontsize=7.5,
                    color="0.2", va="center", ha="right" if left else "left", arrowprops=dict(arrowstyle="-", color="0.7", lw=0.5) if le != np.log10(e)
                    else None)
    for verdict, colour in VERDICT_COLOUR.items():
        if any(r.verdict == verdict for r in pts):
            ax.plot([], [], "o", color=colour, label=verdict)
    ax.plot([], [], "o", mfc="none", color="0.55", label="hollow: contrast model")
    if floored:
        ax.plot([], [], "<", color="0.55", label=f"faster than {TIME_FLOOR * 1e3:g} ms (drawn there)")
    ax.set_xlabel("run time (s): solve time; stored references: the time they were solved in")
    ax.set_ylabel("largest relative error (scalar quantities)")
    ax.set_title("Cost against error of every model of every scene", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return save_figure(fig, path)


def time_error(rows: list[dict], path: Path, title: str) -> str:
    """Log-log run time against error, one line per model and quantity (bench): left against the analytic
    solution, right against the model's own finest setting (discretisation error alone)."""
    fig, axes = plt.subplots(1, 2, figsize=(11.5, 4.4), sharey=True)
    names = list(dict.fromkeys(k[4:] for r in rows for k in r
                               if k.startswith("err_") and not k.startswith("err_self_")))
    for ax, prefix, label in ((axes[0], "err_", "error vs analytic"),
                              (axes[1], "err_self_", "change vs own finest setting")):
        quantities = [q for q in names if prefix == "err_" or not q.startswith("pressure_profile")]
        for model in sorted({r["model"] for r in rows}):
            for q in quantities:
                mk = {"p_max": "o", "half_width": "s"}.get(q, "^")
                pts = [(r["time_s"], r[prefix + q]) for r in rows if r["model"] == model and r.get(prefix + q)]
                if pts:
                    t, e = zip(*pts)
                    ax.loglog(t, e, marker=mk, label=f"{model}: {q}")
        ax.set_xlabel("run time (s)")
        ax.set_title(label)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    axes[0].set_ylabel("relative error")
    fig.suptitle(title)
    return save_figure(fig, path)


def _edges(values: tuple[float, ...], log: bool) -> np.ndarray:
    """Cell edges around grid values: midpoints (geometric on a log axis), the ends extended symmetrically."""
    v = np.log(values) if log else np.asarray(values, dtype=float)
    mid = 0.5 * (v[1:] + v[:-1])
    e = np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
    return np.exp(e) if log else e


def validity_heatmap(vmap, comparison: tuple[str, str, str], path: Path) -> str:
    """Heat map of log10 |relative error| of one (model, reference, quantity) over the map grid, the region
    within tolerance outlined in white, grid points without a value (refused / failed) crossed out."""
    err, ok, tol = vmap.grid(comparison)
    x, y = np.asarray(vmap.x.values, dtype=float), np.asarray(vmap.y.values, dtype=float)
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    with np.errstate(divide="ignore"):
        z = np.log10(np.maximum(err, 1e-16))
    ex, ey = _edges(vmap.x.values, vmap.x.log), _edges(vmap.y.values, vmap.y.log)
    mesh = ax.pcolormesh(ex, ey, z, cmap="viridis", shading="flat")
    fig.colorbar(mesh, ax=ax, label="log10 relative error")
    # outline of the region within tolerance: every edge between a passing cell and anything else
    inside = np.pad(ok == 1.0, 1)
    for iy, ix in zip(*np.nonzero(inside[1:-1, 1:-1])):
        i, j = iy + 1, ix + 1
        for di, dj, xs, ys in ((-1, 0, ex[ix:ix + 2], [ey[iy]] * 2), (1, 0, ex[ix:ix + 2], [ey[iy + 1]] * 2),
                               (0, -1, [ex[ix]] * 2, ey[iy:iy + 2]), (0, 1, [ex[ix + 1]] * 2, ey[iy:iy + 2])):
            if not inside[i + di, j + dj]:
                ax.plot(xs, ys, "w-", lw=2.2)
    for iy, ix in zip(*np.nonzero(np.isnan(err))):
        ax.plot(x[ix], y[iy], "rx", ms=7)
    if vmap.x.log:
        ax.set_xscale("log")
    if vmap.y.log:
        ax.set_yscale("log")
    ax.set_xlabel(vmap.x.key)
    ax.set_ylabel(vmap.y.key)
    model, ref, q = comparison
    tol_txt = f"tolerance {tol:.3g} (white: within)" if tol is not None else "no tolerance set"
    ax.set_title(f"{vmap.scene}: {model} vs {ref}, {q}\n{tol_txt}; x: no value", fontsize=9)
    return save_figure(fig, path)
