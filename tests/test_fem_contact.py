"""FEM building blocks: contact algorithms against an independent QP solution, Richardson extrapolation on
known sequences, mesh matching, and the 2D model against Hertz."""
import numpy as np
import pytest
from scipy import optimize

from femcheck.analytic.hertz import line_contact
from femcheck.errors import ConvergenceError
from femcheck.solvers import frictionless
from femcheck.solvers.convergence import richardson
from femcheck.fem.line_contact import FEMLineSettings, solve_level
from femcheck.meshes.plane import MeshSpec, block_half, contact_abscissae, cylinder_half
from femcheck.materials import Elastic, effective_modulus


def _random_system(n=30, seed=1):
    rng = np.random.default_rng(seed)
    x = np.linspace(0, 1, n)
    W = np.exp(-np.abs(x[:, None] - x[None, :]) / 0.3) + 0.05 * np.eye(n)   # SPD compliance
    W += 0.01 * (lambda M: M @ M.T)(rng.normal(size=(n, n))) / n
    return frictionless.CondensedContact(g0=0.5 * x**2, c=-np.ones(n), W=W, force=3.0)


def test_active_set_matches_quadratic_program():
    # With c = -1 the contact conditions are the KKT conditions of
    # min 1/2 lam.W.lam + g0.lam  s.t. sum(lam) = F, lam >= 0 (delta is the multiplier of the sum).
    sys = _random_system()
    sol = frictionless.active_set(sys)
    qp = optimize.minimize(lambda l: 0.5 * l @ sys.W @ l + sys.g0 @ l, np.full(30, 0.1),
                           jac=lambda l: sys.W @ l + sys.g0, method="SLSQP", bounds=[(0, None)] * 30,
                           constraints=[{"type": "eq", "fun": lambda l: l.sum() - 3.0}],
                           options={"ftol": 1e-14, "maxiter": 500})
    np.testing.assert_allclose(sol.lam, qp.x, atol=1e-6)
    assert sol.lam.sum() == pytest.approx(3.0, rel=1e-12)
    assert (sol.lam >= 0).all() and (sol.gap >= -1e-12).all()
    assert np.abs(sol.lam * sol.gap).max() < 1e-12


def test_penalty_converges_to_active_set_as_one_over_kappa():
    sys = _random_system()
    exact = frictionless.active_set(sys).lam
    errs = [np.abs(frictionless.penalty(sys, kappa).lam - exact).max() for kappa in (1e3, 1e4, 1e5)]
    assert errs[0] / errs[1] == pytest.approx(10, rel=0.2)
    assert errs[1] / errs[2] == pytest.approx(10, rel=0.2)


def test_active_set_reports_cycling_as_error():
    sys = _random_system()
    with pytest.raises(ConvergenceError, match="primal-dual active set"):
        frictionless.active_set(sys, active0=np.eye(1, 30, 29, dtype=bool).ravel(), max_iter=1)


def test_richardson_recovers_order_and_limit():
    h = [0.4, 0.2, 0.1]
    e = richardson(h, [3.0 + 0.7 * hh**2 for hh in h])
    assert e.order == pytest.approx(2.0, abs=1e-9)
    assert e.value == pytest.approx(3.0, abs=1e-12)
    assert e.error_estimate == pytest.approx(0.7 * 0.01, rel=1e-9)


def test_richardson_refuses_to_extrapolate_oscillation():
    e = richardson([0.4, 0.2, 0.1], [1.0, 1.1, 1.05])
    assert e.order is None and e.value == 1.05 and e.error_estimate == pytest.approx(0.05)


def test_contact_nodes_of_both_bodies_match():
    spec = MeshSpec(0.01, 0.13, 0.4, 0.2)
    xs = contact_abscissae(spec)
    b, c = block_half(4.0, 2.0, spec), cylinder_half(1.0, spec)
    on_b = np.abs(b.points[1]) < 1e-12
    assert np.allclose(np.sort(b.points[0, on_b & (b.points[0] <= 0.13 + 1e-12)]), xs)
    circle = np.abs(c.points[1] - (1 - np.sqrt(np.clip(1 - c.points[0] ** 2, 0, None)))) < 1e-12
    assert np.allclose(np.sort(c.points[0, circle & (c.points[0] <= 0.13 + 1e-12)]), xs)


@pytest.fixture(scope="module")
def rigid_case():
    steel = Elastic(210e9, 0.3)
    rigid = Elastic(210e9, 0.3, rigid=True)
    h = line_contact(1e6, 0.01, effective_modulus(rigid, steel))
    return steel, rigid, h


@pytest.mark.parametrize("method", ["active_set", "penalty"])
def test_fem_level_against_hertz(rigid_case, method):
    steel, rigid, h = rigid_case
    lv = solve_level(0.01, rigid, steel, 1e6, h.half_width, 1, FEMLineSettings(method=method))
    assert lv.p_max == pytest.approx(h.p_max, rel=3e-3)
    assert lv.half_width == pytest.approx(h.half_width, rel=3e-3)
    assert lv.total_force == pytest.approx(1e6, rel=1e-10)
    assert (lv.p >= 0).all()


def test_penalty_and_active_set_agree(rigid_case):
    steel, rigid, h = rigid_case
    a = solve_level(0.01, rigid, steel, 1e6, h.half_width, 1, FEMLineSettings(method="active_set"))
    p = solve_level(0.01, rigid, steel, 1e6, h.half_width, 1, FEMLineSettings(method="penalty"))
    assert p.p_max == pytest.approx(a.p_max, rel=1e-3)      # penalty factor 1e3: overlap ~ 1e-3 h
    assert 0 < p.penetration < 1e-3 * h.half_width**2 / 0.02


def test_mixed_formulation_removes_locking(rigid_case):
    # nu = 0.4999: the displacement P2 formulation locks (its nodal pressures oscillate; the shape-agnostic peak
    # estimate is off by -1.8 % at this level, +1.7 % with the former Hertz-shaped one), the Taylor-Hood P2/P1
    # mixed formulation stays within 0.2 % of Hertz.
    rubberlike = Elastic(210e9, 0.4999)
    rigid = rigid_case[1]
    h = line_contact(1e6, 0.01, effective_modulus(rigid, rubberlike))
    mixed = solve_level(0.01, rigid, rubberlike, 1e6, h.half_width, 1, FEMLineSettings(formulation="mixed"))
    disp = solve_level(0.01, rigid, rubberlike, 1e6, h.half_width, 1,
                       FEMLineSettings(formulation="displacement"))
    assert mixed.p_max == pytest.approx(h.p_max, rel=2e-3)
    assert abs(disp.p_max / h.p_max - 1) > 5e-3


def test_contact_leaving_candidate_zone_is_an_error(rigid_case):
    steel, rigid, h = rigid_case
    with pytest.raises(ConvergenceError, match="candidate zone"):
        solve_level(0.01, rigid, steel, 1e6, 0.5 * h.half_width, 0, FEMLineSettings())
