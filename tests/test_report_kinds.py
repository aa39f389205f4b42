"""The per-kind report extension point (femcheck.report.kinds): a kind without a module gets an empty section,
a kind with one gets its tables and figures rendered into the report."""
from __future__ import annotations

import sys
import types

from femcheck.report import kinds
from femcheck.report.html import write_report
from femcheck.result import ModelResult, RunResult


def _run(kind):
    m = ModelResult("toy", "ok", 0.01, {"q": 1.0})
    return RunResult("toy-scene", {}, {"toy": m}, [], kind, "a toy scene")


def test_kind_without_a_module_has_an_empty_section(tmp_path):
    sec = kinds.section(_run("no_such_kind"), tmp_path, "00")
    assert sec.tables == [] and sec.figures == []


def test_kind_section_tables_and_figures_reach_the_report(tmp_path, monkeypatch):
    mod = types.ModuleType("femcheck.report.kinds.toy_kind")

    def section(run, outdir, prefix):
        (outdir / f"{prefix}-toy.png").write_bytes(b"\x89PNG")
        return kinds.KindSection([kinds.Table("Toy table 2", ["quantity", "value"], [["f_x", 4.96e-3]], "seed 000")],
                                 [kinds.Figure(f"{prefix}-toy.png", "toy caption")])

    mod.section = section
    monkeypatch.setitem(sys.modules, "femcheck.report.kinds.toy_kind", mod)
    monkeypatch.setattr(kinds, "find_spec", lambda name: object())
    index = write_report([_run("toy_kind")], tmp_path / "rep", "toy", 0.1)
    html = index.read_text()
    assert "Toy table 2" in html and "toy caption" in html and "00-toy-scene-toy.png" in html
    assert (tmp_path / "rep" / "00-toy-scene-toy.png").is_file()
