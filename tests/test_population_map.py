"""The stored indent-population risk map (seed 004 Figs 4.10-4.11; femcheck.population_map) and its report
section: current for today's code, its cells the same numbers as the separately stored §4.3.1 life run, its
population mean reproduced by an independent quadrature, and a stale or missing map never shown."""
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import norm

from femcheck import population_map
from femcheck.analytic import indent_risk
from femcheck.report import population

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def stored():
    doc, status = population_map.load_current()
    assert status == "current", ("the stored population map is stale or missing: run benchmarks/life_population.py "
                                 "(under the CPU lock) and then with --report --store")
    return doc["result"]


def test_median_cell_is_the_life_runs_number(stored):
    """The map's cell at the thesis' median indent (Phi 0.56, D/Phi 0.6, K 4, 129^2) is the pseudo-transient risk
    ratio I_D/I_S that benchmarks/ehl_life.py stored from its own run (the full EHL crossing at the same point, its
    centred step), dry and lubricated, fatigue limit 0.7 T_Smax(dry) and none. Same computation reached by two
    scripts and two stored files: agreement to 1e-9 (round-off; measured: identical)."""
    life = json.loads((ROOT / "benchmarks/results/ehl_life.json").read_text())
    run = next(r for r in life["runs"] if r["grid"] == stored["grid"])
    i, j = stored["phis"].index(0.56), stored["slopes"].index(0.6)
    for lab, life_lab in (("limit_0.7", "limit_0.7_dry"), ("no_limit", "no_limit")):
        for who in ("dry", "ehl"):
            assert stored["maps"][f"{who} {lab}"][i][j] == pytest.approx(
                run[life_lab]["pseudo"][who]["risk_ratio"], rel=1e-9)


@pytest.mark.parametrize("name", population.PANELS)
def test_population_mean_by_independent_quadrature(stored, name):
    """E[I_D/I_S] stored (indent_risk.map_population_mean: Gauss-Legendre between the map's nodes) against a
    trapezoid rule on 2001 x 2001 points over +-8 sigma of ln Phi and ln D/Phi, which converges as h^2 across the
    interpolant's kinks. Tolerance 1e-4 (measured: 2e-6; 32 x 32 Gauss-Hermite nodes, the rule used before, are off
    by up to 0.8 % on these maps)."""
    pop = stored["population"]
    R = np.array(stored["maps"][name], dtype=float)
    f = indent_risk.map_interpolant(stored["phis"], stored["slopes"], R)
    (dm, dg), (sm, sg) = [(pop[k]["median"], pop[k]["gsd"]) for k in ("diameter", "slope")]
    u = np.linspace(-8.0, 8.0, 2001)
    w = norm.pdf(u)
    P, S = np.meshgrid(dm * dg ** u, sm * sg ** u, indexing="ij")
    mean = np.trapezoid(np.trapezoid(f(P, S) * w[None, :], u, axis=1) * w, u)
    assert pop[name]["mean_risk_ratio"] == pytest.approx(mean, rel=1e-4)


@pytest.mark.parametrize("k", [1, 3, 8])
def test_map_rule_on_clipped_lognormal_moments(k):
    """E[clip(X, lo, hi)^k], ln X ~ N(ln m, s^2), s = ln 1.5, in closed form: lo^k F(a) + hi^k (1 - F(b)) +
    m^k exp(k^2 s^2/2) [F(b - k s) - F(a - k s)], a, b the standardised logs of lo, hi, F the normal CDF. The
    clipped power is smooth between the knots and constant beyond, as a map's interpolant is: to 1e-12."""
    m, g, knots = 0.56, 1.5, [0.25, 0.4, 0.56, 0.8, 1.0]
    s = np.log(g)
    a, b = np.log(knots[0] / m) / s, np.log(knots[-1] / m) / s
    exact = (knots[0] ** k * norm.cdf(a) + knots[-1] ** k * norm.sf(b)
             + m ** k * np.exp(k * k * s * s / 2) * (norm.cdf(b - k * s) - norm.cdf(a - k * s)))
    x, w = indent_risk.map_rule(m, g, knots)
    assert np.sum(w * np.clip(x, knots[0], knots[-1]) ** k) == pytest.approx(exact, rel=1e-12)
    assert np.sum(w) == pytest.approx(1.0, rel=1e-14)


def _copy_scripts(tmp_path):
    for rel in population_map.SCRIPTS:
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, tmp_path / rel)
    return tmp_path


def test_key_follows_code_and_inputs_not_comments(tmp_path):
    """The key changes with a statement of a script or an input; a comment does not change it."""
    inputs = {"grid": 129, "phis": [0.25, 1.0]}
    root = _copy_scripts(tmp_path)
    k0 = population_map.key(inputs, root=root)
    assert k0 == population_map.key(inputs, root=ROOT)
    assert population_map.key({**inputs, "grid": 257}, root=root) != k0
    script = root / population_map.SCRIPTS[1]
    text = script.read_text()
    script.write_text(text + "\n# a comment\n")
    assert population_map.key(inputs, root=root) == k0
    script.write_text(text.replace("TAU_RATIO = 0.7", "TAU_RATIO = 0.6"))
    assert "TAU_RATIO = 0.7" in text and population_map.key(inputs, root=root) != k0


def test_report_section_shows_only_a_current_map(stored, tmp_path):
    sec = population.section(tmp_path, "00-x")
    assert (tmp_path / "00-x-population.png").is_file() and sec.figures
    row = next(r for r in sec.tables[0].rows if r[0].startswith("EHL, tau_inf"))
    assert row[1] == stored["population"]["ehl limit_0.7"]["mean_risk_ratio"]
    # missing: an empty store; stale: the stored map under a key today's code does not give
    refs = tmp_path / "refs"
    assert population.section(tmp_path, "01-x", refs=refs).tables[0].rows[0][0] == "missing"
    doc, _ = population_map.load_current()
    doc["provenance"]["key"] = "0" * 32
    (refs / population_map.KIND).mkdir(parents=True)
    (refs / population_map.KIND / f"{population_map.NAME}-{'0' * 16}.json").write_text(json.dumps(doc))
    sec = population.section(tmp_path, "02-x", refs=refs)
    assert sec.tables[0].rows[0][0] == "stale" and not sec.figures
    assert not (tmp_path / "02-x-population.png").exists()
