"""HTML report + summary.json for one or more scene runs, written atomically into an output directory."""
from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import Any

from jinja2 import Environment, PackageLoader, select_autoescape

from .. import __version__
from ..result import RunResult
from . import kinds, pictures, plots


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return ", ".join(map(str, v))
    return str(v)


def _env() -> Environment:
    env = Environment(loader=PackageLoader("femcheck", "report/templates"), autoescape=select_autoescape())
    env.filters["fmt"] = _fmt
    env.filters["pct"] = lambda v: "-" if v is None else f"{100 * v:.3g} %"
    return env


class AtomicDir:
    """Write files into a temporary sibling directory, then move them into place on success only."""

    def __init__(self, out: Path):
        self.out = Path(out)

    def __enter__(self) -> Path:
        self.out.parent.mkdir(parents=True, exist_ok=True)
        self.tmp = Path(tempfile.mkdtemp(prefix=f".{self.out.name}-", dir=self.out.parent))
        return self.tmp

    def __exit__(self, exc_type, *_):
        if exc_type is None:
            self.out.mkdir(parents=True, exist_ok=True)
            for f in self.tmp.iterdir():
                os.replace(f, self.out / f.name)
        shutil.rmtree(self.tmp, ignore_errors=True)
        return False


def summary(runs: list[RunResult], title: str, elapsed_s: float) -> dict[str, Any]:
    return {"title": title, "femcheck_version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S"),
            "elapsed_s": elapsed_s, "passed": all(r.passed for r in runs),
            "scenes": [{**r.to_json(), "passed": r.passed} for r in runs]}


def write_report(runs: list[RunResult], out: Path, title: str, elapsed_s: float) -> Path:
    """Write ``out/index.html``, ``out/summary.json`` and the figures; returns the index path."""
    with AtomicDir(out) as tmp:
        scenes = []
        for i, r in enumerate(runs):
            figs = {}
            for key, fn in (("pressure", plots.pressure_overlay), ("traction", plots.traction_overlay),
                            ("adhesion", plots.adhesion_map), ("axial", plots.axial_profile),
                            ("map", plots.pressure_map), ("mesh", plots.fem_mesh),
                            ("convergence", plots.fem_convergence), ("stress", plots.stress_field)):
                name = fn(r, tmp / f"{i:02d}-{r.scene}-{key}.png")
                if name:
                    figs[key] = name
            figs.update(pictures.fem_views(r, tmp, f"{i:02d}-{r.scene}"))
            scenes.append({"run": r, "figs": figs, "extra": kinds.section(r, tmp, f"{i:02d}-{r.scene}")})
        data = summary(runs, title, elapsed_s)
        (tmp / "summary.json").write_text(json.dumps(data, indent=1))
        html = _env().get_template("index.html.j2").render(title=title, scenes=scenes, summary=data)
        (tmp / "index.html").write_text(html)
    return Path(out) / "index.html"


def write_map_report(vmap, out: Path, elapsed_s: float) -> Path:
    """Write ``out/index.html``, ``out/map.json`` and one heat map per (model, reference, quantity)."""
    with AtomicDir(out) as tmp:
        figs = [plots.validity_heatmap(vmap, c, tmp / f"map-{c[0]}-vs-{c[1]}-{c[2]}.png".replace("@", "_"))
                for c in vmap.comparisons()]
        data = {"femcheck_version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S"),
                "elapsed_s": elapsed_s, **vmap.to_json()}
        (tmp / "map.json").write_text(json.dumps(data, indent=1))
        html = _env().get_template("map.html.j2").render(
            m=vmap, figs=figs, statements=data["statements"], version=__version__, created=data["created"],
            elapsed_s=elapsed_s)
        (tmp / "index.html").write_text(html)
    return Path(out) / "index.html"
