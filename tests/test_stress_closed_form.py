"""McEwen sub-surface stresses against independent values: Flamant superposition by quadrature (seed 001
eq 25 and its sigma_x, sigma_z siblings), the Smith-Liu form of seed 004 App. C, the axis formulas and the
textbook maxima (Johnson 1985 §4.2: tau_1 = 0.300 p0 at z = 0.786 a; |tau_xz| = 0.25 p0 at x = 0.87 a,
z = 0.5 a)."""
import numpy as np
import pytest
from scipy import integrate, optimize

from femcheck.analytic.hertz import line_contact
from femcheck.analytic.stress import line_contact_field, mcewen

A, P0 = 1.0, 1.0
POINTS = [(0.0, 0.3), (0.3, 0.5), (0.87, 0.5), (-0.7, 1.3), (1.5, 0.2), (0.99, 0.05), (2.5, 2.0)]


def flamant(x, z):
    """Stresses of p = p0 sqrt(1 - s^2) by superposing Flamant line loads (Johnson eq. 2.15)."""
    def q(f):
        return integrate.quad(lambda s: P0 * np.sqrt(1 - s * s) * f(s), -A, A, limit=400, epsabs=1e-13)[0]
    r4 = lambda s: ((x - s) ** 2 + z * z) ** 2
    sx = -2 / np.pi * z * q(lambda s: (x - s) ** 2 / r4(s))
    sz = -2 / np.pi * z**3 * q(lambda s: 1 / r4(s))
    txz = -2 / np.pi * z**2 * q(lambda s: (x - s) / r4(s))     # seed 001 eq (25)
    return sx, sz, txz


def smith_liu(X, Z):
    """Seed 004 eq (C.1)."""
    c1, c2 = (1 + X) ** 2 + Z**2, (1 - X) ** 2 + Z**2
    r = np.sqrt(c2 / c1)
    den = r * np.sqrt(2 * r + (c1 + c2 - 4) / c1)
    psi, psib = np.pi / c1 * (1 - r) / den, np.pi / c1 * (1 + r) / den
    return (-Z / np.pi * (psib * (1 + 2 * X**2 + 2 * Z**2) - 2 * np.pi - 3 * X * psi),
            -Z / np.pi * (psib - X * psi), -Z**2 * psi / np.pi)


@pytest.mark.parametrize("x,z", POINTS)
def test_mcewen_matches_flamant_quadrature(x, z):
    s = mcewen(x, z, A, P0, 0.3)
    ref = flamant(x, z)
    for key, r in zip(("sigma_x", "sigma_z", "tau_xz"), ref):
        assert float(s[key]) == pytest.approx(r, abs=1e-9)


@pytest.mark.parametrize("x,z", POINTS)
def test_mcewen_matches_smith_liu(x, z):
    s = mcewen(x, z, A, P0, 0.3)
    for key, r in zip(("sigma_x", "sigma_z", "tau_xz"), smith_liu(x, z)):
        assert float(s[key]) == pytest.approx(r, abs=1e-12)


def test_axis_formulas():
    z = np.linspace(0.01, 3, 50)
    s = mcewen(np.zeros_like(z), z, A, P0, 0.3)
    root = np.sqrt(1 + z * z)
    np.testing.assert_allclose(s["sigma_z"], -1 / root, atol=1e-13)
    np.testing.assert_allclose(s["sigma_x"], -((1 + 2 * z * z) / root - 2 * z), atol=1e-13)
    np.testing.assert_allclose(s["tau_xz"], 0.0, atol=1e-15)


def test_surface_stresses_inside_contact_equal_pressure():
    x = np.linspace(-0.95, 0.95, 21)
    s = mcewen(x, np.zeros_like(x), A, P0, 0.3)
    np.testing.assert_allclose(s["sigma_z"], -np.sqrt(1 - x * x), atol=1e-12)
    np.testing.assert_allclose(s["sigma_x"], -np.sqrt(1 - x * x), atol=1e-12)


def test_textbook_maxima():
    h = line_contact(1e6, 0.01, 115e9)
    f = line_contact_field(h, 0.3)
    a, p0 = h.half_width, h.p_max
    assert f.maxima["tau_max"] / p0 == pytest.approx(0.300, abs=0.0005)
    assert f.maxima["tau_max_depth"] / a == pytest.approx(0.786, abs=0.001)
    assert f.maxima["tau_xz_max"] / p0 == pytest.approx(0.250, abs=0.0005)
    assert f.maxima["tau_xz_max_depth"] / a == pytest.approx(0.5, abs=0.001)
    assert f.maxima["tau_xz_max_x"] / a == pytest.approx(np.sqrt(3) / 2, abs=0.001)


def test_von_mises_maximum_against_axis_optimum():
    # Independent: von Mises on the axis from the closed axis formulas, maximised by a scalar optimiser.
    nu = 0.3

    def vm_axis(z):
        root = np.sqrt(1 + z * z)
        sz, sx = -1 / root, -((1 + 2 * z * z) / root - 2 * z)
        sy = nu * (sx + sz)
        return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2))

    best = optimize.minimize_scalar(lambda z: -vm_axis(z), bounds=(0.1, 2), method="bounded",
                                    options={"xatol": 1e-10})
    h = line_contact(1e6, 0.01, 115e9)
    f = line_contact_field(h, nu)
    assert f.maxima["von_mises_max"] / h.p_max == pytest.approx(-best.fun, rel=1e-6)
    assert f.maxima["von_mises_max_depth"] / h.half_width == pytest.approx(best.x, rel=1e-4)
    assert -best.fun == pytest.approx(0.5575, abs=0.0005)   # ~0.56 p0 at ~0.70 a for nu = 0.3
