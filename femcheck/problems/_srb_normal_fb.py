"""The finite-body reference of the srb_contact kind (shared helper, not a kind): the frictionless normal contact of
seed 000's roller with both raceways on fine conformal grids, with finite-body influence coefficients (the
developed half-space plus the FE correction of the whole roller and two ring segments,
:mod:`femcheck.fem.srb_normal_finite_body`), certified in the three parts of srb-rolling's finite-body reference
(:mod:`femcheck.problems._srb_rolling_fb`, whose correction levels it solves: the same bodies, grids and meshes):

1. **The correction** (FE mesh and correction grid refined together by 1.5, ``numerics.fb_correction_levels``;
   two element layers per cell and a one-cell near-field fill) on the scene's contact grid
   (``numerics.cect_cells_*``, as the cect model's). Certified by
   :func:`femcheck.solvers.finite_body_certificate.correction_certificate` at the correction's formal order with
   the measured re-meshing floor (the coarsest correction on ``numerics.fb_scatter_meshes`` more meshes,
   :func:`femcheck.solvers.split_certificate.remesh_floor`).
2. **The far field** (grading and largest element / 1.5 per level, ``numerics.fb_farfield_levels``, the first
   level the coarsest correction's own) on the coarsest correction grid and its near field
   (:func:`femcheck.problems._srb_rolling_fb.mesh_of`), same floor.
3. **The contact grid** at the finest correction: ``numerics.fb_grid_levels`` levels from ``numerics.fb_cells_x``
   x ``fb_cells_s`` refining by sqrt 2 (odd counts: a cell stays on the contact's centre, where p_max is read),
   each the mean over ``numerics.fb_phases`` lattice phases of the window along x and s together (the edges
   along both axes snap to their lattices; :mod:`femcheck.cect.lattice_phase`). Certified by
   :func:`femcheck.solvers.split_certificate.grid_certificate` at first order (a piecewise-constant pressure
   places the edge to O(dx)).

Combined value and estimate per quantity: :func:`femcheck.solvers.split_certificate.combine`. The FE tables of
the correction levels above the coarsest come from the result cache when srb-rolling-finite (or an earlier run)
solved them: they depend on the geometry, materials, load and mesh settings only (:func:`fb_params` passes the
same keys); with a dask scheduler the missing ones are solved on the cluster first.
"""
from __future__ import annotations

import math
import time
from typing import Any

from .. import executor
from ..cect import lattice_phase
from ..cect.influence import combined_constants
from ..cect.refinement import KALKER_ORDER
from ..fem import srb_normal_finite_body as nb
from ..fem import srb_rolling as fe
from ..materials import Elastic
from ..result import ModelResult
from ..scene import Key
from ..solvers.finite_body_certificate import certify_parts
from ..solvers.split_certificate import SCATTER_MESHES_KEY, scatter_scales
from . import _srb_rolling_fb as rfb

GRID_RATIO = math.sqrt(2.0)
QUANTITIES = tuple(f"{q}_{c}" for c in nb.CONTACTS for q in nb.QUANTITIES)

SCHEMA: dict[str, Key] = {
    "numerics.cect_cells_x": Key("int", "-", "cect: cells along x per contact", lo=9, hi=401, lo_closed=True,
                                 hi_closed=True),
    "numerics.cect_cells_s": Key("int", "-", "cect: cells along s per contact", lo=9, hi=801, lo_closed=True,
                                 hi_closed=True),
    "numerics.cect_domain_x": Key("float", "a_H", "cect and fem_finite_body: window half-length along x / the "
                                  "larger Hertz a_H", lo=1.1, hi=2.0, lo_closed=True, hi_closed=True),
    "numerics.cect_domain_s": Key("float", "b_H", "cect and fem_finite_body: window half-width along s / the "
                                  "larger Hertz b_H (clipped to the roller)", lo=1.1, hi=1.4, lo_closed=True,
                                  hi_closed=True),
    "numerics.fb_correction_cells_x": Key("int", "-", "fem_finite_body: correction cells along x, coarsest level",
                                          lo=5, hi=41, lo_closed=True, hi_closed=True),
    "numerics.fb_correction_cells_s": Key("int", "-", "fem_finite_body: correction cells along the roller, "
                                          "coarsest level", lo=7, hi=61, lo_closed=True, hi_closed=True),
    "numerics.fb_correction_levels": Key("int", "-", "fem_finite_body: correction levels (ratio 1.5)", lo=1, hi=5,
                                         lo_closed=True, hi_closed=True),
    "numerics.fb_farfield_levels": Key("int", "-", "fem_finite_body: far-field levels on the coarsest correction",
                                       lo=0, hi=4, lo_closed=True, hi_closed=True),
    "numerics.fb_h_contact": Key("float", "dx", "fem_finite_body: FE element size at the contact line / the "
                                 "correction cell", lo=0.3, hi=2.0, lo_closed=True, hi_closed=True),
    "numerics.fb_grading": Key("float", "-", "fem_finite_body: FE mesh grading away from the contacts", lo=0.05,
                               hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.fb_cells_x": Key("int", "-", "fem_finite_body: contact cells along x, coarsest contact grid", lo=9,
                               hi=201, lo_closed=True, hi_closed=True),
    "numerics.fb_cells_s": Key("int", "-", "fem_finite_body: contact cells along s, coarsest contact grid", lo=9,
                               hi=401, lo_closed=True, hi_closed=True),
    "numerics.fb_grid_levels": Key("int", "-", "fem_finite_body: contact-grid levels (ratio sqrt 2)", lo=1, hi=6,
                                   lo_closed=True, hi_closed=True),
    "numerics.fb_phases": Key("int", "-", "fem_finite_body: lattice phases averaged per contact-grid level", lo=1,
                              hi=8, lo_closed=True, hi_closed=True),
    "numerics.fb_scatter_meshes": SCATTER_MESHES_KEY,
}
DEFAULTS: dict[str, Any] = {
    "numerics.cect_cells_x": 61,
    "numerics.cect_cells_s": 121,
    "numerics.cect_domain_x": 1.35,
    "numerics.cect_domain_s": 1.25,
    # the srb-rolling finite-body reference's correction family (its defaults: the same FE tables)
    "numerics.fb_correction_cells_x": 9,
    "numerics.fb_correction_cells_s": 15,
    "numerics.fb_correction_levels": 3,
    "numerics.fb_farfield_levels": 3,
    "numerics.fb_h_contact": 0.35,
    "numerics.fb_grading": 0.4,
    "numerics.fb_cells_x": 41,
    "numerics.fb_cells_s": 81,
    "numerics.fb_grid_levels": 4,
    "numerics.fb_phases": 4,
    "numerics.fb_scatter_meshes": 3,
}
COARSE = {"numerics.fb_correction_levels": 1, "numerics.fb_farfield_levels": 0, "numerics.fb_grid_levels": 1,
          "numerics.fb_phases": 1, "numerics.fb_scatter_meshes": 0}


def constants_of(p: dict[str, Any]):
    return combined_constants(*(Elastic(float(p[f"materials.{b}.E"]), float(p[f"materials.{b}.nu"]))
                                for b in ("roller", "ring")))


def fb_params(p: dict[str, Any]) -> dict[str, Any]:
    """The parameters :mod:`femcheck.problems._srb_rolling_fb`'s correction levels read, under its names: the
    geometry, materials and load of the scene, the FE's roller length (:data:`femcheck.fem.srb_rolling.ROLLER_LENGTH`,
    not in Table 1) and the correction's mesh settings."""
    out = {k: v for k, v in p.items() if k.startswith(("geometry.", "materials.", "load."))}
    out["geometry.roller_length"] = fe.ROLLER_LENGTH
    for k in ("fb_correction_cells_x", "fb_correction_cells_s", "fb_h_contact"):
        out[f"numerics.{k}"] = p[f"numerics.{k}"]
    out["numerics.fem_grading"] = p["numerics.fb_grading"]
    return out


def cect(p: dict[str, Any], progress=None) -> ModelResult:
    """The conformal half-space normal contact of both raceways (:mod:`femcheck.fem.srb_normal_finite_body` without
    the correction) on ``numerics.cect_cells_x`` x ``cect_cells_s`` cells."""
    t0 = time.perf_counter()
    st = nb.setup(p, int(p["numerics.cect_cells_x"]), int(p["numerics.cect_cells_s"]),
                  float(p["numerics.cect_domain_x"]), float(p["numerics.cect_domain_s"]))
    r = nb.solve_pair(st, constants_of(p))
    g = st["inner"].grid
    stats = {"solver": "Polonsky-Keer (DC-FFT developed half-space) in a secant on the approach per contact",
             "gap": "exact conformal undeformed distance (seed 000 eq 16)", "nx": g.nx, "ns": g.ns, "dx": g.dx,
             "ds": g.ds, "iterations": r.iterations, "residual": r.residual}
    return ModelResult("cect", time_s=time.perf_counter() - t0, quantities=nb.quantities(st, r), stats=stats)


def finite_body(p: dict[str, Any], progress=None) -> ModelResult:
    """The three-part certified finite-body normal contact (module docstring)."""
    t0 = time.perf_counter()
    pf, constants = fb_params(p), constants_of(p)
    n_corr, n_far, n_grid, phases = (int(p[f"numerics.fb_{k}"]) for k in
                                     ("correction_levels", "farfield_levels", "grid_levels", "phases"))
    if (scheduler := executor.current_scheduler()) is not None:
        rfb.prefetch(pf, rfb.far_field_plan(n_corr, n_far), scheduler, progress)
    cells0 = (int(p["numerics.fb_cells_x"]), int(p["numerics.fb_cells_s"]))
    domain0 = (float(p["numerics.cect_domain_x"]), float(p["numerics.cect_domain_s"]))
    # the correction's and the far field's levels on the scene's grid: level 0 is what reference_check re-solves
    scene_setup = nb.setup(p, int(p["numerics.cect_cells_x"]), int(p["numerics.cect_cells_s"]), *domain0)
    start = nb.solve_pair(scene_setup, constants)

    def on_scene_grid(corr, warm) -> tuple[nb.NormalPair, dict]:
        r = nb.solve_pair(scene_setup, constants, corr, warm)
        return r, {**nb.quantities(scene_setup, r), "passes": r.passes}

    corr_levels, warm, corr = [], start, None
    for k in range(n_corr):
        corr = rfb.correction_level(pf, constants, k, None, progress)
        warm, q = on_scene_grid(corr, warm)
        nx, ns, half_x, _ = rfb.correction_grid(pf, k)
        st = corr.stats["fe"]
        corr_levels.append({"level": k, "far_field": None, "nx": nx, "ns": ns, "half_x": half_x,
                            "h": 1.0 / rfb.CORRECTION_RATIO ** k, "n_dofs": st.get("n_dofs"),
                            "fe_time_s": st.get("total_s"), **q})
        if progress:
            progress(f"fem_finite_body: correction level {k + 1}: semi_axis_y inner {q['semi_axis_y_inner']:.6e} m")
    finest_corr = corr
    # the far field's first level is the coarsest correction (the same mesh)
    far_levels = [{**corr_levels[0], "far_field": 0}] if n_far else []
    for far in range(1, n_far):
        _, q = on_scene_grid(rfb.correction_level(pf, constants, 0, far, progress), start)
        far_levels.append({"level": 0, "far_field": far, "h": 1.0 / rfb.CORRECTION_RATIO ** far, **q})
    scatter_levels = []
    for scale in scatter_scales(p["numerics.fb_scatter_meshes"]):
        _, q = on_scene_grid(rfb.correction_level(pf, constants, 0, None, progress, scale), start)
        scatter_levels.append({"h_contact_factor": scale, **q})
    grid_levels, prev = [], warm
    for lv in lattice_phase.levels(cells0, domain0, GRID_RATIO, n_grid, odd=True):
        samples = []
        # both windows dilated together: the x edges snap to the x lattice, the s edges to the s lattice
        for j, (dx_, ds_) in enumerate(zip(lattice_phase.phase_domains(lv.cells[0], lv.domain[0], phases),
                                           lattice_phase.phase_domains(lv.cells[1], lv.domain[1], phases))):
            if progress:
                progress(f"fem_finite_body: contact grid {lv.cells[0]} x {lv.cells[1]}, phase {j + 1}/{phases}")
            su = nb.setup(p, *lv.cells, dx_, ds_)
            prev = nb.solve_pair(su, constants, finest_corr, prev)
            samples.append(nb.quantities(su, prev))
        mean, spread = lattice_phase.phase_mean(samples)
        grid_levels.append({"nx": lv.cells[0], "ns": lv.cells[1], "h": lv.h, "domain_x": lv.domain[0],
                            "domain_s": lv.domain[1], "phases": phases, **mean,
                            **{f"{k}_phase_spread": v for k, v in spread.items()}})
    parts = certify_parts(QUANTITIES, corr_levels, far_levels, scatter_levels, grid_levels, KALKER_ORDER)
    certs = parts.pop("combined")
    quantities = {q: c.value for q, c in certs.items()}
    quantities.update({f"total_force_{c}": grid_levels[-1][f"total_force_{c}"] for c in nb.CONTACTS})
    quantities["total_force"] = quantities["total_force_inner"]
    stats = {"solver": "conformal normal contact (Polonsky-Keer, DC-FFT developed half-space) + FE finite-body "
                       "correction (P2, PARDISO/LU), fixed point on the pressures",
             "levels": corr_levels, "far_field_levels": far_levels, "scatter_levels": scatter_levels,
             "grid_levels": grid_levels, "level_quantities": list(QUANTITIES), **parts,
             "halfspace_start": nb.quantities(scene_setup, start), "time_s": time.perf_counter() - t0}
    return ModelResult("fem_finite_body", time_s=time.perf_counter() - t0, quantities=quantities, stats=stats)
