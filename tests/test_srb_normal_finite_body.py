"""The frictionless normal contact of seed 000's roller on both raceways (femcheck.fem.srb_normal_finite_body): the
conformal half-space against Hertz (spec srb-rolling 10.1 item 7), and the finite-body fixed point checked with
corrections whose effect is known in closed form (on 41 x 81 cells per contact)."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.fem import srb_normal_finite_body as nb
from femcheck.fem import srb_rolling as fe
from femcheck.geometry.srb import radii
from femcheck.problems import _srb_normal_fb as drv
from femcheck.scene import load_scene

from _corrections import correction_with

K_UNIFORM = 2.0e-12          # m/N: a uniform normal compliance, 1/4 of the roller's diametral one (Hertz 5.5 kN)
L_TILT = 0.01                # m


@pytest.fixture(scope="module")
def case():
    p = load_scene("srb-normal-finite").params
    st = nb.setup(p, 41, 81, 1.35, 1.25)
    c = drv.constants_of(p)
    return p, st, c, nb.solve_pair(st, c)


def centroid_s(st, r, c):
    p, s = r.pressure[c], st[c].grid.s
    return float((p.sum(axis=0) * s).sum() / p.sum())


def test_conformal_halfspace_is_hertz_at_the_nominal_pose(case):
    """Spec srb-rolling 10.1 item 7: semi-axes within 2 % of Hertz, p_max within 2 % of 1.370 / 1.181 GPa; each
    contact carries N along its contact line (the load control's tolerance, 1e-9; the plain sum of the pressures is
    0.08 / 0.09 % more: the normals turn by up to 4.9 / 5.4 deg along the grooves)."""
    p, st, c, r = case
    q = nb.quantities(st, r)
    hz = fe.hertz_estimates(p, 5500.0)
    for name, p0 in (("inner", 1.370e9), ("outer", 1.181e9)):
        assert q[f"p_max_{name}"] == pytest.approx(p0, rel=0.02)
        assert q[f"semi_axis_x_{name}"] == pytest.approx(hz[name].semi_axis_x, rel=0.02)
        assert q[f"semi_axis_y_{name}"] == pytest.approx(hz[name].semi_axis_y, rel=0.02)
        # the resultant along the contact line, from the grid's own normals (not the solver's weights)
        g = st[name].grid
        along = (g.normal(g.s) @ g.normal(0.0))[None, :]
        assert float(np.sum(r.pressure[name] * along) * g.cell_area) == pytest.approx(5500.0, rel=1e-8)


def test_uniform_correction_moves_only_the_approaches_by_the_load_of_both_contacts(case):
    """A uniform normal compliance K on every pair (the roller couples the contacts: each opens by K times the
    normal force of both) is a rigid opening: the approaches grow by K sum_d sum p_d dA, up to the turn of the
    normals along the profile (theta = s/r_g <= 0.09: within theta^2/2), and the pressures stay."""
    p, st, c, r0 = case

    def k(kernels, lags, grids):
        for K in kernels.values():
            K[2, 2] = K_UNIFORM

    corr = correction_with(fe.grids(p, 9, 17, 5500.0, half_x=1.35, half_s=3.0), k)
    r = nb.solve_pair(st, c, corr, tol=1e-8)
    opening = K_UNIFORM * sum(r.pressure[n].sum() * st[n].grid.cell_area for n in nb.CONTACTS)
    theta = max(np.abs(st[n].grid.s[r.pressure[n].any(axis=0)]).max() / st[n].grid.radius for n in nb.CONTACTS)
    q0, q = nb.quantities(st, r0), nb.quantities(st, r)
    for n in nb.CONTACTS:
        assert r.approach[n] - r0.approach[n] == pytest.approx(opening, rel=0.5 * theta ** 2)
        for name in ("p_max", "semi_axis_x", "semi_axis_y"):
            assert q[f"{name}_{n}"] == pytest.approx(q0[f"{name}_{n}"], rel=1e-4)


def test_cross_influence_tilts_the_other_contact(case):
    """A cross correction d_nn(inner <- outer) = K s_I / L opens the inner gap by alpha s, alpha = K F_out / L
    (F_out = sum p_out dA): the inner gap s^2/(2 R_y) + alpha s moves the inner contact by -alpha R_y along s
    (within 1 %: the exact conformal gap is a parabola to 0.2 % over the contact; measured 0.3 %), and
    the outer contact, which the correction does not reach, stays."""
    p, st, c, r0 = case

    def k(kernels, lags, grids):
        s_r = grids["inner"].s
        kernels[("inner", "outer")][2, 2] = K_UNIFORM * 50.0 * (s_r / L_TILT)[None, :, None]

    corr = correction_with(fe.grids(p, 9, 17, 5500.0, half_x=1.35, half_s=3.0), k)
    r = nb.solve_pair(st, c, corr, tol=1e-8)
    f_out = r.pressure["outer"].sum() * st["outer"].grid.cell_area
    alpha = K_UNIFORM * 50.0 * f_out / L_TILT
    ry = radii(p)["inner"][1]
    shift = centroid_s(st, r, "inner") - centroid_s(st, r0, "inner")
    assert shift == pytest.approx(-alpha * ry, rel=0.01)
    assert np.abs(r.pressure["outer"] - r0.pressure["outer"]).max() <= 1e-6 * r0.pressure["outer"].max()
