"""The finite-body reference of the groove-rolling kind (``fem_finite_body``; shared helper, not a kind): free
rolling by the conformal exact theory with finite-body influence coefficients on fine contact grids, certified in
two parts.

The coefficients are the developed half-space's plus the FE finite-body correction D of
:mod:`femcheck.fem.compliance_split` (the crowned body and the ring segment of :mod:`femcheck.fem.groove_rolling`
minus the half-space), entering every free-rolling solve as a given displacement, a fixed point on the tractions
(:mod:`femcheck.fem.groove_finite_body`). Two discretisations, refined apart:

1. **The correction** (FE mesh and correction grid refined together, on the ``fem`` reference's grids: cells and
   the section's grading by ``numerics.fem_ratio`` per level), its grid over +-``CORRECTION_HALF_X`` a_H (wider
   than the contact windows of the lattice phases below) and the ``fem`` window along s; the FE mesh at
   ``numerics.fb_h_contact`` dx at the contact line with ``LAYERS_PER_CELL`` element layers per cell and a
   near-field fill of one cell (``NEAR_FIELD``), srb-rolling-finite's design: with fem's mesh (0.7 dx, one layer,
   a two-cell fill) the levels moved p_max by +0.39 % then -0.13 % and a fourth level by +0.30 %, the FE's error
   of the singular response oscillating next to the fill (docs/notes/srb-split-compliance.md). Free rolling on
   the scene's contact grid (``numerics.conformal_cells_*``) for each, as the mean over the lattice phases of
   item 2 (a single window's adhesion fraction jumps by a row of cells when the mesh moves the edge). Certified
   by srb-rolling-finite's rule (:func:`femcheck.solvers.finite_body_certificate.correction_certificate`: the
   formal order 2, never a faster observed one; a last change below the floor and at most 1/r^2 of the one before
   is convergence) with the re-meshing scatter as its floor: per quantity the larger of the assumed 0.2 %
   (:mod:`femcheck.solvers.split_certificate`) and the spread measured over the coarsest level solved on
   ``numerics.fb_scatter_meshes`` more meshes (:func:`~femcheck.solvers.split_certificate.remesh_floor`; the
   contact-line element size scaled by 1 %, 2 %, ...). fem's mesh kept certify's plain rule: there a fourth level
   moved the adhesion by +1.6 %, beyond what the srb rule would have estimated from three.
2. **The contact grid** at the finest correction: levels from the scene's cells refining by sqrt 2 with exactly
   geometric cell sizes and odd counts, each the mean over ``numerics.fb_phases`` lattice phases of the
   contact's edges along x and s together (:mod:`femcheck.cect.lattice_phase`); certified at Kalker's first
   order, changes below the levels' phase spread counting as converged
   (:func:`femcheck.solvers.split_certificate.grid_certificate`). Its first level is the finest correction's.

Combined value and estimate per quantity: :func:`femcheck.solvers.split_certificate.combine`. The mesh's largest
element (max(b_H, 2 a_H), as the ``fem`` reference's) is not refined: it is larger than the body's section only
where the grading's size already reaches it.

The approach of the finite bodies is the crowned body's axis towards the ring segment's clamped base (the FE
tables' datum, which the correction carries): ``body_approach``, comparable with the ``fem`` reference's, not
with the half-space models' ``approach``.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

from ..cect import lattice_phase
from ..cect.groove_contact import GridSpec, GrooveSolution, solve_groove_cect
from ..cect.refinement import KALKER_ORDER
from ..fem import compliance_split as cs
from ..fem import groove_rolling as fe
from ..fem.groove_finite_body import finite_body_rolling
from ..result import ModelResult
from ..solvers.finite_body_certificate import certify_parts
from ..solvers.split_certificate import scatter_scales

CORRECTION_HALF_X = 1.5     # a_H: the phases' dilated windows reach 1.42 a_H at 41 cells
GRID_RATIO = math.sqrt(2.0)
NEAR_FIELD = 1              # cells of harmonic fill around the loaded cell (compliance_split.correction)
LAYERS_PER_CELL = 2         # FE element layers per correction cell along s
QUANTITIES = ("body_approach", "p_max", "contact_half_length_s", "angle_span", "adhesion_fraction", "creepage_x",
              "friction_power")


def correction_level(p: dict[str, Any], constants, k: int, progress=None, scale: float = 1.0) -> cs.Correction:
    """The correction of level k (module docstring item 1): the FE tables of the ``fem`` reference's level-k grid
    over +-CORRECTION_HALF_X a_H, meshed at ``numerics.fb_h_contact`` dx (times ``scale``: the same level
    re-meshed) with LAYERS_PER_CELL layers per cell, filled over NEAR_FIELD cells."""
    g = fe.setup(p)
    grid = fe._grid(g, {**p, "numerics.fem_half_x": CORRECTION_HALF_X}, k)
    if progress:
        progress(f"fem_finite_body: FE correction level {k + 1} ({grid.nx} x {grid.ns} cells)")
    tables = fe.compliance(p, grid, k, h_contact=float(p["numerics.fb_h_contact"]) * scale,
                           layers_per_cell=LAYERS_PER_CELL)
    return cs.correction(tables, constants, NEAR_FIELD)


def _values(sol: GrooveSolution) -> dict[str, float]:
    q = sol.quantities
    return {"body_approach": float(q["approach"]), "p_max": float(q["p_max"]),
            "contact_half_length_s": float(q["half_length_s"]), "angle_span": float(q["angle_span"]),
            "adhesion_fraction": float(q["adhesion_fraction"]), "creepage_x": float(q["creepage_x"]),
            "friction_power": float(q["friction_power"])}


def finite_body(p: dict[str, Any], geom, constants, spec: GridSpec, solver_args: dict, progress=None) -> ModelResult:
    """The two-part certified finite-body free rolling (module docstring) on the scene's grid ``spec``;
    ``solver_args`` the exact theory's remaining arguments (influence, variable_dq, solver, tol,
    compliance_weights)."""
    t0 = time.perf_counter()
    n_corr, n_grid, phases = (int(p["numerics.fb_correction_levels"]), int(p["numerics.fb_grid_levels"]),
                              int(p["numerics.fb_phases"]))
    load, mu, speed = float(p["load.normal"]), float(p["friction.mu"]), float(p["kinematics.speed"])

    def solver(sp: GridSpec):
        def solve(extra, omega0):
            return solve_groove_cect(geom, load, mu, constants, speed, sp, extra_displacement=extra, omega0=omega0,
                                     **solver_args)
        return solve

    def phased(cells: tuple[int, int], domain: tuple[float, float], corr, sol, label: str):
        """The phase mean and spread over ``phases`` lattice phases of the contact's edges along x and s together
        (phase j moves the Hertz edge inward by j/K cells on both axes: the leading edge snaps to the x lattice,
        the lateral extent's power-law edges to the s lattice); the last solution (another grid or correction)
        starts each fixed point, its tractions giving the first correction field."""
        samples, iterations = [], 0
        for j, (dx_, ds_) in enumerate(lattice_phase.phase_windows(cells, domain, phases)):
            if progress and phases > 1:
                progress(f"fem_finite_body: {label}, contact grid {cells[0]} x {cells[1]}, phase {j + 1}/{phases}")
            sp = replace(spec, cells_x=cells[0], cells_s=cells[1], domain_x=dx_, domain_s=ds_)
            fb = finite_body_rolling(solver(sp), corr, sol)
            sol, iterations = fb.solution, max(iterations, fb.iterations)
            samples.append(_values(sol))
        mean, spread = lattice_phase.phase_mean(samples)
        return mean, spread, sol, iterations

    scene_cells, scene_domain = (spec.cells_x, spec.cells_s), (spec.domain_x, spec.domain_s)
    start = solver(spec)(None, None)
    corr_levels, sol, corr, finest_spread = [], start, None, {}
    # every correction level is solved on the scene's grid as its lattice-phase mean: a single window's adhesion
    # fraction jumps by a row of cells when the FE mesh moves the edge across a cell centre (+1.6 % on the third
    # level at 1.027, docs/notes/srb-split-compliance.md), which is the grid's error, not the correction's
    for k in range(n_corr):
        corr = correction_level(p, constants, k, progress)
        mean, finest_spread, sol, iterations = phased(scene_cells, scene_domain, corr, sol,
                                                      f"correction level {k + 1}")
        st = corr.stats["fe"]
        lv = {"level": k, "nx": corr.grids["groove"].nx, "ns": corr.grids["groove"].ns,
              "h": 1.0 / float(p["numerics.fem_ratio"]) ** k, "n_dofs": st.get("n_dofs"),
              "fe_time_s": st.get("total_s"), "outer_iterations": iterations, "phases": phases, **mean}
        corr_levels.append(lv)
        if progress:
            progress(f"fem_finite_body: correction level {k + 1}: creepage {lv['creepage_x']:.5e}, p_max "
                     f"{lv['p_max']:.5e} Pa")
    # the re-meshing scatter of each quantity, measured: the coarsest correction on fb_scatter_meshes more meshes of
    # the same level (the section's element size at the contact line scaled by 1 %, 2 %, ...: every element moves)
    scatter_levels = []
    for scale in scatter_scales(p["numerics.fb_scatter_meshes"]):
        mean_j, _, _, _ = phased(scene_cells, scene_domain, correction_level(p, constants, 0, progress, scale),
                                 start, f"re-meshed coarsest correction x {scale:g}")
        scatter_levels.append({"h_contact_factor": scale, **mean_j})
    grid_levels = []
    # odd counts: the creepage is read at the centre cell and p_max sits there (an even count moved both by 0.04 %)
    for lv in lattice_phase.levels(scene_cells, scene_domain, GRID_RATIO, n_grid, odd=True):
        if lv.cells == scene_cells and all(math.isclose(a, b, rel_tol=1e-12) for a, b in zip(lv.domain, scene_domain)):
            # the scene's grid at the finest correction: the last correction level's phase mean, already solved
            mean, spread = {q: corr_levels[-1][q] for q in QUANTITIES}, finest_spread
        else:
            mean, spread, sol, _ = phased(lv.cells, lv.domain, corr, sol, "finest correction")
        grid_levels.append({"nx": lv.cells[0], "ns": lv.cells[1], "h": lv.h, "domain_x": lv.domain[0],
                            "domain_s": lv.domain[1], "phases": phases, **mean,
                            **{f"{k}_phase_spread": v for k, v in spread.items()}})
    parts = certify_parts(QUANTITIES, corr_levels, None, scatter_levels, grid_levels, KALKER_ORDER)
    certs = parts.pop("combined")
    stats = {"solver": "conformal CECT free rolling (half-space DC-FFT) + FE finite-body correction (P2, "
                       "PARDISO), fixed point on the tractions",
             "levels": corr_levels, "grid_levels": grid_levels, "level_quantities": list(QUANTITIES),
             "scatter_levels": scatter_levels, **parts, "halfspace_start": _values(start),
             "time_s": time.perf_counter() - t0}
    r, dg = sol.result, sol.grid
    fields = {"map_x": dg.x, "map_y": dg.s, "pressure_map": r.pressure, "adhesion_map": r.adhesion.astype(float),
              "s": dg.s, "lateral_normal": r.lateral_normal, "lateral_fx": r.lateral_fx}
    return ModelResult("fem_finite_body", quantities={q: c.value for q, c in certs.items()}, stats=stats,
                       fields=fields)
