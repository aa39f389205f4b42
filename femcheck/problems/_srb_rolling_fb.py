"""The finite-body reference of the srb-rolling kind (shared helper, not a kind): the roller's own equilibrium with
finite-body influence coefficients on fine contact grids, certified in two parts.

The roller equilibrium of :mod:`femcheck.cect.roller_equilibrium` (pose, speeds, approach: seven unknowns) is
solved with the half-space coefficients plus the FE finite-body correction D (:mod:`femcheck.fem.compliance_split`:
the whole roller and two ring segments minus the half-space; :mod:`femcheck.fem.srb_finite_body`: the correction as
extra gap and slip in every contact solve, a fixed point on the tractions). Three discretisations, refined apart:

1. **The correction** (FE mesh and correction grid refined together): correction grids spanning the roller
   (ns_k + 1 = (ns_0 + 1) 1.5^k cells along s, ds = L_R / (ns_k + 1); dx_k = dx_0 / 1.5^k exactly with
   dx_0 = 2.7 a_H / nx_0, nx_k the next odd count above nx_0 1.5^k plus one cell beyond each end, which the
   lattice phases' dilated contact windows need), the FE mesh at ``numerics.fb_h_contact`` dx_k with
   ``LAYERS_PER_CELL`` element layers per cell, near-field fill of one cell (``NEAR_FIELD``); the equilibrium on
   the scene's contact grid (``numerics.conformal_cells_*``) for each. The fill is sized by the FE's near-field
   error, not by the grid: with one layer per cell at 0.7 dx the FE's error of the singular response spreads two
   cells, and a two-cell fill on the coarsest grid (3 mm of a 9 mm contact) moved sum f_lat by 20 %; at 0.35 dx
   with two layers and a one-cell fill the family converges in one step (docs/notes/srb-split-compliance.md).
   Certified by :func:`femcheck.solvers.finite_body_certificate.correction_certificate` at the correction's formal
   order 2 with the re-meshing floor: per quantity the larger of the assumed 0.2 % and the spread measured over
   the coarsest level solved on ``numerics.fb_scatter_meshes`` more meshes (the contact-line element size scaled
   by 1 %, 2 %, ...; :func:`femcheck.solvers.split_certificate.remesh_floor`).
2. **The far field** on the coarsest correction grid and its near field: the mesh grading and the largest element
   divided by 1.5 per level (``numerics.fb_farfield_levels``, the first level the coarsest correction's own), the
   part of the FE mesh that family 1 does not refine. Certified with the same floor, no expected order; its step
   is taken from its first level, on which every other level is solved. Its effect depends on the near field it
   is measured with: on a near field at 0.7 dx with one layer per cell the far levels moved sum f_lat by +0.07 %
   where on this one they move it by +0.46 % and then -0.02 % (docs/notes/srb-split-compliance.md).
3. **The contact grid** at the finest correction: levels from ``numerics.fb_cells_x`` x ``fb_cells_s`` refining
   by sqrt 2 with exactly geometric cell sizes, each level the mean over ``numerics.fb_phases`` lattice phases of
   the contact's leading edge (:mod:`femcheck.cect.lattice_phase`: a single window's lateral forces snap to its
   lattice by +-1.2 %). Certified by :func:`femcheck.solvers.split_certificate.grid_certificate` at Kalker's first
   order (changes between levels below the levels' own phase spread count as converged).

Combined value and estimate per quantity: :func:`femcheck.solvers.split_certificate.combine` (the contact grid's
value plus the other parts' extrapolation steps; the sum of the parts' estimates). Certified when every part is.

Cost: the FE tables of the correction levels depend on the geometry, materials, load (the Hertz semi-axes scale
the grids) and mesh settings only; levels above the coarsest are kept in the result cache
(:mod:`femcheck.cache`), so a second friction coefficient reuses them. They are independent FE solves: with a dask
cluster (``femcheck run --scheduler``, :func:`femcheck.executor.current_scheduler`) the missing ones are solved
there side by side first (:func:`prefetch`), each on one worker, and stored in this machine's cache. The
coarsest level is always computed here: it is what :mod:`femcheck.reference_check` re-solves, with its meshes
recorded (:mod:`femcheck.replay`).
"""
from __future__ import annotations

import hashlib
import json
import math
import time
from dataclasses import dataclass, replace
from typing import Any, Callable

from .. import cache, executor, provenance
from ..cect import lattice_phase
from ..cect.refinement import KALKER_ORDER
from ..cect.roller_equilibrium import EquilibriumResult
from ..fem import compliance_split as cs
from ..fem import compliance_store
from ..fem import srb_rolling as fe
from ..fem.rolling_compliance import MeshSettings
from ..fem.srb_finite_body import finite_body_equilibrium
from ..result import ModelResult
from ..solvers.finite_body_certificate import certify_parts
from ..solvers.split_certificate import scatter_scales
from . import _srb_rolling_out as out

CORRECTION_RATIO = 1.5          # correction grids: ns + 1 = 16, 24, 36 cells along the roller (integers)
GRID_RATIO = math.sqrt(2.0)     # contact grids: 41 x 81, 58 x 115, 82 x 162, 116 x 229
CORRECTION_HALF_X = 1.35        # correction window along x / a_H on the coarsest level (as the CECT's)
CORRECTION_SPAN_S = 3.0         # along s: clipped to the roller length (fe.grids), so it spans the roller
NEAR_FIELD = 1                  # cells of harmonic fill around the loaded cell (compliance_split.correction)
LAYERS_PER_CELL = 2             # FE element layers per correction cell along s
QUANTITIES = ("f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "f_lat_sum", "d_y", "tilt", "skew",
              "friction_power_inner", "friction_power_outer", "adhesion_fraction_inner", "adhesion_fraction_outer",
              "omega_m_deviation", "omega_R_deviation")


def correction_grid(p: dict[str, Any], k: int) -> tuple[int, int, float, dict]:
    """Correction level k: (nx, ns, half_x in a_H, grids) of module docstring item 1."""
    nx0, ns0 = int(p["numerics.fb_correction_cells_x"]), int(p["numerics.fb_correction_cells_s"])
    f = CORRECTION_RATIO ** k
    ns = int(round((ns0 + 1) * f)) - 1
    nx = int(math.ceil(nx0 * f - 1e-9))
    nx += 1 - nx % 2
    nx += 2          # a cell beyond each end: the contact windows of the lattice phases reach 1.42 a_H (+ dx)
    half_x = CORRECTION_HALF_X * nx / (nx0 * f)
    grids = fe.grids(p, nx, ns, float(p["load.normal"]), half_x=half_x, half_s=CORRECTION_SPAN_S)
    return nx, ns, half_x, grids


def mesh_of(p: dict[str, Any], far: int | None = None, scale: float = 1.0) -> MeshSettings:
    """FE mesh of a correction level (``far`` None) or of far-field level ``far`` (0, 1, ...; level 0 is the
    correction's): ``fb_h_contact`` dx at the contact line (times ``scale``: the same level re-meshed),
    ``LAYERS_PER_CELL`` layers per cell, the grading and the largest element (2 mm) divided by 1.5^far."""
    f = CORRECTION_RATIO ** (far or 0)
    return MeshSettings(p["numerics.fb_h_contact"] * scale, p["numerics.fem_grading"] / (math.sqrt(2.0) * f),
                        2e-3 / f, LAYERS_PER_CELL, 2)


def _tables_key(p: dict[str, Any], k: int, mesh: MeshSettings) -> str:
    body = {q: v for q, v in sorted(p.items()) if q.startswith(("geometry.", "materials.", "load."))}
    blob = json.dumps({"level": list(correction_grid(p, k)[:3]), "mesh": str(mesh), "params": body,
                       "code": provenance.code_digest(("femcheck.fem.srb_rolling", "femcheck.fem.compliance_store"))},
                      sort_keys=True, default=str)
    return "srb-fb-tables-" + hashlib.sha256(blob.encode()).hexdigest()[:32]


def _tables_path(p: dict[str, Any], k: int, far: int | None, mesh: MeshSettings | None = None):
    return cache.cache_dir() / f"{_tables_key(p, k, mesh_of(p, far) if mesh is None else mesh)}.npz"


def _tables_case(case: tuple[dict[str, Any], int, int | None]):
    """The FE tables of correction level k (``far`` None) or far-field level ``far`` (a picklable case for
    :func:`femcheck.executor.map_cases`)."""
    p, k, far = case
    return fe.compliance(p, correction_grid(p, k)[3], mesh_of(p, far))


def prefetch(p: dict[str, Any], levels: list[tuple[int, int | None]], scheduler: str, progress=None) -> list:
    """Solve the FE tables of the ``levels`` [(k, far), ...] (far None: correction level k; else far-field level
    far) that the result cache lacks on the dask cluster at ``scheduler``, all at once, and store them in the
    cache, where :func:`correction_level` finds them. The coarsest correction (0, None) is left out: it is always
    solved here (a stored reference records its meshes). Returns the levels solved."""
    todo = [(k, far) for k, far in levels if (k, far) != (0, None) and not _tables_path(p, k, far).is_file()]
    if not todo:
        return []

    finished = []

    def done(i: int, tables) -> None:
        compliance_store.save(_tables_path(p, *todo[i]), tables)
        finished.append(i)
        if progress:
            k, far = todo[i]
            progress(f"fem_finite_body: FE {_level_name(k, far)} solved on the cluster "
                     f"({len(finished)} of {len(todo)} levels done)")

    if progress:
        progress(f"fem_finite_body: {len(todo)} FE correction levels sent to the dask cluster at {scheduler}")
    executor.map_cases(_tables_case, [(dict(p), k, far) for k, far in todo], on_done=done, scheduler=scheduler)
    return todo


def far_field_plan(n_corr: int, n_far: int) -> list[tuple[int, int | None]]:
    """The FE levels [(k, far), ...] of ``n_corr`` correction and ``n_far`` far-field levels (the far field's
    first is the coarsest correction, not solved twice)."""
    return [(k, None) for k in range(n_corr)] + [(0, far) for far in range(1, n_far)]


def _level_name(k: int, far: int | None) -> str:
    return f"correction level {k + 1}" if far is None else f"far-field level {far + 1}"


def correction_level(p: dict[str, Any], constants, k: int, far: int | None = None, progress=None,
                     scale: float = 1.0) -> cs.Correction:
    """The correction of level k (``far`` None) or of far-field level ``far`` on the coarsest correction grid
    (``scale``: the contact-line element size scaled, the same level re-meshed) (FE tables computed, or read from
    the result cache except the coarsest correction (0, None, 1), whose meshes a stored reference records)."""
    nx, ns, _, grids = correction_grid(p, k)
    mesh = mesh_of(p, far, scale)
    reuse = k > 0 or far is not None or scale != 1.0
    path = _tables_path(p, k, far, mesh)
    tables = compliance_store.load(path, grids) if reuse and path.is_file() else None
    if tables is None:
        if progress:
            progress(f"fem_finite_body: FE {_level_name(k, far)} ({nx} x {ns} cells over the roller)")
        tables = fe.compliance(p, grids, mesh)
        if reuse:
            compliance_store.save(path, tables)
    return cs.correction(tables, constants, NEAR_FIELD)


@dataclass
class Families:
    """The FE families of a finite-body reference on the scene's contact grid, as level dicts (``h`` and the
    quantities): ``correction`` (levels 0, 1, ...), ``far_field`` (its first level the coarsest correction's, not
    solved twice), ``scatter`` (the coarsest correction re-meshed, ``h_contact_factor``); ``finest`` the finest
    correction and ``state`` the solution with it, from which the contact-grid levels start."""

    correction: list[dict]
    far_field: list[dict]
    scatter: list[dict]
    finest: cs.Correction
    state: Any


def correction_families(p: dict[str, Any], constants, counts: tuple[int, int, int],
                        solve: Callable[[cs.Correction, Any], tuple[Any, dict]], start: Any, progress=None,
                        shown: str = "f_lat_sum") -> Families:
    """Solve the reference's contact problem on the scene's grid with every FE level of the correction family, the
    far-field family and the re-meshed coarsest correction (module docstring items 1 and 2). ``counts``: correction
    levels, far-field levels (0: none, as in a coarse re-solve), re-meshed copies; ``solve(corr, warm) -> (state,
    quantities)``: the reference's solve with correction ``corr`` from the solution ``warm``; ``start``: the
    half-space solution; ``shown``: the quantity the progress lines show. With a dask scheduler in effect the
    missing FE levels are solved there first (:func:`prefetch`)."""
    n_corr, n_far, n_scatter = counts
    if (scheduler := executor.current_scheduler()) is not None:
        prefetch(p, far_field_plan(n_corr, n_far), scheduler, progress)

    def level(k: int, far: int | None, warm: Any) -> tuple[cs.Correction, Any, dict]:
        corr = correction_level(p, constants, k, far, progress)
        state, q = solve(corr, warm)
        nx, ns, half_x, _ = correction_grid(p, k)
        lv = {"level": k, "far_field": far, "nx": nx, "ns": ns, "h": 1.0 / CORRECTION_RATIO ** (k + (far or 0)),
              "half_x": half_x, "n_dofs": corr.stats["fe"].get("n_dofs"),
              "fe_time_s": corr.stats["fe"].get("total_s"), **q}
        if progress:
            progress(f"fem_finite_body: {_level_name(k, far)}: {shown} {lv[shown]:.5e}")
        return corr, state, lv

    # the coarsest correction first, from the half-space start: level 0 of the stored reference, which
    # reference_check re-solves alone
    correction, state, finest = [], start, None
    for k in range(n_corr):
        finest, state, lv = level(k, None, state)
        correction.append(lv)
    far_field = [{**correction[0], "far_field": 0}] if n_far else []
    warm = start
    for far in range(1, n_far):
        _, warm, lv = level(0, far, warm)
        far_field.append(lv)
    # the re-meshing scatter of each quantity, measured: the coarsest correction re-meshed n_scatter times (the
    # contact-line element size scaled by 1 %, 2 %, ...: Gmsh moves every element)
    scatter = []
    for scale in scatter_scales(n_scatter):
        _, q = solve(correction_level(p, constants, 0, None, progress, scale), start)
        scatter.append({"h_contact_factor": scale, **q})
    return Families(correction, far_field, scatter, finest, state)


def _values(problem, r: EquilibriumResult) -> dict[str, float]:
    q = out.quantities(problem, r)
    return {k: float(q[k]) for k in QUANTITIES if q.get(k) is not None}


def finite_body(p: dict[str, Any], problem, numerics, constants, start: EquilibriumResult,
                progress=None) -> ModelResult:
    """The three-part certified finite-body equilibrium (module docstring) from the half-space equilibrium
    ``start`` on the scene's grid ``numerics``."""
    t0 = time.perf_counter()
    n_grid, phases = int(p["numerics.fb_grid_levels"]), int(p["numerics.fb_phases"])
    counts = (int(p["numerics.fb_correction_levels"]), int(p["numerics.fb_farfield_levels"]),
              int(p["numerics.fb_scatter_meshes"]))

    def on_scene_grid(corr: cs.Correction, warm: EquilibriumResult) -> tuple[EquilibriumResult, dict]:
        fb = finite_body_equilibrium(problem, numerics, corr, warm)
        return fb.result, {"outer_iterations": fb.iterations, **_values(problem, fb.result)}

    fam = correction_families(p, constants, counts, on_scene_grid, start, progress)
    corr, prev = fam.finest, fam.state
    grid_levels = []
    cells0 = (int(p["numerics.fb_cells_x"]), int(p["numerics.fb_cells_s"]))
    domain0 = (float(p["numerics.conformal_domain_x"]), float(p["numerics.conformal_domain_s"]))
    for lv in lattice_phase.levels(cells0, domain0, GRID_RATIO, n_grid):
        samples = []
        # phases along x only: the lateral window's phase moves sum f_lat by 0.15 % (x: 1.2 %), and dilating it
        # would push the offset windows of mu = 0.3 past the roller's ends
        for j, (dx_, ds_) in enumerate(lattice_phase.phase_windows(lv.cells, lv.domain, phases, along_s=False)):
            if progress:
                progress(f"fem_finite_body: contact grid {lv.cells[0]} x {lv.cells[1]}, phase {j + 1}/{phases}")
            num = replace(numerics, nx=lv.cells[0], ns=lv.cells[1], domain_x=dx_, domain_s=ds_)
            fb = finite_body_equilibrium(problem, num, corr, prev)
            prev = fb.result
            samples.append(_values(problem, fb.result))
        grid_levels.append(lattice_phase.level_record(lv, phases, samples))
    names = [q for q in QUANTITIES if q in fam.correction[0]]
    parts = certify_parts(names, fam.correction, fam.far_field, fam.scatter, grid_levels, KALKER_ORDER)
    combined = parts.pop("combined")
    stats = {"solver": "CECT roller equilibrium (half-space DC-FFT contacts) + FE finite-body correction "
                       "(P2, PARDISO/LU), fixed point on the tractions",
             "levels": fam.correction, "grid_levels": grid_levels, "level_quantities": names,
             "far_field_levels": fam.far_field, "scatter_levels": fam.scatter, **parts,
             "halfspace_start": _values(problem, start), "time_s": time.perf_counter() - t0}
    return ModelResult("fem_finite_body", quantities={q: c.value for q, c in combined.items()}, stats=stats)
