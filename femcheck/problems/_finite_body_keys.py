"""Scene keys of the finite-body references (``fem_finite_body`` of groove-rolling, srb-rolling and srb-normal):
one definition per key, shared by the kinds that read it.

``FINITE_BODY_KEYS`` / ``FINITE_BODY_DEFAULTS``: the FE mesh at the contact line, the contact-grid part and the
measured re-meshing floor, common to every finite-body reference (:mod:`femcheck.solvers.split_certificate`). ``SRB_KEYS`` / ``SRB_DEFAULTS``: the correction and far-field
family of the spherical roller bearing's FE (:mod:`femcheck.problems._srb_rolling_fb`), which srb-rolling and
srb-normal share: with the same defaults they read the same FE tables. ``FINITE_BODY_COARSE`` / ``SRB_COARSE``:
the overrides that make a finite-body reference its coarsest level (the coarsest correction on the scene's grid: what
:mod:`femcheck.reference_check` re-solves). Each kind keeps ``numerics.fb_correction_levels`` where its range
differs (the levels' FE cost).
"""
from __future__ import annotations

from typing import Any

from ..scene import Key

FINITE_BODY_KEYS: dict[str, Key] = {
    "numerics.fb_h_contact": Key("float", "dx", "fem_finite_body: FE element size at the contact line / the "
                                 "correction grid's dx", lo=0.1, hi=2.0, hi_closed=True),
    "numerics.fb_grid_levels": Key("int", "-", "fem_finite_body: contact-grid levels from the coarsest contact grid "
                                   "(refined by sqrt 2)", lo=1, hi=6, lo_closed=True, hi_closed=True),
    "numerics.fb_phases": Key("int", "-", "fem_finite_body: lattice phases averaged per contact-grid level", lo=1,
                              hi=16, lo_closed=True, hi_closed=True),
    "numerics.fb_scatter_meshes": Key("int", "-", "fem_finite_body: extra meshes of the coarsest correction that "
                                      "measure the re-meshing scatter", lo=0, hi=5, lo_closed=True, hi_closed=True),
}

SRB_KEYS: dict[str, Key] = {
    "numerics.fb_correction_cells_x": Key("int", "-", "fem_finite_body: correction cells along x on its coarsest "
                                          "level", lo=5, hi=41, lo_closed=True, hi_closed=True),
    "numerics.fb_correction_cells_s": Key("int", "-", "fem_finite_body: correction cells along the roller on its "
                                          "coarsest level (ns + 1 times 1.5^k should stay an integer)", lo=7, hi=81,
                                          lo_closed=True, hi_closed=True),
    "numerics.fb_correction_levels": Key("int", "-", "fem_finite_body: correction levels (FE mesh and correction "
                                         "grid refined together by 1.5)", lo=1, hi=5, lo_closed=True, hi_closed=True),
    "numerics.fb_farfield_levels": Key("int", "-", "fem_finite_body: far-field mesh levels on the coarsest "
                                       "correction, itself the first (grading and largest element divided by 1.5)",
                                       lo=0, hi=4, lo_closed=True, hi_closed=True),
    "numerics.fb_cells_x": Key("int", "-", "fem_finite_body: contact cells along x on the coarsest contact grid",
                               lo=9, hi=201, lo_closed=True, hi_closed=True),
    "numerics.fb_cells_s": Key("int", "-", "fem_finite_body: contact cells along s on the coarsest contact grid",
                               lo=9, hi=401, lo_closed=True, hi_closed=True),
    **FINITE_BODY_KEYS,
}

FINITE_BODY_DEFAULTS: dict[str, Any] = {
    "numerics.fb_h_contact": 0.35,
    "numerics.fb_grid_levels": 4,
    "numerics.fb_phases": 4,
    "numerics.fb_scatter_meshes": 3,
}

SRB_DEFAULTS: dict[str, Any] = {
    "numerics.fb_correction_cells_x": 9,
    "numerics.fb_correction_cells_s": 15,
    "numerics.fb_correction_levels": 3,
    "numerics.fb_farfield_levels": 3,
    "numerics.fb_cells_x": 41,
    "numerics.fb_cells_s": 81,
    **FINITE_BODY_DEFAULTS,
}

# the coarsest correction on the scene's grid, without re-meshed copies
FINITE_BODY_COARSE: dict[str, Any] = {"numerics.fb_correction_levels": 1, "numerics.fb_grid_levels": 1,
                                      "numerics.fb_scatter_meshes": 0}
# srb's correction levels are single-phase equilibria, so its coarsest level is one phase (and no far field); the
# groove solves every correction level as a phase mean, so its coarse re-solve keeps the scene's phases
SRB_COARSE: dict[str, Any] = {**FINITE_BODY_COARSE, "numerics.fb_phases": 1, "numerics.fb_farfield_levels": 0}
