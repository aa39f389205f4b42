"""Half-plane boundary-integral engine: DC-FFT against direct sums, strip influence against quadrature,
Polonsky-Keer contact against Hertz and its own invariants."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from femcheck.analytic.hertz import line_contact
from femcheck.bem.convolution import DCFFT
from femcheck.bem.influence import half_plane_strip
from femcheck.bem.line import solve_line_contact
from femcheck.bem.polonsky_keer import polonsky_keer
from femcheck.errors import ConvergenceError
from femcheck.qoi import contact_edge, half_width


@settings(max_examples=25, deadline=None)
@given(n=st.integers(1, 40), seed=st.integers(0, 2**31 - 1))
def test_dcfft_1d_equals_direct_linear_convolution(n, seed):
    rng = np.random.default_rng(seed)
    kernel = lambda t: np.exp(-np.abs(t)) * (1 + 0.3 * t)     # deliberately not even
    p = rng.normal(size=n)
    op = DCFFT(kernel, (n,), (0.7,))
    x = 0.7 * np.arange(n)
    direct = kernel(x[:, None] - x[None, :]) @ p
    np.testing.assert_allclose(op(p), direct, rtol=1e-10, atol=1e-12)


@settings(max_examples=10, deadline=None)
@given(n1=st.integers(1, 12), n2=st.integers(1, 12), seed=st.integers(0, 2**31 - 1))
def test_dcfft_2d_equals_direct_with_anisotropic_spacing(n1, n2, seed):
    rng = np.random.default_rng(seed)
    kernel = lambda tx, ty: 1.0 / (1.0 + tx**2 + 3 * ty**2 + 0.5 * tx)
    p = rng.normal(size=(n1, n2))
    op = DCFFT(kernel, (n1, n2), (0.5, 2.0))
    X, Y = np.meshgrid(0.5 * np.arange(n1), 2.0 * np.arange(n2), indexing="ij")
    K = kernel(X.ravel()[:, None] - X.ravel()[None, :], Y.ravel()[:, None] - Y.ravel()[None, :])
    np.testing.assert_allclose(op(p).ravel(), K @ p.ravel(), rtol=1e-10, atol=1e-12)


def test_strip_influence_matches_log_kernel_quadrature():
    # Johnson eq. 2.25b: u(x) = -(2/(pi E*)) int ln|x - s| / d ds over the strip, by adaptive quadrature.
    e_star, w, d = 1.0e11, 1e-5, 1e-2
    for t in (0.0, 0.3e-5, 0.5e-5, 2.7e-5, 1e-3):
        ref = integrate.quad(lambda s: np.log(abs(t - s) / d), -w / 2, w / 2, points=[t] if abs(t) < w / 2 else None,
                             limit=200)[0] * (-2 / (np.pi * e_star))
        assert half_plane_strip(np.array(t), w, e_star, d) == pytest.approx(ref, rel=1e-10, abs=0.0)   # u ~ 1e-16: no abs floor


def test_strip_matrix_positive_definite_with_datum():
    n, dx = 200, 1e-6
    x = dx * np.arange(n)
    K = half_plane_strip(x[:, None] - x[None, :], dx, 1e11, 8 * n * dx)
    assert np.linalg.eigvalsh(0.5 * (K + K.T)).min() > 0


@pytest.fixture(scope="module")
def steel_line():
    R, e_star, load = 0.01, 115.4e9, 1e6
    return R, e_star, load, line_contact(load, R, e_star)


def _parabola(R):
    return lambda x: x * x / (2 * R)


def test_bem_reproduces_hertz_parabolic_gap(steel_line):
    R, e_star, load, h = steel_line
    sol = solve_line_contact(_parabola(R), e_star, load, 1.25 * h.half_width, 1023)
    r = sol.result
    assert r.pressure.max() == pytest.approx(h.p_max, rel=2e-4)
    assert half_width(sol.x, r.pressure) == pytest.approx(h.half_width, rel=5e-4)
    assert r.load == pytest.approx(load, rel=1e-12)
    assert r.residual < 1e-10 and r.iterations > 1
    assert (r.pressure >= 0).all()
    inside = np.abs(sol.x) < 0.9 * h.half_width
    np.testing.assert_allclose(r.pressure[inside], h.pressure(sol.x[inside]), rtol=0, atol=2e-3 * h.p_max)


def test_bem_error_decreases_with_refinement(steel_line):
    R, e_star, load, h = steel_line
    errs = []
    for n in (63, 255, 1023):
        sol = solve_line_contact(_parabola(R), e_star, load, 1.25 * h.half_width, n)
        x, p = sol.x, sol.result.pressure
        errs.append(np.linalg.norm(p - h.pressure(x)) / np.linalg.norm(h.pressure(x)))
    assert errs[0] > errs[1] > errs[2]


def test_polonsky_keer_raises_when_not_converged(steel_line):
    R, e_star, load, h = steel_line
    with pytest.raises(ConvergenceError, match="after 3 iterations"):
        solve_line_contact(_parabola(R), e_star, load, 1.25 * h.half_width, 255, max_iter=3)


def test_polonsky_keer_flat_punch_load_and_rigid_approach():
    # A flat rigid punch on a strip of width 2b: the whole strip is in contact and the pressure is the
    # Sadowsky singular profile p = W / (pi sqrt(b^2 - x^2)) (Johnson eq. 2.64); check it away from the ends.
    b, n, e_star, load = 1e-3, 400, 1e11, 1e5
    dx = 2 * b / n
    x = -b + (np.arange(n) + 0.5) * dx
    op = DCFFT(lambda t: half_plane_strip(t, dx, e_star, 16 * b), (n,), (dx,))
    r = polonsky_keer(np.zeros(n), op, load, dx)
    mid = np.abs(x) < 0.5 * b
    np.testing.assert_allclose(r.pressure[mid], load / (np.pi * np.sqrt(b * b - x[mid] ** 2)), rtol=5e-3)
    assert r.contact.all()


def test_contact_edge_exact_for_elliptical_profile():
    a = 1.3
    x = np.linspace(0, 2, 37)
    p = np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    assert contact_edge(x, p) == pytest.approx(a, rel=1e-10)
    assert half_width(np.concatenate([-x[:0:-1], x]), np.concatenate([p[:0:-1], p])) == pytest.approx(a, rel=1e-10)


@pytest.mark.parametrize("n", [16, 32, 64])
def test_symmetric_even_grid_start_does_not_stagnate(steel_line, n):
    # Even strip counts start from the two symmetric centre cells: the gap over the contact set is uniform,
    # the CG step is zero, and before the Winkler seeding of penetrating cells the solver stalled (residual 1.75).
    R, e_star, load, h = steel_line
    sol = solve_line_contact(_parabola(R), e_star, load, 1.25 * h.half_width, n)
    assert sol.result.residual < 1e-10
    assert sol.result.pressure.max() == pytest.approx(h.p_max, rel=0.02)
