"""Report section of the ehl_contact kind: film table against the formulas, centre lines and maps; with an indent
the crossing history and the EHL-vs-dry table."""
import numpy as np
import pytest

from femcheck.report import kinds
from femcheck.runner import run
from femcheck.scene import load_scene


def test_smooth_section_has_film_table_lines_and_maps(tmp_path):
    r = run(load_scene("ehl-smooth", {"numerics.grid": 65, "numerics.refinements": 1}), use_cache=False)
    sec = kinds.section(r, tmp_path, "00")
    assert [t.title for t in sec.tables] == ["EHL film and pressure against the classical formulas"]
    rows = {row[0]: row for row in sec.tables[0].rows}
    e = r.models["ehl"].quantities
    hd = r.models["hamrock_dowson"].quantities
    assert rows["h_central"][1] == e["h_central"]
    assert rows["h_central"][6] == pytest.approx(hd["h_central"] / e["h_central"] - 1.0, rel=1e-12)
    assert len(sec.figures) == 2 and all((tmp_path / f.file).stat().st_size > 1000 for f in sec.figures)


@pytest.mark.slow
def test_indent_section_has_history_and_dry_table(tmp_path):
    sc = load_scene("ehl-indent", {"numerics.grid": 65, "ehl.M": 100.0, "ehl.L": 10.0, "indent.diameter": 1.0,
                                   "indent.slope": 0.25, "numerics.bem_cells": 129})
    r = run(sc, use_cache=False)
    sec = kinds.section(r, tmp_path, "01")
    titles = [t.title for t in sec.tables]
    assert "Additional pressure of the indent at X_D = 0: EHL against dry" in titles
    dp = next(t for t in sec.tables if t.title.startswith("Additional"))
    assert [row[0] for row in dp.rows] == ["rear", "front", "lateral", "centre"]
    assert all(row[5] < 1.0 for row in dp.rows[:3])          # below the dry bound
    assert len(sec.figures) == 3
    f = r.models["ehl"].fields
    # kept steps over the whole crossing, the centred one (X_D = 0) among them
    assert f["pressure_steps"].shape[1:] == (65, 65) and np.abs(f["steps_x_indent"]).min() < 1e-15
    assert f["history_x_indent"][-1] >= (1.0 + 1.5 * 1.0) * r.models["ehl"].stats["b"] * (1 - 1e-12)
    # the reported amplitudes are the centred ones (X_D = 0), not those of the last step
    i0 = int(np.argmin(np.abs(f["history_x_indent"])))
    q = r.models["ehl"].quantities
    assert f["history_x_indent"][i0] == pytest.approx(0.0, abs=1e-15) and i0 + 1 == r.models["ehl"].stats["centre_step"]
    assert all(q[f"additional_pressure_{k}"] == f[f"history_dp_{k}"][i0] for k in ("rear", "front", "lateral", "centre"))
    assert q["additional_pressure_centre"] < 0 < q["additional_pressure_rear"]
