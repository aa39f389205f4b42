"""benchmarks/life_eq46.py's samples are the ``indent-life`` scene's own numbers (seed 004 eq 4.6 fitted on them).

Slow (65^2 cells, two BEM pairs and two pseudo-transient passes; 7 s measured): one indent's sample from the
benchmark (its own call of the BEM, the pseudo-transient history and the life model, four fatigue limits from one
history) against ``femcheck.run("indent-life")`` with the same keys (the ``bem`` model's life output, computed
through the scene's adapter): the life ratio and the stress ratio to 1e-9 (the same discrete problem; measured
equal to round-off), at T_inf = 0 and at T_inf = 0.7 T_Smax (the scene run with that limit in Pa).
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

import femcheck

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "life_eq46.py"


@pytest.mark.slow
def test_eq46_samples_are_the_indent_life_scene_numbers():
    spec = importlib.util.spec_from_file_location("life_eq46_under_test", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    d = mod.indent_samples(0.5, 1.0, 3.0, 65, limits=(0.0, 0.7))
    p_h = None
    for row in d["samples"]:                     # t = 0 first: its run gives p_H for the limit in Pa of the next
        tau = 0.0 if p_h is None else row["limit_ratio"] * d["T_Smax_over_pH"] * p_h
        res = femcheck.run("indent-life", {"numerics.bem_cells": 65, "life.fatigue_limit": tau}, models=["bem"])
        q = res.models["bem"].quantities
        assert row["life_ratio"] == pytest.approx(q["life_ratio"], rel=1e-9)
        assert row["stress_ratio"] == pytest.approx(q["stress_ratio"], rel=1e-9)
        assert row["risk_ratio"] == pytest.approx(res.models["bem"].stats["life"]["risk_ratio"], rel=1e-9)
        p_h = res.models["bem"].stats["life"]["p_hertz"]
