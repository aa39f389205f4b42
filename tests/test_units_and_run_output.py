"""What a user reads: every quantity of every built-in scene has an SI unit (report and terminal), `femcheck run`
ends with one line that concludes (and exits 1 when nothing was compared), and `--json` is standard JSON."""
import glob
import json
import subprocess
import sys
from pathlib import Path

import pytest

import femcheck
from femcheck.report.units import unit_of
from femcheck.scene import load_scene

ROOT = Path(__file__).resolve().parent.parent


def _strict(text: str):
    def refuse(constant):
        raise ValueError(f"non-standard JSON constant {constant}")
    return json.loads(text, parse_constant=refuse)


def test_every_stored_reference_quantity_has_a_unit():
    """The quantities of every stored reference (the FE and EHL models) have a unit. Every model's quantities in
    a whole run of every built-in scene are checked where that run is graded (tests/grading.py, called by
    test_verdicts and the scenes' own tests)."""
    missing = []
    for path in glob.glob(str(ROOT / "references" / "*" / "*.json")):
        meta = json.loads(Path(path).read_text())
        if "model" not in meta:     # a stored benchmark result (the indent-population maps), not a scene's model
            continue
        sc = load_scene(meta["provenance"]["scene"])
        missing += [f"{sc.name} {meta['model']}.{q}" for q in meta["quantities"]
                    if unit_of(q, sc.params, sc.kind) == "?"]
    assert not missing, "quantities without a unit: " + ", ".join(sorted(set(missing)))


def test_unknown_quantity_has_no_unit():
    """The check above can fail: a quantity no unit rule knows is "?"."""
    sc = load_scene("hertz-line")
    assert unit_of("no_such_quantity_xyz", sc.params, sc.kind) == "?"


def test_units_that_depend_on_the_scene():
    line, point = load_scene("life-line"), load_scene("life-point", {"life.c": 31 / 3, "life.h": 7 / 3})
    assert unit_of("risk_integral", line.params, line.kind) == "Pa^8·m^3/m"        # per metre of line
    assert unit_of("risk_integral_smooth", point.params, point.kind) == "Pa^10.3333·m^0.666667"
    assert unit_of("total_force", line.params, line.kind) == "N/m"
    srb = load_scene("srb-rolling")
    assert unit_of("f_lat_inner", srb.params, srb.kind).startswith("- (F / mu N)")
    assert unit_of("friction_power_outer", srb.params, srb.kind) == "W"


def _femcheck(*args):
    return subprocess.run([sys.executable, "-m", "femcheck.cli", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=600)


def test_run_prints_units_and_a_closing_verdict():
    r = _femcheck("run", "hertz-line", "--models", "analytic,bem")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "p_max=1.9165e+09 Pa" in r.stdout and "half_width=0.00033219 m" in r.stdout
    last = r.stdout.strip().splitlines()[-1]
    assert last.startswith("PASS: 4 of 4 comparisons valid") and "nothing written (--out DIR" in last


def test_a_run_that_compares_nothing_exits_1():
    r = _femcheck("run", "ehl-smooth", "--models", "moes,hamrock_dowson")
    assert r.returncode == 1, r.stdout + r.stderr
    assert r.stdout.strip().splitlines()[-1].startswith("NOTHING COMPARED: no reference ran (models.references: ehl")


def test_json_output_is_standard_json_with_an_infinite_life():
    # a fatigue limit above every stress amplitude: nothing is at risk, the life is infinite
    r = _femcheck("run", "life-point", "--models", "analytic,bem", "--set", "life.fatigue_limit=5e10", "--json")
    data = _strict(r.stdout)
    bem = data["models"]["bem"]["quantities"]
    assert bem["risk_integral"] == 0.0 and bem["fatigue_life"] == "Infinity"
    assert float(bem["fatigue_life"]) == float("inf")
    assert r.stderr.strip().splitlines()[-1].startswith(("PASS", "FAIL"))


@pytest.mark.parametrize("value, text", [(float("inf"), '"Infinity"'), (float("-inf"), '"-Infinity"'),
                                         (float("nan"), '"NaN"'), (1.5, "1.5")])
def test_dumps_writes_nonfinite_numbers_as_strings(value, text):
    from femcheck.result import dumps

    assert dumps({"x": [value]}) == '{"x": [' + text + "]}"


def test_a_scene_of_contrasts_only_is_informational_not_pass():
    """trb-mill-4row compares only contrasts (rigid rings against the measured row shares): nothing is claimed
    valid, so the scene says INFORMATIONAL, never a green PASS, and exits 0 (nothing failed). (Its other contrast,
    the flexible chock, is an FE model of about a minute: tests/test_mill_chock.py runs the whole scene.)"""
    res = femcheck.run("trb-mill-4row", models=["rigid_ring", "measured"])
    assert res.passed and res.verdict == "INFORMATIONAL"
    assert femcheck.run("hertz-line", models=["analytic", "bem"]).verdict == "PASS"
    r = _femcheck("run", "trb-mill-4row", "--models", "rigid_ring,measured")
    assert r.returncode == 0 and r.stdout.strip().splitlines()[-1].startswith("INFORMATIONAL: only contrast models")
