"""3D half-space engine against independent values: elliptic Hertz checked by integrating its own pressure's
displacement (Boussinesq, polar quadrature), Love's kernel against adaptive quadrature, the BEM against Hertz."""
import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic.hertz import elliptic_contact, point_contact
from femcheck.bem.halfspace import grid, solve
from femcheck.bem.influence import love_rectangle
from femcheck.errors import InputError
from femcheck.qoi import ellipse_fit
from femcheck.scene import load_scene


def test_sphere_by_hand():
    # a = (3 P R / 4 E*)^(1/3) = (3 * 1000 * 0.01 / 4.61538e11)^(1/3) = 4.0207e-4 m; p0 = 3P/(2 pi a^2) = 2.9535 GPa
    h = point_contact(1000.0, 0.01, 210e9 / (2 * 0.91))
    assert h.semi_axis_x == pytest.approx(4.0207e-4, rel=1e-4)
    assert h.p_max == pytest.approx(2.9535e9, rel=1e-4)
    assert h.approach == pytest.approx(h.semi_axis_x**2 / 0.01, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [1.0, 3.0, 40.0, 500.0])
def test_elliptic_hertz_satisfies_contact_equations(ratio):
    """Independent check: the displacement of p0 sqrt(1 - x^2/a^2 - y^2/b^2), integrated numerically
    (u = 1/(pi E*) int p / r dA in polar coordinates around the point), must equal delta - x^2/2Rx - y^2/2Ry
    inside the contact; and int p dA = P."""
    E, P, Rx = 1e11, 500.0, 0.01
    h = elliptic_contact(P, Rx, Rx * ratio, E)
    a, b = h.semi_axis_x, h.semi_axis_y
    assert 2 / 3 * np.pi * a * b * h.p_max == pytest.approx(P, rel=1e-12)
    for fx, fy in ((0.0, 0.0), (0.5, 0.2), (-0.3, 0.7)):
        x0, y0 = fx * a, fy * b

        def inner(theta):
            c, s = np.cos(theta), np.sin(theta)
            # distance to the ellipse edge along the ray: quadratic in rho
            A = (c / a) ** 2 + (s / b) ** 2
            B = 2 * (x0 * c / a**2 + y0 * s / b**2)
            C = (x0 / a) ** 2 + (y0 / b) ** 2 - 1
            rmax = (-B + np.sqrt(B * B - 4 * A * C)) / (2 * A)
            return integrate.quad(lambda r: h.pressure(x0 + r * c, y0 + r * s), 0, rmax, limit=200)[0]

        u = integrate.quad(inner, 0, 2 * np.pi, limit=400, epsrel=1e-11)[0] / (np.pi * E)
        expected = h.approach - x0**2 / (2 * h.Rx) - y0**2 / (2 * h.Ry)
        assert u == pytest.approx(expected, rel=2e-8)


def test_elliptic_axes_orientation_and_symmetry():
    h1 = elliptic_contact(100.0, 0.01, 0.05, 1e11)
    h2 = elliptic_contact(100.0, 0.05, 0.01, 1e11)
    assert h1.semi_axis_y > h1.semi_axis_x                   # elongated across the larger radius
    assert h1.semi_axis_x == pytest.approx(h2.semi_axis_y, rel=1e-12)
    assert h1.p_max == pytest.approx(h2.p_max, rel=1e-12)


@pytest.mark.parametrize("tx,ty", [(0.2, 0.7), (0.5, 0.0), (3.0, -2.0), (20.0, 30.0), (-1.1, 0.3)])
def test_love_rectangle_matches_quadrature(tx, ty):
    dx, dy = 1.0, 3.0
    ref = integrate.dblquad(lambda y, x: 1 / np.hypot(tx - x, ty - y), -dx / 2, dx / 2, -dy / 2, dy / 2,
                            epsabs=1e-12)[0] / np.pi
    assert love_rectangle(tx, ty, dx, dy, 1.0) == pytest.approx(ref, rel=1e-9)


def test_love_rectangle_centre_of_square():
    # Centre of a square of side 2c: each quadrant gives int int dA/r = 2 int_0^(pi/4) c / cos(t) dt
    # = 2 c ln(1 + sqrt 2), so u = 8 c ln(1 + sqrt 2) / (pi E*) per unit pressure.
    assert love_rectangle(0.0, 0.0, 2.0, 2.0, 1.0) == pytest.approx(8 / np.pi * np.log(1 + np.sqrt(2)), rel=1e-14)


def test_ellipse_fit_exact_on_hertz_field():
    X, Y = np.meshgrid(np.linspace(-2, 2, 41), np.linspace(-1, 1, 31), indexing="ij")
    p = np.sqrt(np.clip(1 - (X / 1.37) ** 2 - (Y / 0.61) ** 2, 0, None))
    f = ellipse_fit(X, Y, p)
    assert f["semi_axis_x"] == pytest.approx(1.37, rel=1e-10)
    assert f["semi_axis_y"] == pytest.approx(0.61, rel=1e-10)
    assert f["fit_residual"] < 1e-12


def test_warm_start_gives_same_solution():
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 65, 65)
    gap = lambda X, Y: (X * X + Y * Y) / 0.02
    cold = solve(g, gap, h.modulus, 1000.0)
    warm = solve(g, gap, h.modulus, 1000.0, warm_levels=2)      # 65 -> 33; 17 is below min_cells
    assert [lv["nx"] for lv in warm.stats["levels"]] == [33, 65]
    np.testing.assert_allclose(warm.result.pressure, cold.result.pressure, atol=1e-7 * h.p_max)


@pytest.mark.parametrize("scene,tol", [("hertz-point", 1e-3), ("hertz-elliptic", 1e-2)])
def test_bem_matches_hertz(femcheck_run, femcheck_assert_agree, scene, tol):
    res = femcheck_run(scene)
    for q in ("p_max", "semi_axis_x", "semi_axis_y", "approach"):
        femcheck_assert_agree(res, q, "bem", "analytic", rtol=tol)


def test_elliptic_ratio_400_on_coarse_grid(femcheck_run, femcheck_assert_agree):
    # Issue 3: semi-axes and p_max within 1 % of exact Hertz at Ry/Rx = 400; here on a 33 x 33 grid.
    res = femcheck_run("hertz-elliptic", {"numerics.bem_cells": 33})
    for q in ("p_max", "semi_axis_x", "semi_axis_y"):
        femcheck_assert_agree(res, q, "bem", "analytic", rtol=0.01)


def test_point_scene_refuses_conflicting_geometry():
    with pytest.raises(InputError, match="geometry.radius"):
        load_scene("hertz-point", {"geometry.Rx": 0.01})
    with pytest.raises(InputError, match="both bodies rigid"):
        load_scene("hertz-point", {"materials.body1.rigid": True, "materials.body2.rigid": True})
    with pytest.raises(InputError, match="load.normal"):
        load_scene("hertz-point", {"load.normal": 1e9})


def test_approach_control_reproduces_load_control():
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 49, 49)
    gap = lambda X, Y: (X * X + Y * Y) / 0.02
    by_load = solve(g, gap, h.modulus, 1000.0).result
    by_approach = solve(g, gap, h.modulus, None, approach=by_load.approach).result
    assert by_approach.load == pytest.approx(1000.0, rel=1e-8)
    np.testing.assert_allclose(by_approach.pressure, by_load.pressure, atol=1e-6 * h.p_max)


def test_approach_control_against_hertz_load():
    # Hertz: delta = a^2 / R carries P; the BEM at a/dx = 26 must carry P within 0.1 %.
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 65, 65)
    res = solve(g, lambda X, Y: (X * X + Y * Y) / 0.02, h.modulus, None, approach=h.approach).result
    assert res.load == pytest.approx(1000.0, rel=1e-3)


def test_approach_that_never_touches_is_refused():
    g = grid(1e-3, 1e-3, 17, 17)
    with pytest.raises(ValueError, match="no contact"):
        solve(g, lambda X, Y: 1e-6 + (X * X + Y * Y) / 0.02, 1e11, None, approach=1e-7)


def _boussinesq(x, y, z, nu):
    """Point-load stresses, Johnson (1985) eq 3.22 in cylindrical form rotated to Cartesian (unit load)."""
    r2 = x * x + y * y
    r, rho, c = np.sqrt(r2), np.sqrt(r2 + z * z), 1 / (2 * np.pi)
    sr = c * ((1 - 2 * nu) / r2 * (1 - z / rho) - 3 * z * r2 / rho**5)
    st = -c * (1 - 2 * nu) * ((1 - z / rho) / r2 - z / rho**3)
    trz = -3 * c * r * z * z / rho**5
    co, si = x / r, y / r
    return {"sigma_x": sr * co * co + st * si * si, "sigma_y": sr * si * si + st * co * co,
            "sigma_z": -3 * c * z**3 / rho**5, "tau_xy": (sr - st) * co * si, "tau_xz": trz * co,
            "tau_yz": trz * si}


@pytest.mark.parametrize("tx,ty,z", [(0.3, 0.4, 0.7), (2.0, -1.3, 0.5), (0.1, 0.05, 1.3), (-0.45, 0.9, 0.05)])
def test_rectangle_stress_kernels_match_boussinesq_quadrature(tx, ty, z):
    from femcheck.bem.stress import rectangle_stress

    k = rectangle_stress(tx, ty, z, 1.0, 2.0, 0.3)
    for name, value in k.items():
        ref = integrate.dblquad(lambda eta, xi: _boussinesq(tx - xi, ty - eta, z, 0.3)[name], -0.5, 0.5, -1.0, 1.0,
                                epsabs=1e-13, epsrel=1e-11)[0]
        assert float(value) == pytest.approx(ref, abs=1e-11)


def test_sphere_axis_textbook_maxima():
    from femcheck.analytic.stress import hertz_sphere_maxima

    m = hertz_sphere_maxima(1.0, 1.0, 0.3)      # Johnson 1985 §4.2: tau_1 = 0.31 p0 at z = 0.48 a (nu = 0.3)
    assert m["tau_max"] == pytest.approx(0.31, abs=0.002)
    assert m["tau_max_depth"] == pytest.approx(0.48, abs=0.005)


def test_bem_subsurface_stress_matches_closed_form(femcheck_run, femcheck_assert_agree):
    # Issue 3: maximum von Mises and its depth within 1 % of the closed form for hertz-point.
    res = femcheck_run("hertz-point")
    for q in ("von_mises_max", "von_mises_max_depth", "tau_max"):
        femcheck_assert_agree(res, q, "bem", "analytic", rtol=0.01)
    at = res.models["bem"].stats["stress"]["von_mises_max_at"]
    assert abs(at["x"]) < 1e-12 and abs(at["y"]) < 1e-12            # on the axis
