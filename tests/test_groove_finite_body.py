"""The groove-rolling finite-body reference's machinery (femcheck.fem.groove_finite_body, problems/_groove_fb):
the exact theory with the half-space coefficients plus the FE correction reproduces the pure FE where the two
must agree, and the correction moves the answer the way the finite bodies do.

One FE level 0 (11 x 21 cells, 85k DOFs, about 10 s) serves every check here.
"""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.cect.groove_contact import GridSpec, solve_groove_cect
from femcheck.fem import compliance_split as cs
from femcheck.fem import groove_rolling as fg
from femcheck.fem.groove_finite_body import finite_body_rolling
from femcheck.problems import groove_rolling as kind
from femcheck.scene import load_scene

pytestmark = pytest.mark.slow      # one FE level (85k DOFs) and three free-rolling solves: about 20 s


@pytest.fixture(scope="module")
def level0():
    p = {**fg.FEM_DEFAULTS, **load_scene("groove-rolling").params}
    grid = fg._grid(fg.setup(p), p, 0)
    comp = fg.compliance(p, grid, 0)
    fe = fg.solve_level(p, 0, comp=comp)
    return p, comp, fe


def _solver(p, spec):
    geom, const = kind.geometry(p), kind._constants(p)

    def solve(extra, omega0):
        return solve_groove_cect(geom, p["load.normal"], p["friction.mu"], const, p["kinematics.speed"], spec,
                                 extra_displacement=extra, omega0=omega0)

    return solve


def test_hybrid_on_the_fe_grid_without_fill_is_the_fe(level0):
    # near = 0 keeps the whole FE table: A_HS + (A_FE - A_HS) = A_FE on the FE's own 11 x 21 cells, so the exact
    # theory with the correction solves the FE's own contact problem (frames, signs, the rolling difference of the
    # correction's displacement, the tangential-normal coupling that only the correction carries). What differs is
    # the kinematic datum: the exact theory takes the body's rigid velocities at its approached pose, the FE at the
    # nominal one; the rolling radius differs by delta / r0 = 11 um / 9.9 mm = 1.1e-3, which the creepage and the
    # frictional power see (bound 3 delta / r0); the normal quantities do not (bound 1e-3: the solvers'
    # tolerances are 1e-9).
    p, comp, fe = level0
    q_fe = fe["quantities"]
    corr = cs.correction(comp, kind._constants(p), near=0)
    fb = finite_body_rolling(_solver(p, GridSpec(11, 21)), corr, tol=1e-7)
    q = fb.solution.quantities
    datum = 3.0 * q_fe["body_approach"] / p["geometry.rolling_radius"]
    assert q["approach"] == pytest.approx(q_fe["body_approach"], rel=1e-3)
    assert q["p_max"] == pytest.approx(q_fe["p_max"], rel=1e-3)
    assert q["half_length_s"] == pytest.approx(q_fe["contact_half_length_s"], rel=1e-3)
    assert q["adhesion_fraction"] == pytest.approx(q_fe["adhesion_fraction"], abs=1.0 / (11 * 21))
    assert q["creepage_x"] == pytest.approx(q_fe["creepage_x"], rel=datum)
    assert q["friction_power"] == pytest.approx(q_fe["friction_power"], rel=datum)


def test_the_correction_stiffens_the_contact_as_the_finite_bodies_do(level0):
    # On the exact theory's own 41 x 81 grid, the correction (near-field fill 2 cells) takes the half-space
    # solution towards the FE's: the approach to the FE's datum (finite bodies: the ring's clamped base and the
    # body's axis) within the FE level's own change to the next level (fem reference: 11.04 -> 11.07 um, 0.3 %);
    # p_max up and the contact narrower than on the half-space (the 9.9 mm roller is stiffer than a half-space),
    # by less than the FE-vs-cect difference stated for groove-rolling (p_max 1.6 %, extent 1.9 %) plus the FE
    # level's error (0.4 % on p_max, 0.2 % on the extent against its 3-level value).
    p, comp, fe = level0
    corr = cs.correction(comp, kind._constants(p), near=2)
    solve = _solver(p, GridSpec(41, 81))
    hs = solve(None, None)
    fb = finite_body_rolling(solve, corr, hs)
    assert fb.iterations <= 4 and fb.history[-1] < 1e-4
    q, h = fb.solution.quantities, hs.quantities
    assert q["approach"] == pytest.approx(fe["quantities"]["body_approach"], rel=3e-3)
    assert q["approach"] < 0.9 * h["approach"]
    assert 0.0 < q["p_max"] / h["p_max"] - 1.0 < 0.016 + 0.004
    assert 0.0 < 1.0 - q["half_length_s"] / h["half_length_s"] < 0.019 + 0.002
    assert np.isclose(q["total_force"], p["load.normal"], rtol=1e-6)

