"""The ``life`` output of the point, line, roller and indent kinds through scenes and the CLI: graded
comparisons, the infinite life, the depth-0 indent, bad input, the report section."""
import json
import math
import subprocess
import sys

import pytest

import femcheck
from femcheck.errors import InputError
from femcheck.report.html import write_report
from femcheck.scene import load_scene

CLI = [sys.executable, "-m", "femcheck.cli"]
COARSE_INDENT = {"numerics.bem_cells": 65, "numerics.life_depths": 8, "life.size_sweep": False}


def femcheck_cli(*args):
    return subprocess.run([*CLI, *args], capture_output=True, text=True)


@pytest.mark.parametrize("key,value", [("life.e", "0"), ("life.fatigue_limit", "-1"), ("life.window", "10")])
def test_bad_life_input_is_one_line_exit_2(key, value, tmp_path):
    r = femcheck_cli("run", "life-point", "--set", f"{key}={value}", "--out", str(tmp_path / "rep"))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0] and "allowed" in lines[0]
    assert r.stdout == "" and not (tmp_path / "rep").exists()


def test_bad_life_input_in_process():
    for key, value in (("life.e", -0.5), ("life.window", 0.5), ("life.c", 0.0), ("life.h", -1.0),
                       ("numerics.life_depths", 1)):
        with pytest.raises(InputError) as err:
            load_scene("life-point", {key: value})
        assert err.value.key == key and "allowed" in str(err.value)


def test_bad_indent_life_input_and_rigid_body():
    with pytest.raises(InputError) as err:
        load_scene("indent-life", {"life.indent_fraction": 1.5})
    assert err.value.key == "life.indent_fraction"
    with pytest.raises(InputError) as err:
        load_scene("life-point", {"materials.body2.rigid": True})
    assert err.value.key == "outputs.life"


def test_life_is_skipped_unless_asked():
    res = femcheck.run("hertz-point", {"outputs.subsurface_stress": False}, models=["analytic", "bem"])
    assert "risk_integral" not in res.models["bem"].quantities and "life" not in res.models["bem"].stats


@pytest.mark.slow
def test_point_life_graded_and_infinite_above_the_fatigue_limit():
    res = femcheck.run("life-point")
    assert res.passed
    hist = [c for c in res.comparisons if c.quantity == "stress_history_max"]
    assert hist and hist[0].passed and hist[0].rel_error < 0.005
    bem = res.models["bem"]
    assert bem.quantities["risk_integral"] > 0 and math.isfinite(bem.quantities["fatigue_life"])
    t_max = bem.quantities["stress_history_max"]
    r = femcheck_cli("run", "life-point", "--set", f"life.fatigue_limit={1.001 * t_max}", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)["models"]["bem"]
    assert d["status"] == "ok"
    # standard JSON has no infinity: femcheck writes it as the string "Infinity" (femcheck.result.strict_json)
    assert d["quantities"]["risk_integral"] == 0.0 and d["quantities"]["fatigue_life"] == "Infinity"
    assert d["stats"]["life"]["infinite_life"] is True
    # just below the limit the life is finite and long
    r2 = femcheck.run("life-point", {"life.fatigue_limit": 0.999 * t_max}, models=["bem"])
    assert math.isfinite(r2.models["bem"].quantities["fatigue_life"])
    assert r2.models["bem"].quantities["fatigue_life"] > 1e3 * bem.quantities["fatigue_life"]


def test_line_life_bem_against_mcewen():
    res = femcheck.run("life-line")
    assert res.passed
    got = {c.quantity: c for c in res.comparisons if c.model == "bem"}
    for q in ("risk_integral", "fatigue_life", "stress_history_max"):
        assert got[q].tolerance is not None and got[q].passed
    assert got["stress_history_max"].reference_value / 1.9165e9 == pytest.approx(0.557, abs=1e-3)
    # both infinite above the fatigue limit: they agree
    res = femcheck.run("life-line", {"life.fatigue_limit": 1.2e9})
    assert res.models["bem"].quantities["fatigue_life"] == math.inf
    assert [c for c in res.comparisons if c.quantity == "fatigue_life"][0].rel_error == 0.0


def test_flat_roller_life_is_shorter_than_the_crowned_one():
    """The flat roller's edge peaks (p_max ~ 2 x Hertz) concentrate the stresses: its life is a fraction of the
    crowned roller's, which stays near the infinite line's (contrast)."""
    flat = femcheck.run("roller-finite", {"outputs.life": True}, models=["analytic", "bem"]).models
    crowned = femcheck.run("roller-crowned", {"outputs.life": True}, models=["analytic", "bem"]).models
    L_line = flat["analytic"].quantities["fatigue_life"]
    assert flat["bem"].quantities["fatigue_life"] < 0.5 * crowned["bem"].quantities["fatigue_life"]
    assert 0.6 * L_line < crowned["bem"].quantities["fatigue_life"] < L_line


def test_depth_zero_indent_has_life_ratio_exactly_one():
    res = femcheck.run("indent-life", {**COARSE_INDENT, "indent.slope": 0.0}, models=["bem"])
    q = res.models["bem"].quantities
    assert res.models["bem"].status == "ok"
    assert q["life_ratio"] == 1.0 and q["stress_ratio"] == 1.0
    assert q["risk_integral"] == q["risk_integral_smooth"]


@pytest.mark.slow
def test_indent_life_and_report_section(tmp_path):
    res = femcheck.run("indent-life", COARSE_INDENT, models=["bem"])
    bem = res.models["bem"]
    assert bem.status == "ok"
    q = bem.quantities
    assert q["stress_ratio"] > 1.1 and 0.0 < q["life_ratio"] < 1.0
    # f_d -> the closed form of the dented track
    st = bem.stats["life"]
    assert q["life_ratio"] == pytest.approx(st["risk_ratio"] ** (-1 / st["e"]), rel=1e-12)
    half = femcheck.run("indent-life", {**COARSE_INDENT, "life.indent_fraction": 0.25}, models=["bem"])
    assert half.models["bem"].quantities["life_ratio"] == pytest.approx(
        (1 + 0.25 * (st["risk_ratio"] - 1)) ** (-1 / st["e"]), rel=1e-9)
    index = write_report([res], tmp_path / "rep", "life", 0.1)
    html = index.read_text()
    assert "Rolling-contact fatigue life" in html and "life-section.png" in html
    assert (tmp_path / "rep" / "00-indent-life-life-section.png").is_file()


def test_load_life_exponents_through_the_scenes():
    """Hertz self-similarity (spec B.5): the scenes' grids scale with the contact, so without fatigue limit the
    relative life falls exactly as Q^-3 (point, c = 8, e = 10/9) and Q^-4 (line, e = 9/8); this checks the whole
    chain (history, window, depth and track scaling, p_H^c, the relative life)."""
    from femcheck.analytic.life import local_exponents

    loads = (500.0, 2000.0)
    lives = [femcheck.run("life-point", {"load.normal": W, "life.fatigue_limit": 0.0},
                          models=["bem"]).models["bem"].quantities["fatigue_life"] for W in loads]
    assert local_exponents(loads, lives) == pytest.approx([3.0], rel=1e-6)
    loads = (5e5, 2e6)
    for model in ("analytic", "bem"):
        lives = [femcheck.run("life-line", {"load.per_length": W, "life.fatigue_limit": 0.0},
                              models=[model]).models[model].quantities["fatigue_life"] for W in loads]
        # the line BEM's gap is the exact circle, not Hertz's parabola: self-similar only to O((a/R)^2) ~ 1e-3
        assert local_exponents(loads, lives) == pytest.approx([4.0], rel=1e-6 if model == "analytic" else 1e-3), model


def test_an_infinite_life_survives_the_cache_and_the_references(tmp_path, monkeypatch):
    from femcheck import cache, references
    from femcheck.result import ModelResult

    res = ModelResult("bem_transient", quantities={"fatigue_life": math.inf, "risk_integral": 0.0},
                      stats={"life": {"infinite_life": True}})
    cache.store("lifekey", res)
    assert cache.load("lifekey").quantities["fatigue_life"] == math.inf
    monkeypatch.setenv("FEMCHECK_REFERENCES", str(tmp_path))
    references.store("indent_contact", "bem_transient", "lifekey", res, "indent-life", {})
    back = references.load("indent_contact", "bem_transient", "lifekey")
    assert back is not None and back.quantities["fatigue_life"] == math.inf
