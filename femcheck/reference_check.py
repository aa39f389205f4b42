"""Stale references cannot pass: re-solve the coarsest level of a stored reference and compare it with the stored
coarse-level numbers (issue 12, finding 1).

A stored reference (:mod:`femcheck.references`) is looked up under the content key of the current code and inputs;
that alone proves only that a file exists. Here the model is run again on its coarsest mesh level alone (seconds,
not minutes: the kind's ``DEPENDS[model]["coarse"]`` overrides, e.g. ``numerics.fem_levels = 1``) and every
level-0 quantity of the stored file must be reproduced to ``rtol`` (meshes are deterministic: single-threaded Gmsh,
content-keyed mesh cache). A change that the key misses (a library's behaviour, a nondeterministic mesher, a stale
mesh cache) or a hand-edited reference then fails. Level 0 never depends on the number of levels (every model
sizes level k from level 0 alone).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from . import references
from .problems import problem
from .result import ModelResult
from .runner import model_key, run_model
from .scene import load_scene

# Per-level numbers that must be reproduced (physics and mesh size; timings and iteration histories are not).
COMPARED = ("p_max", "p_centre", "p_end", "half_width", "semi_axis_x", "semi_axis_y", "contact_area", "edge_peak_y",
            "approach", "total_force", "p_max_nodal", "n_nodes", "n_dofs", "n_elements", "h",
            # steady rolling (groove-rolling and srb-rolling fem)
            "body_approach", "contact_half_length_s", "creepage_x", "adhesion_fraction", "friction_power",
            "f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "omega_m", "omega_R")


@dataclass
class CoarseCheck:
    """``stored``: the reference read for the current key (None when there is none: ``command`` regenerates it);
    ``compared``: (table, quantity, stored, re-solved) for every number compared; ``mismatches``: those beyond
    ``rtol``."""

    scene: str
    model: str
    key: str
    command: str
    stored: ModelResult | None = None
    fresh: ModelResult | None = None
    compared: list[tuple[str, str, float, float]] = field(default_factory=list)
    mismatches: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.stored is not None and self.fresh is not None and self.fresh.status == "ok" \
            and bool(self.compared) and not self.mismatches


def level_tables(stats: dict[str, Any]) -> dict[str, list[dict]]:
    """The per-level tables of a reference's stats: one table per contact (``levels`` entries carrying
    ``contact``), per coating (nested stats with their own ``levels``), or the single ``levels`` list."""
    out: dict[str, list[dict]] = {}
    for lv in stats.get("levels", []):
        if isinstance(lv, dict):
            out.setdefault(str(lv.get("contact", "")), []).append(lv)
    for name, sub in stats.items():
        if isinstance(sub, dict) and isinstance(sub.get("levels"), list) and name not in out:
            if not any(isinstance(lv, dict) and "contact" in lv for lv in stats.get("levels", [])):
                out[name] = [lv for lv in sub["levels"] if isinstance(lv, dict)]
    return out


def compare_coarse(stored: ModelResult, fresh: ModelResult, rtol: float,
                   whole: bool = False) -> tuple[list, list[str]]:
    """(compared, mismatches) between the first level of every table of ``stored`` and of ``fresh``; with
    ``whole`` (the re-solve was the whole model, e.g. a single-level reference) every quantity too (an infinite
    one, e.g. a life, must stay infinite)."""
    compared, bad = [], []

    def same(table: str, where: str, q: str, x: float, y: float | None) -> None:
        if y is None:
            bad.append(f"{where}.{q}: missing from the re-solve")
        elif not (np.isfinite(x) and np.isfinite(y)):
            if x != y:
                bad.append(f"{where}.{q}: stored {x}, re-solved {y}")
        else:
            compared.append((table, q, float(x), float(y)))
            if abs(y - x) > rtol * max(abs(x), 1e-300):
                bad.append(f"{where}.{q}: stored {x:.10g}, re-solved {y:.10g} "
                           f"(relative {abs(y / x - 1) if x else float('inf'):.2e} > {rtol:g})")

    if whole:
        for q, x in stored.quantities.items():
            same("quantities", "quantities", q, x, fresh.quantities.get(q))
    old, new = level_tables(stored.stats), level_tables(fresh.stats)
    if set(old) != set(new):
        return compared, bad + [f"level tables differ: stored {sorted(old)}, re-solved {sorted(new)}"]
    for table in sorted(old):
        a, b = old[table][0], new[table][0]
        for q in COMPARED:
            if q in a:
                same(table, f"{table or 'levels'}[0]", q, float(a[q]), None if q not in b else float(b[q]))
    if not compared:
        bad.append("no level-0 quantity to compare")
    return compared, bad


def check(scene_name: str, model: str, rtol: float = 1e-6, stored: ModelResult | None = None,
          coarse: dict | None = None, params: dict | None = None) -> CoarseCheck:
    """Re-solve the coarsest level of ``model`` of the built-in scene ``scene_name`` and compare it with the
    stored reference for the current key (or with ``stored``, e.g. an older file, to see what a change moved).
    ``coarse``: the overrides that make the run its coarsest level (default: the kind's DEPENDS[model]['coarse'];
    without either the whole model is re-solved). ``params``: overrides of the scene that a second stored
    reference of it was solved with (e.g. friction.mu = 0.3 of srb-rolling)."""
    sc = load_scene(scene_name, params or {})
    dep = problem(sc.kind).DEPENDS[model]
    k = model_key(sc, model)
    sets = "".join(f" --set {key}={v}" for key, v in (params or {}).items())
    # a run under --set goes to the cache only, unless told where to store it
    where = f" --references {references.reference_dir()}" if params else ""
    out = CoarseCheck(scene_name, model, k, f"femcheck run {scene_name}{sets} --models {model} --rebuild{where}")
    out.stored = stored if stored is not None else references.load(sc.kind, model, k)
    if out.stored is None:
        return out
    overrides = dep.get("coarse", {}) if coarse is None else coarse
    coarse_scene = sc.with_overrides(overrides) if overrides else sc
    out.fresh = run_model(coarse_scene, model, use_cache=False)
    if out.fresh.status != "ok":
        out.mismatches.append(f"the coarse re-solve {out.fresh.status}: {out.fresh.error}")
        return out
    out.compared, out.mismatches = compare_coarse(out.stored, out.fresh, rtol, whole=not overrides)
    return out


def stored_any(scene_name: str, model: str) -> ModelResult | None:
    """The most recent stored reference of ``scene_name``'s ``model`` whatever its key (for showing what a code
    change moved: :func:`check` with ``stored=``)."""
    import json

    sc = load_scene(scene_name)
    base = references.reference_dir() / sc.kind
    best = None
    for path in sorted(base.glob(f"{model}-*.json")):
        meta = json.loads(path.read_text())
        prov = meta["provenance"]
        if prov.get("scene") != scene_name or prov.get("model") != model:
            continue
        if best is None or prov.get("created", "") > best[0]:
            best = (prov.get("created", ""), prov["key"])
    return None if best is None else references.load(sc.kind, model, best[1])
