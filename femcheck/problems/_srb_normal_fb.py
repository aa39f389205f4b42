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

from ..cect import lattice_phase
from ..cect.influence import combined_constants
from ..cect.refinement import KALKER_ORDER
from ..fem import srb_normal_finite_body as nb
from ..fem import srb_rolling as fe
from ..materials import Elastic
from ..result import ModelResult
from ..scene import Key
from ..solvers.finite_body_certificate import certify_parts
from . import _srb_rolling_fb as rfb
from ._finite_body_keys import SRB_COARSE, SRB_DEFAULTS, SRB_KEYS

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
    "numerics.fb_grading": Key("float", "-", "fem_finite_body: FE mesh grading away from the contacts", lo=0.05,
                               hi=1.0, lo_closed=True, hi_closed=True),
    **SRB_KEYS,
}
DEFAULTS: dict[str, Any] = {
    "numerics.cect_cells_x": 61,
    "numerics.cect_cells_s": 121,
    "numerics.cect_domain_x": 1.35,
    "numerics.cect_domain_s": 1.25,
    "numerics.fb_grading": 0.4,
    # the srb-rolling finite-body reference's correction family (its defaults: the same FE tables)
    **SRB_DEFAULTS,
}
COARSE = SRB_COARSE


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
    n_grid, phases = int(p["numerics.fb_grid_levels"]), int(p["numerics.fb_phases"])
    counts = (int(p["numerics.fb_correction_levels"]), int(p["numerics.fb_farfield_levels"]),
              int(p["numerics.fb_scatter_meshes"]))
    cells0 = (int(p["numerics.fb_cells_x"]), int(p["numerics.fb_cells_s"]))
    domain0 = (float(p["numerics.cect_domain_x"]), float(p["numerics.cect_domain_s"]))
    # the FE families on the scene's grid: the coarsest correction is what reference_check re-solves
    scene_setup = nb.setup(p, int(p["numerics.cect_cells_x"]), int(p["numerics.cect_cells_s"]), *domain0)
    start = nb.solve_pair(scene_setup, constants)

    def on_scene_grid(corr, warm: nb.NormalPair) -> tuple[nb.NormalPair, dict]:
        r = nb.solve_pair(scene_setup, constants, corr, warm)
        return r, {**nb.quantities(scene_setup, r), "passes": r.passes}

    fam = rfb.correction_families(pf, constants, counts, on_scene_grid, start, progress, shown="semi_axis_y_inner")
    grid_levels, prev = [], fam.state
    for lv in lattice_phase.levels(cells0, domain0, GRID_RATIO, n_grid, odd=True):
        samples = []
        # both windows dilated together: the x edges snap to the x lattice, the s edges to the s lattice
        for j, (dx_, ds_) in enumerate(lattice_phase.phase_windows(lv.cells, lv.domain, phases)):
            if progress:
                progress(f"fem_finite_body: contact grid {lv.cells[0]} x {lv.cells[1]}, phase {j + 1}/{phases}")
            su = nb.setup(p, *lv.cells, dx_, ds_)
            prev = nb.solve_pair(su, constants, fam.finest, prev)
            samples.append(nb.quantities(su, prev))
        grid_levels.append(lattice_phase.level_record(lv, phases, samples))
    parts = certify_parts(QUANTITIES, fam.correction, fam.far_field, fam.scatter, grid_levels, KALKER_ORDER)
    certs = parts.pop("combined")
    quantities = {q: c.value for q, c in certs.items()}
    quantities.update({f"total_force_{c}": grid_levels[-1][f"total_force_{c}"] for c in nb.CONTACTS})
    quantities["total_force"] = quantities["total_force_inner"]
    stats = {"solver": "conformal normal contact (Polonsky-Keer, DC-FFT developed half-space) + FE finite-body "
                       "correction (P2, PARDISO/LU), fixed point on the pressures",
             "levels": fam.correction, "far_field_levels": fam.far_field, "scatter_levels": fam.scatter,
             "grid_levels": grid_levels, "level_quantities": list(QUANTITIES), **parts,
             "halfspace_start": nb.quantities(scene_setup, start), "time_s": time.perf_counter() - t0}
    return ModelResult("fem_finite_body", time_s=time.perf_counter() - t0, quantities=quantities, stats=stats)
