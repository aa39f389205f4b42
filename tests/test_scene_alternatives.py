"""Inputs that replace each other (a kind's ALTERNATIVES) are never silently replaced: the one given last wins.
Each pair is checked by running the overridden scene against the same scene written with only the overriding
inputs (the scene's own option removed with None): the results must be identical."""
import pytest

import femcheck
from femcheck.problems import problem
from femcheck.scene import builtin_scene_files, load_scene

CASES = [
    # (scene, overrides, the scene keys they must remove, models)
    ("ehl-smooth", {"load.normal": 50.0, "kinematics.mean_speed": 2.0}, ("ehl.M", "ehl.L"),
     ["moes", "hamrock_dowson"]),
    ("layer-line", {"layer.h_over_a": 0.1}, ("layer.thickness",), ["thin_layer", "bem"]),
    ("layer-line", {"layer.E_ratio": 3.0}, ("layer.E",), ["thin_layer", "bem"]),
    ("hertz-point", {"geometry.Rx": 0.02, "geometry.Ry": 0.03}, ("geometry.radius",), ["analytic", "bem"]),
    ("creep-curve", {"geometry.radius": 0.01}, ("geometry.Rx", "geometry.Ry"), ["analytic", "linear"]),
]


@pytest.mark.parametrize("scene, over, removed, models", CASES, ids=[f"{c[0]}-{next(iter(c[1]))}" for c in CASES])
def test_the_input_given_last_wins(scene, over, removed, models):
    sc = load_scene(scene, over)
    assert not any(k in sc.params for k in removed), f"{removed} kept beside {over}"
    assert all(sc[k] == v for k, v in over.items())
    written = femcheck.run(scene, {**over, **{k: None for k in removed}}, models=models)
    overridden = femcheck.run(scene, over, models=models)
    for m in models:
        assert overridden.models[m].quantities == written.models[m].quantities
    # and the override changed the answer (the scene's own inputs would have given another one)
    base = femcheck.run(scene, models=models)
    assert any(overridden.models[m].quantities != base.models[m].quantities for m in models)


def test_the_moes_groups_win_over_a_scene_written_with_load_and_speed():
    physical = {"ehl.M": None, "ehl.L": None, "load.normal": 50.0, "kinematics.mean_speed": 2.0}
    sc = load_scene("ehl-smooth", physical).with_overrides({"ehl.M": 300.0, "ehl.L": 8.0})
    assert "load.normal" not in sc.params and "kinematics.mean_speed" not in sc.params


def test_every_alternatives_group_of_every_kind_is_exercised():
    kinds = {load_scene(n).kind for n in builtin_scene_files()}
    declared = {(k, i) for k in kinds for i, _ in enumerate(getattr(problem(k), "ALTERNATIVES", ()))}
    covered = set()
    for scene, over, removed, _ in CASES:
        kind = load_scene(scene).kind
        for i, group in enumerate(getattr(problem(kind), "ALTERNATIVES", ())):
            keys = {k for o in group for k in ((o,) if isinstance(o, str) else o)}
            if set(over) <= keys and set(removed) <= keys:
                covered.add((kind, i))
    assert declared <= covered, f"replacing groups without a test: {sorted(declared - covered)}"
