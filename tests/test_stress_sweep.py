"""Stress sweeps a user can run (issue 16 item 3, issue 12 finding 7): FE references left out unless asked, each
case compared with every reference that ran, a case compared with nothing flagged, progress per case."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest

from femcheck.result import StressCase
from femcheck.scene import load_scene
from femcheck.stability import _run_case, case_models, default_models


def test_fe_references_are_left_out_by_default():
    assert default_models(load_scene("hertz-point")) == ["analytic", "bem"]
    assert default_models(load_scene("layer-line")) == ["bem", "thin_layer", "analytic"]
    # a case that restricts its models keeps its restriction
    case = StressCase("rigid substrate", {"models.run": ["bem", "thin_layer"]})
    assert case_models(case, ["bem", "thin_layer", "analytic"]) == ["bem", "thin_layer"]


@pytest.mark.slow
def test_case_with_no_comparison_is_unchecked_not_ok():
    # issue 12 finding 7: carter-2d with a rigid cylinder skips Carter (its only reference): nothing compared
    sc = load_scene("carter-2d")
    case = _run_case((sc, StressCase("rigid cylinder", {"materials.cylinder.rigid": True}), ["exact", "analytic"]))
    assert case.models["analytic"]["status"] == "skipped"
    assert case.status == "unchecked" and any(p.startswith("not compared") for p in case.problems)


def test_case_is_compared_with_every_reference_that_ran():
    # hertz-line's references are Hertz and the FE model (one coarse level here): the BEM meets both
    sc = load_scene("hertz-line", {"numerics.fem_levels": 1, "tolerances.fem.p_max": 0.05,
                                   "tolerances.fem.half_width": 0.05})
    case = _run_case((sc, StressCase("load x 2", {"load.per_length": 2e6}), ["analytic", "bem", "fem"]))
    refs = {e["reference"] for e in case.models["bem"]["errors"]}
    assert refs == {"analytic", "fem"}, case.models["bem"]
    assert case.status == "ok", case.problems
    # err_<q> is the worst over the references
    worst = max(e["rel_error"] for e in case.models["bem"]["errors"] if e["quantity"] == "p_max")
    assert case.models["bem"]["err_p_max"] == worst


@pytest.mark.slow
def test_stress_cli_prints_each_case_and_writes_json(tmp_path):
    r = subprocess.run([sys.executable, "-m", "femcheck.cli", "stress", "hertz-line", "--workers", "2",
                        "--out", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    d = json.loads((tmp_path / "stress.json").read_text())
    n = len(d["cases"])
    assert d["models"] == ["analytic", "bem"] and "left out: fem" in r.stdout
    for i in range(1, n + 1):                          # one line per finished case, counted
        assert f"[{i:>{len(str(n))}}/{n}]" in r.stderr
    assert all(c["status"] in ("ok", "refused") for c in d["cases"]), d["cases"]
