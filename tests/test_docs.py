"""The documentation site builds with warnings as errors, and every command and example it shows works.

The build is MkDocs + mkdocstrings (``mkdocs.yml``); the rules for running a page's blocks are in
``tests/docs_blocks.py``. The build and the parse checks are quick (seconds); running every page's commands
takes about a minute and is marked slow.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from docs_blocks import DOCS, DURATION, NOT_RUN, ROOT, PageRun, blocks, check_not_run, commands, pages

ISSUE_REF = re.compile(r"\b[Ii]ssues? *#?\d+|(?<![\w&/])#\d+\b")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file",
                        str(ROOT / "mkdocs.yml"), "--site-dir", str(out)], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "WARNING" not in r.stderr, r.stderr
    return out


def test_site_builds_strict_and_has_every_page(site):
    for page in DOCS.rglob("*.md"):
        rel = page.relative_to(DOCS)
        if rel.parts[0] in ("notes", "_tooling"):
            continue
        html = site / rel.parent / ("" if rel.stem == "index" else rel.stem) / "index.html"
        assert html.is_file(), f"{rel} was not built"


def test_development_notes_stay_out_of_the_site(site):
    assert not (site / "notes").exists()
    assert not (site / "_tooling").exists()


def test_api_reference_is_rendered_from_the_docstrings(site):
    html = (site / "api" / "analytic" / "index.html").read_text()
    # the docstring of femcheck.analytic.hertz.line_contact names its source: it must be on the page
    import femcheck.analytic.hertz as hertz

    first = hertz.line_contact.__doc__.strip().split("\n")[0][:40]
    assert re.sub(r"\s+", " ", first.replace("`", "")).split("(")[0].strip() in re.sub(r"<[^>]+>", "", html)
    assert 'id="femcheck.analytic.hertz.line_contact"' in html


def test_kind_pages_cover_every_kind_and_show_its_keys(site):
    from femcheck.problems import KINDS, problem

    for kind in KINDS:
        page = "tangential" if kind in ("line_tangential", "point_tangential") else kind
        src = (DOCS / "kinds" / f"{page}.md").read_text()
        assert f"<!-- keys: {kind} -->" in src, f"kinds/{page}.md lacks the keys table of {kind}"
        html = (site / "kinds" / page / "index.html").read_text()
        for key in problem(kind).SCHEMA:
            assert f"<code>{key}</code>" in html, f"{kind}: key {key} missing from kinds/{page}"


def test_no_issue_numbers_in_the_user_documentation(site):
    texts = {p.relative_to(ROOT).as_posix(): p.read_text() for p in pages()}
    texts.update({h.relative_to(site).as_posix(): re.sub(r"<[^>]+>", " ", h.read_text())
                  for h in site.rglob("*.html") if "search" not in h.parts})
    found = {name: ISSUE_REF.findall(t) for name, t in texts.items()}
    assert not {k: v for k, v in found.items() if v}, found


def test_not_run_blocks_say_why_and_how_long_and_still_parse():
    checked = 0
    for page in pages():
        written = {b.file for b in blocks(page) if b.file}
        for b in blocks(page):
            if b.lang not in ("bash", "console"):
                continue
            if b.not_run:
                assert DURATION.search(b.before), f"{b.where()}: a block not run must say how long it takes"
                for command, expected in commands(b):
                    check_not_run(command, expected, written)
                    checked += 1
    assert checked >= 5


def test_every_femcheck_command_shown_parses(tmp_path, monkeypatch):
    """Quick check of every command (run or not): the CLI parses it and its scene and keys are valid."""
    monkeypatch.chdir(tmp_path)
    n = 0
    for page in pages():
        written = {b.file for b in blocks(page) if b.file}
        for b in blocks(page):
            if b.file:
                (tmp_path / b.file).parent.mkdir(parents=True, exist_ok=True)
                (tmp_path / b.file).write_text(b.text)
            if b.lang in ("bash", "console"):
                for command, expected in commands(b):
                    if "femcheck" in command:
                        check_not_run(command, expected, written)
                        n += 1
    assert n >= 20, n


def _runnable_pages() -> list[Path]:
    """The documentation pages with blocks to run (the README is run by test_readme_examples.py)."""
    return [p for p in pages()[1:] if any(not b.not_run and b.lang in ("bash", "console", "python") for b in blocks(p))]


@pytest.mark.slow
@pytest.mark.parametrize("page", _runnable_pages(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page_commands_and_examples_run(page, tmp_path):
    run = PageRun(tmp_path)
    for b in blocks(page):
        run.run(b)
    assert run.ran > 0


def test_not_run_marker_is_the_documented_phrase():
    # the phrase the pages use is the one the tests look for (a reworded page would silently run nothing)
    used = sum(NOT_RUN in p.read_text() for p in pages())
    assert used >= 3
