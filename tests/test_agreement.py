"""Scene-level model agreement, written with the femcheck pytest plugin as a user would write it.

Acceptance numbers of the hertz-line scene: BEM within 1 % of Hertz; FEM within 3 % at its finest level and
within 1 % after Richardson extrapolation; the FEM reference agrees with the BEM."""
import pytest

SCENE = "hertz-line"
pytestmark = pytest.mark.slow          # one hertz-line run with its three FE levels, shared by every test here


@pytest.mark.parametrize("quantity", ["p_max", "half_width"])
def test_bem_matches_hertz(femcheck_run, femcheck_assert_agree, quantity):
    res = femcheck_run(SCENE)
    femcheck_assert_agree(res, quantity, "bem", "analytic", rtol=0.01)


@pytest.mark.parametrize("quantity", ["p_max", "half_width"])
def test_fem_finest_and_extrapolated_match_hertz(femcheck_run, femcheck_assert_agree, quantity):
    res = femcheck_run(SCENE)
    femcheck_assert_agree(res, quantity, "fem@finest", "analytic", rtol=0.03)
    femcheck_assert_agree(res, quantity, "fem", "analytic", rtol=0.01)


def test_richardson_error_estimate_covers_fem_to_bem_difference(femcheck_run):
    # Independent check of the certification: the extrapolated FEM and the BEM (a different discretisation
    # of the same half-space physics) differ by less than the FEM error estimate plus the finite-block bias
    # FEM-NOTES measured (+0.1 % on p0 for a clamped 40a x 20a block).
    res = femcheck_run(SCENE)
    fem, bem = res.models["fem"], res.models["bem"]
    est = fem.stats["richardson"]["p_max"]["error_estimate"]
    assert abs(fem.quantities["p_max"] - bem.quantities["p_max"]) <= est + 1.5e-3 * bem.quantities["p_max"]


def test_textbook_stress_maxima(femcheck_run, femcheck_assert_agree):
    res = femcheck_run(SCENE, models=["analytic"])
    p0, a = res.models["analytic"].quantities["p_max"], res.models["analytic"].quantities["half_width"]
    q = res.models["analytic"].quantities
    assert q["tau_max"] == pytest.approx(0.300 * p0, rel=2e-3)           # Johnson 1985 §4.2
    assert res.models["analytic"].stats["stress_maxima"]["tau_max_depth"] == pytest.approx(0.786 * a, rel=2e-3)
    assert q["tau_xz_max"] == pytest.approx(0.250 * p0, rel=2e-3)


@pytest.mark.parametrize("overrides", [
    {"materials.cylinder.rigid": True},
    {"materials.cylinder.E": 70e9, "materials.cylinder.nu": 0.33},        # aluminium roller on steel
    {"materials.block.nu": 0.4999, "materials.cylinder.rigid": True},      # near-incompressible block
])
def test_fem_and_bem_agree_on_variants(femcheck_run, femcheck_assert_agree, overrides):
    res = femcheck_run(SCENE, overrides, models=["analytic", "bem", "fem"])
    femcheck_assert_agree(res, "p_max", "fem", "analytic", rtol=0.01)
    femcheck_assert_agree(res, "p_max", "bem", "fem", rtol=0.01)
    femcheck_assert_agree(res, "half_width", "bem", "fem", rtol=0.01)


def test_penalty_method_scene(femcheck_run, femcheck_assert_agree):
    res = femcheck_run(SCENE, {"numerics.fem_method": "penalty"}, models=["analytic", "fem"])
    femcheck_assert_agree(res, "p_max", "fem", "analytic", rtol=0.01)
    assert res.models["fem"].stats["method"] == "penalty"


def test_fem_cache_reuses_result(femcheck_run):
    from femcheck.runner import run

    first = femcheck_run(SCENE)
    again = run(SCENE, models=["fem"])
    assert again.models["fem"].cached
    assert again.models["fem"].quantities == first.models["fem"].quantities


def test_outputs_decide_what_is_computed(femcheck_run):
    res = femcheck_run(SCENE, {"outputs.subsurface_stress": False}, models=["analytic"])
    assert "von_mises_max" not in res.models["analytic"].quantities
    assert "von_mises" not in res.models["analytic"].fields
