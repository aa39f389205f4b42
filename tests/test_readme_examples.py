"""The README: short, opening with the two commands CI runs, its picture present, its links alive, and its
examples working as written (the CLI lines, the Python lines, and the pytest example run by pytest itself in a
fresh project). The rules for running blocks are shared with the documentation pages (``tests/docs_blocks.py``).
"""
from __future__ import annotations

import re

import pytest

from docs_blocks import ROOT, PageRun, blocks, check_not_run, commands

README = ROOT / "README.md"
OPENING = ("python3 -m venv .venv && . .venv/bin/activate && pip install -c constraints.txt -e '.[viz]' && "
           "femcheck suite quick\n"
           "python3 -m venv .venv && . .venv/bin/activate && pip install -c constraints.txt -e '.[test]' && pytest\n")
MAX_LINES = 150     # "a README of at most about 150 lines": the rest belongs in the documentation site


def test_readme_opens_with_the_two_commands_and_ci_runs_the_second():
    first = blocks(README)[0]
    assert first.lang == "bash" and first.text == OPENING
    ci = (ROOT / ".ci" / "run").read_text()
    assert OPENING.split("\n")[1] in ci.split("\n"), ".ci/run must run the README's second line verbatim"


def test_readme_is_short():
    n = len(README.read_text().split("\n"))
    assert n <= MAX_LINES, f"README has {n} lines; move the detail to docs/"


def test_readme_picture_exists_and_is_small():
    text = README.read_text()
    pictures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert pictures
    for p in pictures:
        f = ROOT / p
        assert f.is_file(), p
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert f.stat().st_size < 300_000, f"{p}: {f.stat().st_size} bytes"


def test_readme_links_point_at_existing_files():
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README.read_text()):
        if "://" in target:
            continue
        assert (ROOT / target).exists(), f"README links to {target}, which does not exist"


def test_readme_commands_parse():
    n, written = 0, {b.file for b in blocks(README) if b.file}
    for b in blocks(README):
        if b.lang == "bash":
            for command, expected in commands(b):
                check_not_run(command, expected, written)
                n += 1
    assert n >= 6


def test_readme_python_example_runs(tmp_path):
    run = PageRun(tmp_path)
    code = [b for b in blocks(README) if b.lang == "python" and not b.file]
    assert code
    for b in code:
        run.run(b)


@pytest.mark.slow
def test_readme_runs_as_written(tmp_path):
    """Every block of the README in order, in a fresh directory: the CLI lines, the Python lines, and the pytest
    example written to tests/ and run by pytest (the first block, the install, is what CI runs)."""
    run = PageRun(tmp_path)
    for b in blocks(README)[1:]:
        run.run(b)
    assert run.ran >= 4
