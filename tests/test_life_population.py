"""benchmarks/life_population.py: the risk map of indent populations (seed 004 Figs 4.10-4.11).

Slow (65^2, one EHL march to the centre, one dry BEM pair, two pseudo-transient passes; 13 s measured alone): the map's
cell at the thesis' median indent (Phi = 0.56 b, D/Phi = 0.6, K = 4, §4.3.1) against benchmarks/ehl_life.py's
stored 65^2 result for the same indent (benchmarks/results/ehl_life.json: its own full crossing, whose centred
step feeds its pseudo-transient pass): I_D/I_S lubricated and dry at T_inf = 0.7 T_Smax(dry) and without a limit
to 1e-6 relative (the same discrete problem reached through the other benchmark's code; measured to 1e-12), and
the fatigue limit in Pa to 1e-6. Then a one-indent population (gsd = 1) of that map is that cell, and widening
the population raises E[I_D/I_S] (eq 4.6: the excess grows like Phi^3 [.]^c, convex in the logs).
"""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_median_indent_cell_matches_the_ehl_life_benchmark():
    spec = importlib.util.spec_from_file_location("life_population_under_test", ROOT / "benchmarks" / "life_population.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    ref = next(r for r in json.loads((ROOT / "benchmarks" / "results" / "ehl_life.json").read_text())["runs"]
               if r["grid"] == 65)
    pt = mod.Point(65)
    assert mod.TAU_RATIO * pt.t_smax_dry == pytest.approx(ref["fatigue_limit_material"], rel=1e-6)
    c = pt.case(0.56, 0.6)
    for lab, rlab in (("limit_0.7", "limit_0.7_dry"), ("no_limit", "no_limit")):
        for who in ("ehl", "dry"):
            assert c[who][lab]["risk_ratio"] == pytest.approx(ref[rlab]["pseudo"][who]["risk_ratio"], rel=1e-6)
    # a population built on a map whose median cell is this one
    doc = {"phis": [0.4, 0.56, 0.8], "slopes": [0.3, 0.6, 1.2], "cases": []}
    for p in doc["phis"]:
        for s in doc["slopes"]:
            k = (p / 0.56) ** 3 * (s / 0.6) ** 8          # an eq 4.6-like excess around the computed cell
            doc["cases"].append({"phi": p, "slope": s, **{w: {lab: {"risk_ratio": 1.0 + (c[w][lab]["risk_ratio"] - 1.0) * k}
                                                            for lab in ("limit_0.7", "no_limit")} for w in ("ehl", "dry")}})
    one = mod.population(doc, (0.56, 1.0), (0.6, 1.0), [1.0])
    wide = mod.population(doc, (0.56, 1.3), (0.6, 1.3), [1.0])
    assert one["dry limit_0.7"]["mean_risk_ratio"] == pytest.approx(c["dry"]["limit_0.7"]["risk_ratio"], rel=1e-12)
    assert wide["dry limit_0.7"]["mean_risk_ratio"] > one["dry limit_0.7"]["mean_risk_ratio"]
