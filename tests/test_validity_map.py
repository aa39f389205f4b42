"""Validity maps and the executor: grid points agree with single runs, refusals are recorded, the CLI contract
holds, and the same sweep on a dask LocalCluster gives the same numbers as local processes."""
import json
import subprocess
import sys

import numpy as np
import pytest

from femcheck.errors import InputError
from femcheck.executor import map_cases
from femcheck.runner import run
from femcheck.scene import load_scene
from femcheck.validity_map import parse_axis, validity_map

FAST = ["analytic", "bem"]
# hertz-line with a coarse BEM grid so the map cells are fast and the errors are well above round-off
BASE = {"numerics.bem_elements": 128}


@pytest.fixture(scope="module")
def scene():
    return load_scene("hertz-line", BASE)


@pytest.fixture(scope="module")
def small_map(scene):
    x = parse_axis("--x", "load.per_length=2e5:2e6:2", scene)
    y = parse_axis("--y", "geometry.radius=0.005:0.02:2", scene)
    return validity_map(scene, x, y, FAST, workers=1)


def test_axis_spacing_and_validation(scene):
    a = parse_axis("--x", "load.per_length=1e4:1e6:3", scene)          # two decades: geometric by default
    assert a.log and np.allclose(a.values, [1e4, 1e5, 1e6])
    b = parse_axis("--x", "load.per_length=1e4:1e6:3:lin", scene)
    assert not b.log and np.allclose(b.values, [1e4, 505000.0, 1e6])
    c = parse_axis("--y", "numerics.bem_elements=100:400:4", scene)     # int keys are rounded
    assert c.values == (100, 200, 300, 400)
    for spec, fragment in (("load.per_length=1e4:1e6", "KEY=lo:hi:n"), ("models.run=1:2:3", "numeric key"),
                           ("unicorn=1:2:3", "numeric key"), ("load.per_length=5:1:3", "lo < hi"),
                           ("materials.block.nu=0.1:0.7:3", "materials.block.nu")):
        with pytest.raises(InputError, match=fragment):
            parse_axis("--x", spec, scene)


def test_map_points_equal_single_runs(scene, small_map):
    # every grid point's error must be what a direct run of the scene at that point gives (independent path)
    assert [p.status for p in small_map.points] == ["ok"] * 4
    for p in small_map.points:
        direct = run(scene, p.overrides, models=FAST)
        bem, ana = direct.models["bem"].quantities, direct.models["analytic"].quantities
        e, tol, passed = p.errors[("bem", "analytic", "p_max")]
        assert e == pytest.approx(abs(bem["p_max"] / ana["p_max"] - 1.0), rel=1e-12)
        assert passed == (e <= tol)


def test_map_tolerance_region_and_statements(scene):
    # a tolerance between the errors at the two loads splits the map: the BEM grid is fixed relative to a_H,
    # so the error depends on the load only through the exact-circle vs parabola difference (grows with a/R)
    x = parse_axis("--x", "load.per_length=1e5:4e6:2", scene)
    y = parse_axis("--y", "geometry.radius=0.01:0.02:2", scene)
    errs = {}
    for w in x.values:
        r = run(scene, {"load.per_length": w, "geometry.radius": 0.01}, models=FAST)
        errs[w] = abs(r.models["bem"].quantities["half_width"] / r.models["analytic"].quantities["half_width"] - 1)
    assert errs[1e5] < errs[4e6]
    tol = float(np.sqrt(errs[1e5] * errs[4e6]))
    sc = scene.with_overrides({"tolerances.bem.half_width": tol})
    m = validity_map(sc, x, y, FAST, workers=1)
    err, ok, t = m.grid(("bem", "analytic", "half_width"))
    assert t == tol and ok[0, 0] == 1.0 and ok[0, 1] == 0.0
    text = " ".join(m.statements())
    assert "bem vs analytic" in text and "geometry.radius = 0.01: 1e+05" in text


def test_refused_points_are_recorded(scene):
    # a/R > 0.1 is refused by the scene: the point is kept with the reason, not dropped
    x = parse_axis("--x", "load.per_length=1e6:1e9:2", scene)
    y = parse_axis("--y", "geometry.radius=0.01:0.02:2", scene)
    m = validity_map(scene, x, y, ["analytic"], workers=1)
    refused = [p for p in m.points if p.status == "refused"]
    assert len(refused) == 2 and all("load.per_length" in p.message for p in refused)
    assert any("refused" in s for s in m.statements())


def _square(v):
    return v * v


@pytest.mark.slow
def test_dask_local_cluster_matches_local(scene, small_map):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) \
            as cluster:
        assert map_cases(_square, [3, 1, 2], scheduler=cluster.scheduler_address) == [9, 1, 4]
        remote = validity_map(scene, small_map.x, small_map.y, FAST, scheduler=cluster.scheduler_address)
    for a, b in zip(small_map.points, remote.points):
        assert (a.ix, a.iy, a.status) == (b.ix, b.iy, b.status)
        assert a.errors[("bem", "analytic", "p_max")][0] == pytest.approx(b.errors[("bem", "analytic", "p_max")][0],
                                                                         rel=1e-12)


@pytest.mark.slow
def test_unreachable_scheduler_is_an_input_error():
    pytest.importorskip("distributed")
    with pytest.raises(InputError, match="--scheduler"):
        map_cases(_square, [1, 2], scheduler="tcp://127.0.0.1:1")


@pytest.mark.slow
def test_cli_map_writes_report(tmp_path):
    out = tmp_path / "m"
    r = subprocess.run([sys.executable, "-m", "femcheck.cli", "map", "hertz-line", "--x",
                        "load.per_length=2e5:2e6:2", "--y", "geometry.radius=0.005:0.02:2", "--models",
                        "analytic,bem", "--set", "numerics.bem_elements=128", "--workers", "1", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    data = json.loads((out / "map.json").read_text())
    assert data["x"]["key"] == "load.per_length" and len(data["points"]) == 4
    comp = next(c for c in data["comparisons"] if (c["model"], c["quantity"]) == ("bem", "p_max"))
    assert all(e is not None and e < comp["tolerance"] for row in comp["rel_error"] for e in row)
    assert (out / "index.html").read_text().count("<img") == len(data["comparisons"])
    bad = subprocess.run([sys.executable, "-m", "femcheck.cli", "map", "hertz-line", "--x", "load.per_length=1:2",
                          "--y", "geometry.radius=0.005:0.02:2", "--out", str(tmp_path / "bad")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "--x" in bad.stderr
    assert not (tmp_path / "bad").exists()
