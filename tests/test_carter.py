"""Carter's 2D rolling and the 2D Cattaneo closed forms, checked against independent evaluations: numerical
quadrature of the tractions, the half-plane log kernel (femcheck.bem.influence, exact strip integrals) for the
displacements the closed forms claim, and Johnson's (1985) limits."""
import numpy as np
import pytest

from femcheck.analytic import carter, hertz
from femcheck.bem.influence import half_plane_strip

E, NU, R, W, MU = 210e9, 0.3, 0.010, 1.0e6, 0.3
E_STAR = E / (2.0 * (1.0 - NU**2))          # steel on steel, 1/E* = 2 (1 - nu^2)/E
H = hertz.line_contact(W, R, E_STAR)
A, P0 = H.half_width, H.p_max
XI_SAT = 2.0 * MU * P0 / E_STAR


def _displacement(x_eval, q, x, dx):
    """u(x) = -(2/(pi E*)) int q ln|x - s| ds of a piecewise-constant traction, by exact strip integrals
    (datum 100 a); an independent evaluation of the log kernel the closed forms integrate analytically."""
    K = half_plane_strip(x_eval[:, None] - x[None, :], dx, E_STAR, 100.0 * A)
    return K @ q


@pytest.mark.parametrize("f", [0.2, 0.5, 0.8, 1.0, 1.7])
def test_creep_force_is_integral_of_traction(f):
    # Reference: midpoint quadrature of Carter's traction (seed 000 eq 9) on 200 000 points; the closed-form
    # force (eq 11) must match to 1e-6 (quadrature error of the sqrt edges ~ N^-1.5).
    sol = carter.carter_rolling(W, A, E_STAR, MU, f * XI_SAT)
    n = 200_000
    dx = 2 * A / n
    x = -A + (np.arange(n) + 0.5) * dx
    assert dx * sol.traction(x).sum() == pytest.approx(sol.creep_force, rel=1e-6)


def test_small_creepage_linear_limit_and_sign():
    # Johnson (1985) §8.2: for xi -> 0, F' = -(pi a E*/2) xi (Carter's linear limit); the force opposes xi.
    for xi in (1e-7, -1e-7):
        f = carter.carter_creep_force(xi, W, A, E_STAR, MU)
        assert f == pytest.approx(-np.pi * A * E_STAR / 2 * xi, rel=1e-4)
        assert np.sign(f) == -np.sign(xi)


def test_saturation_gives_mu_w():
    # Beyond xi* = 1 the whole contact slips: |F'| = mu W' exactly (Coulomb).
    f = carter.carter_creep_force(np.array([1.0, 1.5, -3.0]) * XI_SAT, W, A, E_STAR, MU)
    np.testing.assert_allclose(f, [-MU * W, -MU * W, MU * W], rtol=1e-14)


def test_adhesion_at_leading_edge_and_coulomb_bound():
    # Coulomb: |q| <= mu p everywhere, = mu p in the slip zone (x < a - 2c), < mu p in the adhesion zone,
    # whose position [a - 2c, a] (leading edge, c = a (1 - xi*)) is Johnson's eq. 8.21.
    sol = carter.carter_rolling(W, A, E_STAR, MU, 0.4 * XI_SAT)
    assert sol.stick_half_width == pytest.approx(0.6 * A, rel=1e-12)
    x = np.linspace(-0.999 * A, 0.999 * A, 4001)
    q, g = np.abs(sol.traction(x)), MU * sol.pressure(x)
    assert np.all(q <= g * (1 + 1e-12))
    slip_zone = x < A - 2 * sol.stick_half_width - 1e-3 * A
    np.testing.assert_allclose(q[slip_zone], g[slip_zone], rtol=1e-12)
    adhesion = (x > A - 2 * sol.stick_half_width + 1e-3 * A) & (x < A - 1e-3 * A)
    assert np.all(q[adhesion] < g[adhesion])


def test_carter_kinematics_from_log_kernel():
    # The displacement of Carter's traction, computed independently with the half-plane log kernel, must give
    # zero slip s/V = xi - du/dx in the adhesion zone and the slip of seed 000 eq 10 in the slip zone.
    xi = 0.5 * XI_SAT
    sol = carter.carter_rolling(W, A, E_STAR, MU, xi)
    n = 20_000
    dx = 2 * A / n
    x = -A + (np.arange(n) + 0.5) * dx
    q = sol.traction(x)
    probes = np.linspace(-0.93 * A, 0.93 * A, 16)      # none on the stick/slip boundary x = 0
    h = 1e-3 * A
    dudx = (_displacement(probes + h, q, x, dx) - _displacement(probes - h, q, x, dx)) / (2 * h)
    slip = xi - dudx
    # tolerance 0.5 % of xi: discretisation of the traction on 20 000 strips and the central difference
    np.testing.assert_allclose(slip, sol.slip(probes), atol=5e-3 * xi)
    stick = probes > A - 2 * sol.stick_half_width
    assert np.all(np.abs(slip[stick]) < 5e-3 * xi)
    assert np.all(slip[~stick] > 0)          # body 1 slips forward (xi > 0), its traction points back


@pytest.mark.parametrize("ratio", [0.2, 0.6, 0.95])
def test_cattaneo_stick_zone_traction_and_force(ratio):
    # c = a sqrt(1 - Q'/(mu W')) (Johnson 1985 §7.1); the traction balances Q' (quadrature) and stays within
    # the Coulomb bound.
    Q = ratio * MU * W
    sol = carter.cattaneo_line(W, A, E_STAR, MU, Q)
    assert sol.stick_half_width == pytest.approx(A * np.sqrt(1 - ratio), rel=1e-12)
    n = 200_000
    dx = 2 * A / n
    x = -A + (np.arange(n) + 0.5) * dx
    q = sol.traction(x)
    assert dx * q.sum() == pytest.approx(-Q, rel=1e-6)
    assert np.all(np.abs(q) <= MU * sol.pressure(x) * (1 + 1e-12))


@pytest.mark.parametrize("ratio", [0.3, 0.7, 0.99])
def test_cattaneo_shift_from_log_kernel(ratio):
    # Independent: shift = delta - delta_stick, each evaluated by the log kernel at the centre (stick zone) --
    # partial slip traction vs the fully adhered traction Q'/(pi sqrt(a^2 - x^2)) (its displacement is uniform;
    # integrated exactly per strip via the antiderivative arcsin). Within 0.5 % (strip discretisation).
    Q = ratio * MU * W
    sol = carter.cattaneo_line(W, A, E_STAR, MU, Q)
    n = 40_000
    dx = 2 * A / n
    edges = -A + dx * np.arange(n + 1)
    x = 0.5 * (edges[1:] + edges[:-1])
    q_stick = (Q / np.pi) * np.diff(np.arcsin(np.clip(edges / A, -1, 1))) / dx   # exact strip averages
    probe = np.array([0.0])
    # the shift is of body 1 relative to body 2: S = delta + u = 0 in stick -> delta = -u(centre)
    delta = -_displacement(probe, sol.traction(x), x, dx)[0]
    delta_stick = -_displacement(probe, -q_stick, x, dx)[0]
    assert delta - delta_stick == pytest.approx(sol.shift, rel=5e-3)


def test_cattaneo_shift_limits():
    # At the onset of sliding (c -> 0) the micro-slip shift is mu p0 a/(2 E*); it vanishes as Q' -> 0 and is
    # odd in Q'.
    s = carter.cattaneo_line(W, A, E_STAR, MU, (1 - 1e-12) * MU * W).shift
    assert s == pytest.approx(MU * P0 * A / (2 * E_STAR), rel=1e-6)
    assert carter.cattaneo_line(W, A, E_STAR, MU, 1e-9).shift == pytest.approx(0.0, abs=1e-12 * s)
    assert carter.cattaneo_line(W, A, E_STAR, MU, -0.5 * MU * W).shift == \
        pytest.approx(-carter.cattaneo_line(W, A, E_STAR, MU, 0.5 * MU * W).shift, rel=1e-14)
    with pytest.raises(ValueError):
        carter.cattaneo_line(W, A, E_STAR, MU, MU * W)
