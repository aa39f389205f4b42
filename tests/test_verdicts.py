"""Verdicts of comparisons (femcheck.compare, issue 12 finding 7): every comparison graded, a contrast judged by
its band, an uncertified reference never passes, copied and load-balance values not compared twice, and no
built-in scene with an ungraded comparison or a candidate model that is not valid."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck import runner
from femcheck.compare import compare
from femcheck.result import ModelResult, RunResult
from femcheck.scene import builtin_scene_files, load_scene
from grading import assert_fully_graded
from stored_references import use_stored_references


def _scene(**tol):
    over = {"models.run": ["analytic", "bem", "fem"], "models.references": ["analytic"],
            "models.contrast": ["fem"]}
    over.update({f"tolerances.{k.replace('__', '.')}": v for k, v in tol.items()})
    return load_scene("hertz-line", over)


def _res(name, **q):
    return ModelResult(name, "ok", 0.1, dict(q))


def _verdicts(comps):
    return {(c.model, c.quantity): c.verdict for c in comps}


def test_candidate_and_contrast_verdicts():
    sc = load_scene("hertz-line", {"models.references": ["analytic"], "models.contrast": ["fem"],
                                   "tolerances.bem.p_max": 0.01, "tolerances.fem.p_max": 0.01,
                                   "tolerances.bem.half_width": None})          # None removes the key
    results = {"analytic": _res("analytic", p_max=1.0, half_width=2.0),
               "bem": _res("bem", p_max=1.005, half_width=2.1),          # p_max 0.5 %: valid; half_width: none
               "fem": _res("fem", p_max=1.02)}                           # a contrast 2 % off a 1 % band
    comps, _ = compare(sc, results, 1.0)
    v = _verdicts(comps)
    assert v[("bem", "p_max")] == "valid" and v[("fem", "p_max")] == "not valid here"
    assert v[("bem", "half_width")] == "ungraded"
    run = RunResult("hertz-line", sc.params, results, comps)
    # the contrast outside its band does not fail the scene; the ungraded comparison does
    assert any("half_width" in p and "no tolerances.bem.half_width" in p for p in run.problems)
    assert not any(p.startswith("fem") for p in run.problems)
    # within its band a contrast is "contrast", never "valid", and never counts as a pass
    results["fem"] = _res("fem", p_max=1.006)
    comps, _ = compare(sc, results, 1.0)
    c = next(c for c in comps if c.model == "fem")
    assert c.verdict == "contrast" and c.passed is False and c.contrast


def test_candidate_out_of_tolerance_fails_the_scene():
    sc = _scene(bem__p_max=0.001)
    results = {"analytic": _res("analytic", p_max=1.0), "bem": _res("bem", p_max=1.0011)}
    comps, _ = compare(sc, results, 1.0)
    run = RunResult("hertz-line", sc.params, results, comps)
    assert comps[0].verdict == "not valid here" and not run.passed        # 10 % beyond the tolerance
    assert run.problems == ["bem p_max off analytic by 0.0011 > tolerance 0.001"]
    results["bem"] = _res("bem", p_max=1.0009)
    comps, _ = compare(sc, results, 1.0)
    assert comps[0].verdict == "valid" and RunResult("s", sc.params, results, comps).passed


def test_uncertified_reference_cannot_pass():
    sc = load_scene("hertz-line", {"models.references": ["fem"], "tolerances.bem.p_max": 0.5})
    cert = {"p_max": {"value": 1.0, "finest": 1.0, "order": None, "error_estimate": 0.03, "certified": False,
                      "note": "the last three levels oscillate"},
            "half_width": {"value": 2.0, "finest": 2.0, "order": 2.0, "error_estimate": 1e-4, "certified": True,
                           "note": "ok"}}
    fem = ModelResult("fem", "ok", 1.0, {"p_max": 1.0, "half_width": 2.0}, {"certificates": cert})
    bem = _res("bem", p_max=1.0001, half_width=2.0001)
    comps, _ = compare(sc, {"bem": bem, "fem": fem}, 1.0)
    v = {c.quantity: c for c in comps}
    assert v["p_max"].verdict == "reference uncertified" and v["p_max"].passed is False
    assert "oscillate" in v["p_max"].note
    assert v["half_width"].verdict == "valid"
    # far beyond tolerance + the uncertified reference's own error estimate: not valid, whatever its certificate
    comps, _ = compare(sc, {"bem": _res("bem", p_max=1.6, half_width=2.0001), "fem": fem}, 1.0)
    assert {c.quantity: c.verdict for c in comps}["p_max"] == "not valid here"          # 0.6 > 0.5 + 0.03
    comps, _ = compare(sc, {"bem": _res("bem", p_max=1.52, half_width=2.0001), "fem": fem}, 1.0)
    assert {c.quantity: c.verdict for c in comps}["p_max"] == "reference uncertified"   # 0.52 <= 0.53
    # a stats dict from before certificates: a Richardson entry without an observed order is not certified
    fem.stats = {"richardson": {"p_max": {"value": 1.0, "order": None, "error_estimate": 0.0, "finest": 1.0}}}
    comps, _ = compare(sc, {"bem": bem, "fem": fem}, 1.0)
    assert {c.quantity: c.verdict for c in comps}["p_max"] == "reference uncertified"


def test_copied_load_and_singular_values_are_not_compared():
    sc = _scene(bem__p_max=0.01, bem__half_width=0.01, fem__p_max=0.01, fem__half_width=0.01)
    results = {"analytic": _res("analytic", p_max=1.0, half_width=2.0, total_force=5.0),
               "bem": _res("bem", p_max=1.001, half_width=2.0, total_force=5.0 + 1e-12),   # half_width copied
               "fem": _res("fem", p_max=1.001, half_width=2.002)}        # p_max identical to the bem's
    comps, skipped = compare(sc, results, 1.0, singular=("edge_peak",))
    assert {(c.model, c.quantity) for c in comps} == {("bem", "p_max"), ("fem", "half_width")}
    assert not skipped
    results["bem"].quantities["edge_peak"] = 3.0
    results["analytic"].quantities["edge_peak"] = 2.0
    comps, skipped = compare(sc, results, 1.0, singular=("edge_peak",))
    assert "edge_peak" in skipped and all(c.quantity != "edge_peak" for c in comps)


def test_profiles_are_graded_and_json_keeps_pass():
    sc = _scene(bem__p_max=0.01, bem__pressure_profile_l2=0.02, bem__pressure_profile_max=0.05)
    x = np.linspace(0, 1, 50)
    p = np.sqrt(np.clip(1 - x**2, 0, None))
    a = ModelResult("analytic", "ok", 0.0, {"p_max": 1.0}, fields={"x": x, "pressure": p})
    b = ModelResult("bem", "ok", 0.0, {"p_max": 1.0}, fields={"x": x, "pressure": 1.01 * p})   # p_max copied
    comps, _ = compare(sc, {"analytic": a, "bem": b}, 1.0)
    v = {c.quantity: c for c in comps}
    assert set(v) == {"pressure_profile_l2", "pressure_profile_max"}
    assert v["pressure_profile_l2"].rel_error == pytest.approx(0.01, rel=1e-6)
    assert v["pressure_profile_l2"].verdict == "valid"
    d = v["pressure_profile_l2"].to_json()
    assert d["pass"] is True and d["verdict"] == "valid" and "passed" not in d


def test_scene_keys_refuse_contrast_reference_and_unknown_tolerance_model():
    from femcheck.errors import InputError

    with pytest.raises(InputError, match="models.contrast"):
        load_scene("hertz-line", {"models.contrast": ["analytic"]})
    with pytest.raises(InputError, match="did you mean 'bem'"):
        load_scene("hertz-line", {"tolerances.bme.p_max": 0.1})
    assert load_scene("hertz-line", {"tolerances.fem@finest.p_max": 0.1})["tolerances.fem@finest.p_max"] == 0.1


# slow: hertz-line (its 2D FE is solved), indent-life (pseudo-transient, 80 s), srb-rolling and srb-rolling-finite (6 s:
# the CECT equilibrium on 61 x 121), hertz-point (1 s)
SLOW_SCENES = ("hertz-line", "indent-life", "srb-rolling", "srb-rolling-finite", "hertz-point")


# scenes whose own test runs them whole and makes the same checks (assert_fully_graded): run once, not twice
GRADED_ELSEWHERE = {"crb-3d-misaligned": "tests/test_bearing_resolved.py",
                    "trb-mill-4row": "tests/test_mill_chock.py"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_SCENES else n
                                  for n in sorted(builtin_scene_files()) if n not in GRADED_ELSEWHERE])
def test_builtin_scene_is_fully_graded(name, monkeypatch):
    """Every built-in scene is fully graded (:func:`assert_fully_graded`). Stored FE references stand in for the
    FE solves."""
    sc = load_scene(name)
    use_stored_references(monkeypatch)
    assert_fully_graded(runner.run(sc), name)


def test_scenes_graded_elsewhere_are_built_in_and_checked_there():
    """The scenes left out above exist, and their own test calls assert_fully_graded."""
    from pathlib import Path

    for name, path in GRADED_ELSEWHERE.items():
        assert name in builtin_scene_files()
        text = (Path(__file__).parent.parent / path).read_text()
        assert "assert_fully_graded(" in text and f'"{name}"' in text
