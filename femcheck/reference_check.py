"""Stale references cannot pass: re-solve the coarsest level of a stored reference and compare it with the stored
coarse-level numbers.

A stored reference (:mod:`femcheck.references`) is looked up under the content key of the current code and inputs;
that alone proves only that a file exists. Here the model is run again on its coarsest level alone (seconds, not
minutes: the kind's ``DEPENDS[model]["coarse"]`` overrides, e.g. ``numerics.fem_levels = 1``; level 0 never
depends on the number of levels) in two ways:

* :func:`check` (exact): on the inputs recorded with the reference (:mod:`femcheck.replay`: its coarse meshes and
  derived inputs such as a pilot width or the CECT pose), so the only legitimate difference is floating-point
  round-off in assembly and solves, which the solvers' own tolerances bound (iterative solves converged to 1e-9
  to 1e-10; measured: at most 2e-8 relative between AVX-512, AVX2 and baseline numpy/BLAS/glibc code paths).
  Every level-0 number must agree to ``RTOL_EXACT`` = 1e-6: 50 times that round-off, and 1e4 below the smallest
  physics change the check guards (a body stiffness scaled by 1.02 moves p_max by about 1 %).
* :func:`check` with ``replay=False`` (fresh): meshes and derived inputs made anew on this machine, as a user who
  regenerates the reference gets them. Gmsh evaluates sizes and curved boundaries through the CPU-dispatched C
  library, so its mesh for the same spec may differ between CPUs; the fresh level-0 mesh is then another member
  of the same level-0 mesh family, and its result differs from the stored one by at most the two meshes'
  discretisation errors. The tolerance per quantity is therefore ``2 e_0`` (:func:`fresh_tolerance`), e_0 the
  stored reference's own level-0 error estimate (|level 0 - certified value| + the certificate's estimate, or
  the level-0-to-1 change where no certificate applies), never less than RTOL_EXACT. Mesh counts and the element
  size are not compared there (they are reported).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from . import references, replay
from .problems import problem
from .result import ModelResult
from .runner import model_key, run_model
from .scene import load_scene

RTOL_EXACT = 1e-6
# Per-level numbers that must be reproduced (physics and mesh size; timings and iteration histories are not).
COMPARED = ("p_max", "p_centre", "p_end", "half_width", "semi_axis_x", "semi_axis_y", "contact_area", "edge_peak_y",
            "approach", "total_force", "normal_force", "p_max_nodal", "n_nodes", "n_dofs", "n_elements", "h",
            # steady rolling (groove-rolling and srb-rolling fem)
            "body_approach", "contact_half_length_s", "creepage_x", "adhesion_fraction", "friction_power",
            "f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "omega_m", "omega_R",
            "friction_power_inner", "friction_power_outer", "adhesion_fraction_inner", "adhesion_fraction_outer",
            # 2D frictional contact (carter-2d, cattaneo-2d fem)
            "creep_force_x", "adhesion_length", "stick_half_width", "shift",
            # bearing sections (bearing_load fem)
            "q_max", "radial_deflection", "load_zone_angle")
# Numbers of the mesh itself (counts; the element size, which a model may scale by a width it computed first):
# compared exactly on the recorded inputs, only reported on fresh ones.
MESH_DESCRIPTORS = ("n_nodes", "n_dofs", "n_elements", "h")
# Numbers fixed by the inputs alone (the load carried): held to RTOL_EXACT in both modes.
EXACT_ALWAYS = ("total_force", "normal_force")
# Tangential forces are fractions of the normal force of the same row; one that vanishes by the problem's own
# condition (the longitudinal force of free rolling, solved to round-off: 3e-15 N of 5500 N on groove-rolling) is
# compared with an absolute floor of the tolerance times that normal force, never relative to its own round-off.
TANGENTIAL_FORCES = ("creep_force_x", "creep_force_s", "f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer")
NORMAL_FORCES = ("normal_force", "total_force")


@dataclass
class CoarseCheck:
    """``stored``: the reference read for the current key (None when there is none: ``command`` regenerates it);
    ``replayed``: the re-solve ran on the recorded inputs (exact) or not (fresh); ``compared``: (table, quantity,
    stored, re-solved, tolerance) for every number compared; ``mismatches``: those beyond their tolerance, and
    anything else that makes the check fail; ``notes``: what differs without failing (fresh mesh counts)."""

    scene: str
    model: str
    key: str
    command: str
    replayed: bool = True
    stored: ModelResult | None = None
    fresh: ModelResult | None = None
    compared: list[tuple[str, str, float, float, float]] = field(default_factory=list)
    mismatches: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

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


def certificate(stats: dict[str, Any], table: str, q: str) -> dict | None:
    """The stored certificate of quantity ``q`` of level table ``table`` (:func:`level_tables`): in the table's
    own stats (a coating, a contact), as ``q_table`` among the top-level certificates, or as ``q``."""
    sub = stats.get(table) if table else None
    for certs, name in (((sub or {}).get("certificates") if isinstance(sub, dict) else None, q),
                        (stats.get("certificates"), f"{q}_{table}" if table else q)):
        if isinstance(certs, dict) and isinstance(certs.get(name), dict):
            return certs[name]
    return None


def fresh_tolerance(stats: dict[str, Any], table: str, q: str) -> float:
    """Relative tolerance of level-0 quantity ``q`` re-solved on a fresh mesh (module docstring): 2 e_0, e_0 the
    stored reference's own level-0 error estimate, the larger of |Q_0 - V| / |V| + e (certificate value V and
    relative estimate e, where the certificate gives one) and |Q_0 - Q_1| / |Q_0| (the change to level 1, which
    bounds the level-0 error of a converging sequence up to a factor 1 / (1 - r^p)); never below RTOL_EXACT.
    Quantities fixed by the inputs (``EXACT_ALWAYS``) and those with no estimate at all keep RTOL_EXACT."""
    if q in EXACT_ALWAYS:
        return RTOL_EXACT
    levels = level_tables(stats).get(table, [])
    if not levels or q not in levels[0]:
        return RTOL_EXACT
    q0 = float(levels[0][q])
    e0 = 0.0
    cert = certificate(stats, table, q)
    if cert is not None and cert.get("value") not in (None, 0):
        v = float(cert["value"])
        est = cert.get("error_estimate")
        if math.isfinite(v) and q0 != 0 and not isinstance(levels[0][q], list):
            e0 = abs(q0 - v) / abs(v) + (float(est) if est is not None and math.isfinite(float(est)) else 0.0)
    if len(levels) > 1 and q in levels[1] and q0 != 0:
        e0 = max(e0, abs(q0 - float(levels[1][q])) / abs(q0))
    return max(RTOL_EXACT, 2.0 * e0) if math.isfinite(e0) else RTOL_EXACT


def compare_coarse(stored: ModelResult, fresh: ModelResult, rtol: float, whole: bool = False,
                   replayed: bool = True) -> tuple[list, list[str], list[str]]:
    """(compared, mismatches, notes) between the first level of every table of ``stored`` and of ``fresh``;
    with ``whole`` (the re-solve was the whole model, e.g. a single-level reference) every quantity too (an
    infinite one, e.g. a life, must stay infinite). ``replayed``: the re-solve ran on the recorded inputs, so
    every number is held to ``rtol``; otherwise each to :func:`fresh_tolerance` and mesh counts are noted."""
    compared, bad, notes = [], [], []

    def same(table: str, where: str, q: str, x: float, y: float | None, tol: float, scale: float = 0.0) -> None:
        if y is None:
            bad.append(f"{where}.{q}: missing from the re-solve")
        elif not (np.isfinite(x) and np.isfinite(y)):
            if x != y:
                bad.append(f"{where}.{q}: stored {x}, re-solved {y}")
        else:
            compared.append((table, q, float(x), float(y), tol))
            if abs(y - x) > tol * max(abs(x), scale, 1e-300):
                bad.append(f"{where}.{q}: stored {x:.10g}, re-solved {y:.10g} "
                           f"(relative {abs(y / x - 1) if x else float('inf'):.2e} > {tol:.2g})")

    if whole:
        for q, x in stored.quantities.items():
            same("quantities", "quantities", q, x, fresh.quantities.get(q), rtol)
    old, new = level_tables(stored.stats), level_tables(fresh.stats)
    if set(old) != set(new):
        return compared, bad + [f"level tables differ: stored {sorted(old)}, re-solved {sorted(new)}"], notes
    for table in sorted(old):
        a, b = old[table][0], new[table][0]
        where = f"{table or 'levels'}[0]"
        for q in COMPARED:
            if q not in a:
                continue
            if not replayed and q in MESH_DESCRIPTORS:
                if q in b and b[q] != a[q]:
                    notes.append(f"{where}.{q}: {a[q]} recorded, {b[q]} on this machine's mesh")
                continue
            tol = rtol if replayed else max(rtol, fresh_tolerance(stored.stats, table, q))
            scale = next((abs(float(a[n])) for n in NORMAL_FORCES if n in a), 0.0) if q in TANGENTIAL_FORCES else 0.0
            same(table, where, q, float(a[q]), None if q not in b else float(b[q]), tol, scale)
    if not compared:
        bad.append("no level-0 quantity to compare")
    return compared, bad, notes


def check(scene_name: str, model: str, rtol: float = RTOL_EXACT, stored: ModelResult | None = None,
          coarse: dict | None = None, params: dict | None = None, replayed: bool = True) -> CoarseCheck:
    """Re-solve the coarsest level of ``model`` of the built-in scene ``scene_name`` and compare it with the
    stored reference for the current key (or with ``stored``, e.g. an older file, to see what a change moved).
    ``coarse``: the overrides that make the run its coarsest level (default: the kind's DEPENDS[model]['coarse'];
    without either the whole model is re-solved). ``params``: overrides of the scene that a second stored
    reference of it was solved with (e.g. friction.mu = 0.3 of srb-rolling). ``replayed`` (default): on the
    inputs recorded with the reference, to ``rtol``; False: on fresh meshes and inputs, to
    :func:`fresh_tolerance` (module docstring). A replayed re-solve that asks for a mesh or an input the
    reference did not record fails (regenerate the reference: its record is missing or stale)."""
    sc = load_scene(scene_name, params or {})
    dep = problem(sc.kind).DEPENDS[model]
    k = model_key(sc, model)
    sets = "".join(f" --set {key}={v}" for key, v in (params or {}).items())
    # a run under --set goes to the cache only, unless told where to store it
    where = f" --references {references.reference_dir()}" if params else ""
    out = CoarseCheck(scene_name, model, k, f"femcheck run {scene_name}{sets} --models {model} --rebuild{where}",
                      replayed)
    out.stored = stored if stored is not None else references.load(sc.kind, model, k)
    if out.stored is None:
        return out
    overrides = dep.get("coarse", {}) if coarse is None else coarse
    coarse_scene = sc.with_overrides(overrides) if overrides else sc
    if replayed:
        stored_key = out.stored.stats.get("reference", {}).get("key", k)
        rec = replay.load(references.inputs_dir(sc.kind, model, stored_key)) or replay.Record()
        with replay.replaying(rec):
            out.fresh = run_model(coarse_scene, model, use_cache=False)
        if rec.unmatched:
            out.mismatches.append(f"the re-solve asked for inputs the reference did not record ("
                                  f"{', '.join(sorted(set(rec.unmatched)))}): regenerate it with `{out.command}`")
    else:
        out.fresh = run_model(coarse_scene, model, use_cache=False)
    if out.fresh.status != "ok":
        out.mismatches.append(f"the coarse re-solve {out.fresh.status}: {out.fresh.error}")
        return out
    compared, bad, out.notes = compare_coarse(out.stored, out.fresh, rtol, whole=not overrides, replayed=replayed)
    out.compared, out.mismatches = compared, out.mismatches + bad
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
