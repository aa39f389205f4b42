"""Stale references cannot pass (issue 12, finding 1): for every stored frictionless FE reference, the stored file
for the current key exists and its coarsest level is what the code computes now (re-solved alone, compared to
1e-6: meshes are deterministic). Mutations this catches (see the closing notes of issue 12): the FE block
stiffness scaled by 1.02, a Gmsh builder's algorithm or size field changed, the Hertz value returned instead of
the FE's own p_max -- each moves a level-0 number far beyond 1e-6 (and changes the key, so the stored file is
missing too)."""
import pytest

from femcheck import reference_check
from femcheck.result import ModelResult

STORED = [     # (scene, model, scene overrides the reference was solved with)
    pytest.param("layer-rigid", "fem", None, id="layer-rigid"),
    pytest.param("layer-line", "fem", None, id="layer-line"),
    pytest.param("coated-roller", "fem", None, id="coated-roller", marks=pytest.mark.slow),   # 8 s
    pytest.param("layer-point", "fem", None, id="layer-point", marks=pytest.mark.slow),
    pytest.param("hertz-point", "fem", None, id="hertz-point", marks=pytest.mark.slow),       # 11 s
    pytest.param("srb-normal", "fem", None, id="srb-normal-fem", marks=pytest.mark.slow),
    pytest.param("srb-normal", "fem_conformal", None, id="srb-normal-fem_conformal", marks=pytest.mark.slow),
    pytest.param("roller-finite", "fem", None, id="roller-finite", marks=pytest.mark.slow),
    pytest.param("groove-rolling", "fem", None, id="groove-rolling", marks=pytest.mark.slow),             # 10 s
    pytest.param("srb-rolling", "fem", None, id="srb-rolling", marks=pytest.mark.slow),                   # 30 s
    # Table 2's second case, stored beside the default (spec srb-rolling item 15: the FE at the mu = 0.3 pose)
    pytest.param("srb-rolling", "fem", {"friction.mu": 0.3}, id="srb-rolling-mu0.3", marks=pytest.mark.slow),
]
# references whose kind declares no coarsest-level overrides: (scene, model, overrides, numbers compared at least)
OTHERS = [
    pytest.param("crb-rigid-rings", "fem", {"numerics.fem_levels": 1}, 3, id="crb-rigid-rings"),
    pytest.param("crb-elastic-rings", "fem", {"numerics.fem_levels": 1}, 3, id="crb-elastic-rings",
                 marks=pytest.mark.slow),
    pytest.param("crb-housing-arc", "fem", {"numerics.fem_levels": 1}, 3, id="crb-housing-arc",
                 marks=pytest.mark.slow),
    pytest.param("ehl-smooth", "ehl", {}, 1, id="ehl-smooth", marks=pytest.mark.slow),
    # single-level references: the whole model is re-solved (about 100 s and 25 s)
    pytest.param("ehl-indent", "ehl", {}, 10, id="ehl-indent", marks=pytest.mark.slow),
    pytest.param("indent-life", "bem_transient", {}, 5, id="indent-life", marks=pytest.mark.slow),     # the whole model (three grids): 3 s
]


@pytest.mark.parametrize("scene, model, params", STORED)
def test_stored_reference_reproduces_its_coarsest_level(scene, model, params):
    c = reference_check.check(scene, model, params=params)
    assert c.stored is not None, (f"references/ has no {scene} {model} entry for the current code (key "
                                  f"{c.key[:16]}); regenerate it with `{c.command}`")
    assert c.fresh.status == "ok", c.fresh.error
    assert len(c.compared) >= 4
    assert not c.mismatches, f"{scene} {model}: the stored reference is stale:\n  " + "\n  ".join(c.mismatches)
    # the stored reference states per quantity whether it is certified (issue 12, finding 3)
    certs = c.stored.stats.get("certificates") or {
        f"{k}_{name}": v for name, sub in c.stored.stats.items() if isinstance(sub, dict)
        for k, v in sub.get("certificates", {}).items()}
    assert certs and all({"value", "certified", "error_estimate", "note"} <= set(v) for v in certs.values())


@pytest.mark.parametrize("scene, model, coarse, at_least", OTHERS)
def test_other_stored_references_reproduce_their_coarsest_level(scene, model, coarse, at_least):
    c = reference_check.check(scene, model, coarse=coarse)
    assert c.stored is not None, (f"references/ has no {scene} {model} entry for the current code (key "
                                  f"{c.key[:16]}); regenerate it with `{c.command}`")
    assert c.fresh.status == "ok", c.fresh.error
    assert len(c.compared) >= at_least
    assert not c.mismatches, f"{scene} {model}: the stored reference is stale:\n  " + "\n  ".join(c.mismatches)


def test_a_stored_number_off_by_one_part_in_a_million_is_caught():
    level = {"h": 1e-5, "p_max": 2.0e9, "semi_axis_x": 4e-4, "n_nodes": 2410}
    stored = ModelResult("fem", stats={"levels": [level, dict(level, h=5e-6)]})
    same = ModelResult("fem", stats={"levels": [dict(level)]})
    assert reference_check.compare_coarse(stored, same, 1e-6)[1] == []
    moved = ModelResult("fem", stats={"levels": [dict(level, p_max=2.0e9 * (1 + 2e-6))]})
    bad = reference_check.compare_coarse(stored, moved, 1e-6)[1]
    assert len(bad) == 1 and "p_max" in bad[0]


def test_level_tables_of_contacts_and_coatings():
    per_contact = {"levels": [{"contact": "inner", "p_max": 1.0}, {"contact": "outer", "p_max": 2.0},
                              {"contact": "inner", "p_max": 1.1}], "inner": {"levels": [{"p_max": 1.0}]}}
    assert {k: len(v) for k, v in reference_check.level_tables(per_contact).items()} == {"inner": 2, "outer": 1}
    per_coating = {"dlc": {"levels": [{"p_max": 1.0}, {"p_max": 1.1}]}, "si3n4": {"levels": [{"p_max": 2.0}]}}
    assert sorted(reference_check.level_tables(per_coating)) == ["dlc", "si3n4"]
