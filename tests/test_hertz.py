"""Hertz line contact against figures worked by hand and against its own load balance."""
import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic.hertz import line_contact, reduced_radius
from femcheck.materials import Elastic, effective_modulus


def test_steel_cylinder_on_steel_block_by_hand():
    # Worked by hand: E* = 210e9 / (2 (1 - 0.09)) = 115.385 GPa; a^2 = 4 W R / (pi E*) = 4e4 / 3.62491e11
    # = 1.10348e-7 m^2 -> a = 0.332187 mm; p0 = 2 W / (pi a) = 2e6 / 1.043595e-3 = 1.91646 GPa.
    steel = Elastic(210e9, 0.3)
    e_star = effective_modulus(steel, steel)
    assert e_star == pytest.approx(115.385e9, rel=1e-5)
    h = line_contact(1.0e6, 0.010, e_star)
    assert h.half_width == pytest.approx(0.332187e-3, rel=1e-5)
    assert h.p_max == pytest.approx(1.91646e9, rel=1e-5)


def test_rigid_indenter_uses_plane_strain_modulus_of_block():
    e = effective_modulus(Elastic(1.0, 0.0, rigid=True), Elastic(70e9, 0.33))
    assert e == pytest.approx(70e9 / (1 - 0.33**2), rel=1e-12)


def test_both_rigid_refused():
    with pytest.raises(ValueError, match="rigid"):
        effective_modulus(Elastic(1, 0, True), Elastic(1, 0, True))


@pytest.mark.parametrize("load", [1e3, 1e6, 5e7])
def test_pressure_integrates_to_load(load):
    h = line_contact(load, 0.02, 100e9)
    total, _ = integrate.quad(h.pressure, -h.half_width, h.half_width, limit=200)
    assert total == pytest.approx(load, rel=1e-8)


def test_half_width_scales_with_sqrt_load():
    a1 = line_contact(1e5, 0.01, 1e11).half_width
    a2 = line_contact(4e5, 0.01, 1e11).half_width
    assert a2 / a1 == pytest.approx(2.0, rel=1e-12)


def test_reduced_radius():
    assert reduced_radius(0.01, 0.03) == pytest.approx(0.0075, rel=1e-12)
    assert reduced_radius(0.01, -0.03) == pytest.approx(0.015, rel=1e-12)   # concave raceway
    with pytest.raises(ValueError):
        reduced_radius(0.01, -0.005)      # groove tighter than the roller: no Hertzian contact
    assert np.isinf(np.inf) and reduced_radius(0.01) == pytest.approx(0.01)
