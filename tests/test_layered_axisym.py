"""The axisymmetric section FE of the layered point scenes (femcheck.fem.layered_axisym) against independent
solutions: Hertz (layer and substrate of one material) and the Hankel-transform solution of a layer bonded to a
rigid base (femcheck.analytic.layer_axisymmetric, Sneddon's reduction to a Fredholm equation). One level each
(h = a/20, 3-8k DOFs, about a second).

Bands: the a/20 level's discretisation error from the refinement study (a/20, a/40, a/80; docs/notes/
p2-mortar.md): homogeneous p_max +0.003 %, radius +0.040 %; rigid base p_max +0.004 %, radius +0.056 %; the
certified values of three levels lie within 0.01 % of both closed forms. Bands: 0.05 % (p_max) and 0.15 %
(radius), about three times the level's error."""
import pytest

from femcheck.analytic import hertz, layer_axisymmetric
from femcheck.fem import layered_axisym

BASE = {"geometry.radius": 0.01, "load.normal": 100.0, "layer.E": 210e9, "layer.nu": 0.3,
        "layer.thickness": 50e-6, "materials.substrate.E": 210e9, "materials.substrate.nu": 0.3,
        "materials.substrate.rigid": False, "numerics.fem_levels": 1}


def test_axisymmetric_section_is_hertz_for_one_material():
    res = layered_axisym.model(BASE)
    h = hertz.point_contact(100.0, 0.01, 210e9 / (1 - 0.3**2))
    assert res.quantities["p_max"] / h.p_max == pytest.approx(1.0, abs=5e-4)
    assert res.quantities["semi_axis_x"] / h.semi_axis_x == pytest.approx(1.0, abs=1.5e-3)
    assert res.quantities["total_force"] == pytest.approx(100.0, rel=1e-10)


def test_axisymmetric_section_matches_the_transform_solution_on_a_rigid_base():
    res = layered_axisym.model({**BASE, "materials.substrate.rigid": True})
    c = layer_axisymmetric.contact(210e9, 0.3, 50e-6, 0.01, 100.0)
    assert res.quantities["p_max"] / c.p_max == pytest.approx(1.0, abs=5e-4)
    assert res.quantities["semi_axis_x"] / c.a == pytest.approx(1.0, abs=1.5e-3)


def test_axisymmetric_section_refuses_a_line_contact():
    from femcheck.errors import InputError
    from femcheck.problems import layer_contact

    with pytest.raises(InputError, match="fem_axisym"):
        layer_contact.SINGLE["fem_axisym"]({**BASE, "load.per_length": 1e5})


@pytest.mark.parametrize("thickness, nu", [(5e-6, 0.3), (15e-6, 0.45)])
def test_axisymmetric_section_certifies_thin_layers_on_a_rigid_base(thickness, nu):
    """Thin layers on a rigid base (t/a = 0.07 and 0.2): three levels, certified values against the transform
    solution. The separation's 3/2 law holds only within about t of the edge, so its window is at most t long;
    measured radius +0.027 % / -0.009 % (certificate estimates 0.015 % / 0.011 %), p_max within 0.004 %. Bands:
    p_max 0.01 %, radius 0.05 % (the estimate plus the window's bias on a boundary layer of width t; a window of
    0.3 a put the radius 0.30 % low at t/a = 0.07, with a certificate of 0.085 %)."""
    p = {**BASE, "materials.substrate.rigid": True, "layer.thickness": thickness, "layer.nu": nu,
         "numerics.fem_levels": 3}
    res = layered_axisym.model(p)
    c = layer_axisymmetric.contact(210e9, nu, thickness, 0.01, 100.0)
    certs = res.stats["certificates"]
    assert certs["p_max"]["certified"] and certs["semi_axis_x"]["certified"]
    assert res.quantities["p_max"] / c.p_max == pytest.approx(1.0, abs=1e-4)
    assert res.quantities["semi_axis_x"] / c.a == pytest.approx(1.0, abs=5e-4)
