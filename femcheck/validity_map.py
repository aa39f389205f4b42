"""Validity maps: run a scene over a 2D grid of two of its keys and record, at every grid point, how far each
fast model is from each reference and whether that is within the scene's tolerance.

The grid points are independent runs, sent through :func:`femcheck.executor.map_cases` (local processes or a
dask cluster). A point the scene refuses (e.g. outside a model's admissible range) is recorded as
``refused`` with the reason; a model that fails to converge is recorded as ``failed`` — neither is dropped.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from .errors import InputError
from .executor import map_cases
from .problems import problem
from .runner import run
from .scene import Scene, lookup_key


@dataclass(frozen=True)
class Axis:
    """One map axis: a scene key and its grid values (``log``: geometric spacing)."""

    key: str
    values: tuple[float, ...]
    log: bool

    def label(self) -> str:
        return self.key


def parse_axis(option: str, spec: str, scene: Scene) -> Axis:
    """``KEY=lo:hi:n[:log|:lin]``. Spacing is geometric when asked, or by default when 0 < lo and hi/lo >= 10
    (a range over decades, e.g. h/a from 0.01 to 10); the key must be a numeric key of the scene's kind."""
    key, sep, rng = spec.partition("=")
    parts = rng.split(":")
    form = f"{option} takes KEY=lo:hi:n[:log|:lin] (e.g. {option} layer.h_over_a=0.01:10:7)"
    if not sep or len(parts) not in (3, 4):
        raise InputError(option, f"{spec!r} is not valid; {form}")
    key = key.strip()
    k = lookup_key(problem(scene.kind).SCHEMA, key)
    if k is None or k.kind not in ("float", "int"):
        raise InputError(option, f"{key!r} is not a numeric key of a {scene.kind} scene; see `femcheck show "
                                 f"{scene.name}` for the keys")
    try:
        lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError(option, f"{spec!r} is not valid; {form}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi) or not 2 <= n <= 200:
        raise InputError(option, f"{spec!r}: need finite lo < hi and 2 <= n <= 200; {form}")
    spacing = parts[3] if len(parts) == 4 else ("log" if lo > 0 and hi / lo >= 10 else "lin")
    if spacing not in ("log", "lin") or (spacing == "log" and lo <= 0):
        raise InputError(option, f"{spec!r}: spacing is log (needs lo > 0) or lin")
    values = np.geomspace(lo, hi, n) if spacing == "log" else np.linspace(lo, hi, n)
    if k.kind == "int":
        values = np.unique(np.round(values))
    for v in (values[0], values[-1]):          # range-check the ends now: one clear line, not n^2 refusals
        k.coerce(key, int(v) if k.kind == "int" else float(v))
    return Axis(key, tuple(int(v) if k.kind == "int" else float(v) for v in values), spacing == "log")


@dataclass
class MapPoint:
    """One grid point: ``status`` ok | refused | failed; ``errors[(model, reference, quantity)]`` =
    (rel_error, tolerance or None, passed or None); ``failed_models``: model -> reason."""

    ix: int
    iy: int
    overrides: dict[str, Any]
    status: str = "ok"
    message: str = ""
    errors: dict[tuple[str, str, str], tuple[float, float | None, bool | None]] = field(default_factory=dict)
    failed_models: dict[str, str] = field(default_factory=dict)
    time_s: dict[str, float] = field(default_factory=dict)


def _map_point(args: tuple[Scene, int, int, dict[str, Any], list[str] | None]) -> MapPoint:
    scene, ix, iy, overrides, models = args
    pt = MapPoint(ix, iy, overrides)
    try:
        res = run(scene, overrides, models=models)
    except InputError as err:
        pt.status, pt.message = "refused", str(err)
        return pt
    for name, m in res.models.items():
        pt.time_s[name] = m.time_s
        if m.status != "ok":
            pt.failed_models[name] = m.error or m.status
    if pt.failed_models:
        pt.status = "failed"
        pt.message = "; ".join(f"{k}: {v}" for k, v in pt.failed_models.items())
    for c in res.comparisons:
        # the map shows where a model is within its tolerance (or band), whatever its role in the scene
        within = None if c.tolerance is None else bool(c.rel_error <= c.tolerance)
        pt.errors[(c.model, c.reference, c.quantity)] = (c.rel_error, c.tolerance, within)
    return pt


@dataclass
class ValidityMap:
    scene: str
    kind: str
    x: Axis
    y: Axis
    points: list[MapPoint]
    models: list[str]

    def comparisons(self) -> list[tuple[str, str, str]]:
        """Every (model, reference, quantity) met at some grid point, in a stable order."""
        seen = dict.fromkeys(k for p in self.points for k in p.errors)
        return sorted(seen)

    def grid(self, comparison: tuple[str, str, str]) -> tuple[np.ndarray, np.ndarray, float | None]:
        """(rel_error[ny, nx] with NaN where not available, passed[ny, nx] as float 1/0/NaN, tolerance)."""
        ny, nx = len(self.y.values), len(self.x.values)
        err, ok = np.full((ny, nx), np.nan), np.full((ny, nx), np.nan)
        tol = None
        for p in self.points:
            if comparison in p.errors:
                e, t, passed = p.errors[comparison]
                err[p.iy, p.ix] = e
                tol = t if t is not None else tol
                if passed is not None:
                    ok[p.iy, p.ix] = float(passed)
        return err, ok, tol

    def pair_validity(self, model: str, reference: str) -> np.ndarray:
        """True where every toleranced quantity of ``model`` against ``reference`` passes (NaN: no data)."""
        comps = [c for c in self.comparisons() if c[:2] == (model, reference)]
        ny, nx = len(self.y.values), len(self.x.values)
        valid = np.full((ny, nx), np.nan)
        for c in comps:
            ok = self.grid(c)[1]
            have = ~np.isnan(ok)
            valid[have] = np.where(np.isnan(valid[have]), ok[have], np.minimum(valid[have], ok[have]))
        for p in self.points:
            if p.status != "ok" and model in p.failed_models:
                valid[p.iy, p.ix] = 0.0
        return valid

    def statements(self) -> list[str]:
        """Plain sentences: where each model may be used, row by row of the y axis."""
        out = []
        pairs = dict.fromkeys(c[:2] for c in self.comparisons())
        for model, ref in pairs:
            v = self.pair_validity(model, ref)
            n_ok, n = int(np.nansum(v)), int(np.sum(~np.isnan(v)))
            comps = [c for c in self.comparisons() if c[:2] == (model, ref)]
            judged = [c for c in comps if self.grid(c)[2] is not None]
            worst = "; ".join(f"{c[2]} max {100 * np.nanmax(self.grid(c)[0]):.3g} %" for c in comps
                              if not c[2].startswith("pressure_profile") and c[2] != "total_force"
                              and np.any(~np.isnan(self.grid(c)[0])))
            if not judged:
                out.append(f"{model} vs {ref}: no tolerance set, so no verdict ({worst}).")
                continue
            quants = ", ".join(f"{c[2]} {self.grid(c)[2]:.3g}" for c in judged)
            head = (f"{model} vs {ref} (tolerances: {quants}): within tolerance at {n_ok} of {n} grid points "
                    f"({worst})")
            rows = []
            for iy, yv in enumerate(self.y.values):
                spans = _spans(v[iy], self.x.values)
                rows.append(f"{self.y.key} = {yv:.3g}: " + (", ".join(spans) if spans else "nowhere"))
            out.append(head + ". Valid for " + self.x.key + " in — " + "; ".join(rows) + ".")
        refused = [p for p in self.points if p.status == "refused"]
        if refused:
            out.append(f"{len(refused)} grid point(s) refused by the scene (outside an admissible range), "
                       f"e.g. {refused[0].overrides}: {refused[0].message}")
        failed = [p for p in self.points if p.status == "failed"]
        if failed:
            out.append(f"{len(failed)} grid point(s) with a model that failed, e.g. {failed[0].overrides}: "
                       f"{failed[0].message}")
        return out

    def to_json(self) -> dict[str, Any]:
        comps = self.comparisons()
        data: dict[str, Any] = {
            "scene": self.scene, "kind": self.kind,
            "x": {"key": self.x.key, "values": list(self.x.values), "log": self.x.log},
            "y": {"key": self.y.key, "values": list(self.y.values), "log": self.y.log},
            "comparisons": [], "statements": self.statements(),
            "points": [{"ix": p.ix, "iy": p.iy, "overrides": p.overrides, "status": p.status,
                        "message": p.message, "failed_models": p.failed_models, "time_s": p.time_s}
                       for p in self.points],
        }
        for c in comps:
            err, ok, tol = self.grid(c)
            data["comparisons"].append({
                "model": c[0], "reference": c[1], "quantity": c[2], "tolerance": tol,
                "rel_error": [[None if np.isnan(e) else float(e) for e in row] for row in err],
                "pass": [[None if np.isnan(o) else bool(o) for o in row] for row in ok]})
        return data


def _spans(valid_row: np.ndarray, xs: tuple[float, ...]) -> list[str]:
    """Contiguous runs of grid points that pass, as 'lo–hi' strings."""
    spans, start = [], None
    for i, v in enumerate(list(valid_row) + [0.0]):
        good = v == 1.0
        if good and start is None:
            start = i
        if not good and start is not None:
            lo, hi = xs[start], xs[i - 1]
            spans.append(f"{lo:.3g}" if start == i - 1 else f"{lo:.3g}–{hi:.3g}")
            start = None
    return spans


def validity_map(scene: Scene, x: Axis, y: Axis, models: list[str] | None = None, workers: int | None = None,
                 scheduler: str | None = None, on_done: Callable[[int, MapPoint], None] | None = None
                 ) -> ValidityMap:
    """Run ``scene`` at every (x, y) grid point (through the executor) and collect the comparisons."""
    if x.key == y.key:
        raise InputError("--y", f"the two axes must be different keys (both are {x.key})")
    cases = [(scene, ix, iy, {x.key: xv, y.key: yv}, models)
             for iy, yv in enumerate(y.values) for ix, xv in enumerate(x.values)]
    points = map_cases(_map_point, cases, workers, on_done, scheduler)
    names = list(models) if models else list(scene["models.run"])
    return ValidityMap(scene.name, scene.kind, x, y, points, names)
