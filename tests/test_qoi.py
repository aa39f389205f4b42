"""Shape-agnostic estimators of contact edge and peak pressure (femcheck.qoi, issue 12 finding 2) on fields with
known answers that are not Hertzian: the flat punch (inverse square-root edge, singular peak), a thin layer on a
rigid base (parabolic pressure), layered contacts, and Hertz. Criterion of the issue: the known edge and peak
within 0.5 % at the default resolutions of the models that use them."""
import numpy as np
import pytest

from femcheck import qoi
from femcheck.analytic import layer_plane
from femcheck.bem.line import solve_line_contact
from femcheck.runner import run

# p = (1 - x^2/a^2)^alpha: Hertz 1/2, Winkler (thin compressible layer) 1, squeeze film 2, flat punch -1/2
FAMILIES = [("hertz", 0.5), ("winkler", 1.0), ("squeeze film", 2.0), ("flat punch", -0.5)]


def _field(x, a, alpha):
    inside = np.abs(x) < a
    return np.where(inside, np.clip(1.0 - (x / a) ** 2, 1e-300, None) ** alpha, 0.0)


@pytest.mark.parametrize("name, alpha", FAMILIES)
@pytest.mark.parametrize("offset", [0.0, 0.37, 0.81])
def test_power_law_edges_are_exact_whatever_the_exponent(name, alpha, offset):
    # point samples (BEM collocation) at a/dx = 20, the grid shifted against the edge
    a = 1.3e-4
    x = (np.arange(-30, 31) + offset) * a / 20
    e_right, e_left = qoi.edges(x, _field(x, a, alpha))
    for e in (e_right, e_left):
        assert e.fitted and e.position == pytest.approx(a, rel=1e-6)
        assert e.exponent == pytest.approx(alpha, abs=1e-4)
        assert e.singular == (alpha < 0)


def test_hertzian_p2_fit_is_off_on_a_parabolic_field():
    # the former estimator (least squares of p^2 near the edge) assumes Hertz: on Johnson's parabolic thin-layer
    # pressure it is short by ~1 %; the power-law estimator is exact
    a = 1.0
    x = np.linspace(0.0, 1.3, 27)
    p = _field(x, a, 1.0)
    assert abs(qoi.contact_edge(x, p) / a - 1) > 5e-3
    assert qoi.edge(x, p).position == pytest.approx(a, rel=1e-9)


@pytest.mark.parametrize("name, alpha, bias", [("parabola", 1.0, 1e-12), ("hertz", 0.5, 1e-4),
                                               ("flat punch", -0.5, 3e-4)])
def test_centre_value_of_smooth_fields(name, alpha, bias):
    a = 2.0e-4
    x = np.linspace(-a, a, 801)[1:-1]
    c = qoi.centre_value(x, _field(x, a, alpha), 0.5 * a)
    assert abs(c.value - 1.0) < bias


def test_peak_off_the_centre_and_singular_peaks():
    x = np.linspace(-1.0, 1.0, 401)
    p = (1 - x**2) * (1 + 3 * x**2)                  # two maxima at x = +-sqrt(1/3), p = 4/3
    pk = qoi.peak(x, p, centre=0.0)
    assert not pk.singular and pk.value == pytest.approx(4 / 3, rel=1e-6)
    assert abs(pk.position) == pytest.approx(np.sqrt(1 / 3), abs=5e-3)
    punch = qoi.peak(x, _field(x, 1.001, -0.5), centre=0.0)
    assert punch.singular and punch.points == 1
    # a symmetric half model (x >= 0) peaks on its symmetry line: a smooth maximum, not an edge
    half = x[x >= 0]
    for pk in (qoi.peak(half, _field(half, 0.8, 0.5), centre=0.0), qoi.peak(half, (1 - half**2) * (1 + 3 * half**2),
                                                                             centre=0.0)):
        assert not pk.singular and pk.points > 5
    assert qoi.peak(half, _field(half, 0.8, 0.5), centre=0.0).value == pytest.approx(1.0, abs=1e-4)
    assert qoi.peak(half, _field(half, 0.8, -0.5), centre=0.0).singular


def test_elliptic_fields_in_2d_full_and_quarter():
    # semi-axes 1.37 and 0.61, Hertz and parabolic (thin layer on a rigid base): strips along both axes
    g = np.linspace(-2.0, 2.0, 81)
    X, Y = np.meshgrid(g, np.linspace(-1.0, 1.0, 61), indexing="ij")
    r2 = (X / 1.37) ** 2 + (Y / 0.61) ** 2
    for alpha in (0.5, 1.0):
        p = np.where(r2 < 1, np.clip(1 - r2, 0, None) ** alpha, 0.0)
        full = qoi.symmetric_contact(X, Y, p)
        q = (X >= 0) & (Y >= 0)
        quarter = qoi.symmetric_contact(X[q], Y[q], p[q])
        for f in (full, quarter):
            assert f["semi_axis_x"] == pytest.approx(1.37, rel=1e-6)
            assert f["semi_axis_y"] == pytest.approx(0.61, rel=1e-6)
            assert f["p_max"] == pytest.approx(1.0, abs=1e-4)


def _flat_punch(n):
    # rigid flat punch of half-width b on a half-plane (Johnson eq. 2.64): p = W / (pi sqrt(b^2 - x^2))
    b, load, e_star = 1.0e-4, 1.0e5, 1.15e11
    sol = solve_line_contact(lambda x: np.where(np.abs(x) <= b, 0.0, 1e-3), e_star, load, 1.25 * b, n)
    return sol, b, load


def test_flat_punch_by_the_bem_at_the_default_resolution():
    sol, b, load = _flat_punch(1024)               # the line scenes' bem_elements
    p = sol.result.pressure
    right, left = qoi.edges(sol.x, p)
    for e in (right, left):
        assert e.singular and e.exponent == pytest.approx(-0.5, abs=0.02)
        assert e.position == pytest.approx(b, rel=5e-3)
    assert qoi.centre_value(sol.x, p, 0.5 * b).value == pytest.approx(load / (np.pi * b), rel=5e-3)
    pk = qoi.peak(sol.x, p, centre=0.0)
    assert pk.singular and abs(abs(pk.position) - b) < 2 * sol.dx     # reported as singular, at the edge


def test_thin_layer_on_a_rigid_base_against_the_fourier_solution(femcheck_run):
    # layer-rigid (h/a = 0.09; BEM 1024 strips) against the plane-strain transform solution of the bonded layer
    # (femcheck.analytic.layer_plane): the adapted power-law edge within 1e-3 (measured +3.8e-4), the peak within
    # 1e-5 (measured 3.4e-7). Johnson's thin-layer closed form is the h/a -> 0 limit: at h/a = 0.09 its edge lies
    # +1.1 % and its peak +0.07 % from the exact solution (measured), inside the scene's 5 % band for the closed form.
    res = femcheck_run("layer-rigid", models=["thin_layer", "bem"])
    bem, thin = res.models["bem"].quantities, res.models["thin_layer"].quantities
    exact = layer_plane.contact(210e9, 0.3, 2e-6, 0.01, 1e5)
    assert bem["half_width"] == pytest.approx(exact.a, rel=1e-3)
    assert bem["p_max"] == pytest.approx(exact.p_max, rel=1e-5)
    assert 5e-3 < thin["half_width"] / exact.a - 1 < 0.05
    assert thin["p_max"] == pytest.approx(exact.p_max, rel=2e-3)


def test_thin_layer_on_a_rigid_base_point_contact():
    # sphere on a 1 um layer on a rigid base (h/a = 0.025), layered BEM at the point scenes' 65 cells per side
    res = run("layer-point", {"materials.substrate.rigid": True, "layer.thickness": 1e-6,
                              "models.run": ["bem", "thin_layer"]}, models=["bem", "thin_layer"])
    bem, thin = res.models["bem"].quantities, res.models["thin_layer"].quantities
    for q in ("semi_axis_x", "semi_axis_y", "p_max"):
        assert bem[q] == pytest.approx(thin[q], rel=5e-3)


def test_layered_edge_is_stable_under_refinement():
    # layer-line (h/a = 0.27, E1/E2 = 2): no closed form; the estimator on the BEM at 1024 and 8192 strips
    res = [run("layer-line", {"numerics.bem_elements": n}, models=["bem"]).models["bem"].quantities
           for n in (1024, 8192)]
    assert res[0]["half_width"] == pytest.approx(res[1]["half_width"], rel=1e-3)
    assert res[0]["p_max"] == pytest.approx(res[1]["p_max"], rel=1e-3)


def test_hertz_by_the_bem_at_the_default_resolutions(femcheck_run):
    line = femcheck_run("hertz-line", models=["analytic", "bem"]).models
    assert line["bem"].quantities["half_width"] == pytest.approx(line["analytic"].quantities["half_width"], rel=5e-4)
    point = femcheck_run("hertz-point", models=["analytic", "bem"]).models
    for q in ("semi_axis_x", "semi_axis_y"):
        assert point["bem"].quantities[q] == pytest.approx(point["analytic"].quantities[q], rel=1e-3)
