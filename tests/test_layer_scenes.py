"""layer_contact scenes (layer-line, layer-point, coated-roller): the seed-001 figures, the dimensionless layer
keys, input refusal, load balance and the bounds of the layered solution."""
import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.bem.layered import LayeredSolid, response_factor
from femcheck.errors import InputError
from femcheck.problems import layer_contact
from femcheck.runner import run
from femcheck.scene import load_scene


def test_coated_roller_thin_layer_reproduces_seed_001_and_bem_sees_the_steel():
    res = run("coated-roller", models=["bem", "thin_layer", "analytic"], use_cache=False)
    assert res.models["bem"].status == "ok" and res.models["thin_layer"].status == "ok"
    thin, bem, hz = (res.models[m].quantities for m in ("thin_layer", "bem", "analytic"))
    # seed 001 §4: "tau_max = 0.3 p0 = 2.25 GPa" for the alumina-coated roller, i.e. p0 = 7.5 GPa
    assert thin["p_max_al2o3"] == pytest.approx(2.25e9 / 0.3, rel=0.01)
    # Hertz of a rigid 6.35 mm cylinder on uncoated steel (Johnson eq 4.45 with E* = E/(1 - nu^2))
    ref = hertz.line_contact(3683.6 / 0.0127, 0.00635, 206e9 / (1 - 0.3**2))
    assert hz["p_max_dlc"] == pytest.approx(ref.p_max, rel=1e-12)
    t = np.logspace(-4, 2, 2001)
    for c, (E, nu) in {"si3n4": (250e9, 0.20), "al2o3": (300e9, 0.21), "dlc": (220e9, 0.21)}.items():
        # Bracket from the frequency response: the layered compliance is r(kh) times steel's with r between its
        # extremes over all wavenumbers, so the contact lies between Hertz on steel with E* / r_max and with
        # E* / r_min (line Hertz: p0 ~ sqrt(E*)). A low-Poisson coating (Si3N4 0.20, DLC 0.21 on steel 0.30)
        # is up to 1.3 % / 4 % MORE compliant than steel near kh ~ 0.3-0.7 despite its higher E: r_max > 1.
        s = LayeredSolid(E, nu, 1.0, 206e9, 0.3)
        r = response_factor(t, s) * s.modulus_substrate / s.modulus_layer
        lo, hi = ref.p_max / np.sqrt(r.max()), ref.p_max / np.sqrt(r.min())
        assert lo * (1 - 1e-3) <= bem[f"p_max_{c}"] <= hi * (1 + 1e-3)
        # and a 2-6 um coating on a ~100 um contact barely moves it from steel: far from the thin-layer 3-4x
        assert thin[f"p_max_{c}"] / bem[f"p_max_{c}"] > 3.0
    # alumina is stiffer than steel at every wavenumber (r <= 1): the coated roller's peak must exceed steel's
    assert bem["p_max_al2o3"] > ref.p_max
    assert res.models["bem"].quantities["total_force"] == pytest.approx(3683.6 / 0.0127, rel=1e-9)


def test_dimensionless_layer_keys_resolve_to_the_dimensional_ones():
    sc = load_scene("layer-line")
    ref = hertz.line_contact(1e5, 0.01, 210e9 / (1 - 0.09))       # rigid cylinder on the uncoated substrate
    over = {"layer.thickness": None, "layer.E": None, "layer.h_over_a": 0.5, "layer.E_ratio": 2.0}
    lp = layer_contact.resolve_layer(sc.with_overrides(over).params)
    assert lp["layer.thickness"] == pytest.approx(0.5 * ref.half_width, rel=1e-12)
    assert lp["layer.E"] == pytest.approx(420e9, rel=1e-12)
    assert "layer.h_over_a" not in lp and "layer.E_ratio" not in lp
    # the same layer given both ways gives the same BEM result
    a = run(sc, {"layer.thickness": lp["layer.thickness"]}, models=["bem"], use_cache=False).models["bem"]
    b = run(sc, over, models=["bem"], use_cache=False).models["bem"]
    assert b.quantities["p_max"] == pytest.approx(a.quantities["p_max"], rel=1e-12)


@pytest.mark.parametrize("over,key", [
    ({"layer.h_over_a": 0.5, "layer.thickness": 1e-5}, "layer.thickness"),  # both of a pair
    ({"layer.E": None}, "layer.E"),                                        # neither of a pair
    ({"materials.substrate.rigid": True, "layer.thickness": None, "layer.h_over_a": 0.5,
      "models.run": "bem"}, "layer.h_over_a"),                           # no Hertz size on a rigid base
    ({"load.normal": 100.0}, "load.per_length"),                           # line and point at once
    ({"layer.nu": 0.6}, "layer.nu"),
])
def test_bad_layer_input_names_the_key(over, key):
    # (an override naming one key of a pair replaces the other: test_override_replaces_its_alternative)
    with pytest.raises(InputError) as err:
        load_scene("layer-line").with_overrides(over)
    assert err.value.key == key


def test_layer_point_scene_runs_and_balances_the_load():
    res = run("layer-point", models=["bem", "thin_layer", "analytic"], use_cache=False)
    bem = res.models["bem"].quantities
    assert bem["total_force"] == pytest.approx(100.0, rel=1e-9)
    # 420 GPa layer (h/a = 0.34) on 210 GPa steel: stiffer than steel, softer than the layer material as a
    # half-space (Hertz of each bounds the layered answer); axisymmetric: semi-axes equal to the grid's accuracy
    steel = hertz.elliptic_contact(100.0, 0.01, 0.01, 210e9 / 0.91)
    coat = hertz.elliptic_contact(100.0, 0.01, 0.01, 420e9 / (1 - 0.25**2))
    assert steel.p_max < bem["p_max"] < coat.p_max
    assert coat.semi_axis_x < bem["semi_axis_x"] < steel.semi_axis_x
    assert bem["semi_axis_y"] == pytest.approx(bem["semi_axis_x"], rel=1e-9)


@pytest.mark.parametrize("label", ["h/a=0.001", "E1/E2=100", "layer nu=0.5", "rigid substrate"])
def test_stress_cases_converge(label):
    sc = load_scene("layer-line")
    case = next(c for c in layer_contact.stress_cases(sc) if c.label == label)
    res = run(sc, case.overrides, models=["bem", "thin_layer"], use_cache=False)
    m = res.models["bem"]
    assert m.status == "ok", m.error
    assert m.quantities["total_force"] == pytest.approx(1e5, rel=1e-9)
    assert np.isfinite(m.quantities["p_max"]) and m.quantities["half_width"] > 0


def test_override_replaces_its_alternative():
    # layer-line is written with layer.thickness and layer.E; --set layer.h_over_a / layer.E_ratio replace them
    sc = load_scene("layer-line", {"layer.h_over_a": 0.5, "layer.E_ratio": 2.0})
    assert "layer.thickness" not in sc.params and "layer.E" not in sc.params
    a_h = hertz.line_contact(sc["load.per_length"], sc["geometry.radius"],
                             sc["materials.substrate.E"] / (1 - sc["materials.substrate.nu"] ** 2)).half_width
    lp = layer_contact.resolve_layer(sc.params)
    assert lp["layer.thickness"] == pytest.approx(0.5 * a_h, rel=1e-12)
    assert lp["layer.E"] == pytest.approx(2.0 * sc["materials.substrate.E"], rel=1e-12)
