"""The report's validity dashboard and its truthful plots (issue 16 items 1-2): one row per scene and model with
the worst error against each reference, tolerance, verdict and cost; summary.json 'validity'; the quick report's
top fits a 1400 x 1000 browser window; units on quantity rows; sources by author and year; convergence against
the reference's own value; maps with equal axes and colour scales not set by a grid-dependent peak."""
from __future__ import annotations

import json
import re
import shutil
import subprocess

import numpy as np
import pytest

from femcheck.compare import compare
from femcheck.report import dashboard, fe_plots, plots
from femcheck.report.html import write_report
from femcheck.report.sources import cite
from femcheck.report.units import unit_of
from femcheck.result import ModelResult, RunResult
from femcheck.scene import builtin_scene_files, load_scene


def _toy_run() -> RunResult:
    sc = load_scene("hertz-line", {"models.contrast": ["bem"], "tolerances.fem.half_width": 1e-4})
    levels = [{"h_over_a": h, "n_elements": 10, "n_dofs": 20, "p_max": 1.0 + h ** 2, "half_width": 2.0 + h,
               "iterations": 3, "residual": 1e-12, "time_s": 0.1} for h in (0.1, 0.05, 0.025)]
    certs = {"p_max": {"value": 1.0, "finest": 1.000625, "order": 2.0, "error_estimate": 8e-4, "certified": True,
                       "note": "observed order 2.00"},
             "half_width": {"value": 2.025, "finest": 2.025, "order": None, "error_estimate": 0.04,
                            "certified": False, "note": "the last three levels oscillate"}}
    results = {
        "analytic": ModelResult("analytic", "ok", 1e-4, {"p_max": 1.0, "half_width": 2.0}),
        "bem": ModelResult("bem", "ok", 0.02, {"p_max": 1.2, "half_width": 2.0001}),
        "fem": ModelResult("fem", "ok", 200.0, {"p_max": 1.0004, "half_width": 2.0003},
                           {"levels": levels, "certificates": certs, "finest": {"p_max": 1.000625},
                            "reference": {"run_time_s": 183.0, "key": "k" * 32, "created": "x",
                                          "femcheck_version": "0"}}, cached=True),
    }
    comps, nc = compare(sc, results, 1.0)
    return RunResult("hertz-line", dict(sc.params), results, comps, sc.kind, "Seed 001 roller (issue 3: 2 %)", nc)


def test_dashboard_rows_and_validity(tmp_path):
    run = _toy_run()
    rows = {r.model: r for r in dashboard.rows(run)}
    assert rows["analytic"].verdict == "reference" and rows["analytic"].role == "reference"
    assert rows["bem"].role == "contrast" and rows["bem"].verdict == "not valid here"     # 20 % off a 1 % band
    # one verdict per reference: bem against analytic and against fem, each with the design quantity (p_max)
    assert {rv.reference for rv in rows["bem"].per_reference} == {"analytic", "fem"}
    assert all(rv.design.quantity == "p_max" and rv.worst.quantity == "p_max" for rv in rows["bem"].per_reference)
    assert rows["fem"].time_text == "stored, solved in 183 s" and rows["fem"].time_s == 183.0
    index = write_report([run], tmp_path / "rep", "toy", 1.0)
    data = json.loads((tmp_path / "rep" / "summary.json").read_text())
    v = data["validity"]
    assert v and all(set(x) >= {"scene", "model", "reference", "quantity", "rel_error", "tolerance", "verdict"}
                     for x in v)
    assert {(x["model"], x["reference"], x["quantity"]) for x in v} == \
        {(c.model, c.reference, c.quantity) for c in run.comparisons}
    html = index.read_text()
    assert html.index('class="dash"') < html.index("<section"), "the dashboard comes first"
    assert "stored, solved in 183 s" in html and "not valid here (contrast)" in html
    assert "Johns-Rahnejat et al. 2023 roller (2 %)" in html and "issue 3" not in html     # sources by author
    assert "dashboard-cost-error.png" in html and (tmp_path / "rep" / "dashboard-cost-error.png").is_file()


def test_units_and_sources():
    assert unit_of("p_max") == "Pa" and unit_of("p_max_inner") == "Pa" and unit_of("half_width_al2o3") == "m"
    assert unit_of("creep_force_x", {"load.per_length": 1e6}) == "N/m" and unit_of("creep_force_x", {}) == "N"
    assert unit_of("contact_area") == "m²" and unit_of("spin_moment") == "N·m"
    assert unit_of("fem@finest") == "?" and unit_of("semi_axis_y_outer") == "m"
    assert cite("seed 000's bearing") == "Blanco-Lorenzo et al. 2022's bearing"
    assert cite("Seed 004 eq 2.16 (issue 5)") == "Biboulet 2008 eq 2.16"


def test_convergence_is_drawn_against_the_reported_value(tmp_path, monkeypatch):
    run = _toy_run()
    drawn = {}
    real = plots.plt.Axes.loglog

    def spy(ax, x, y, *a, label=None, **k):
        if label:
            drawn[label.split(":")[0]] = (np.asarray(x), np.asarray(y), label)
        return real(ax, x, y, *a, label=label, **k)

    monkeypatch.setattr(plots.plt.Axes, "loglog", spy)
    names = fe_plots.convergence(run, tmp_path / "c.png")
    assert names and (tmp_path / names[0]).is_file()
    x, y, label = drawn["p_max"]                 # certified: |q_level / value - 1|, value = 1.0 (not Hertz)
    assert np.allclose(y, np.array([0.01, 0.0025, 0.000625])) and "certified" in label
    x, y, label = drawn["half_width"]            # uncertified: the change to the finest level, finest not drawn
    assert len(y) == 2 and np.allclose(y, np.abs(np.array([2.1, 2.05]) / 2.025 - 1)) and "not certified" in label


def test_maps_keep_true_aspect_or_say_the_stretch_and_clip_a_singular_peak(tmp_path, monkeypatch):
    x = np.linspace(-1e-4, 1e-4, 21)
    y = np.linspace(-4e-3, 4e-3, 161)                         # a 1:40 footprint
    p = np.outer(np.sqrt(np.clip(1 - (x / 1e-4) ** 2, 0, None)), np.ones_like(y)) * 1e9
    p[10, -1] = 50e9                                          # a grid-dependent edge spike
    m = ModelResult("bem", "ok", 0.1, {"p_max": 50e9}, fields={"map_x": x, "map_y": y, "pressure_map": p})
    run = RunResult("roller", {}, {"bem": m}, [], "roller_contact", "",
                    {"p_max": "grows with refinement by nature (a pressure peak at a sharp edge): not compared"})
    seen = {}
    real = plots.plt.Axes.pcolormesh

    def spy(ax, *a, **k):
        if "vmax" in k:                                       # the map, not the colour bar's own mesh
            seen["aspect"], seen["vmax"] = ax.get_aspect(), k["vmax"]
        return real(ax, *a, **k)

    monkeypatch.setattr(plots.plt.Axes, "pcolormesh", spy)
    assert plots.pressure_map(run, tmp_path / "m.png")
    # a 1:40 footprint at true aspect would be a 0.14-inch sliver: x is stretched by a stated factor
    assert seen["aspect"] == 12.0
    assert plots._map_figure(x, y)[2] == "x stretched 12x"
    assert seen["vmax"] < 1.01 and seen["vmax"] > 0.9         # GPa: the spike does not set the scale
    run.not_compared = {}
    plots.pressure_map(run, tmp_path / "m2.png")
    assert seen["vmax"] == pytest.approx(50.0)
    # a 1:2 footprint reads at its true aspect
    wide = ModelResult("bem", "ok", 0.1, {}, fields={"map_x": x, "map_y": y / 20, "pressure_map": p})
    plots.pressure_map(RunResult("roller", {}, {"bem": wide}, [], "roller_contact"), tmp_path / "m3.png")
    assert seen["aspect"] == 1.0


def test_cattaneo_analytic_traction_has_the_friction_sign_and_spans_the_contact():
    import femcheck

    res = femcheck.run("cattaneo", {"numerics.exact_cells": 21, "numerics.exact_levels": 1}, models=["exact", "analytic"])
    an, ex = res.models["analytic"], res.models["exact"]
    a = an.quantities["semi_axis_x"]
    assert an.fields["x"].min() < -a and an.fields["x"].max() > a
    assert np.sign(an.fields["traction_x"].sum()) == np.sign(an.quantities["creep_force_x"]) == -1
    # on the exact grid's centre line the two tractions agree to a fraction of mu p0
    q_an = np.interp(ex.fields["x"], an.fields["x"], an.fields["traction_x"])
    mu_p0 = res.params["friction.mu"] * an.quantities["p_max"]
    assert np.abs(q_an - ex.fields["traction_x"]).max() < 0.35 * mu_p0
    assert np.abs(q_an - ex.fields["traction_x"]).mean() < 0.05 * mu_p0


MEASURE = """<script>
window.addEventListener('load', () => {
  const out = {vw: innerWidth, vh: innerHeight, rows: []};
  for (const t of document.querySelectorAll('.dash table')) {
    const scene = t.querySelector('th a').textContent;
    for (const tr of [...t.querySelectorAll('tr')].slice(1)) {
      const td = tr.querySelectorAll('td'), r = tr.getBoundingClientRect();
      out.rows.push({scene, model: td[0].textContent.trim(), verdict: td[2].textContent.trim(),
                     time: td[3].textContent.trim(), bottom: r.bottom, right: r.right,
                     clipped: td[2].scrollWidth > td[2].clientWidth + 1 || td[3].scrollWidth > td[3].clientWidth + 1});
    }
  }
  const pre = document.createElement('pre'); pre.id = 'measure'; pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script></body>"""


def measured_in_browser(index, script: str, budget_ms: int, timeout_s: float) -> dict:
    """Open the report ``index`` with ``script`` appended in a 1400 x 1000 headless Chromium and return the JSON
    the script writes into ``<pre id="measure">``."""
    probe = index.with_name("probe.html")
    probe.write_text(index.read_text().replace("</body>", script))
    r = subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                        "--window-size=1400,1000", f"--virtual-time-budget={budget_ms}", "--dump-dom",
                        probe.as_uri()], capture_output=True, text=True, timeout=timeout_s)
    found = re.search(r'<pre id="measure">(.*?)</pre>', r.stdout, flags=re.S)
    assert found, r.stderr[-2000:]
    return json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("chromium") is None, reason="needs chromium (apt install chromium)")
def test_quick_report_top_shows_every_scene_verdict_and_cost(tmp_path, monkeypatch):
    """The quick suite's report, opened in a 1400 x 1000 headless browser: every scene and every model's
    verdict and run time are in the first screen, none cut off."""
    from femcheck import runner
    from stored_references import use_stored_references

    use_stored_references(monkeypatch)
    scenes = [load_scene(n) for n in builtin_scene_files() if "quick" in load_scene(n).tags]
    runs = [runner.run(sc) for sc in scenes]
    m = measured_in_browser(write_report(runs, tmp_path / "quick", "quick", 1.0), MEASURE, 3000, 120)
    assert {row["scene"] for row in m["rows"]} == {sc.name for sc in scenes}
    assert len(m["rows"]) == sum(len(run.models) for run in runs)
    # and every quantity of the quick suite has its SI unit in the report
    unknown = {(run.scene, q) for run in runs for res in run.models.values() for q in res.quantities
               if unit_of(q, run.params, run.kind) == "?"}
    assert not unknown, unknown
    for row in m["rows"]:
        assert row["bottom"] <= 1000 and row["right"] <= 1400, row
        assert row["verdict"] and row["time"] and not row["clipped"], row


def test_one_verdict_per_reference_and_the_design_quantity():
    """An uncertified FE reference does not hide a valid comparison with the closed form; a bearing row shows
    Q_max (the kind's design quantity) even where another quantity is worse against its tolerance."""
    from femcheck.result import Comparison

    def comp(model, ref, q, err, tol, verdict):
        return Comparison(q, model, ref, 1.0 + err, 1.0, err, tol, verdict == "valid", verdict)

    ok = ModelResult("bem", "ok", 0.01, {"p_max": 1.011})
    run = RunResult("hertz-line", {"models.references": ["analytic", "fem"]}, {"bem": ok},
                    [comp("bem", "analytic", "p_max", 0.011, 0.02, "valid"),
                     comp("bem", "fem", "p_max", 0.012, 0.02, "reference uncertified")], "line_contact")
    (row,) = dashboard.rows(run)
    assert [(rv.reference, rv.verdict) for rv in row.per_reference] == [("analytic", "valid"),
                                                                        ("fem", "reference uncertified")]
    bearing = RunResult("crb-elastic-rings", {"models.references": ["fem"]}, {"rigid_ring": ok},
                        [comp("rigid_ring", "fem", "load_zone_angle", 0.123, 0.05, "not valid here"),
                         comp("rigid_ring", "fem", "q_max", 0.157, 0.2, "contrast")], "bearing_load")
    (row,) = dashboard.rows(bearing)
    (rv,) = row.per_reference
    assert rv.design.quantity == "q_max" and rv.worst.quantity == "load_zone_angle" and rv.verdict == "not valid here"


FIGURES = """<script>
window.addEventListener('load', () => {
  const out = {vw: innerWidth, page_width: document.scrollingElement.scrollWidth, imgs: []};
  for (const im of document.querySelectorAll('img')) {
    const r = im.getBoundingClientRect();
    out.imgs.push({src: im.getAttribute('src'), nw: im.naturalWidth, nh: im.naturalHeight,
                   width: r.width, height: r.height, right: r.right});
  }
  const pre = document.createElement('pre'); pre.id = 'measure'; pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script></body>"""


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("chromium") is None, reason="needs chromium (apt install chromium)")
def test_report_figures_read_at_1400_px(tmp_path, monkeypatch):
    """The plots of the scenes whose figures used to fail a reader (long contacts drawn as slivers, wide FE tables
    off the page), opened in a 1400 x 1000 headless browser: every figure loads, none is a sliver (at least
    150 px tall and 0.35 as tall as wide: a 0.5 x 20 mm map at true aspect was a few pixels), none runs past the
    window, and the page itself does not scroll sideways (wide tables scroll in their own box)."""
    from femcheck import runner
    from stored_references import use_stored_references

    use_stored_references(monkeypatch)
    runs = [runner.run(load_scene(n)) for n in ("groove-rolling", "roller-finite", "carter-2d", "creep-curve")]
    m = measured_in_browser(write_report(runs, tmp_path / "figs", "figs", 1.0), FIGURES, 5000, 180)
    assert m["page_width"] <= m["vw"] + 1, m["page_width"]
    assert len(m["imgs"]) >= 4 * len(runs)
    for im in m["imgs"]:
        assert im["nw"] > 0, f"{im['src']} did not load"
        assert im["height"] >= 150, im
        # measured: every figure 0.45-0.6 tall for its width; long maps at true aspect (the former slivers) 0.23
        assert im["nh"] >= 0.35 * im["nw"], im
        assert im["right"] <= m["vw"] + 1, im
