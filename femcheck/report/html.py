"""HTML report + summary.json for one or more scene runs, written atomically into an output directory."""
from __future__ import annotations

import multiprocessing
import os
import shutil
import sys
from concurrent.futures import ProcessPoolExecutor
import tempfile
import time
from pathlib import Path
from typing import Any

from jinja2 import Environment, PackageLoader, select_autoescape

from .. import __version__
from ..compare import certificates
from ..result import VERDICTS, RunResult, dumps
from . import charts, dashboard, fe_plots, kinds, pictures, plots
from .sources import cite
from .units import unit_of


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return ", ".join(map(str, v))
    return str(v)


def _pct(v: Any) -> str:
    if v is None:
        return "-"
    return f"{100 * v:.2g} %" if 100 * v < 10 else f"{100 * v:.3g} %"


def _env() -> Environment:
    env = Environment(loader=PackageLoader("femcheck", "report/templates"), autoescape=select_autoescape())
    env.filters["fmt"] = _fmt
    env.filters["pct"] = _pct
    env.filters["cite"] = lambda text: cite(str(text or ""))
    env.filters["unit"] = lambda q, run: unit_of(q, run.params, run.kind)
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
    """``summary.json``: overall pass, the verdicts (``validity``: one object per scene, model, reference and
    quantity) and every scene's run (the ``--json`` object of ``femcheck run``) with its pass and problems."""
    return {"title": title, "femcheck_version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S"),
            "elapsed_s": elapsed_s, "passed": all(r.passed for r in runs),
            "validity": dashboard.validity(runs),
            "scenes": [{**r.to_json(), "passed": r.passed, "problems": r.problems} for r in runs]}


def _figures(r: RunResult, tmp: Path, prefix: str) -> dict[str, Any]:
    figs: dict[str, Any] = {"pressure": plots.pressure_overlay(r, tmp / f"{prefix}-pressure.png"),
                            "convergence": fe_plots.convergence(r, tmp / f"{prefix}-convergence.png")}
    for key, fn in (("traction", plots.traction_overlay), ("adhesion", plots.adhesion_map),
                    ("axial", plots.axial_profile), ("map", plots.pressure_map), ("mesh", fe_plots.fem_mesh),
                    ("stress", plots.stress_field)):
        name = fn(r, tmp / f"{prefix}-{key}.png")
        if name:
            figs[key] = name
    figs.update(pictures.fem_views(r, tmp, prefix))
    return figs


# Figures of the scenes drawn in parallel worker processes (forked: they inherit the runs, nothing is pickled but
# the file names coming back). Drawing and writing the ~50 PNGs of the quick suite took 6.3 s against its 4.2 s
# of scenes on one core; matplotlib's layout and rasterising are single-threaded, so processes are the lever.
FIGURE_WORKERS = 2
_JOBS: list[tuple[RunResult, Path, str]] = []


def _figures_at(i: int) -> dict[str, Any]:
    return _figures(*_JOBS[i])


def all_figures(jobs: list[tuple[RunResult, Path, str]]) -> list[dict[str, Any]]:
    """:func:`_figures` of every (run, folder, prefix), in forked processes where the platform forks (Linux)
    and there is more than one scene and one CPU; in this process otherwise."""
    workers = min(len(jobs), os.cpu_count() or 1, FIGURE_WORKERS)
    if workers < 2 or not sys.platform.startswith("linux"):
        return [_figures(*j) for j in jobs]
    global _JOBS
    _JOBS = jobs
    # the scenes with FE fields (meshes, 3D pictures) take 3-8x the others: hand them out first
    order = sorted(range(len(jobs)), key=lambda i: "fem" not in jobs[i][0].models)
    try:
        with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
            done = dict(zip(order, pool.map(_figures_at, order)))
    finally:
        _JOBS = []
    return [done[i] for i in range(len(jobs))]


def write_report(runs: list[RunResult], out: Path, title: str, elapsed_s: float) -> Path:
    """Write ``out/index.html`` (the validity dashboard first, then one section per scene), ``out/summary.json``
    and the figures; returns the index path."""
    with AtomicDir(out) as tmp:
        scenes, rows = [], []
        figures = all_figures([(r, tmp, f"{i:02d}-{r.scene}") for i, r in enumerate(runs)])
        for i, r in enumerate(runs):
            prefix = f"{i:02d}-{r.scene}"
            scene_rows = dashboard.rows(r)
            rows += scene_rows
            fem = r.models.get("fem")
            scenes.append({"run": r, "rows": scene_rows, "figs": figures[i],
                           "certificates": certificates(fem) if fem is not None and fem.status == "ok" else {},
                           "extra": kinds.section(r, tmp, prefix)})
        chart = charts.cost_error(rows, tmp / "dashboard-cost-error.png")
        data = summary(runs, title, elapsed_s)
        (tmp / "summary.json").write_text(dumps(data, indent=1))
        by_verdict = {v: sum(x["verdict"] == v for x in data["validity"]) for v in reversed(VERDICTS)}
        counts = {"total": len(data["validity"]), "by_verdict": {v: n for v, n in by_verdict.items() if n}}
        html = _env().get_template("index.html.j2").render(title=title, scenes=scenes, summary=data, chart=chart,
                                                           counts=counts)
        (tmp / "index.html").write_text(html)
    return Path(out) / "index.html"


def write_map_report(vmap, out: Path, elapsed_s: float) -> Path:
    """Write ``out/index.html``, ``out/map.json`` and one heat map per (model, reference, quantity)."""
    with AtomicDir(out) as tmp:
        figs = [charts.validity_heatmap(vmap, c, tmp / f"map-{c[0]}-vs-{c[1]}-{c[2]}.png".replace("@", "_"))
                for c in vmap.comparisons()]
        data = {"femcheck_version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S"),
                "elapsed_s": elapsed_s, **vmap.to_json()}
        (tmp / "map.json").write_text(dumps(data, indent=1))
        html = _env().get_template("map.html.j2").render(
            m=vmap, figs=figs, statements=data["statements"], version=__version__, created=data["created"],
            elapsed_s=elapsed_s)
        (tmp / "index.html").write_text(html)
    return Path(out) / "index.html"
