"""Matrix-free tangential solver of Kalker's exact theory (femcheck.cect.tangential_fft): FFT block convolution,
preconditioned FGMRES, semi-smooth Newton-GMRES. Every number is checked against an independent value named in
a comment: the dense influence matrices and the dense LU Newton solver (femcheck.cect.exact), numpy's LU,
Cattaneo-Mindlin and Kalker's published creep coefficients."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.analytic.hertz import elliptic_contact, point_contact
from femcheck.analytic.mindlin import mindlin
from femcheck.bem.halfspace import Grid, grid
from femcheck.cect.creep import coefficients_on_grid, creep_coefficients
from femcheck.cect.exact import dense_operator, solve_contact
from femcheck.cect.influence import CombinedConstants, combined_constants
from femcheck.cect.tangential_fft import (TangentialConvolution, fgmres, solve_adhesion,
                                          solve_tangential_fft)
from femcheck.errors import ConvergenceError, InputError
from femcheck.materials import Elastic

STEEL = Elastic(210e9, 0.3)
ALUMINIUM = Elastic(70e9, 0.33)


def _ellipse_cells(n, a_over_b=1.0):
    a, b = np.sqrt(a_over_b), 1.0 / np.sqrt(a_over_b)
    g = Grid(n, n, 2.0 * a / n, 2.0 * b / n)
    X, Y = g.mesh()
    return g, np.nonzero((X / a) ** 2 + (Y / b) ** 2 < 1.0), X, Y


@pytest.mark.parametrize("rolling", [True, False])
def test_block_convolution_equals_dense_influence_matrix(rolling):
    # reference: the dense block matrix of exact.dense_operator (lag table gathered element by element), which
    # the dense solver uses; the FFT product is an exact linear convolution, so agreement to round-off
    cc = CombinedConstants(1.0, 0.3, 0.0)
    g = Grid(13, 9, 0.7, 0.4)
    cells = np.nonzero(np.ones((g.nx, g.ny), dtype=bool))
    rng = np.random.default_rng(1)
    p = rng.standard_normal((2, g.nx, g.ny))
    dense = dense_operator(g, cells, cc, "xy", "xy", rolling) @ p.reshape(2, -1).ravel()
    fftop = TangentialConvolution(g, cc, rolling)(p).reshape(2, -1).ravel()
    assert np.max(np.abs(fftop - dense)) <= 1e-12 * np.max(np.abs(dense))
    # the element's own slip per unit traction is the matrix diagonal
    assert fftop is not None and TangentialConvolution(g, cc, rolling).self_coefficients[0] == pytest.approx(
        dense_operator(g, cells, cc, "x", "x", rolling)[0, 0], rel=1e-13)


def test_fgmres_solves_a_nonsymmetric_system():
    # reference: numpy's LU solution of the same diagonally shifted random (nonsymmetric) system
    rng = np.random.default_rng(2)
    A = np.eye(80) * 4.0 + rng.standard_normal((80, 80)) / 4.0
    b = rng.standard_normal(80)
    res = fgmres(lambda v: A @ v, b, lambda v: v / 4.0, rtol=1e-12, restart=15)
    assert res.converged and res.residual <= 1e-12
    assert np.max(np.abs(res.x - np.linalg.solve(A, b))) <= 1e-10 * np.max(np.abs(res.x))


@pytest.mark.parametrize("a_over_b,nu", [(1.0, 0.25), (5.0, 0.5), (0.2, 0.0)])
def test_full_adhesion_matches_dense_lu(a_over_b, nu):
    # reference: the dense LU full-adhesion solve of femcheck.cect.creep on the same grid (same discrete
    # equations), for the creep coefficients of three ellipses; GMRES is run to a relative residual of 1e-11
    dense = coefficients_on_grid(a_over_b, nu, 24, "dense")
    fft = coefficients_on_grid(a_over_b, nu, 24, "fft")
    for k in ("c11", "c22", "c23", "c33"):
        assert fft[k] == pytest.approx(dense[k], rel=1e-9)


def test_preconditioner_removes_the_grid_dependence():
    # reference: the same GMRES without preconditioner on the same 64^2 full-adhesion rolling system (measured
    # 471 iterations); the upwind-sum + circulant preconditioner must need under a fifth of them
    g, cells, X, Y = _ellipse_cells(64)
    cc = CombinedConstants(1.0, 0.25, 0.0)
    C = cells[0].size
    w = np.stack([np.ones(C), np.zeros(C)])
    p, res = solve_adhesion(g, cells, cc, w)
    op = TangentialConvolution(g, cc, True)
    flat = np.ravel_multi_index(cells, (g.nx, g.ny))

    def matvec(v):
        full = np.zeros((2, g.nx * g.ny))
        full[:, flat] = v.reshape(2, C)
        return op(full.reshape(2, g.nx, g.ny)).reshape(2, -1)[:, flat].ravel()

    plain = fgmres(matvec, -w.ravel(), lambda v: v, rtol=1e-11, max_iter=3000)
    assert plain.converged
    assert res.iterations < plain.iterations / 5
    assert np.max(np.abs(p.ravel() - plain.x)) <= 1e-8 * np.max(np.abs(plain.x))


def _ellipse(n, body2=STEEL, rx=0.005, ry=0.02, P=1000.0):
    cc = combined_constants(STEEL, body2)
    h = elliptic_contact(P, rx, ry, cc.contact_modulus)
    return cc, grid(1.1 * h.semi_axis_x, 1.1 * h.semi_axis_y, n, n), (lambda X, Y: X * X / (2 * rx) + Y * Y / (2 * ry))


CASES = {
    "rolling xi+eta+phi": dict(creepages=(0.005, 0.002, 10.0)),
    "rolling pure spin": dict(creepages=(0.0, 0.0, 40.0)),
    "rolling saturated": dict(creepages=(-0.06, 0.08, 0.0)),
    "shift Fx+Fy near mu P": dict(tangential_load=(-290.0, 30.0)),
}


@pytest.mark.parametrize("case", list(CASES))
def test_newton_gmres_matches_dense_newton(case):
    # reference: the dense semi-smooth Newton (LU of the assembled Jacobian) on the same grid and equations;
    # both stop at max|F| / (mu p_max) < 1e-9, so resultants agree to ~1e-9 mu N and adhesion maps exactly
    cc, g, gap = _ellipse(21)
    mu, P = 0.3, 1000.0
    dense = solve_contact(g, gap, cc, P, mu, tangential_solver="dense", **CASES[case])
    fft = solve_contact(g, gap, cc, P, mu, tangential_solver="fft", **CASES[case])
    assert fft.stats["tangential_solver"] == "fft" and dense.stats["tangential_solver"] == "dense"
    assert abs(fft.creep_force_x - dense.creep_force_x) <= 1e-8 * mu * P
    assert abs(fft.creep_force_y - dense.creep_force_y) <= 1e-8 * mu * P
    assert abs(fft.spin_moment - dense.spin_moment) <= 1e-8 * mu * P * g.dx * g.nx
    assert np.array_equal(fft.adhesion, dense.adhesion)
    scale = mu * dense.pressure.max()
    assert np.max(np.abs(fft.px - dense.px)) <= 1e-7 * scale
    assert np.max(np.abs(fft.py - dense.py)) <= 1e-7 * scale
    if dense.shift is not None:
        assert fft.shift[0] == pytest.approx(dense.shift[0], rel=1e-7)


def test_dissimilar_bodies_panagiotopoulos_matches_dense():
    # reference: the dense solver inside the same Panagiotopoulos process (steel on aluminium, K != 0)
    cc, g, gap = _ellipse(21, body2=ALUMINIUM)
    assert cc.coupling != 0
    kw = dict(creepages=(0.003, 0.0, 5.0))
    dense = solve_contact(g, gap, cc, 1000.0, 0.3, tangential_solver="dense", **kw)
    fft = solve_contact(g, gap, cc, 1000.0, 0.3, tangential_solver="fft", **kw)
    assert fft.stats["outer_iterations"] == dense.stats["outer_iterations"] >= 2
    assert abs(fft.creep_force_x - dense.creep_force_x) <= 1e-8 * 300.0
    assert abs(fft.creep_force_y - dense.creep_force_y) <= 1e-8 * 300.0
    assert np.array_equal(fft.adhesion, dense.adhesion)


@pytest.mark.slow
def test_fine_grid_cattaneo_mindlin():
    # reference: Cattaneo-Mindlin closed form (Johnson 1985 eqs 7.40, 7.42). On a 129^2 grid (a/dx = 59, out of
    # reach of the dense solver) the shift is within 0.3 % and the stick radius within 1 % (the stick area of a
    # staircase circle is exact to about one element ring: 2 dx/a ~ 3 % bound, 1 % measured range)
    mu, P, R = 0.3, 100.0, 0.01
    cc = combined_constants(STEEL, STEEL)
    a = point_contact(P, R, cc.contact_modulus).semi_axis_x
    g = grid(1.1 * a, 1.1 * a, 129, 129)
    Q = 0.6 * mu * P
    sol = solve_contact(g, lambda X, Y: (X * X + Y * Y) / (2 * R), cc, P, mu, tangential_load=(-Q, 0.0))
    assert sol.stats["tangential_solver"] == "fft"            # "auto" above 300 contact elements
    m = mindlin(P, Q, R, mu, cc.contact_modulus, 2 * (2 - cc.poisson) / cc.shear_modulus)
    assert sol.shift[0] == pytest.approx(m.shift, rel=0.003)
    assert np.sqrt(sol.adhesion.sum() * g.cell_area / np.pi) == pytest.approx(m.stick_radius, rel=0.01)


@pytest.mark.slow
def test_creep_coefficients_on_fine_grids_match_kalker():
    # reference: Kalker (1990) Table E.3 (CONTACT's linrol): a/b = 5 (b/a = 0.2 row), nu = 0.5: C11 = 8.82,
    # C22 = 9.79, C23 = 7.89 -- the slowest-converging case of the table, extrapolated from 32/64/128 grids
    # (matrix-free; the dense path stops at 48). Within 1 % (the table's 3 digits are 0.1 %).
    k = creep_coefficients(5.0, 0.5, (32, 64, 128))
    assert k.c11 == pytest.approx(8.82, rel=0.01)
    assert k.c22 == pytest.approx(9.79, rel=0.01)
    assert k.c23 == pytest.approx(7.89, rel=0.01)


def test_non_convergence_raises():
    # a partial-slip problem cannot be solved in one Newton step: ConvergenceError, not a silent answer
    cc, g, gap = _ellipse(21)
    from femcheck.bem.halfspace import half_space_operator  # noqa: F401  (normal problem via solve_contact)
    sol = solve_contact(g, gap, cc, 1000.0, 0.3, creepages=(0.005, 0.002, 10.0), tangential_solver="fft")
    cells = np.nonzero(sol.contact)
    X, Y = g.mesh()
    w = np.stack([0.005 - 10.0 * Y[cells], 0.002 + 10.0 * X[cells]])
    with pytest.raises(ConvergenceError):
        solve_tangential_fft(g, cells, cc, w, 0.3 * sol.pressure[cells], rolling=True, max_iter=1)
    # and a solution of the same data with enough steps is the one solve_contact returned
    ok = solve_tangential_fft(g, cells, cc, w, 0.3 * sol.pressure[cells], rolling=True, tol=1e-9)
    assert np.max(np.abs(ok.p[0] - sol.px[cells])) <= 1e-6 * 0.3 * sol.pressure.max()


def test_bad_solver_name():
    cc, g, gap = _ellipse(11)
    with pytest.raises(InputError):
        solve_contact(g, gap, cc, 1000.0, 0.3, creepages=(0.001, 0, 0), tangential_solver="lu")
    with pytest.raises(InputError):
        coefficients_on_grid(1.0, 0.25, 12, "lu")
