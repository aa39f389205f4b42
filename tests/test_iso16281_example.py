"""ISO/TS 16281:2008 against a published worked example: the deep-groove ball bearing of the public repository
``minzhun/ISO16281``, file ``Test_BallBearing.py`` (Examples 1-7), whose expected values are printed in its
comments and appear to come from MASTA (the file's variable ``Delta_a_MASTA``; spec bearing-load.md §3.6 D):

    Z = 7, D_w = 11.5 mm, D_pw = 43.5 mm, r_i = 0.52 D_w, r_e = 0.53 D_w (the file's ``geometry``), E = 210 GPa,
    nu = 0.3, C = 23 400 N, inner ring rotating, ball 0 on the radial load line; radial load F_x, axial load F_z,
    moment M_x (about the radial load line) in N, N mm.

Model: :mod:`femcheck.analytic.iso16281_ball` (written from the TS equations; the repository's code was read for
its equations and numbers only). The example's deflections are reproduced only with Hertz's exact constant
sqrt(2) pi/3 = 1.480961 in the spring constant c_p, not with the TS's rounded 1.48 (which makes the radial deflections
0.030-0.044 % larger: test_ts_rounded_constant_shifts_the_radial_deflection_by_its_rounding).

Tolerances, from the printed digits and the measured differences (all with the exact constant):
- deflections and tilts are printed to 5-7 significant digits; ours differ by 0.0000-0.0034 %, i.e. 0.2-9 units
  of the last printed digit (largest: Example 5, tilt 2.68711 against 2.6872 mrad and delta_r 19.59177 against
  19.5923 um; Example 1, delta_r 15.11020 against 15.1101 um). Band 5e-5 relative: the TS's rounded 1.48, or any
  error in the osculations or the ellipse ratio, moves them by 3e-4 or more.
- L10r is printed to 8 significant digits; ours differ by 0.0002-0.0067 % (radial, axial and combined cases) and
  0.022 % (the pure moment, Example 6). We cannot attribute these remaining differences (MASTA's own evaluation
  of the elliptic integrals or element ratings is not published). Band 1e-4, 3e-4 for Example 6: the
  TS's L10r exponent -9/10 replaced by the roller's -8/9 moves L10r by 9-15 %, the rotating ring's equivalent-load
  exponent 3 replaced by the roller's 4 by 12-33 % (benchmarks/mutations: iso-ball-*).
The roller case of the spec §3.6 D (delta_r = 3.5023 um, Q = 683.56 / 316.44 N) is asserted in
tests/test_bearing_load.py::test_iso_case_d.
"""
import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.analytic import iso16281_ball as ib

E, NU, RATING = 210e9, 0.3, 23400.0
Z, DW, DPW = 7, 11.5e-3, 43.5e-3

# (example, s_r (m), F_r (N), F_a (N), M_x (N m), published: delta_r (um), delta_a (um), tilt (mrad), L10r (1e6 rev))
EXAMPLES = [
    (1, 0.0, 1000.0, 0.0, 0.0, {"delta_r": 15.1101, "L10r": 13163.019}),
    (2, 0.0, 0.0, 1000.0, 0.0, {"delta_a": 133.5381, "L10r": 2222.7318}),
    (3, 0.01e-3, 1000.0, 0.0, 0.0, {"delta_r": 21.223, "L10r": 10795.7948}),
    (4, 0.01e-3, 0.0, 1000.0, 0.0, {"delta_a": 149.1717, "L10r": 3115.8781}),
    (5, 0.01e-3, 1000.0, 1000.0, 0.0, {"delta_r": 19.5923, "delta_a": 146.4603, "tilt": 2.6872, "L10r": 1630.5367}),
    (6, 0.0, 0.0, 0.0, 1.0, {"tilt": 3.6957, "L10r": 785144.7521}),
    (7, 0.01e-3, 1000.0, 1000.0, 1.0, {"delta_r": 19.7144, "delta_a": 146.3084, "tilt": 2.7239,
                                        "L10r": 1627.7479}),
]


def solve(clearance, fr, fa, mx, constant=ib.HERTZ_CONSTANT):
    b = ib.radial_ball_bearing(Z, DW, DPW, clearance)
    cp = ib.spring_constant(E, NU, DW, DPW, b.inner_groove, b.outer_groove, constant=constant)
    # M_x turns about the radial load line (x): it tilts the ring in the plane normal to the load.
    eq = ib.ball_equilibrium(b, cp, fr, fa, 0.0, mx)
    got = {"delta_r": eq.radial_displacement * 1e6, "delta_a": eq.delta_a * 1e6, "tilt": eq.misalignment * 1e3,
           "L10r": ib.reference_rating_life(eq.loads, b, RATING)}
    return b, eq, got


def test_spring_constant_is_two_hertz_contacts_in_series():
    """c_p with Hertz's exact constant equals Q / (delta_i + delta_e)^(3/2) of femcheck's own elliptical Hertz
    solution (:func:`femcheck.analytic.hertz.elliptic_contact`, Johnson's eqs 4.36-4.39 through Carlson's R_D, an
    independent route) for the example's ball: inner contact 1/R_x = 2/D_w + 2/(D_pw - D_w), 1/R_y = 2/D_w - 1/r_i;
    outer 1/R_x = 2/D_w - 2/(D_pw + D_w), 1/R_y = 2/D_w - 1/r_e; E* = E/(2(1 - nu^2)). Tolerance 1e-9 (both solve the same equations to 1e-15); the
    ellipse ratio chi = a/b of the TS's eq 2 is Hertz's too (9.80 at the inner contact)."""
    b = ib.radial_ball_bearing(Z, DW, DPW)
    es = E / (2.0 * (1.0 - NU**2))
    q = 1000.0
    inner = hertz.elliptic_contact(q, 1.0 / (2.0 / DW + 2.0 / (DPW - DW)), 1.0 / (2.0 / DW - 1.0 / b.inner_groove), es)
    outer = hertz.elliptic_contact(q, 1.0 / (2.0 / DW - 2.0 / (DPW + DW)), 1.0 / (2.0 / DW - 1.0 / b.outer_groove), es)
    expected = q / (inner.approach + outer.approach) ** 1.5
    cp = ib.spring_constant(E, NU, DW, DPW, b.inner_groove, b.outer_groove, constant=ib.HERTZ_CONSTANT)
    assert cp == pytest.approx(expected, rel=1e-9)
    chi = ib.ellipse_ratio(ib.curvature(DW, DPW, b.inner_groove, 0.0, "inner")[1])
    assert chi == pytest.approx(inner.semi_axis_y / inner.semi_axis_x, rel=1e-9)
    assert ib.HERTZ_CONSTANT == pytest.approx(1.48, abs=1e-3)


@pytest.mark.parametrize("example, clearance, fr, fa, mx, published", EXAMPLES, ids=[f"ex{e[0]}" for e in EXAMPLES])
def test_published_ball_bearing_example(example, clearance, fr, fa, mx, published):
    """Deflections, tilt and L10r of ``minzhun/ISO16281`` ``Test_BallBearing.py`` Example ``example`` (module doc:
    source and tolerances). The equilibrium is met to 1e-9 of the load."""
    _, eq, got = solve(clearance, fr, fa, mx)
    assert eq.residual < 1e-9
    assert np.isclose((eq.loads * np.cos(eq.contact_angles) * np.cos(ib.radial_ball_bearing(Z, DW, DPW).azimuths)
                       ).sum(), fr, atol=1e-6 * max(fr, fa, 1.0))
    for key, value in published.items():
        tol = 5e-5 if key != "L10r" else (3e-4 if example == 6 else 1e-4)
        assert got[key] == pytest.approx(value, rel=tol), key


RADIAL = [e for e in EXAMPLES if "delta_r" in e[5]]


@pytest.mark.parametrize("example, clearance, fr, fa, mx, published", RADIAL, ids=[f"ex{e[0]}" for e in RADIAL])
def test_ts_rounded_constant_shifts_the_radial_deflection_by_its_rounding(example, clearance, fr, fa, mx, published):
    """With the TS's rounded 1.48 the ball is 1.480961/1.48 = 1.00065 times softer in c_p, so the radial
    deflection of a load-controlled case is (1.480961/1.48)^(2/3) = 1.00043 times the published one (the clearance
    and the contact angles shift this slightly: measured 1.00030-1.00044). Tolerance 1.5e-4 on that ratio. (The
    axial displacement grows mostly through the contact angle, about as delta^(1/2): 1.00013-1.00017.)"""
    _, _, got = solve(clearance, fr, fa, mx, constant=1.48)
    expected = (ib.HERTZ_CONSTANT / 1.48) ** (2.0 / 3.0)
    assert got["delta_r"] / published["delta_r"] == pytest.approx(expected, abs=1.5e-4)


def test_radial_example_loads_follow_stribeck():
    """Example 1 (zero clearance, radial load, contact angles 0): every loaded ball's deflection is
    delta_r cos(psi_j) (the rigid-ring kinematics, spec §3.1) and Q_j = c_p delta_j^(3/2) with the independent
    Hertz c_p of test_spring_constant_is_two_hertz_contacts_in_series; the loads carry F_r. Tolerance 1e-9."""
    b, eq, _ = solve(0.0, 1000.0, 0.0, 0.0)
    psi = b.azimuths
    expected = np.clip(eq.delta_r * np.cos(psi), 0.0, None)
    assert eq.deflection.clip(0.0) == pytest.approx(expected, rel=1e-9, abs=1e-15)
    assert np.abs(eq.contact_angles).max() < 1e-9
    assert (eq.loads * np.cos(psi)).sum() == pytest.approx(1000.0, rel=1e-9)
    assert int((eq.loads > 0).sum()) == 3           # psi = 0, +-51.4 deg


@pytest.mark.parametrize("example", [5, 7])
def test_tilt_needs_the_pitch_radius(example):
    """The published tilts (Examples 5 and 7) need R = D_pw/2 in the tilt kinematics (the TS's moment arm): with
    R = R_i = D_pw/2 + (r_i - D_w/2) cos(alpha_0) the same R theta is reached with theta smaller by
    (D_pw/2)/R_i = 0.9895, i.e. 1 % off the printed value, 30 times the band of test_published_ball_bearing_example."""
    _, clearance, fr, fa, mx, published = EXAMPLES[example - 1]
    b = ib.radial_ball_bearing(Z, DW, DPW, clearance)
    cp = ib.spring_constant(E, NU, DW, DPW, b.inner_groove, b.outer_groove, constant=ib.HERTZ_CONSTANT)
    eq = ib.ball_equilibrium(b, cp, fr, fa, 0.0, mx, radius="groove")
    ratio = 0.5 * DPW / b.inner_groove_centre_radius
    assert eq.misalignment * 1e3 / published["tilt"] == pytest.approx(ratio, abs=1e-3)
