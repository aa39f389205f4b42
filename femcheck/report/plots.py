"""Matplotlib figures for reports (Agg backend, PNG files). Lengths are shown in mm, pressures in GPa."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..result import RunResult  # noqa: E402

# Drawn in this order, widest first, so a curve that coincides with another stays visible under it.
STYLE = {"exact": dict(color="tab:blue", lw=3.0, alpha=0.6, zorder=1), "analytic": dict(color="k", lw=1.2, zorder=3),
         "bem": dict(color="tab:blue", ls="--", lw=1.4, zorder=2),
         "fem": dict(color="tab:red", marker=".", ms=3, ls="none", zorder=4),
         "finite_line": dict(color="tab:green", marker="+", ms=4, ls="-", lw=0.8, zorder=2),
         "fastsim": dict(color="tab:orange", ls="-.", lw=1.3, zorder=3),
         "full_slip": dict(color="tab:green", ls=":", lw=1.6, zorder=3),
         "strip": dict(color="tab:purple", ls="--", lw=1.2, zorder=3)}


def save_figure(fig, path: Path) -> str:
    """Lay out, write (110 dpi) and close ``fig``; the file name for the report."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path.name


# ---- which contact a field belongs to ---------------------------------------------------------------------------
def parts(run: RunResult) -> list[tuple[str, str]]:
    """(field suffix, label) of each contact the run's fields describe. A scene of several contacts (the two
    raceways of srb-normal, the coatings of coated-roller) gives the first contact's fields as ``x``/``pressure``
    and the others' as ``x_<part>``/``pressure_<part>``; the quantities name every part (``p_max_<part>``)."""
    fields = {k for m in run.models.values() for k in m.fields}
    others = sorted({k[len("pressure_"):] for k in fields if k.startswith("pressure_")
                     and f"x_{k[len('pressure_'):]}" in fields})
    named = {q.rpartition("_")[2] for m in run.models.values() for q in m.quantities
             if q.startswith(("p_max_", "half_width_", "semi_axis_x_"))}
    first = sorted(named - set(others))
    label = (lambda p: {"inner": "inner raceway", "outer": "outer raceway"}.get(
        p, f"coating {p}" if run.kind == "layer_contact" else p))
    if not others:
        return [("", label(first[0]) if len(first) == 1 else "")]
    return [("", label(first[0]) if len(first) == 1 else "first contact")] + [(f"_{p}", label(p)) for p in others]


def singular_note(run: RunResult) -> str:
    """'' or why colour scales and tables must not be set by a quantity: one that grows with refinement."""
    grows = [q for q, why in run.not_compared.items() if "refinement" in why]
    return f"{', '.join(grows)} grows with refinement by nature" if grows else ""


def profile(fields: dict, x_field: str, p_field: str) -> tuple[np.ndarray, np.ndarray, bool] | None:
    """(x, p, cut) of a model's pressure along ``x_field``: the 1D profile itself, or, where the model gives a
    field over (x, y) (``p_field`` of shape (nx, ny), or ``pressure_map`` over ``map_x`` x ``map_y``), its cut along
    x through the peak (``cut`` True)."""
    if x_field in fields and p_field in fields:
        x, p = np.asarray(fields[x_field]), np.asarray(fields[p_field])
    elif x_field == "x" and p_field == "pressure" and "pressure_map" in fields and "map_x" in fields:
        x, p = np.asarray(fields["map_x"]), np.asarray(fields["pressure_map"])
    else:
        return None
    if p.ndim == 2 and p.shape[0] == x.size:
        return x, p[:, int(np.argmax(p.max(axis=0)))], True
    return (x, p, False) if p.shape == x.shape else None


def _overlay(run: RunResult, path: Path, x_field: str, p_field: str, xlabel: str, ylabel: str, title: str,
             positive_x: bool = False, suffix: str = "", part: str = "") -> str | None:
    """Profiles ``p_field`` against ``x_field`` of every ok model that has them, on one axis (mm, GPa); a model
    with a 2D field contributes its cut through the peak (:func:`profile`)."""
    xf, pf = x_field + suffix, p_field + suffix
    curves = {k: c for k, m in run.models.items() if m.status == "ok" and (c := profile(m.fields, xf, pf))}
    if not curves:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 3.7))
    for name, (x, p, cut) in curves.items():
        keep = x >= 0 if positive_x else np.ones(x.shape, dtype=bool)
        ax.plot(x[keep] * 1e3, p[keep] / 1e9, label=name + (" (cut through the peak)" if cut else ""),
                **STYLE.get(name, {}))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(f"{run.scene}: {title}" + (f" ({part})" if part else ""))
    ax.legend()
    ax.grid(alpha=0.3)
    return save_figure(fig, path)


def pressure_overlay(run: RunResult, path: Path) -> list[str]:
    """Pressure profiles across the contact (x >= 0; the profiles are symmetric), one figure per contact."""
    out = []
    for suffix, part in parts(run):
        p = path.with_name(path.stem + suffix + path.suffix)
        name = _overlay(run, p, "x", "pressure", "x (mm)", "contact pressure (GPa)", "pressure profiles",
                        positive_x=True, suffix=suffix, part=part)
        if name:
            out.append(name)
    return out


def axial_profile(run: RunResult, path: Path) -> str | None:
    """Pressure along the roller axis on the centre line x = 0 (dog-bone edge peaks)."""
    return _overlay(run, path, "y", "pressure_axial", "y along the roller (mm)", "pressure at x = 0 (GPa)",
                    "axial pressure profile")


MAP_WIDTH, MAP_MIN_HEIGHT, MAP_MAX_HEIGHT = 5.6, 1.6, 4.5       # inches of the map axis


def _map_figure(x: np.ndarray, y: np.ndarray) -> tuple:
    """(figure, axis, scale note) for a map with y horizontal and x vertical (mm). True aspect where it reads (a
    1:4 ellipse looks 1:4); a contact so long that its true aspect would leave a sliver under MAP_MIN_HEIGHT
    inches (a roller's 0.5 mm x 20 mm) is stretched along x by a stated factor (``note``: "x stretched 12x")."""
    width, height = float(np.ptp(y)) or 1.0, float(np.ptp(x)) or 1.0
    true_h = MAP_WIDTH * height / width
    stretch = 1.0 if true_h >= MAP_MIN_HEIGHT else float(np.ceil(MAP_MIN_HEIGHT / true_h))
    ax_h = min(true_h * stretch, MAP_MAX_HEIGHT)
    fig, ax = plt.subplots(figsize=(MAP_WIDTH + 1.4, ax_h + 1.5))
    ax.set_aspect(stretch)
    return fig, ax, ("equal axes" if stretch == 1.0 else f"x stretched {stretch:g}x")


def pressure_map(run: RunResult, path: Path) -> str | None:
    """The contact pressure field of the first model that has one (footprint), equal axes. Where a quantity
    grows with refinement (a peak at a sharp edge), the colour scale stops at the 99th percentile of the loaded
    cells instead of at that grid-dependent peak, and says so."""
    m = next((m for m in run.models.values() if m.status == "ok" and "pressure_map" in m.fields
              and "map_x" in m.fields), None)
    if m is None:
        return None
    x, y, p = m.fields["map_x"], m.fields["map_y"], m.fields["pressure_map"]
    fig, ax, scale = _map_figure(x, y)
    note = singular_note(run)
    vmax = float(np.percentile(p[p > 0], 99)) if note and np.any(p > 0) else float(p.max())
    cs = ax.pcolormesh(y * 1e3, x * 1e3, p / 1e9, shading="nearest", cmap="magma", vmin=0, vmax=vmax / 1e9)
    cb = fig.colorbar(cs, ax=ax, label="pressure (GPa)", orientation="horizontal", pad=0.25,
                      extend="max" if note else "neither")
    if note:
        cb.set_label(f"pressure (GPa); scale clipped at the 99th percentile ({note})", fontsize=7)
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("x (mm)")
    part = parts(run)[0][1]
    ax.set_title(f"{run.scene}: contact pressure ({m.model}" + (f", {part}" if part else "") + f"; {scale})",
                 fontsize=9)
    return save_figure(fig, path)


def traction_overlay(run: RunResult, path: Path) -> str | None:
    """Tangential traction along the rolling direction (2D: the whole profile; 3D: the centre line y = 0) of
    every model that has one, with the traction bound mu p of the first such model. Tractions are those on
    body 1 (the cylinder, the ball), as the creep forces."""
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
    three_d = any("traction_x" in m.fields for m in models.values())
    ax.set_xlabel("x, rolling direction (mm)" + (", centre line y = 0" if three_d else ""))
    ax.set_ylabel("tangential traction on body 1 (GPa)")
    ax.set_title(f"{run.scene}: tangential traction")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save_figure(fig, path)


def adhesion_map(run: RunResult, path: Path) -> str | None:
    """Adhesion (stick) and slip areas of the first model that gives an adhesion map (3D exact theory)."""
    m = next((m for m in run.models.values() if m.status == "ok" and "adhesion_map" in m.fields), None)
    if m is None:
        return None
    x, y = m.fields["map_x"], m.fields["map_y"]
    state = np.where(m.fields["pressure_map"] > 0, 1.0 + m.fields["adhesion_map"], 0.0)   # 0 out, 1 slip, 2 stick
    fig, ax, scale = _map_figure(x, y)
    cmap = matplotlib.colors.ListedColormap(["white", "tab:orange", "tab:blue"])
    ax.pcolormesh(y * 1e3, x * 1e3, state, shading="nearest", cmap=cmap, vmin=-0.5, vmax=2.5)
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("x, rolling direction (mm)")
    ax.set_title(f"{run.scene}: adhesion (blue) and slip (orange) areas ({m.model}; {scale})", fontsize=9)
    return save_figure(fig, path)


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
    return save_figure(fig, path)
