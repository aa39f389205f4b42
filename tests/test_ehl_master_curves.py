"""The nabla_Phi master-curve sweep (benchmarks/ehl_master_curves.py): case cache and resume, a failed case
reported while the others finish, the initial-slope extrapolation and the dry reference slope against the
linear elastic response of a half-space."""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import numpy as np
import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "ehl_master_curves.py"


@pytest.fixture(scope="module")
def mc():
    spec = importlib.util.spec_from_file_location("ehl_master_curves", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod              # the worker processes find run_case by module name
    spec.loader.exec_module(mod)
    yield mod
    sys.modules.pop(spec.name, None)


def _quiet(_msg):
    pass


def test_second_run_computes_nothing(mc, tmp_path):
    cases = [mc.dry_case(1.0, 3.0), mc.dry_case(1.0, 8.0)]
    first = mc.sweep(cases, tmp_path, workers=1, log=_quiet)
    assert (first["computed"], first["cached"]) == (2, 0)
    assert len(list(tmp_path.glob("*.json"))) == 2
    second = mc.sweep(cases, tmp_path, workers=1, log=_quiet)
    assert (second["computed"], second["cached"]) == (0, 2)
    assert [r["slope"] for r in second["results"]] == [r["slope"] for r in first["results"]]


def test_interrupted_sweep_resumes_with_the_unfinished_cases(mc, tmp_path):
    cases = [mc.dry_case(1.0, 3.0), mc.dry_case(1.0, 8.0), mc.dry_case(1.0, 5.0)]

    def stop_after_first(msg):
        if msg.startswith("[1/"):
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        mc.sweep(cases, tmp_path, workers=1, log=stop_after_first)
    assert len(list(tmp_path.glob("*.json"))) == 1           # the finished case was stored before the stop
    again = mc.sweep(cases, tmp_path, workers=1, log=_quiet)
    assert (again["computed"], again["cached"]) == (2, 1)
    assert all(r["status"] == "ok" for r in again["results"])


def test_cache_key_follows_inputs_and_code(mc):
    a, b = mc.dry_case(1.0, 3.0), mc.dry_case(1.0, 8.0)
    assert mc.case_key(a, "code1") != mc.case_key(b, "code1")
    assert mc.case_key(a, "code1") != mc.case_key(a, "code2")
    assert mc.case_key(a, "code1") == mc.case_key(dict(a), "code1")


def test_a_failed_case_is_reported_and_the_others_finish(mc, tmp_path):
    bad = mc.ehl_case(-1.0, 8.0, 1.0, 3.0, 65)                # M < 0: invalid
    cases = [mc.dry_case(1.0, 3.0), bad, mc.dry_case(1.0, 8.0)]
    lines = []
    out = mc.sweep(cases, tmp_path, workers=2, log=lines.append)      # two worker processes
    status = [r["status"] for r in out["results"]]
    assert status == ["ok", "failed", "ok"]
    assert "M, L, Phi, K must be > 0" in out["results"][1]["error"]
    assert any("FAILED" in line and "M=-1" in line for line in lines)
    a = mc.analyse(out["results"])
    assert [f["case"]["M"] for f in a["failed"]] == [-1.0]
    # the failure is cached too (deterministic inputs and code) and retried on request
    assert mc.sweep(cases, tmp_path, workers=1, log=_quiet)["computed"] == 0
    assert mc.sweep(cases, tmp_path, workers=1, retry_failed=True, log=_quiet)["computed"] == 1


def test_richardson_removes_the_quadratic_term(mc):
    s = [0.05, 0.1]
    assert mc.richardson(s, [0.7 * x + 3.0 * x * x for x in s]) == pytest.approx(0.7, rel=1e-12)


def test_master_curve_fit_recovers_its_parameters(mc):
    x = np.geomspace(0.5, 20.0, 12)
    f = mc.fit_master(x, mc.master(x, 2.3, 1.4))
    assert (f["c"], f["q"]) == (pytest.approx(2.3, rel=1e-6), pytest.approx(1.4, rel=1e-6))
    assert f["rms"] < 1e-8


def _half_space_slopes(phi: float, K: float, n: int = 2048, half: float = 4.0) -> tuple[float, float]:
    """Initial slopes (max dP, min dP in the hole) of an indent in a fully closed contact, from the linear
    elastic response of a half-space alone: in the Hertz units of seed 004 (deformation (2/pi^2) int P/r dA)
    the pressure that makes the surfaces follow a height R(X, Y) is, in Fourier space, P = (pi |k| / 4) R
    (the operator's symbol is 4/(pi |k|)). Eq 2.16 written out here: R = -D exp(-K r^2/Phi^2) cos(pi r/Phi)."""
    x = (np.arange(n) - n // 2) * (2 * half / n)
    X, Y = np.meshgrid(x, x, indexing="ij")
    r = np.hypot(X, Y)
    D = phi                                                     # D/Phi = 1: a slope (the response is linear)
    R = -D * np.exp(-K * r * r / phi**2) * np.cos(np.pi * r / phi)
    k = 2 * np.pi * np.fft.fftfreq(n, 2 * half / n)
    kk = np.hypot(*np.meshgrid(k, k, indexing="ij"))
    P = np.real(np.fft.ifft2(np.pi * kk / 4 * np.fft.fft2(R)))
    return float(P.max()), float(P[r <= 0.5 * phi].min())


@pytest.mark.parametrize("K", [3.0, 8.0])
def test_dry_slope_equals_the_half_space_response_of_a_small_indent(mc, K):
    # the dry reference of the master curves: femcheck's BEM on the Hertz contact at D/Phi 0.05 and 0.1 with
    # Richardson; a small indent (Phi = 0.25, a quarter of the contact radius) at the centre of a closed contact
    # carries the pressure of the half-space's linear response (measured: 0.1 % apart at K = 3, 0.3 % at K = 8)
    r = mc.run_case(mc.dry_case(0.25, K))
    assert r["status"] == "ok"
    amp, centre = _half_space_slopes(0.25, K)
    assert r["slope"]["amplitude"] == pytest.approx(amp, rel=0.005)
    assert r["slope"]["centre"] == pytest.approx(centre, rel=0.005)


def test_stored_results_hold_the_dry_upper_bound():
    # the committed sweep: seed 004 §3.3 "the dry contact is an upper boundary" for pure rolling; the rear and
    # front shoulders' and the hole's EHL initial slopes stay below the dry ones in every case of the sweep
    path = SCRIPT.parent / "results" / "ehl_master_curves.json"
    doc = json.loads(path.read_text())
    ratios = [c["ratio"][n] for c in doc["cases"] for n in ("rear", "front", "centre")]
    finite = [v for v in ratios if np.isfinite(v)]          # NaN: no shoulder peak found on that side
    assert len(finite) >= 100
    assert 0.0 < min(finite) and max(finite) <= 1.0
