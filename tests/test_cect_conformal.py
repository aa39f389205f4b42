"""Conformal CECT (femcheck.cect.conformal, influence_conformal): the planar limit bit for bit, the kappa row
scaling, the frictionless limit against elliptic Hertz on seed 000's raceways, the angle-corrected influence
coefficients and the 3D resultants (spec srb-rolling §4.2-4.3, checks 5-7 of §10.1)."""
import numpy as np
import pytest

from femcheck.analytic.hertz import elliptic_contact
from femcheck.bem.halfspace import grid as make_grid
from femcheck.cect.conformal import GridTooSmall, resultants, solve_conformal
from femcheck.cect.exact import solve_contact
from femcheck.cect.influence import combined_constants
from femcheck.cect import influence_conformal
from femcheck.cect.influence_conformal import block_operator, dense_block
from femcheck.geometry import srb_bearing as sb
from femcheck.geometry.conformal_surface import developed_grid, undeformed_distance
from femcheck.materials import Elastic
from femcheck.problems import point_tangential as pt
from femcheck.qoi import contact_edge, half_width
from femcheck.scene import load_scene

STEEL = combined_constants(Elastic(207e9, 0.3), Elastic(207e9, 0.3))
B = sb.SEED_000
OMEGA_I = sb.OMEGA_INNER_SEED_000


def _creep_curve(n):
    p = load_scene("creep-curve").params
    h = pt._hertz(p)
    rx, ry = pt.radii(p)
    g = make_grid(1.1 * h.semi_axis_x, 1.1 * h.semi_axis_y, n, n)
    X, Y = g.mesh()
    return p, g, X * X / (2 * rx) + Y * Y / (2 * ry), X, Y


@pytest.mark.parametrize("solver,n", [("dense", 21), ("fft", 31)])
def test_kappa_one_reproduces_the_planar_exact_solver_bit_for_bit(solver, n):
    # check 5: the creep-curve scene (xi, eta, phi, mu = 0.3) by the planar solver and by the conformal solver
    # with kappa = 1, the Hertz quadratic gap and the planar rigid slip: identical tractions
    p, g, h, X, Y = _creep_curve(n)
    cc = pt._constants(p)
    xi, eta, phi = pt.creepages(p)
    ref = solve_contact(g, lambda x, y: h, cc, p["load.normal"], p["friction.mu"], creepages=(xi, eta, phi),
                        tangential_solver=solver)
    slip = np.stack([xi - phi * Y, eta + phi * X])
    for kappa in (None, np.ones(g.ny)):
        res = solve_conformal(g, h, cc, p["friction.mu"], slip, 1.0, kappa, load=p["load.normal"],
                              tangential_solver=solver)
        assert res.stats["tangential_solver"] == ref.stats["tangential_solver"] == solver
        np.testing.assert_array_equal(res.pressure, ref.pressure)
        np.testing.assert_array_equal(res.px, ref.px)
        np.testing.assert_array_equal(res.ps, ref.py)
        np.testing.assert_array_equal(res.adhesion, ref.adhesion)
        assert res.frictional_power == ref.frictional_power


@pytest.mark.parametrize("solver,n", [("dense", 21), ("fft", 31)])
def test_uniform_kappa_with_scaled_slip_gives_the_same_tractions(solver, n):
    # check 6: s = c w + c (u - u')/dx has the zeros and directions of w + (u - u')/dx, so a uniform kappa = c
    # with rigid slip c w must reproduce the kappa = 1 solution (catches a kappa missing from either path)
    p, g, h, X, Y = _creep_curve(n)
    cc = pt._constants(p)
    xi, eta, phi = pt.creepages(p)
    slip = np.stack([xi - phi * Y, eta + phi * X])
    base = solve_conformal(g, h, cc, p["friction.mu"], slip, 1.0, None, load=p["load.normal"], tangential_solver=solver)
    c = 0.93
    scaled = solve_conformal(g, h, cc, p["friction.mu"], c * slip, 1.0, np.full(g.ny, c), load=p["load.normal"],
                             tangential_solver=solver)
    scale = np.abs(base.px).max()
    assert np.abs(scaled.px - base.px).max() < 1e-8 * scale and np.abs(scaled.ps - base.ps).max() < 1e-8 * scale
    # and it is not a trivial identity: the same slip without the kappa scaling gives other tractions
    other = solve_conformal(g, h, cc, p["friction.mu"], c * slip, 1.0, None, load=p["load.normal"],
                            tangential_solver=solver)
    assert np.abs(other.px - base.px).max() > 1e-3 * scale


def _contact(contact, nx, ns, omega_scale=(1.0, 1.0), pose=sb.Pose()):
    om, orr = sb.nominal_speeds(B, OMEGA_I)
    h = elliptic_contact(5500.0, *sb.hertz_radii(B)[contact], STEEL.contact_modulus)
    ci = sb.contact_input(B, pose, contact, om * omega_scale[0], orr * omega_scale[1], OMEGA_I, 0.0,
                          1.35 * h.semi_axis_x, 1.25 * h.semi_axis_y, nx, ns)
    dg = ci.grid
    n0 = dg.surface.normal(0.0)

    def gap(d):        # the roller approaches the ring by d along the nominal normal
        return undeformed_distance(dg, ci.roller.translated(-d * n0), ci.ring)

    return ci, gap, h, np.broadcast_to(dg.normals @ n0, (nx, ns))


def _solve(contact, mu, nx=41, ns=81, kappa=True, influence="halfspace", solver="auto", **kw):
    ci, gap, h, wts = _contact(contact, nx, ns, **kw)
    r = solve_conformal(ci.grid.grid, gap, STEEL, mu, np.stack([ci.slip.wx, ci.slip.ws]), ci.speeds.reference,
                        ci.speeds.kappa if kappa else None, load=5500.0, load_weights=wts, approach0=h.approach,
                        influence=influence, radius=ci.grid.surface.radius, s=ci.grid.s, tangential_solver=solver)
    return r, ci, h


@pytest.mark.parametrize("influence", ["halfspace", "blanco"])
@pytest.mark.parametrize("contact", sb.CONTACTS)
def test_frictionless_limit_matches_elliptic_hertz(contact, influence):
    # check 7: mu = 1e-6 at the nominal pose, 5.5 kN along the nominal normal: semi-axes and p_max within 2 % of
    # elliptic Hertz, the contact-angle span 10.0 / 10.95 deg within 0.5 deg (spec). Measured at 41 x 81:
    # a -0.25 / -0.19 %, b -0.14 / -0.13 %, p_max +0.15 / +0.19 %, approach +0.21 / +0.26 %, span 10.005 /
    # 10.937 deg; asserted tighter (0.5-1 %) so that a 2 % error in the contact modulus (p_max, approach 1.3 %)
    # cannot pass
    r, ci, h = _solve(contact, 1e-6, influence=influence)
    s, x = ci.grid.s, ci.grid.x
    j = int(np.argmin(np.abs(s - r.pressure_centre)))
    a = half_width(x, r.pressure[:, j])
    ridge = r.pressure.max(axis=0)
    right, left = contact_edge(s, ridge), -contact_edge(-s[::-1], ridge[::-1])
    assert a == pytest.approx(h.semi_axis_x, rel=0.01)
    assert 0.5 * (right - left) == pytest.approx(h.semi_axis_y, rel=0.005)
    assert r.pressure.max() == pytest.approx(h.p_max, rel=0.005)
    assert r.approach == pytest.approx(h.approach, rel=0.006)
    span = np.degrees((right - left) / ci.grid.surface.radius)
    assert span == pytest.approx(10.0 if contact == "inner" else 10.95, abs=0.5)
    # the load is the pressure resultant along the nominal normal
    R = resultants(r, ci.grid, ci.roller.centre)
    assert R.force @ ci.grid.surface.normal(0.0) == pytest.approx(5500.0, rel=1e-7)
    assert r.stats["process"] == ("Johnson" if influence == "halfspace" else "Panagiotopoulos")


def test_dense_and_matrix_free_paths_agree_with_variable_kappa():
    # the same discrete equations (kappa rows, the Coulomb law) by LU and by Newton-GMRES: near-equilibrium
    # speeds (strip theory's) at mu = 0.3, where partial slip covers a quarter of the patch
    kw = dict(mu=0.3, nx=21, ns=41, omega_scale=(1 - 1.16e-5, 1 + 4.104e-3))
    d, ci, _ = _solve("inner", solver="dense", **kw)
    f, _, _ = _solve("inner", solver="fft", **kw)
    assert d.stats["tangential_solver"] == "dense" and f.stats["tangential_solver"] == "fft"
    assert 0.05 < d.adhesion_fraction < 0.95 and ci.speeds.kappa.min() < 0.97
    scale = np.abs(d.px).max()
    assert np.abs(d.px - f.px).max() < 1e-6 * scale and np.abs(d.ps - f.ps).max() < 1e-6 * scale


def test_variable_rolling_step_changes_the_contact_forces_little():
    # seed 000 §3.2.2: the variable dq "has little influence" here (kappa 0.96-1.00 over the patch). At the
    # strip-theory speeds (near the equilibrium, nominal pose, 41 x 81) kappa(s) against kappa = 1 changes the
    # net rolling-direction force F_x (a small difference of the opposing slip bands, 1-3 % of mu N) by
    # 0.6-0.8 N = 0.05-0.13 % of mu N and the lateral force F_s by 0.03-0.4 %. Whether f_x, sum f_lat and d_y
    # change by < 3 % at the equilibrium (spec check 6) is for the roller equilibrium to report.
    for mu, speeds in ((0.1, (1 - 6.64e-5, 1 + 3.695e-3)), (0.3, (1 - 1.16e-5, 1 + 4.104e-3))):
        for c in sb.CONTACTS:
            k, _, _ = _solve(c, mu, omega_scale=speeds)
            one, _, _ = _solve(c, mu, omega_scale=speeds, kappa=False)
            assert abs(k.force_x - one.force_x) < 3e-3 * mu * 5500.0
            assert k.force_s == pytest.approx(one.force_s, rel=0.03)
            assert abs(k.force_x - one.force_x) > 1e-5 * mu * 5500.0       # kappa does act


def test_angle_corrected_coefficients_rotate_the_source_traction_into_the_receiver_frame(monkeypatch):
    # spec §4.3 sign test: a traction field that is the same 3D vector f at every element must act, in the
    # "blanco" variant, as the half-space response to f resolved in the receiver's own frame; the variant with
    # the response rotated is its adjoint (Betti); the FFT operator equals the dense matrix
    ring = sb.ring_body(B, "inner")
    surf = sb.contact_surface(B, "inner", ring, 1.0)
    dg = developed_grid(surf, 0.3e-3, 10e-3, 5, 13)
    g = dg.grid
    cells = np.nonzero(np.ones((g.nx, g.ny), bool))
    frames = surf.frame(dg.s)                                   # rows e_x, t, n per column
    f = np.array([0.3, -0.5, 1.0])
    local = frames @ f                                          # (ns, 3): local components of f
    P = np.stack([np.broadcast_to(local[:, k], (g.nx, g.ny)) for k in range(3)])
    B1 = dense_block(g, cells, STEEL, "xsn", "xsn", False, "blanco", surf.radius)
    A = dense_block(g, cells, STEEL, "xsn", "xsn", False, "halfspace")
    u = (B1 @ P.reshape(-1)).reshape(3, g.nx, g.ny)
    for I in range(g.nx * g.ny):
        i, j = cells[0][I], cells[1][I]
        uniform = np.stack([np.full((g.nx, g.ny), local[j, k]) for k in range(3)]).reshape(-1)
        expected = (A @ uniform).reshape(3, g.nx, g.ny)[:, i, j]
        assert u[:, i, j] == pytest.approx(expected, rel=1e-12, abs=1e-12 * np.abs(u).max())
    B3 = dense_block(g, cells, STEEL, "xsn", "xsn", False, "rotated_response", surf.radius)
    assert np.abs(B3 - B1.T).max() < 1e-12 * np.abs(B1).max()
    op = block_operator(g, STEEL, "xsn", "xsn", False, "blanco", surf.radius)
    assert np.abs(op(P).reshape(-1) - B1 @ P.reshape(-1)).max() < 1e-12 * np.abs(u).max()
    # the opposite sign of the rotation angle breaks the identity: the test fixes the sign
    rotation = influence_conformal._rotation
    monkeypatch.setattr(influence_conformal, "_rotation", lambda ts, radius: rotation(-np.asarray(ts), radius))
    flipped = dense_block(g, cells, STEEL, "xsn", "xsn", False, "blanco", surf.radius)
    assert np.abs(flipped @ P.reshape(-1) - u.reshape(-1)).max() > 1e-3 * np.abs(u).max()


def test_resultants_in_3d():
    # tractions at near-equilibrium speeds, mu = 0.1: the 3D sums against their local counterparts
    r, ci, _ = _solve("inner", 0.1, omega_scale=(1 - 6.64e-5, 1 + 3.695e-3))
    dg = ci.grid
    R = resultants(r, dg, ci.roller.centre)
    # force along the rolling direction = sum p_x dA exactly (e_x is uniform); lateral = sum p_s dA to
    # O((b/r_g)^2) (t(s) turns by up to 5 deg over the patch)
    assert R.force @ dg.surface.ex == pytest.approx(r.force_x, rel=1e-12)
    assert R.force @ dg.surface.tangent(0.0) == pytest.approx(r.force_s, rel=0.01)
    # moment about the roller centre along t(0): ((P - C) x p_x e_x).t = p_x (P - C).(e_x x t), e_x x t = -n for
    # the left-handed triad; the lever is about D/2 (less towards the patch ends: the profile curves away)
    n0 = dg.surface.normal(0.0)
    handed = np.cross(dg.surface.ex, dg.surface.tangent(0.0)) @ n0
    R_px = resultants(r, dg, ci.roller.centre, tractions=(r.px, 0 * r.ps, 0 * r.pressure))
    arm = (dg.points - ci.roller.centre) @ n0
    assert R_px.moment @ dg.surface.tangent(0.0) == pytest.approx(
        handed * float((r.px * arm).sum() * dg.grid.cell_area), rel=1e-10)
    assert np.all(np.abs(arm[r.contact] / (0.5 * B.roller_diameter) + 1.0) < 0.05)
    assert R.moment @ dg.surface.tangent(0.0) == pytest.approx(R_px.moment @ dg.surface.tangent(0.0), rel=1e-3)
    # spin moment about n(0): sum (x p_s - s p_x) dA in the local frame, sign -1 for the left-handed triad
    X, S = np.meshgrid(dg.x, dg.s, indexing="ij")
    local = handed * float(((X * r.ps - S * r.px).sum()) * dg.grid.cell_area)
    assert R.spin_moment == pytest.approx(local, rel=0.01)
    assert abs(R.spin_moment) > 0.1          # N m: spin is what drives the lateral creep here


def test_contact_reaching_the_grid_edge_is_refused():
    ci, gap, h, wts = _contact("inner", 21, 41)
    with pytest.raises(GridTooSmall) as err:
        solve_conformal(ci.grid.grid, gap, STEEL, 0.1, np.stack([ci.slip.wx, ci.slip.ws]), ci.speeds.reference,
                        load=4 * 5500.0, load_weights=wts, approach0=h.approach)
    assert "s-" in err.value.edges and "s+" in err.value.edges
