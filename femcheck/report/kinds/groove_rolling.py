"""Report section of the groove_rolling kind: the FE reference, the conformal and planar exact theories side by
side, the adhesion/slip map of the conformal contact and the lateral distributions of normal and tangential load
(seed 000 Figs 8-11 for one contact)."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ...result import RunResult  # noqa: E402
from ..plots import save_figure  # noqa: E402
from . import Figure, KindSection, Table  # noqa: E402

ROWS = (("approach", "approach", 1e6, "um"), ("p_max", "p_max", 1e-9, "GPa"),
        ("contact_half_length_s", "half length along the groove", 1e3, "mm"),
        ("angle_span", "angle span", 180.0 / np.pi, "deg"), ("adhesion_fraction", "adhesion fraction", 1.0, "-"),
        ("creepage_x", "free-rolling creepage", 1.0, "-"), ("spin_moment", "spin moment", 1.0, "N m"),
        ("friction_power", "frictional power", 1.0, "W"))


def _value(run: RunResult, model: str, key: str) -> float | None:
    m = run.models.get(model)
    if m is None or m.status != "ok":
        return None
    if model == "fem" and key == "approach":
        key = "body_approach"
    return m.quantities.get(key)


def _diff(v: float | None, ref: float | None) -> str:
    return "" if ref in (None, 0.0) or v is None else f"{100.0 * (v - ref) / abs(ref):+.2f} %"


def _table(run: RunResult) -> Table:
    rows = []
    for key, label, scale, unit in ROWS:
        vf, vc, vp = (_value(run, m, key) for m in ("fem", "cect", "planar"))
        rows.append([f"{label} ({unit})"] + ["" if v is None else v * scale for v in (vf, vc, vp)]
                    + ["" if key == "approach" else _diff(vc, vf), _diff(vp, vc)])
    note = ("fem: frictional FE reference (finite roller and ring segment, FE compliances, its own semi-smooth "
            "Newton; Richardson value where certified, see the certificates); its approach row is the approach of "
            "the roller axis towards the ring's clamped base, not comparable with the half-space approach of the "
            "exact theories. cect: conformal exact theory (exact crown/groove gap, varying rolling radii, variable "
            "dq); planar: planar exact theory with the Hertz gap. All roll freely (F_x = 0). Spin moment: zero by "
            "symmetry (parallel axes).")
    return Table("FE reference, conformal and planar exact theory",
                 ["quantity", "fem", "cect", "planar", "cect - fem", "planar - cect"], rows, note)


def _maps(run: RunResult, path: Path) -> str | None:
    m = run.models.get("cect")
    if m is None or m.status != "ok" or "adhesion_map" not in m.fields:
        return None
    x, s = m.fields["map_x"], m.fields["map_y"]
    p = m.fields["pressure_map"]
    state = np.where(p > 0, 1.0 + m.fields["adhesion_map"], 0.0)
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 5.2), sharex=True)
    cmap = matplotlib.colors.ListedColormap(["white", "tab:orange", "tab:blue"])
    axes[0].pcolormesh(s * 1e3, x * 1e3, state, shading="nearest", cmap=cmap, vmin=-0.5, vmax=2.5)
    axes[0].contour(s * 1e3, x * 1e3, p / 1e9, levels=5, colors="k", linewidths=0.5)
    axes[0].set_ylabel("x, rolling (mm)")
    axes[0].set_title(f"{run.scene}: adhesion (blue) / slip (orange), pressure contours (cect)")
    pd = m.fields.get("power_density_map")
    if pd is not None:
        cs = axes[1].pcolormesh(s * 1e3, x * 1e3, pd / 1e6, shading="nearest", cmap="viridis")
        fig.colorbar(cs, ax=axes[1], label="frictional power (W/mm^2)", orientation="horizontal", pad=0.25)
    axes[1].set_xlabel("s along the groove (mm)")
    axes[1].set_ylabel("x, rolling (mm)")
    return save_figure(fig, path)


def _lateral(run: RunResult, path: Path) -> str | None:
    models = {k: m for k, m in run.models.items() if m.status == "ok" and "lateral_normal" in m.fields}
    if not models:
        return None
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 5.2), sharex=True)
    for name, m in models.items():
        s = m.fields["s"] * 1e3
        axes[0].plot(s, m.fields["lateral_normal"] / 1e3, label=name)
        axes[1].plot(s, m.fields["lateral_fx"] / 1e3, label=name)
    axes[0].set_ylabel("N* (N/mm)")
    axes[1].set_ylabel("F_x* (N/mm)")
    axes[1].set_xlabel("s along the groove (mm)")
    axes[0].set_title(f"{run.scene}: lateral distributions of normal and rolling-direction load")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    return save_figure(fig, path)


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    out = KindSection(tables=[_table(run)])
    name = _maps(run, Path(outdir) / f"{prefix}-groove-maps.png")
    if name:
        out.figures.append(Figure(name, "Conformal contact: adhesion (blue) and slip (orange) areas with pressure "
                                        "contours, and the frictional power density; s along the groove, x along "
                                        "the rolling direction (leading edge at +x)."))
    name = _lateral(run, Path(outdir) / f"{prefix}-groove-lateral.png")
    if name:
        out.figures.append(Figure(name, "Lateral distributions N*(s) = sum_x p_n dx and F_x*(s) = sum_x p_x dx "
                                        "(N/mm); free rolling: the F_x* bands cancel."))
    return out
