"""The finite-body reference of the groove-rolling kind (``fem_finite_body``; shared helper, not a kind): free
rolling by the conformal exact theory with finite-body influence coefficients on fine contact grids, certified in
two parts.

The coefficients are the developed half-space's plus the FE finite-body correction D of
:mod:`femcheck.fem.compliance_split` (the crowned body and the ring segment of :mod:`femcheck.fem.groove_rolling`
minus the half-space), entering every free-rolling solve as a given displacement, a fixed point on the tractions
(:mod:`femcheck.fem.groove_finite_body`). Two discretisations, refined apart:

1. **The correction** (FE mesh and correction grid refined together, as the ``fem`` reference's levels: cells and
   the section's grading by ``numerics.fem_ratio`` per level, one element layer per cell), its grid over
   +-``CORRECTION_HALF_X`` a_H (wider than the contact windows of the lattice phases below) and the ``fem``
   window along s, near-field fill 2 cells; free rolling on the scene's contact grid
   (``numerics.conformal_cells_*``) for each. Certified by :func:`femcheck.solvers.convergence.certify` at the
   correction's formal order 2 with the re-meshing scatter as its floor: per quantity the larger of the assumed
   0.2 % (:mod:`femcheck.solvers.split_certificate`) and the spread measured over the coarsest level solved on
   ``numerics.fb_scatter_meshes`` more meshes (:func:`~femcheck.solvers.split_certificate.remesh_floor`; the section's element size at the contact
   line scaled by 1 %, 2 %, ...). The near-field quantities (p_max at the centre, the adhesion of a few % of the
   cells) scatter by more than 0.2 % from mesh to mesh of one level.
2. **The contact grid** at the finest correction: levels from the scene's cells refining by sqrt 2 with exactly
   geometric cell sizes and odd counts, each the mean over ``numerics.fb_phases`` lattice phases of the
   contact's edges along x and s together (:mod:`femcheck.cect.lattice_phase`); certified at Kalker's first order, changes below
   the levels' phase spread counting as converged
   (:func:`femcheck.solvers.split_certificate.grid_certificate`).

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
from ..solvers.convergence import Certificate, certify
from ..solvers.finite_body_certificate import certify_parts
from ..solvers.split_certificate import CORRECTION_ORDER, scatter_scales

CORRECTION_HALF_X = 1.5     # a_H: the phases' dilated windows reach 1.42 a_H at 41 cells
GRID_RATIO = math.sqrt(2.0)
NEAR_FIELD = 2              # cells of harmonic fill around the loaded cell (compliance_split.correction)
QUANTITIES = ("body_approach", "p_max", "contact_half_length_s", "angle_span", "adhesion_fraction", "creepage_x",
              "friction_power")


def correction_level(p: dict[str, Any], constants, k: int, progress=None) -> cs.Correction:
    """The correction of level k (module docstring item 1): the FE tables of the ``fem`` reference's level-k mesh
    on a grid over +-CORRECTION_HALF_X a_H."""
    g = fe.setup(p)
    grid = fe._grid(g, {**p, "numerics.fem_half_x": CORRECTION_HALF_X}, k)
    if progress:
        progress(f"fem_finite_body: FE correction level {k + 1} ({grid.nx} x {grid.ns} cells)")
    return cs.correction(fe.compliance(p, grid, k), constants, NEAR_FIELD)


def plain_correction_certificate(h, q, floor: float) -> Certificate:
    """The groove's correction part: :func:`femcheck.solvers.convergence.certify` at the correction's formal order
    with the re-meshing floor, without the srb family's extra rules (faster-than-formal order, converged after one
    step): on the groove's correction family a fourth level (1.2M DOFs) moved the adhesion fraction by +1.6 %,
    beyond the estimate those rules would give from three levels."""
    return certify(h, q, CORRECTION_ORDER, floor=floor)


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

    start = solver(spec)(None, None)
    corr_levels, sol, corr = [], start, None
    for k in range(n_corr):
        corr = correction_level(p, constants, k, progress)
        fb = finite_body_rolling(solver(spec), corr, sol)
        sol = fb.solution
        st = corr.stats["fe"]
        lv = {"level": k, "nx": corr.grids["groove"].nx, "ns": corr.grids["groove"].ns,
              "h": 1.0 / float(p["numerics.fem_ratio"]) ** k, "n_dofs": st.get("n_dofs"),
              "fe_time_s": st.get("total_s"), "outer_iterations": fb.iterations, **_values(sol)}
        corr_levels.append(lv)
        if progress:
            progress(f"fem_finite_body: correction level {k + 1}: creepage {lv['creepage_x']:.5e}, p_max "
                     f"{lv['p_max']:.5e} Pa")
    # the re-meshing scatter of each quantity, measured: the coarsest correction on fb_scatter_meshes more meshes of
    # the same level (the section's element size at the contact line scaled by 1 %, 2 %, ...: every element moves)
    scatter_levels = []
    for scale in scatter_scales(p["numerics.fb_scatter_meshes"]):
        pj = {**p, "numerics.fem_h_contact": float(p["numerics.fem_h_contact"]) * scale}
        fb = finite_body_rolling(solver(spec), correction_level(pj, constants, 0, progress), start)
        scatter_levels.append({"h_contact_factor": scale, **_values(fb.solution)})
    grid_levels = []
    # odd counts: the creepage is read at the centre cell and p_max sits there (an even count moved both by 0.04 %)
    for lv in lattice_phase.levels((spec.cells_x, spec.cells_s), (spec.domain_x, spec.domain_s), GRID_RATIO, n_grid,
                                   odd=True):
        samples = []
        # both windows dilated together (phase j moves the Hertz edge inward by j/K cells along x and along s):
        # the leading edge snaps to the x lattice, the lateral extent's power-law edges to the s lattice
        for j, (dx_, ds_) in enumerate(zip(lattice_phase.phase_domains(lv.cells[0], lv.domain[0], phases),
                                           lattice_phase.phase_domains(lv.cells[1], lv.domain[1], phases))):
            if progress:
                progress(f"fem_finite_body: contact grid {lv.cells[0]} x {lv.cells[1]}, phase {j + 1}/{phases}")
            sp = replace(spec, cells_x=lv.cells[0], cells_s=lv.cells[1], domain_x=dx_, domain_s=ds_)
            # the last solution (another grid) starts the fixed point: its tractions give the first correction field
            fb = finite_body_rolling(solver(sp), corr, sol)
            sol = fb.solution
            samples.append(_values(sol))
        mean, spread = lattice_phase.phase_mean(samples)
        grid_levels.append({"nx": lv.cells[0], "ns": lv.cells[1], "h": lv.h, "domain_x": lv.domain[0],
                            "domain_s": lv.domain[1], "phases": phases, **mean,
                            **{f"{k}_phase_spread": v for k, v in spread.items()}})
    parts = certify_parts(QUANTITIES, corr_levels, None, scatter_levels, grid_levels, KALKER_ORDER,
                          correction_rule=plain_correction_certificate)
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
