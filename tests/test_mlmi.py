"""Multilevel multi-integration and the circulant CG preconditioner, both checked against DC-FFT (itself checked
against direct sums in test_bem.py) and against Hertz."""
from functools import partial

import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic.hertz import point_contact
from femcheck.bem.convolution import DCFFT, CirculantPreconditioner
from femcheck.bem.halfspace import grid, solve
from femcheck.bem.influence import love_rectangle
from femcheck.bem.mlmi import MLMI, _interpolation_matrix, error_against, lagrange_midpoint_weights


def test_midpoint_weights_are_the_textbook_ones():
    np.testing.assert_allclose(lagrange_midpoint_weights(4), np.array([-1, 9, 9, -1]) / 16, rtol=1e-14)
    np.testing.assert_allclose(lagrange_midpoint_weights(6), np.array([3, -25, 150, 150, -25, 3]) / 256,
                               rtol=1e-14)


@pytest.mark.parametrize("order", [4, 6, 8])
def test_interpolation_is_exact_for_polynomials_below_its_order(order):
    P = _interpolation_matrix(-1, 40, -1 - order, 21 + order, lagrange_midpoint_weights(order))
    coarse = np.arange(-1 - order, 22 + order) * 2.0          # coarse point J sits at fine point 2J
    fine = np.arange(-1, 41) * 1.0
    for degree in range(order):
        np.testing.assert_allclose(P @ (0.01 * coarse) ** degree, (0.01 * fine) ** degree, rtol=1e-12, atol=1e-14)


def _love(shape, spacing):
    return partial(love_rectangle, dx=spacing[0], dy=spacing[1], modulus=1.0)


@pytest.mark.parametrize("shape,spacing", [((65, 65), (1.0, 1.0)), ((40, 100), (1.0, 1.0)),
                                           ((97, 65), (1.0, 2.0)), ((129, 129), (1e-5, 1e-5))])
def test_mlmi_agrees_with_dcfft_on_rough_fields(shape, spacing):
    # measured max relative error on random pressures: order 6 / correction 10: 7e-6 (square cells) to 1.3e-5
    # (dy = 2 dx); the 1e-5 m case checks that tiny physical kernels are not cut by ndimage's weight threshold
    K = _love(shape, spacing)
    p = np.random.default_rng(1).random(shape)
    assert error_against(DCFFT(K, shape, spacing), MLMI(K, shape, spacing, order=6, correction=10), p) < 2e-5


def test_mlmi_error_falls_with_order_and_correction():
    shape, spacing = (129, 129), (1.0, 1.0)
    K = _love(shape, spacing)
    ref = DCFFT(K, shape, spacing)
    p = np.random.default_rng(2).random(shape)
    errs = [error_against(ref, MLMI(K, shape, spacing, order=o, correction=m), p)
            for o, m in ((4, 4), (6, 6), (6, 10), (8, 12))]
    # measured 1.5e-3, 1.5e-4, 9e-6, 7e-7: each step gains more than 5x
    assert all(b < a / 5 for a, b in zip(errs, errs[1:]))


def test_mlmi_one_dimensional_smooth_kernel():
    K = lambda t: 1.0 / np.sqrt(1.0 + t * t)                  # noqa: E731 -- smooth 1/r-like kernel
    p = np.random.default_rng(3).random(1000)
    assert error_against(DCFFT(K, (1000,), (1.0,)), MLMI(K, (1000,), (1.0,)), p) < 5e-5   # measured 2.8e-5


def test_mlmi_refuses_elongated_cells():
    with pytest.raises(ValueError, match="near-square"):
        MLMI(_love((33, 33), (1.0, 3.0)), (33, 33), (1.0, 3.0))


def test_mlmi_contact_solution_matches_dcfft_and_hertz():
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 65, 65)
    gap = lambda X, Y: (X * X + Y * Y) / 0.02                  # noqa: E731
    fft_sol = solve(g, gap, h.modulus, 1000.0).result
    mlmi_sol = solve(g, gap, h.modulus, 1000.0, convolution="mlmi").result
    # operator error ~1e-5 -> pressure difference 5e-5 (measured); both within 1e-4 of Hertz's p_max here
    assert mlmi_sol.pressure.max() == pytest.approx(fft_sol.pressure.max(), rel=2e-4)
    assert mlmi_sol.pressure.max() == pytest.approx(h.p_max, rel=1e-3)


def test_circulant_preconditioner_inverts_the_periodic_convolution():
    # the preconditioner is the exact inverse of the periodic (circulant) convolution with the same kernel
    n, spacing = (48, 30), (1.0, 1.5)
    K = _love(n, spacing)
    M = CirculantPreconditioner(K, n, spacing)
    lag = [np.where(np.arange(k) <= k // 2, np.arange(k), np.arange(k) - k) * s for k, s in zip(n, spacing)]
    kernel = K(lag[0][:, None], lag[1][None, :])
    u = np.random.default_rng(4).random(n)
    periodic = np.real(np.fft.ifft2(np.fft.fft2(M(u)) * np.fft.fft2(kernel)))
    np.testing.assert_allclose(periodic, u, rtol=1e-10, atol=1e-12)


def test_preconditioned_cg_same_answer_fewer_iterations():
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 129, 129)
    gap = lambda X, Y: (X * X + Y * Y) / 0.02                  # noqa: E731
    plain = solve(g, gap, h.modulus, 1000.0, precondition=False).result
    pre = solve(g, gap, h.modulus, 1000.0).result
    np.testing.assert_allclose(pre.pressure, plain.pressure, atol=1e-7 * h.p_max)
    assert pre.iterations < plain.iterations / 2             # measured 21 against 59


def test_preconditioned_approach_control_matches_hertz_approach():
    h = point_contact(1000.0, 0.01, 1.154e11)
    g = grid(1.25 * h.semi_axis_x, 1.25 * h.semi_axis_x, 65, 65)
    res = solve(g, lambda X, Y: (X * X + Y * Y) / 0.02, h.modulus, None, approach=h.approach).result
    assert res.load == pytest.approx(1000.0, rel=2e-3)
    # and the pressure integrates to the load it reports
    assert integrate.trapezoid(integrate.trapezoid(res.pressure, g.y), g.x) == pytest.approx(res.load, rel=1e-2)
