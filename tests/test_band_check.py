"""Bands that cannot fail (femcheck.band_check): every built-in scene's tolerances are narrower than half of what
their quantity moves over the scene's own stress sweep, or the scene states why in [tolerances.exceptions].

The measure (module doc): e_blind = min_c max_i |c - v_i|/|v_i|, the worst error of the best constant model over the
sweep's reference values v_i; a band must be below FRACTION e_blind = e_blind/2, which also rejects a model that
follows half of the quantity's logarithmic response. Cost: the sweeps of 24 scenes run live (about 25 s for the
file under the CPU lock); indent-life's (101 s: its stand-in, the pseudo-transient life BEM, at 13 points) and
srb-rolling's (128 s: the CECT roller equilibrium at 6 points) are stored in tests/data/band_sweeps and judged
from the file (regenerate: `python -m femcheck.band_check --store tests/data/band_sweeps SCENE`).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from femcheck import band_check
from femcheck.errors import InputError
from femcheck.scene import builtin_scene_files, load_scene

STORED = Path(__file__).parent / "data" / "band_sweeps"
EXPENSIVE = {"indent-life", "srb-rolling", "srb-rolling-finite"}       # their sweeps are stored (module doc)
SLOW = {"creep-curve", "indent-dry"}             # 6-7 s sweeps (the 3D exact theory, the indent BEM)


def test_blind_error_closed_forms():
    # one sign: (max - min) / (max + min), reached by c = 2 max min / (max + min); both signs: 1 (c = 0);
    # zeros and non-finite values are not compared, so they are left out; fewer than two values: undefined
    assert band_check.blind_error([1.0, 3.0]) == pytest.approx(0.5)
    assert band_check.blind_error([-1.0, -3.0, -2.0]) == pytest.approx(0.5)
    assert band_check.blind_error([2.0, -1.0]) == 1.0
    assert band_check.blind_error([1.0, 0.0, math.inf, 1.0]) == 0.0
    assert math.isnan(band_check.blind_error([5.0, 0.0]))
    v = np.array([1.0, 1.7, 3.0])
    c = 2 * v.max() * v.min() / (v.max() + v.min())
    assert np.abs(c / v - 1).max() == pytest.approx(band_check.blind_error(v), rel=1e-12)


@pytest.mark.parametrize("ratio", [1.01, 1.3, 3.0, 100.0, 1e6])
def test_half_of_the_blind_error_rejects_a_half_right_model(ratio):
    # The criterion's justification: v' = sqrt(v v0) (half the logarithmic response) with the best v0 misses by
    # tanh(ln(ratio)/4) >= e_blind/2 somewhere, so a band below e_blind/2 fails it.
    v = np.geomspace(1.0, ratio, 201)
    best = min(np.abs(np.sqrt(v * v0) / v - 1).max() for v0 in np.geomspace(1.0, ratio, 2001))
    assert best == pytest.approx(np.tanh(np.log(ratio) / 4), rel=1e-3)
    assert best >= band_check.FRACTION * band_check.blind_error(v) * (1 - 1e-9)


def test_at_the_limit_a_half_right_model_passes_for_a_small_spread():
    # quantity moving by 30 % over a sweep: e_blind = 0.13, limit 0.065; the half-right model misses by 0.0655, so a
    # band of 0.066 (at the limit, judged vacuous) passes it at every point, one of 0.06 fails it
    v = np.geomspace(1.0, 1.3, 41)
    limit = band_check.FRACTION * band_check.blind_error(v)
    half = min(np.abs(np.sqrt(v * v0) / v - 1).max() for v0 in np.linspace(1.0, 1.3, 3001))   # best v0
    assert limit == pytest.approx(0.0652, abs=1e-4) and half == pytest.approx(0.0655, abs=1e-4)
    assert half <= 0.066 and half > 0.06


def test_a_wide_band_is_found():
    # hertz-line's BEM band on p_max widened from 1 % to 0.6: above half the blind error over the sweep (0.998:
    # loads over six decades) -> vacuous; the half-width's 1 % stays ok
    sc = load_scene("hertz-line", {"tolerances.bem.p_max": 0.6})
    rep = band_check.check_scene(sc, workers=1)
    f = {x.key: x for x in rep.findings}
    assert f["bem.p_max"].status == "vacuous" and f["bem.half_width"].status == "ok"
    assert f["bem.p_max"].source == "analytic" and len(f["bem.p_max"].values) == len(rep.points)
    assert f["bem.p_max"].limit == pytest.approx(0.499, abs=1e-3)
    assert [x.key for x in rep.failing()] == ["bem.p_max"]
    # just below the limit the band passes
    ok = band_check.check_scene(load_scene("hertz-line", {"tolerances.bem.p_max": 0.49}), workers=1)
    assert not ok.failing()


def test_a_band_on_a_quantity_the_sweep_does_not_move_is_found():
    # roller-finite's edge-peak position sits at the roller's end over the whole sweep (e_blind = 0): without the
    # scene's exception the band is vacuous; with it, excepted with the scene's reason
    sc = load_scene("roller-finite")
    rep = band_check.check_scene(sc, workers=1)
    f = {x.key: x for x in rep.findings}["finite_line.edge_peak_y"]
    assert f.status == "excepted" and f.blind_error == 0.0 and "roller's end" in f.note
    bare = band_check.check_scene(dataclasses.replace(sc, band_exceptions={}), workers=1)
    assert {x.key: x for x in bare.findings}["finite_line.edge_peak_y"].status == "vacuous"


def test_exceptions_are_read_from_the_toml_and_checked(tmp_path):
    text = (Path(builtin_scene_files()["hertz-line"]).read_text()
            + '\n[tolerances.exceptions]\n"bem.p_max" = "a deliberate exception"\n')
    path = tmp_path / "mine.toml"
    path.write_text(text)
    assert load_scene(path).band_exceptions == {"bem.p_max": "a deliberate exception"}
    assert "tolerances.exceptions.bem.p_max" not in load_scene(path).params      # not a parameter
    # an exception that names no band of the scene, or gives no reason, is refused naming its key
    path.write_text(text.replace('"bem.p_max" = ', '"bem.p_mux" = '))
    with pytest.raises(InputError, match="names no tolerance") as err:
        load_scene(path)
    assert err.value.key == "tolerances.exceptions.bem.p_mux"
    path.write_text(text.replace('"a deliberate exception"', '" "'))
    with pytest.raises(InputError, match="non-empty"):
        load_scene(path)


def test_a_stored_sweep_must_have_the_current_cases():
    sw = band_check.load_sweep(STORED / "srb-rolling.json")
    assert sw.labels == band_check.case_labels("srb-rolling")
    sw.labels = sw.labels[:-1]
    with pytest.raises(InputError, match="other cases"):
        band_check.check_scene("srb-rolling", stored=sw)


def _scene_params() -> list:
    return [pytest.param(name, marks=[pytest.mark.slow] if name in SLOW else [], id=name)
            for name in builtin_scene_files()]


@pytest.mark.parametrize("name", _scene_params())
def test_no_builtin_band_is_vacuous(name):
    stored = band_check.load_sweep(STORED / f"{name}.json") if name in EXPENSIVE else None
    rep = band_check.check_scene(name, stored=stored, workers=1)
    bad = rep.failing()
    assert not bad, f"{name}: bands that cannot fail (fix at the source or explain in [tolerances.exceptions]):\n  " \
        + "\n  ".join(f.line() for f in bad)
    judged = [f for f in rep.findings if f.status in ("ok", "excepted")]
    assert judged, f"{name}: no band judged"
    # every excepted band is a real exception: without its reason it would fail
    assert all(f.status == "excepted" for f in rep.findings if f.key in load_scene(name).band_exceptions)
