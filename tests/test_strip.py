"""Strip theory (femcheck.cect.strip) against Carter per unit length, the exact 2D solver, Kalker's a/b -> 0
creep-coefficient asymptotes, Coulomb saturation and Kalker's sign convention."""
import numpy as np
import pytest

from femcheck.analytic import carter
from femcheck.cect.line import solve_line_friction
from femcheck.cect.strip import strip_theory
from femcheck.errors import InputError

G, NU, MU = 80e9, 0.3, 0.3
E_X = G / (1 - NU)                  # in-plane strip modulus E* = G/(1 - nu)
A, B, N = 0.2e-3, 200e-3, 2.0e5     # b/a = 1000: a very elongated ellipse
P0 = 3 * N / (2 * np.pi * A * B)
XI_SAT = 2 * MU * P0 / E_X          # saturation creepage of the central strip


@pytest.mark.parametrize("f", [0.2, 0.6, 0.95])
def test_central_strip_is_carter_per_unit_length(f):
    # b >> a, pure xi: the force per unit width of the central strip is Carter's 2D creep force with the
    # central a, p0 (W' = pi a p0/2), within 0.1 % (the strip load is the exact strip integral, a' and p0'
    # the centre values).
    r = strip_theory(A, B, N, G, NU, MU, xi=f * XI_SAT, n_strips=2001)
    k = r.n_strips // 2
    per_width = r.force_x[k] / r.width
    ref = carter.carter_creep_force(f * XI_SAT, np.pi * A * P0 / 2, A, E_X, MU)
    assert per_width == pytest.approx(ref, rel=1e-3)


def test_central_strip_against_exact_2d_solver():
    # Another model: Kalker's exact 2D theory on the central strip's Hertz line contact (same a, p0), 2 %.
    f = 0.5
    r = strip_theory(A, B, N, G, NU, MU, xi=f * XI_SAT, n_strips=2001)
    k = r.n_strips // 2
    w_line = np.pi * A * P0 / 2
    radius = np.pi * E_X * A**2 / (4 * w_line)          # the cylinder radius giving this a (Hertz)
    t = solve_line_friction(lambda x: x**2 / (2 * radius), E_X, w_line, 1.25 * A, 500, MU,
                            xi=f * XI_SAT).tangential
    assert r.force_x[k] / r.width == pytest.approx(t.tangential_force, rel=0.02)


@pytest.mark.parametrize("nu", [0.0, 0.25, 0.45])
def test_linear_limit_kalker_asymptotes(nu):
    # Kalker (1967/1990), a/b -> 0: C11 = pi^2/(4(1 - nu)), C22 = pi^2/4, with Fx = -G c^2 C11 xi,
    # Fy = -G c^2 C22 eta, c^2 = a b. Strip theory is exact in that limit; 0.1 % at 2000 strips.
    c2 = A * B
    xi = 1e-6 * XI_SAT
    r = strip_theory(A, B, N, G, nu, MU, xi=xi, n_strips=2000)
    assert -r.creep_force_x / (G * c2 * xi) == pytest.approx(np.pi**2 / (4 * (1 - nu)), rel=1e-3)
    r = strip_theory(A, B, N, G, nu, MU, eta=xi, n_strips=2000)
    assert -r.creep_force_y / (G * c2 * xi) == pytest.approx(np.pi**2 / 4, rel=1e-3)


def test_saturation_gives_mu_n():
    # Coulomb: beyond saturation in every strip |F| = mu N, along the creepage direction when nu = 0 (equal
    # in-plane and anti-plane strip moduli), with no adhesion left.
    for xi, eta in ((1.0, 0.0), (-1.0, 0.0), (0.3, -0.4)):
        r = strip_theory(A, B, N, G, 0.0, MU, xi=xi, eta=eta, n_strips=101)
        assert np.hypot(r.creep_force_x, r.creep_force_y) == pytest.approx(MU * N, rel=1e-12)
        unit = np.array([r.creep_force_x, r.creep_force_y]) / (MU * N)
        np.testing.assert_allclose(unit, -np.array([xi, eta]) / np.hypot(xi, eta), atol=1e-12)
        assert r.adhesion_fraction == 0.0
    assert r.normal_force == pytest.approx(N, rel=1e-12)     # load balance over the strips


def test_kalker_sign_convention():
    # Fx = -G c^2 C11 xi, Fy = -G c^2 C22 eta - G c^3 C23 phi, Mz = +G c^3 C23 eta - G c^4 C33 phi:
    # xi > 0 -> Fx < 0; eta > 0 -> Fy < 0 and Mz > 0; phi > 0 -> Mz < 0 (strips give no Fy from spin).
    s = 1e-3 * XI_SAT
    a, b = 1e-3, 2e-3
    r = strip_theory(a, b, N, G, NU, MU, xi=s)
    assert r.creep_force_x < 0 and r.creep_force_y == 0
    r = strip_theory(a, b, N, G, NU, MU, eta=s)
    assert r.creep_force_y < 0 and r.spin_moment > 0
    r = strip_theory(a, b, N, G, NU, MU, phi=s / b)
    assert r.spin_moment < 0 and r.creep_force_y == 0


def test_spin_linear_limit():
    # Longitudinal creepage -phi y per strip: Mz = -(pi^2 a b^3/16) G/(1 - nu) phi (integral of the linear
    # strip forces), i.e. C33 = pi^2 b/(16 (1 - nu) a), Kalker's a/b -> 0 asymptote; 0.1 % at 2000 strips.
    phi = 1e-6 * XI_SAT / B
    r = strip_theory(A, B, N, G, NU, MU, phi=phi, n_strips=2000)
    assert -r.spin_moment / (G * (A * B) ** 2 * phi) == pytest.approx(np.pi**2 * B / (16 * (1 - NU) * A), rel=1e-3)


def test_adhesion_fraction_limits_and_input():
    # No creepage: all adhesion; the area-weighted fraction drops monotonically to 0 at saturation.
    assert strip_theory(A, B, N, G, NU, MU).adhesion_fraction == pytest.approx(1.0, rel=1e-14)
    fr = [strip_theory(A, B, N, G, NU, MU, xi=f * XI_SAT).adhesion_fraction for f in (0.2, 0.5, 0.9)]
    assert fr[0] > fr[1] > fr[2] > 0
    with pytest.raises(InputError, match="mu"):
        strip_theory(A, B, N, G, NU, 0.0, xi=0.001)
    with pytest.raises(InputError, match="nu"):
        strip_theory(A, B, N, G, 0.5, MU, xi=0.001)
