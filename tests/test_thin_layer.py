"""Johnson's thin layer on a rigid base: load balance by quadrature, the governing equations by finite
differences, the load exponents, and refusal of the compressible form at nu = 0.5."""
import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic.hertz import line_contact
from femcheck.analytic.thin_layer import compressible, constrained_modulus, incompressible
from femcheck.errors import InputError

E, NU, B, R = 300e9, 0.21, 3e-6, 6.35e-3          # Al2O3 3 um on the seed-001 roller (radius 6.35 mm)
W_LINE, P_POINT = 3683.6 / 0.0127, 100.0


def _load(c):
    if c.geometry == "line":
        return integrate.quad(c.pressure, -c.a, c.a, epsabs=0, epsrel=1e-12)[0]
    return integrate.quad(lambda r: 2 * np.pi * r * c.pressure(r), 0, c.a, epsabs=0, epsrel=1e-12)[0]


@pytest.mark.parametrize("make", [
    lambda: compressible(E, NU, B, R, W_LINE, "line"),
    lambda: compressible(E, NU, B, R, P_POINT, "circular"),
    lambda: incompressible(E, B, R, W_LINE, "line"),
    lambda: incompressible(E, B, R, P_POINT, "circular"),
    lambda: incompressible(E, B, R, W_LINE, "line", top="bonded"),
])
def test_pressure_integrates_to_the_load(make):
    c = make()
    assert _load(c) == pytest.approx(W_LINE if c.geometry == "line" else P_POINT, rel=1e-9)
    assert c.pressure(np.array([0.0]))[0] == pytest.approx(c.p_max, rel=1e-12)
    assert c.pressure(np.array([c.a, 1.5 * c.a])) == pytest.approx([0.0, 0.0], abs=1e-6 * c.p_max)


def test_compressible_layer_is_a_winkler_foundation_of_the_constrained_modulus():
    c = compressible(E, NU, B, R, W_LINE, "line")
    x = np.linspace(-0.9, 0.9, 7) * c.a
    # eqs 19-21: p = (M / b) (delta - x^2 / 2R) with the rigid approach delta
    np.testing.assert_allclose(c.pressure(x), constrained_modulus(E, NU) / B * (c.approach - x * x / (2 * R)),
                               rtol=1e-12)
    assert constrained_modulus(E, 0.0) == E and constrained_modulus(E, 0.25) == pytest.approx(1.2 * E)


@pytest.mark.parametrize("geometry", ["line", "circular"])
def test_incompressible_layer_satisfies_the_squeeze_equation(geometry):
    c = incompressible(E, B, R, W_LINE if geometry == "line" else P_POINT, geometry)
    k = 3 * (E / 3) / B**3
    h = 1e-4 * c.a
    x = np.linspace(0.1, 0.9, 9) * c.a
    p = c.pressure
    d2 = (p(x + h) - 2 * p(x) + p(x - h)) / h**2
    d1 = (p(x + h) - p(x - h)) / (2 * h)
    lhs = d2 if geometry == "line" else d2 + d1 / x           # (1/r) d/dr (r dp/dr)
    np.testing.assert_allclose(lhs, -k * (c.approach - x * x / (2 * R)), rtol=1e-5)
    # free boundary: the pressure leaves the edge with zero slope, so a one-sided slope falls linearly with h
    slope = [(p(np.array([c.a - s])) - p(np.array([c.a])))[0] / s for s in (h, h / 10)]
    assert slope[0] / slope[1] == pytest.approx(10.0, rel=1e-3)


@pytest.mark.parametrize("make,exponent", [
    (lambda w: compressible(E, NU, B, R, w, "line"), 1 / 3),
    (lambda w: compressible(E, NU, B, R, w, "circular"), 1 / 4),
    (lambda w: incompressible(E, B, R, w, "line"), 1 / 5),
    (lambda w: incompressible(E, B, R, w, "circular"), 1 / 6),
])
def test_contact_size_grows_with_the_load_exponent(make, exponent):
    assert make(8.0).a / make(1.0).a == pytest.approx(8.0**exponent, rel=1e-12)


def test_hard_thin_coating_is_far_stiffer_than_the_half_space():
    # seed 001 §4: hard 2-3 um coatings give several times the Hertz pressure of the uncoated roller
    hz = line_contact(W_LINE, R, 1.0 / (2 * (1 - 0.3**2) / 206e9))
    c = compressible(E, NU, B, R, W_LINE, "line")
    assert 4.0 < c.p_max / hz.p_max < 8.0 and 0.1 < c.a / hz.half_width < 0.3


def test_compressible_form_refuses_incompressible_layers():
    with pytest.raises(InputError, match="layer.nu"):
        compressible(E, 0.5, B, R, W_LINE)
    with pytest.raises(InputError, match="layer.thickness"):
        incompressible(E, 0.0, R, W_LINE)


def test_alumina_coated_roller_reproduces_seed_001_peak_pressure():
    # seed 001 §4 (eq 27 discussion): for the alumina-coated roller "tau_max = 0.3 p0 = 2.25 GPa", i.e.
    # p0 = 7.5 GPa; Johnson's compressible layer with the load-balance exponent 1/3 and the roller radius
    # 6.35 mm (diameter 12.7 mm) gives 7.49 GPa
    c = compressible(300e9, 0.21, 3e-6, 6.35e-3, 3683.6 / 0.0127, "line")
    assert c.p_max == pytest.approx(2.25e9 / 0.3, rel=0.01)
