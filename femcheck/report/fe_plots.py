"""Figures of multi-level (FE) references: the mesh near the contact and the convergence of each quantity over
the mesh levels, drawn against the reference's own extrapolated value (its certificate), never against another
model: a contrast model there would read as divergence."""
from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.tri import Triangulation

from ..compare import is_singular
from ..result import ModelResult, RunResult
from .plots import plt, save_figure


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
    ax.set_title(f"{run.scene}: FE mesh near the contact (finest level, symmetric half)", fontsize=9)
    ax.legend(loc="lower right")
    return save_figure(fig, path)


def level_sets(m: ModelResult) -> list[tuple[str, list[dict], dict[str, dict]]]:
    """(part, levels, certificates) of a multi-level result: the whole result, or each contact of a result that
    keeps one sub-result per contact (``stats[part]["levels"]``). Certificates come from ``certificates`` or, for
    results from before them, from ``richardson`` (certified when it found an observed order)."""
    def certs(st: dict) -> dict[str, dict]:
        if "certificates" in st:
            return st["certificates"]
        # richardson's error estimate is absolute, a certificate's relative
        return {q: {**e, "certified": e.get("order") is not None,
                    "error_estimate": e["error_estimate"] / abs(e["value"]) if e.get("value") else None}
                for q, e in st.get("richardson", {}).items()}

    subs = [(k, v) for k, v in m.stats.items() if isinstance(v, dict) and "levels" in v
            and ("richardson" in v or "certificates" in v)]
    if subs:
        return [(k, v["levels"], certs(v)) for k, v in subs]
    if "levels" in m.stats and ("richardson" in m.stats or "certificates" in m.stats):
        return [("", m.stats["levels"], certs(m.stats))]
    return []


def _part_label(part: str) -> str:
    return {"inner": "inner raceway", "outer": "outer raceway"}.get(part, part)


def convergence(run: RunResult, path: Path) -> list[str]:
    """Per model with levels and per contact: |q_level - q_ref| / |q_ref| against the element size, where q_ref
    is the certificate's value (Richardson-extrapolated when certified). An uncertified quantity's value is its
    finest level: its other levels are drawn dashed, as the change to the finest. The cross at the finest size
    is the certificate's error estimate. A quantity that grows with refinement by nature is not drawn (the
    title says so)."""
    out = []
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
    for name, m in run.models.items():
        if m.status != "ok":
            continue
        for part, levels, certs in level_sets(m):
            if len(levels) < 2 or "h_over_a" not in levels[0] or not certs:
                continue                 # one level has no convergence to draw (its table says so)
            h = np.array([lv["h_over_a"] for lv in levels], dtype=float)
            fig, ax = plt.subplots(figsize=(5.8, 4.0))
            singular = []
            for (q, c), colour in zip(certs.items(), colours * 3):
                if is_singular(c):
                    singular.append(f"{q} (finest {c.get('finest', c.get('value')):.4g})")
                    continue
                if not all(q in lv for lv in levels):
                    continue
                vals = np.array([lv[q] for lv in levels], dtype=float)
                ref = float(c["value"])
                err = np.abs(vals / ref - 1.0)
                if c.get("certified"):
                    how = f"order {c['order']:.2f}" if c.get("order") is not None else "levels agree"
                    ax.loglog(h, np.maximum(err, 1e-9), "o-", color=colour, label=f"{q}: {how}, certified")
                else:
                    ax.loglog(h[:-1], np.maximum(err[:-1], 1e-9), "s--", color=colour,
                              label=f"{q}: not certified (change to the finest level)")
                est = c.get("error_estimate")
                if est:
                    ax.loglog([h[-1]], [est], "x", ms=9, color=colour)
            where = f" ({_part_label(part)})" if part else ""
            title = f"{run.scene}: {name} mesh convergence{where}"
            if singular:
                title += "\nnot drawn, grows with refinement by nature: " + ", ".join(singular)
            ax.set_title(title, fontsize=8)
            ax.set_xlabel("element size on the contact / a")
            ax.set_xticks(h, [f"{v:.3g}" for v in h])
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.set_ylabel("|q - q_reported| / |q_reported|\n(q_reported: extrapolated if certified)")
            ax.grid(alpha=0.3, which="both")
            if ax.get_legend_handles_labels()[0]:
                ax.plot([], [], "x", color="0.3", label="x: error estimate of the reported value")
                ax.legend(fontsize=6.5)
            p = path.with_name(f"{path.stem}-{name}{'-' + part if part else ''}{path.suffix}")
            out.append(save_figure(fig, p))
    return out
