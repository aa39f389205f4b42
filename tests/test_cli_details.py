"""CLI and plugin details a user hits (issue 16 item 4): --version, --models before validation, did-you-mean,
show PATH, integer keys, the suite's count of failed scenes, a user's scene never writing into the package or
the source tree, the pytest plugin's relative paths and its failure message."""
from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

import femcheck
from femcheck.pytest_plugin import resolve_scene_path
from femcheck.result import Comparison, ModelResult, RunResult
from femcheck.testing import assert_agree

CLI = [sys.executable, "-m", "femcheck.cli"]
ROOT = Path(femcheck.__file__).resolve().parent.parent


def femcheck_cli(*args, **kw):
    return subprocess.run([*CLI, *args], capture_output=True, text=True, **kw)


class _Result:
    def __init__(self, returncode, stdout, stderr):
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


@pytest.fixture
def cli_inproc(capsys, monkeypatch):
    """The CLI's own entry point in this process (no interpreter start-up): (returncode, stdout, stderr)."""
    from femcheck import cli

    monkeypatch.setattr(cli, "out_console", cli.Console(width=220))

    def call(*args):
        monkeypatch.setattr(sys, "argv", ["femcheck", *args])
        code = 0
        try:
            cli.main()
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        out = capsys.readouterr()
        return _Result(code, out.out, out.err)

    return call


def test_version():
    r = femcheck_cli("--version")
    assert r.returncode == 0 and r.stdout.strip() == f"femcheck {femcheck.__version__}"


@pytest.mark.slow
def test_models_replace_models_run_before_validation():
    # layer-line lists uncoated Hertz, which needs an elastic substrate: --models without it must run (both models
    # solved; without the scene's reference nothing is compared, which is exit 1 and said in one line)
    r = femcheck_cli("run", "layer-line", "--set", "materials.substrate.rigid=true", "--models", "thin_layer,bem",
                     "--json")
    assert r.returncode == 1 and r.stderr.startswith("NOTHING COMPARED"), r.stderr
    assert set(json.loads(r.stdout)["models"]) == {"thin_layer", "bem"}
    r = femcheck_cli("run", "layer-line", "--set", "materials.substrate.rigid=true", "--models", "thin_layer,analytic")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "elastic substrate" in r.stderr


@pytest.mark.parametrize("args,hint", [
    (["run", "hertz-lin"], "did you mean 'hertz-line'"),
    (["run", "hertz-line", "--set", "load.per_lenght=1e6"], "did you mean 'load.per_length'"),
    (["run", "hertz-line", "--models", "analytic,bme"], "did you mean 'bem'"),
    (["run", "hertz-line", "--set", "tolerances.bme.p_max=0.1"], "did you mean 'bem'"),
    (["suite", "quik"], "did you mean 'quick'"),
])
def test_did_you_mean(args, hint, cli_inproc):
    r = cli_inproc(*args)
    assert r.returncode == 2 and hint in r.stderr and r.stderr.count("\n") == 1, r.stderr


def test_integer_key_says_integer(cli_inproc):
    r = cli_inproc("run", "hertz-line", "--set", "numerics.fem_levels=2.5")
    assert r.returncode == 2 and "allowed: an integer in [1, 6]" in r.stderr


SOFT = ('kind = "line_contact"\n[geometry]\nradius = 0.02\n[materials.cylinder]\nE = 3e9\nnu = 0.4\n'
        '[materials.block]\nE = 210e9\nnu = 0.3\n[load]\nper_length = 2e4\n[models]\nrun = ["analytic", "bem"]\n'
        'references = ["analytic"]\n')


def test_show_path_and_typo_points_to_it(tmp_path, cli_inproc):
    f = tmp_path / "soft.toml"
    f.write_text(SOFT + "[numerics]\nbem_element = 512\n")
    r = cli_inproc("run", str(f))
    assert r.returncode == 2 and f"femcheck show {f}" in r.stderr and "did you mean 'numerics.bem_elements'" \
        in r.stderr, r.stderr
    f.write_text(SOFT)
    r = cli_inproc("show", str(f))
    assert r.returncode == 0 and "load.per_length" in r.stdout and "N/m" in r.stdout


def test_suite_prints_how_many_scenes_failed(monkeypatch):
    from typer.testing import CliRunner

    from femcheck import cli, runner

    def fake_run(sc, **kw):
        bad = sc.name == "layer-point"
        c = Comparison("p_max", "bem", "fem", 1.1 if bad else 1.0, 1.0, 0.1 if bad else 0.0, 0.03, not bad,
                       "not valid here" if bad else "valid")
        return RunResult(sc.name, dict(sc.params), {"bem": ModelResult("bem", "ok", 0.01, {"p_max": 1.0})}, [c],
                         sc.kind)

    monkeypatch.setattr(runner, "run", fake_run)
    monkeypatch.setattr("femcheck.report.html.write_report", lambda runs, out, title, t: Path(out) / "index.html")
    r = CliRunner().invoke(cli.app, ["suite", "layer", "--out", "/nonexistent/never-written"])
    assert r.exit_code == 1
    assert "FAIL: 1 of 4 scene(s) failed (layer-point)" in r.output, r.output


def _digest(root: Path) -> str:
    h = hashlib.sha256()
    for p in sorted(root.rglob("*")):
        if p.is_file() and "__pycache__" not in p.parts:
            h.update(str(p.relative_to(root)).encode())
            h.update(p.read_bytes())
    return h.hexdigest()


@pytest.mark.slow
def test_user_scene_never_writes_into_the_package_or_source_tree(tmp_path):
    # a user's copy of layer-rigid: its FE reference (0.1 s) goes to the cache, or to --references DIR
    # (another load than the built-in scene's, so that no stored reference answers for it)
    scene = (ROOT / "femcheck" / "scenes" / "layer-rigid.toml").read_text().replace(
        'name = "layer-rigid"', 'name = "my-layer"').replace("per_length = 1.0e5", "per_length = 1.1e5")
    assert "per_length = 1.1e5" in scene
    f = tmp_path / "my-layer.toml"
    f.write_text(scene)
    before = {d: _digest(ROOT / d) for d in ("femcheck", "references")}
    env = {"FEMCHECK_CACHE": str(tmp_path / "cache")}
    import os

    r = femcheck_cli("run", str(f), "--out", str(tmp_path / "rep"), cwd=tmp_path, env={**os.environ, **env})
    assert r.returncode == 0, r.stdout + r.stderr
    assert {d: _digest(ROOT / d) for d in ("femcheck", "references")} == before
    assert list((tmp_path / "cache").glob("*.npz"))            # the FE result is in the cache
    mine = tmp_path / "my-refs"
    r = femcheck_cli("run", str(f), "--references", str(mine), cwd=tmp_path, env={**os.environ, **env})
    assert r.returncode == 0, r.stdout + r.stderr
    assert list((mine / "layer_contact").glob("fem-*.json"))
    assert {d: _digest(ROOT / d) for d in ("femcheck", "references")} == before


def test_plugin_resolves_relative_paths_against_the_test_file(tmp_path):
    assert resolve_scene_path("hertz-line", tmp_path) == "hertz-line"
    assert resolve_scene_path("scenes/x.toml", tmp_path) == tmp_path / "scenes" / "x.toml"
    assert resolve_scene_path("x.toml", tmp_path) == tmp_path / "x.toml"
    assert resolve_scene_path(tmp_path / "y.toml", Path("/elsewhere")) == tmp_path / "y.toml"


def test_assert_agree_message_has_significant_digits():
    res = RunResult("s", {}, {"a": ModelResult("a", quantities={"q": 1.000012}),
                              "b": ModelResult("b", quantities={"q": 1.0})}, [])
    with pytest.raises(AssertionError, match=r"by 1.2e-05 \(relative\) > rtol 1e-05"):
        assert_agree(res, "q", "a", "b", rtol=1e-5)
    assert assert_agree(res, "q", "a", "b", rtol=2e-5) == pytest.approx(1.2e-5)
