"""Matplotlib figures for reports (Agg backend, PNG files). Lengths are shown in mm, pressures in GPa."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

from ..result import RunResult  # noqa: E402

STYLE = {"analytic": dict(color="k", lw=1.2), "bem": dict(color="tab:blue", ls="--", lw=1.4),
         "fem": dict(color="tab:red", marker=".", ms=3, ls="none"),
         "finite_line": dict(color="tab:green", marker="+", ms=4, ls="-", lw=0.8)}


def _save(fig, path: Path) -> str:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path.name


def _overlay(run: RunResult, path: Path, x_field: str, p_field: str, xlabel: str, ylabel: str, title: str,
             positive_x: bool = False) -> str | None:
    """Profiles ``p_field`` against ``x_field`` of every ok model that has them, on one axis (mm, GPa)."""
    models = {k: m for k, m in run.models.items() if m.status == "ok" and p_field in m.fields}
    if not models:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 3.7))
    for name, m in models.items():
        x, p = m.fields[x_field], m.fields[p_field]
        keep = x >= 0 if positive_x else np.ones(x.shape, dtype=bool)
        ax.plot(x[keep] * 1e3, p[keep] / 1e9, label=name, **STYLE.get(name, {}))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(f"{run.scene}: {title}")
    ax.legend()
    ax.grid(alpha=0.3)
    return _save(fig, path)


def pressure_overlay(run: RunResult, path: Path) -> str | None:
    """Pressure profiles across the contact (x >= 0; the profiles are symmetric)."""
    return _overlay(run, path, "x", "pressure", "x (mm)", "contact pressure (GPa)", "pressure profiles",
                    positive_x=True)


def axial_profile(run: RunResult, path: Path) -> str | None:
    """Pressure along the roller axis on the centre line x = 0 (dog-bone edge peaks)."""
    return _overlay(run, path, "y", "pressure_axial", "y along the roller (mm)", "pressure at x = 0 (GPa)",
                    "axial pressure profile")


def pressure_map(run: RunResult, path: Path) -> str | None:
    """The contact pressure field of the first model that has one (footprint)."""
    m = next((m for m in run.models.values() if m.status == "ok" and "pressure_map" in m.fields
              and "map_x" in m.fields), None)
    if m is None:
        return None
    x, y, p = m.fields["map_x"], m.fields["map_y"], m.fields["pressure_map"]
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    cs = ax.pcolormesh(y * 1e3, x * 1e3, p / 1e9, shading="nearest", cmap="magma")
    fig.colorbar(cs, ax=ax, label="pressure (GPa)")
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("x (mm)")
    ax.set_title(f"{run.scene}: contact pressure ({m.model})")
    return _save(fig, path)


def traction_overlay(run: RunResult, path: Path) -> str | None:
    """Tangential traction along the rolling direction (2D: the whole profile; 3D: the centre line y = 0) of
    every model that has one, with the traction bound mu p of the first such model."""
    models = {k: m for k, m in run.models.items() if m.status == "ok" and "x" in m.fields
              and ("traction" in m.fields or "traction_x" in m.fields)}
    if not models:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 3.7))
    for name, m in models.items():
        q = m.fields.get("traction", m.fields.get("traction_x"))
        ax.plot(m.fields["x"] * 1e3, q / 1e9, label=name, **STYLE.get(name, {}))
    mu = run.params.get("friction.mu")
    first = next(iter(models.values()))
    if mu is not None and "pressure" in first.fields:
        sign = -1.0 if np.sum(first.fields.get("traction", first.fields.get("traction_x"))) < 0 else 1.0
        ax.plot(first.fields["x"] * 1e3, sign * mu * first.fields["pressure"] / 1e9, color="0.6", lw=0.8,
                ls=":", label="traction bound mu p")
    ax.set_xlabel("x, rolling direction (mm)")
    ax.set_ylabel("tangential traction (GPa)")
    ax.set_title(f"{run.scene}: tangential traction")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _save(fig, path)


def adhesion_map(run: RunResult, path: Path) -> str | None:
    """Adhesion (stick) and slip areas of the first model that gives an adhesion map (3D exact theory)."""
    m = next((m for m in run.models.values() if m.status == "ok" and "adhesion_map" in m.fields), None)
    if m is None:
        return None
    x, y = m.fields["map_x"], m.fields["map_y"]
    state = np.where(m.fields["pressure_map"] > 0, 1.0 + m.fields["adhesion_map"], 0.0)   # 0 out, 1 slip, 2 stick
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    cmap = matplotlib.colors.ListedColormap(["white", "tab:orange", "tab:blue"])
    ax.pcolormesh(y * 1e3, x * 1e3, state, shading="nearest", cmap=cmap, vmin=-0.5, vmax=2.5)
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("x, rolling direction (mm)")
    ax.set_title(f"{run.scene}: adhesion (blue) and slip (orange) areas ({m.model})")
    return _save(fig, path)


def fem_mesh(run: RunResult, path: Path) -> str | None:
    """The FE mesh near the contact (finest level), coloured by body."""
    m = run.models.get("fem")
    if m is None or m.status != "ok":
        return None
    bodies = [b for b in ("block", "cylinder") if f"mesh_{b}_points" in m.fields]
    if not bodies:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for body, colour in zip(bodies, ("tab:blue", "tab:red")):
        pts, tri = m.fields[f"mesh_{body}_points"], m.fields[f"mesh_{body}_triangles"]
        ax.triplot(Triangulation(pts[0] * 1e3, pts[1] * 1e3, tri.T), lw=0.25, color=colour, label=body)
    a = m.quantities.get("half_width", 1e-3)
    ax.set_xlim(0, 3 * a * 1e3)
    ax.set_ylim(-2 * a * 1e3, 1 * a * 1e3)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("FE mesh near the contact (finest level, symmetric half)")
    ax.legend(loc="lower right")
    return _save(fig, path)


def fem_convergence(run: RunResult, path: Path) -> str | None:
    """Per mesh level: |q - q_extrapolated| / q_extrapolated (the discretisation error, solid) and the error
    against the analytic solution (dashed), which levels off at the modelling difference (finite block)."""
    m = run.models.get("fem")
    if m is None or m.status != "ok" or "richardson" not in m.stats:
        return None
    levels = m.stats["levels"]
    h = np.array([lv["h_over_a"] for lv in levels])
    fig, ax = plt.subplots(figsize=(5.6, 3.9))
    ref = run.models.get("analytic")
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    for q, colour in zip(m.stats["richardson"], colours):
        vals = np.array([lv[q] for lv in levels])
        rich = m.stats["richardson"][q]
        if rich["order"] is not None:      # no asymptotic order: there is no extrapolated value to show
            ax.loglog(h, np.abs(vals / rich["value"] - 1), marker="o", color=colour,
                      label=f"{q} vs extrapolated (order {rich['order']:.2f})")
        if ref is not None and ref.status == "ok" and q in ref.quantities:
            ax.loglog(h, np.maximum(np.abs(vals / ref.quantities[q] - 1), 1e-9), marker="s", ls="--",
                      color=colour, alpha=0.6, label=f"{q} vs analytic")
    ax.set_xlabel("element size on the contact / a")
    ax.set_ylabel("relative difference")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    ax.set_title("FEM mesh convergence")
    return _save(fig, path)


def stress_field(run: RunResult, path: Path) -> str | None:
    """Von Mises and orthogonal shear tau_xz in the plane y = 0 below the contact (first model with a field)."""
    m = next((m for m in run.models.values() if m.status == "ok" and "von_mises" in m.fields), None)
    if m is None:
        return None
    x, z = m.fields["stress_x"], m.fields["stress_z"]
    p0 = m.quantities["p_max"]
    fig, axes = plt.subplots(1, 2, figsize=(9.6, 3.6), sharey=True)
    for ax, key, title, cmap in ((axes[0], "von_mises", "von Mises / p0", "viridis"),
                                 (axes[1], "tau_xz", "tau_xz / p0", "RdBu_r")):
        f = m.fields[key] / p0
        lim = np.abs(f).max()
        cs = ax.contourf(x * 1e3, z * 1e3, f, levels=21, cmap=cmap,
                         vmin=-lim if key == "tau_xz" else 0, vmax=lim)
        fig.colorbar(cs, ax=ax)
        ax.set_title(title)
        ax.set_xlabel("x (mm)")
    axes[0].invert_yaxis()
    axes[0].set_ylabel("depth z (mm)")
    fig.suptitle(f"{run.scene}: sub-surface stresses ({m.model})")
    return _save(fig, path)


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
    return _save(fig, path)


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
    return _save(fig, path)
