"""Seed-000 bearing in 3D (femcheck.geometry.srb_bearing, conformal_surface, revolution): the derived numbers of
spec srb-rolling §1.2 and the visible checks 1-4 of §10.1 (pose, exact gap, rigid slip)."""
import numpy as np
import pytest

from femcheck.analytic.hertz import elliptic_contact
from femcheck.geometry import srb_bearing as sb
from femcheck.geometry.conformal_surface import rigid_slip
from femcheck.geometry.revolution import CrownedBody, GroovedRing, ray_intersection
from femcheck.geometry.srb import radii as srb_normal_radii
from femcheck.scene import load_scene

B = sb.SEED_000
OMEGA_I = sb.OMEGA_INNER_SEED_000
E_STAR = 207e9 / (2 * (1 - 0.09))
MM = 1e-3


def nominal():
    om, orr = sb.nominal_speeds(B, OMEGA_I)
    return om, orr


def test_section_1_2_numbers_within_1e_4():
    # spec §1.2 (values given to 5-6 digits: 1e-4; 4-digit values: half a unit of the last digit)
    assert B.pitch_radius == pytest.approx(90.6430 * MM, rel=1e-5)
    r = B.rolling_radii
    assert r["inner"] == pytest.approx(80.9418 * MM, rel=1e-5)
    assert r["outer"] == pytest.approx(100.3443 * MM, rel=1e-5)
    assert r["inner"] / np.cos(B.contact_angle) == pytest.approx(82.600 * MM, rel=1e-5)
    assert r["outer"] / np.cos(B.contact_angle) == pytest.approx(102.400 * MM, rel=1e-5)
    assert np.linalg.norm(B.nominal_centre) == pytest.approx(92.5 * MM, rel=1e-12)
    assert B.inner_groove_distance == pytest.approx(185.6 * MM, rel=1e-12)
    g = sb.ring_body(B, "inner")
    assert (g.groove_axial, g.groove_radial) == pytest.approx((-37.004 * MM, 181.875 * MM), rel=1e-4)
    assert OMEGA_I == pytest.approx(49.8675, rel=1e-5)
    om, orr = nominal()
    assert om == pytest.approx(22.2652, rel=1e-5)
    assert om * 60 / (2 * np.pi) == pytest.approx(212.62, rel=1e-4)
    assert orr == pytest.approx(-225.675, rel=1e-5)
    assert orr * 60 / (2 * np.pi) == pytest.approx(-2155.0, rel=1e-4)
    assert (OMEGA_I - om) * r["inner"] == pytest.approx(2.23418, rel=1e-5)
    assert om * r["outer"] == pytest.approx(2.23418, rel=1e-5)
    Fc = sb.centrifugal_force(B, sb.Pose(), om)
    assert Fc == pytest.approx([0.0, 0.0, 2.948], rel=1e-3, abs=1e-12)     # 4 digits
    assert np.linalg.norm(Fc) == pytest.approx(2.94775, rel=1e-4)
    Mg = sb.gyroscopic_moment(B, sb.Pose(), om, orr)
    assert Mg[0] == pytest.approx(5.880e-3, rel=2e-4) and abs(Mg[1]) + abs(Mg[2]) < 1e-15   # +X (paper §2)
    rad = sb.hertz_radii(B)
    assert rad["inner"] == pytest.approx((8.8404 * MM, 3826.26 * MM), rel=1e-5)
    assert rad["outer"] == pytest.approx((10.9596 * MM, 4890.82 * MM), rel=1e-5)
    # the same radii as srb-normal's geometry (which its stored references hash)
    sr = srb_normal_radii(load_scene("srb-normal").params)
    for c in sb.CONTACTS:
        assert rad[c] == pytest.approx(sr[c], rel=1e-12)
    assert E_STAR == pytest.approx(113.736e9, rel=1e-5)
    for c, (a, b, p0, d) in {"inner": (0.21281, 9.0052, 1.3703, 13.16), "outer": (0.22729, 9.7867, 1.1806, 12.15)}.items():
        h = elliptic_contact(5500.0, *rad[c], E_STAR)
        assert h.semi_axis_x == pytest.approx(a * MM, rel=1e-4)
        assert h.semi_axis_y == pytest.approx(b * MM, rel=1e-4)
        assert h.p_max == pytest.approx(p0 * 1e9, rel=1e-4)
        assert h.approach == pytest.approx(d * 1e-6, rel=5e-4)
        span = np.degrees(2 * h.semi_axis_y / (B.groove_radius_inner if c == "inner" else B.groove_radius_outer))
        assert span == pytest.approx(10.0 if c == "inner" else 10.95, abs=0.05)
    # spin about the normal into the roller at the nominal pose
    assert (OMEGA_I - om) * np.sin(B.contact_angle) == pytest.approx(5.503, rel=1e-4)
    assert om * np.sin(B.contact_angle) == pytest.approx(4.439, rel=1e-4)


def test_frames_and_nominal_points():
    # spec §2.1 (given to 1 um, last digit not rounded consistently: -20.416 is 20.4153, -16.467 is 16.4678 mm)
    assert B.nominal_point("outer") == pytest.approx(np.array([0, -20.416, 100.344]) * MM, abs=1e-3 * MM)
    assert B.nominal_point("inner") == pytest.approx(np.array([0, -16.467, 80.942]) * MM, abs=1e-3 * MM)
    a = B.contact_angle
    assert B.nominal_point("outer") == pytest.approx(B.groove_radius_outer * np.array([0, -np.sin(a), np.cos(a)]),
                                                     rel=1e-14)
    # the nominal points lie on both the roller and their raceway
    roller = sb.roller_body(B, sb.Pose())
    for c in sb.CONTACTS:
        P = B.nominal_point(c)
        assert abs(roller.implicit(P)) < 1e-15 and abs(sb.ring_body(B, c).implicit(P)) < 1e-15
    # pose: tilt and skew turn the axis as v = (-sin g, cos b cos g, sin b cos g) in {x, y, z}
    b_, g_ = 1e-3, -2e-3
    v = sb.roller_frame(B, sb.Pose(tilt=b_, skew=g_))[1]
    comps = [v @ B.e_x, v @ B.e_y, v @ B.e_z]
    assert comps == pytest.approx([-np.sin(g_), np.cos(b_) * np.cos(g_), np.sin(b_) * np.cos(g_)], abs=1e-15)
    d_y, d_z = sb.roller_offsets(B, sb.Pose(d_Y=2e-6, d_Z=-1e-6))
    a = B.contact_angle
    assert d_y == pytest.approx(2e-6 * np.cos(a) - 1e-6 * np.sin(a), rel=1e-12)
    assert d_z == pytest.approx(-2e-6 * np.sin(a) - 1e-6 * np.cos(a), rel=1e-12)


def _grid(contact, pose=sb.Pose(), nx=21, ns=81, half_x=0.3 * MM, half_s=2.0 * MM):
    om, orr = nominal()
    return sb.contact_input(B, pose, contact, om, orr, OMEGA_I, 0.0, half_x, half_s, nx, ns)


@pytest.mark.parametrize("contact", sb.CONTACTS)
def test_gap_at_the_nominal_pose_matches_the_hertz_radii(contact):
    # check 2: h >= 0 with its minimum 0 at (0, 0); h(0, s) = s^2/(2 Ry), h(x, 0) = x^2/(2 Rx) within 1 %
    ci = _grid(contact)
    h, dg = ci.gap, ci.grid
    i0, j0 = dg.grid.nx // 2, dg.grid.ny // 2
    assert h.min() >= -1e-18 and abs(h[i0, j0]) < 1e-18 and np.unravel_index(h.argmin(), h.shape) == (i0, j0)
    rx, ry = sb.hertz_radii(B)[contact]
    s, x = dg.s, dg.x
    lat = h[i0, s != 0] / (s[s != 0] ** 2 / (2 * ry))
    lon = h[x != 0, j0] / (x[x != 0] ** 2 / (2 * rx))
    assert np.abs(lat - 1).max() < 0.01 and np.abs(lon - 1).max() < 0.01
    # the exact conformal gap departs from the quadratic by O(s^2/r^2): measurable but small here
    assert np.abs(lat - 1).max() > 1e-6


@pytest.mark.parametrize("contact,factor", [("inner", 38.1), ("outer", 48.8)])
def test_axial_roller_shift_moves_the_contact_along_the_groove(contact, factor):
    # check 3: a rigid translation d e_y of the roller moves the zero-gap point by d r_g/(r_g - R) along s
    d = 1e-6
    pose = sb.Pose(d_Y=d * np.cos(B.contact_angle), d_Z=d * np.sin(B.contact_angle))   # = d e_y
    ci = _grid(contact, pose, nx=3, ns=801, half_s=0.2 * MM)
    h = ci.gap[1]
    k = int(np.argmin(h))
    s = ci.grid.s
    c = np.polyfit(s[k - 3:k + 4], h[k - 3:k + 4], 2)
    shift = -c[1] / (2 * c[0])
    rg = B.groove_radius_inner if contact == "inner" else B.groove_radius_outer
    assert shift == pytest.approx(d * rg / (rg - B.crown_radius), rel=0.01)
    assert shift / d == pytest.approx(factor, rel=0.01)


@pytest.mark.parametrize("contact,spin", [("inner", 5.503), ("outer", 4.439)])
def test_rigid_slip_at_the_nominal_state(contact, spin):
    # check 4: w_x(0, 0) = 0 at the nominal speeds; the spin gives dw_s/dx at the centre; w_x(0, s)/V_c(s)
    # equals eq 7 (with femcheck's sign: w = v_roller - v_ring along e_x, the material flowing along -e_x)
    ci = _grid(contact)
    dg, w = ci.grid, ci.slip
    i0, j0 = dg.grid.nx // 2, dg.grid.ny // 2
    assert abs(w.wx[i0, j0]) < 1e-12
    dwsdx = (w.ws[i0 + 1, j0] - w.ws[i0 - 1, j0]) / (2 * dg.grid.dx)
    # both local triads (e_x, t, n) are left-handed (x_I = -X, x_E = +X, s towards the mid-plane, n into the
    # roller), so dw_s/dx = -(spin about n); the spin about n is the spec's 5.503 / 4.439 rad/s
    assert np.cross(dg.surface.ex, dg.surface.tangent(0.0)) @ dg.surface.normal(0.0) == pytest.approx(-1.0)
    assert dwsdx == pytest.approx(-spin, rel=2e-4)
    v = ci.speeds
    xi7 = 2 * (v.roller - v.ring) / (v.roller + v.ring)                      # seed 000 eq 7
    assert np.abs(w.wx[i0] / v.mean + xi7).max() < 1e-12
    assert v.kappa[j0] == pytest.approx(1.0, abs=1e-12) and v.reference == pytest.approx(2.23418, rel=1e-5)


def test_eqs_14_15_equal_the_vector_form_on_random_states():
    # check 4: seed 000 eqs 12-15 (with E2: sqrt(w_X^2 + w_Y^2) in eq 13, and E6: theta from -w' towards -u')
    # equal the vector form w = v_P/j + omega_R/j x (I - P) used by geometry.conformal_surface.rigid_slip
    rng = np.random.default_rng(11)
    om0, or0 = nominal()
    worst = 0.0
    for _ in range(1000):
        pose = sb.Pose(*(rng.normal(size=2) * 20e-6), *(rng.normal(size=2) * 2e-3))
        om, orr = om0 * (1 + 0.01 * rng.normal()), or0 * (1 + 0.01 * rng.normal())
        contact = sb.CONTACTS[rng.integers(2)]
        ci = _grid(contact, pose, nx=3, ns=3, half_x=0.5 * MM, half_s=10 * MM)
        dg = ci.grid
        i, j = rng.integers(3), rng.integers(3)
        I = dg.points[i, j]
        C, v = ci.roller.centre, ci.roller.axis
        rate = sb.ring_rate(contact, om, OMEGA_I, 0.0)
        w_vec = rigid_slip(dg, ci.roller, orr, ci.ring, rate)
        # eqs 12-15 with P = the roller centre
        omega = -rate * sb.Y + orr * v
        vP = -rate * np.cross(sb.Y, C - ci.ring.origin)
        psi = np.arctan(-omega[0] / omega[1])
        phi = np.sign(omega[2]) * np.arccos(np.sign(omega[1]) * np.hypot(omega[0], omega[1]) / np.linalg.norm(omega))
        u1 = np.array([np.cos(psi), np.sin(psi), 0.0])
        v1 = np.array([-np.sin(psi) * np.cos(phi), np.cos(psi) * np.cos(phi), np.sin(phi)])
        w1 = np.cross(u1, v1)
        r = I - C
        rp = r - (r @ v1) * v1
        R_I = np.linalg.norm(rp)
        theta = np.arctan2(-(rp @ u1), -(rp @ w1))
        t = dg.tangents[j]
        delta = np.arctan2(t[2], t[1])
        wn = np.linalg.norm(omega)
        wx14 = vP[0] + wn * R_I * (-np.cos(theta) * np.cos(psi) + np.sin(theta) * np.sin(psi) * np.sin(phi))
        ws15 = (vP[1] * np.cos(delta) + vP[2] * np.sin(delta) + wn * R_I * (
            -np.cos(delta) * np.cos(theta) * np.sin(psi) - np.cos(delta) * np.sin(theta) * np.cos(psi) * np.sin(phi)
            + np.sin(delta) * np.sin(theta) * np.cos(phi)))
        worst = max(worst, abs(wx14 - w_vec.wx[i, j] * (dg.surface.ex @ sb.X)), abs(ws15 - w_vec.ws[i, j]))
    assert worst < 1e-12


def test_kappa_range_over_the_hertz_patch():
    # the local rolling speed varies by a few % over +-1.25 b_H (spec §2.5: kappa 0.960-1.002 inner,
    # 0.949-1.001 outer at 5.5 kN, prototype); V(s) is quadratic (crown) plus linear (ring radius ~ sin a)
    om, orr = nominal()
    for c, (lo, hi) in {"inner": (0.960, 1.002), "outer": (0.949, 1.001)}.items():
        h = elliptic_contact(5500.0, *sb.hertz_radii(B)[c], E_STAR)
        ci = sb.contact_input(B, sb.Pose(), c, om, orr, OMEGA_I, 0.0, 1.35 * h.semi_axis_x, 1.25 * h.semi_axis_y,
                              3, 121)
        k = ci.speeds.kappa
        assert k.min() == pytest.approx(lo, abs=0.004) and k.max() == pytest.approx(hi, abs=0.002)


def test_straight_rail_and_wheel_profiles():
    # a wheel-like crown (R < r) on a straight grooved rail: the exact gap is the Hertz quadratic near the
    # contact with 1/Ry = 1/R - 1/r_g and 1/Rx = 1/r (the rail is straight along x)
    r, R, rg = 0.05, 0.03, 0.032
    wheel = CrownedBody(np.array([0.0, 0.0, r]), np.array([0.0, 1.0, 0.0]), r, R)
    rail = GroovedRing(np.zeros(3), np.array([0.0, 1.0, 0.0]), 0.0, rg, rg, rail_height=np.array([0.0, 0.0, 1.0]))
    assert rail.straight and np.isinf(rail.radius_at(np.zeros(3)))
    x = np.linspace(-1e-3, 1e-3, 5)
    s = np.linspace(-0.5e-3, 0.5e-3, 5)
    X, S = np.meshgrid(x, s, indexing="ij")
    P = np.stack([X, S, np.zeros_like(X)], axis=-1)
    n = np.array([0.0, 0.0, 1.0])
    h = ray_intersection(wheel, P, n) - ray_intersection(rail, P, n)
    ry = 1 / (1 / R - 1 / rg)
    quad = X ** 2 / (2 * r) + S ** 2 / (2 * ry)
    assert np.abs(h - quad).max() < 0.01 * quad.max()
    # the rail translates: its velocity is uniform
    assert rail.velocity(P, 3.0) == pytest.approx(np.broadcast_to([3.0, 0, 0], P.shape))
