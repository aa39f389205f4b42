"""The roller equilibrium with a finite-body correction (femcheck.fem.srb_finite_body), checked with corrections
whose effect is known in closed form, on a coarse CECT grid (21 x 41 per contact)."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.cect.roller_equilibrium import equilibrium, require_converged
from femcheck.fem import compliance_split as cs
from femcheck.fem import srb_rolling as fe
from femcheck.fem.srb_finite_body import finite_body_equilibrium, offsets_of
from femcheck.problems import _srb_rolling_out as out
from femcheck.problems import srb_rolling as kind
from femcheck.scene import load_scene

from _corrections import correction_with

K_UNIFORM = 2.0e-12          # m/N: a uniform normal compliance, 1/4 of the roller's diametral one (Hertz 5.5 kN)


@pytest.fixture(scope="module")
def setup():
    p = load_scene("srb-rolling", {"numerics.conformal_cells_x": 21, "numerics.conformal_cells_s": 41}).params
    pr, num = kind.problem_of(p), kind.numerics_of(p)
    start = require_converged(equilibrium(pr, num))
    grids = fe.grids(p, 9, 17, float(p["load.normal"]), half_x=1.35, half_s=3.0)
    return p, pr, num, start, grids


def test_uniform_normal_correction_only_moves_the_approach(setup):
    """A correction that opens the inner gap uniformly by K N (K m/N per unit force anywhere on the inner contact)
    is a rigid shift of the inner ring up to the turn of the normals along the profile (theta = s/r_g <= 0.085
    here): under load control the approach grows by the opening K sum p_n dA (5.5 kN: 11 nm) plus what the small
    difference of the two solves' inner loads asks (dN/d delta = 1.5 N / delta, Hertz), and Table 2's forces and
    d_y stay, both within theta^2/2 (measured: approach 1e-4 of it, forces <= 4.5e-4, d_y 1.3e-4 against
    3.6e-3; the skew, held by a yaw stiffness of ~8 N m/rad, moves by 0.6 % and is not asserted)."""
    p, pr, num, start, grids = setup

    def k(kernels, lags, grids):
        kernels[("inner", "inner")][2, 2] = K_UNIFORM

    fb = finite_body_equilibrium(pr, num, correction_with(grids, k), start, tol=1e-8)
    N = float(p["load.normal"])
    res = fb.result.state.contacts["inner"].result
    opening = K_UNIFORM * res.pressure.sum() * res.cell_area          # u_n = K sum p_n dA (local normals)
    n_hs = start.state.contacts["inner"].result.normal_force
    load_term = (res.normal_force - n_hs) / (1.5 * N / start.approach)
    # the approach acts along e_z, the opening along the local normals, turned by up to theta = s/r_g
    s = np.asarray(fb.result.state.contacts["inner"].inputs.grid.s)[res.pressure.any(axis=0)]
    theta = np.abs(s).max() / pr.bearing.groove_radius_inner
    assert fb.result.approach - start.approach - load_term == pytest.approx(opening, rel=0.5 * theta ** 2)
    a, b = out.quantities(pr, fb.result), out.quantities(pr, start)
    for q in ("f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "f_lat_sum", "d_y"):
        assert a[q] == pytest.approx(b[q], rel=0.5 * theta ** 2), q


def test_offsets_carry_the_rolling_difference_of_the_correction(setup):
    """A correction whose longitudinal displacement grows linearly along x (u_x = alpha x) adds the uniform
    creepage kappa (u - u')/dx = -alpha kappa to the rigid slip per unit speed (seed 000 eq 19, u' one cell
    downstream), and nothing to the lateral slip or the gap."""
    p, pr, num, start, grids = setup
    ci = start.state.contacts["outer"].inputs
    c = grids["outer"]
    alpha = 3e-4
    coarse = {n: np.zeros((3, g.nx, g.ns)) for n, g in grids.items()}
    coarse["outer"][0] = alpha * c.x[:, None]
    gap, slip = offsets_of(cs.Correction(dict(grids), {}, {}, {}), coarse)("outer", ci)
    kappa = np.broadcast_to(np.asarray(ci.speeds.kappa, dtype=float), (ci.grid.x.size, ci.grid.s.size))
    assert np.allclose(slip[0], -alpha * kappa * ci.speeds.reference, rtol=1e-9, atol=0)
    assert np.abs(slip[1]).max() == 0.0 and np.abs(gap).max() == 0.0
