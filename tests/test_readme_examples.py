"""The README's examples work as written (issue 16 item 4): the soft-roller scene file, the pytest example run
by pytest itself from another directory, and the Python lines."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

import femcheck

README = Path(femcheck.__file__).resolve().parent.parent / "README.md"


def _block(lang: str, contains: str) -> str:
    blocks = re.findall(rf"```{lang}\n(.*?)```", README.read_text(), flags=re.S)
    found = [b for b in blocks if contains in b]
    assert len(found) == 1, f"README: expected one {lang} block with {contains!r}"
    return found[0]


def test_readme_scene_file_runs_and_passes(tmp_path):
    f = tmp_path / "soft-roller.toml"
    f.write_text(_block("toml", 'name = "soft-roller"'))
    res = femcheck.run(f)
    assert res.passed, res.problems
    assert res.comparisons and all(c.verdict == "valid" for c in res.comparisons)


def test_readme_python_lines_run():
    code = _block("python", "import femcheck")
    exec(compile(code, "README", "exec"), {})


@pytest.mark.slow
def test_readme_pytest_example_runs_from_another_directory(tmp_path):
    project = tmp_path / "project"
    (project / "tests" / "scenes").mkdir(parents=True)
    (project / "tests" / "scenes" / "soft-roller.toml").write_text(_block("toml", 'name = "soft-roller"'))
    (project / "tests" / "test_roller.py").write_text(_block("python", "def test_soft_roller"))
    # started from the project root: the relative scene path must be read from the test file's directory
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests"], cwd=project,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 passed" in r.stdout
