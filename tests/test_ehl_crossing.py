"""The full EHL crossing of benchmarks/ehl_crossing.py (seed 004 §3.3.1, Table 3.4).

- Fast: the Table 3.4 measure |dP_REAR(X_D = 0) - max dP_REAR| / max dP_REAR over the two position ranges, on a
  hand-made rear history (values by hand).
- Slow (65^2, M = 100, L = 10, Phi = 0.5, D/Phi = 0.25, K = 4; 17 s measured alone): the whole crossing against
  independent values -- the centred step against the centred-only march of benchmarks/ehl_master_curves.py (its
  own indent placement), the shoulders against the dry BEM of the same centred indent (the thesis' upper bound,
  §3.3.1), the rear amplitude's variation while the indent's rim is inside the contact against Table 3.4's largest
  value (6 %), and the pressure after the indent has left against the smooth steady solution.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _load(name):
    spec = importlib.util.spec_from_file_location(f"{name}_under_test", BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def bench():
    return _load("ehl_crossing")


def test_table_3_4_measure_by_hand(bench):
    """Phi = 0.5: the rim (0.65 Phi = 0.325) is inside |X| <= 1 for |X_D| <= 0.675. Rear history 0.10 at X_D = 0
    (centre step 5), 0.11 at X_D = -0.6, 0.30 at X_D = 0.9 (the exit), NaN where no rear shoulder: over the rim-inside
    steps max 0.11, difference |0.10 - 0.11|/0.11 = 0.0909; over |X_D| <= 1 max 0.30, difference 0.6667 (by hand)."""
    x = np.array([-1.5, -1.2, -0.6, -0.3, 0.0, 0.3, 0.6, 0.9, 1.2])
    rear = np.array([np.nan, np.nan, 0.11, 0.105, 0.10, 0.102, 0.104, 0.30, 0.05])
    t = bench.table_3_4(x, rear, 5, 0.5)
    assert t["rear_centred"] == 0.10
    assert t["rim_inside"]["max"] == 0.11 and t["rim_inside"]["max_at_X_D"] == -0.6
    assert t["rim_inside"]["difference"] == pytest.approx(0.01 / 0.11, rel=1e-12)
    assert t["centre_in_contact"]["max"] == 0.30
    assert t["centre_in_contact"]["difference"] == pytest.approx(0.2 / 0.3, rel=1e-12)


@pytest.mark.slow
def test_full_crossing_against_independent_values(bench):
    """65^2 over [-2.5, 1.5] x [-2, 2] b, M = 100, L = 10 (resolved on 65^2: tests/test_ehl_reporting.py's crossing),
    Phi = 0.5, D/Phi = 0.25, K = 4, 76 steps (measured: film minimum 0.0671 b^2/Rx, residual <= 9.9e-8, load error
    <= 4.9e-8, 4-13 W-cycles per step).

    - every step converged (mean scaled residual <= 1e-7, load error <= 1e-7: the solver's tolerances) with a
      positive film (the march refuses a negative one; here checked on the record);
    - the centred step (X_D = 0) equals the centred-only march of benchmarks/ehl_master_curves.py, which places
      the indent itself: rear, front, lateral and centre amplitudes to 1e-9 p_H (the same discrete problem; measured
      bit-identical);
    - the dry contact is an upper bound of the shoulders (seed 004 §3.3.1: "the dry contact is an upper boundary"):
      while the rim is inside the contact, max(rear, front, lateral) <= the dry BEM amplitude of the centred indent
      (benchmarks/ehl_master_curves.py's dry case; measured 0.065 against 0.1675 p_H);
    - the rear amplitude varies by at most 6 % over the steps with the rim inside the contact (seed 004 Table 3.4:
      2-6 % at M = 400, L = 5; measured here 3.7 %);
    - at the last step (X_D >= 1 + 1.5 Phi) the pressure is the smooth steady solution's to 0.5 % of p_H (measured
      0.15 %; spec ehl-life §A.11 check 5c: an indent outside the contact is the smooth contact); the steps before
      the indent's disc reaches the pressurised zone are it to 1e-12 (they need no cycle)."""
    r = bench.crossing_case(100.0, 10.0, 0.5, 0.25, 4.0, 65)
    s, st = r["summary"], r["steps"]
    x = np.array(st["X_D"])
    assert s["residual_max"] <= 1e-7 and s["load_error_max"] <= 1e-7
    assert s["film_min"] > 0
    mc = _load("ehl_master_curves")
    ref = mc._ehl(mc.ehl_case(100.0, 10.0, 0.5, 4.0, 65) | {"slopes": [0.25]})
    for k in ("rear", "front", "lateral", "centre"):
        assert s["centred"][k] == pytest.approx(ref["amplitudes"][k][0], abs=1e-9)
    dry = bench.dry_centred(0.5, 0.25, 4.0)["amplitude"]
    rim = np.abs(x) + bench.RIM * 0.5 <= 1.0
    shoulders = np.nanmax(np.array([st["rear"], st["front"], st["lateral"]])[:, rim], axis=0)
    assert np.all(shoulders <= dry), (shoulders.max(), dry)
    assert s["table_3_4"]["rim_inside"]["difference"] <= 0.06
    assert s["max_abs_dP_last"] <= 5e-3
    early = np.array(st["cycles"]) == 0
    assert early[:3].all() and np.max(np.array(st["max_abs_dP"])[early]) <= 1e-12
