"""The code blocks of the README and the documentation pages, and how the tests run them.

A page is read as a user would follow it: its blocks in order, in one working directory.

- ``bash``: every line (``\\`` continues it) is a command. ``femcheck ...`` and ``pytest ...`` (on the page's own
  files) are run and must exit 0; ``mkdocs build ...`` is run with ``--site-dir`` into the working directory.
- ``console``: ``$ command`` lines are run; the lines shown after a command must appear in its output (a line
  ending in ``...`` only its start); the exit
  code must be 2 when the output shown is a ``femcheck: error:`` line, 0 otherwise.
- ``python``: executed in one namespace per page (statements such as ``assert`` check the numbers shown).
- a block right after ``<!-- file: PATH -->`` is written to PATH in the working directory instead (a scene
  file, a test file) and used by the commands after it.
- ``toml`` blocks must parse, ``json`` blocks must be valid JSON.

A block may be left unrun only when the paragraph just before it says so in words the reader sees:
"Not run by the documentation tests", with the reason and how long the command takes. Its commands are then
checked without running them: a ``femcheck`` command is parsed by the CLI and its scene, ``--set`` keys,
``--models`` and map axes are validated; a benchmark script must exist and compile; ``pip install`` must name
extras that pyproject.toml declares; ``pytest -m X`` must use a declared marker.
"""
from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
NOT_RUN = "Not run by the documentation tests"
DURATION = re.compile(r"\b\d+(\.\d+)?\s*(s|ms|min|minutes?|seconds?|h|hours?)\b")
_FENCE = re.compile(r"^```(\w*)\s*$")
_FILE = re.compile(r"^<!-- file: (\S+) -->$")


@dataclass
class Block:
    page: str
    line: int                 # 1-based line of the opening fence
    lang: str
    text: str
    before: str               # the paragraph just before the block (marker comments left out)
    file: str | None = None   # <!-- file: PATH -->

    @property
    def not_run(self) -> bool:
        return NOT_RUN in self.before

    def where(self) -> str:
        return f"{self.page}:{self.line}"


def pages() -> list[Path]:
    """README.md and every documentation page (not the development notes, not the build tooling)."""
    docs = sorted(p for p in DOCS.rglob("*.md") if not p.relative_to(DOCS).parts[0] in ("notes", "_tooling"))
    return [ROOT / "README.md", *docs]


def blocks(path: Path) -> list[Block]:
    lines = path.read_text().split("\n")
    out: list[Block] = []
    i = 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if not m or not m.group(1):
            i += 1
            continue
        start = i
        j = i + 1
        while j < len(lines) and lines[j].strip() != "```":
            j += 1
        k, marker = start - 1, None
        while k >= 0 and (not lines[k].strip() or _FILE.match(lines[k].strip())):
            marker = marker or (_FILE.match(lines[k].strip()) and _FILE.match(lines[k].strip()).group(1))
            k -= 1
        para: list[str] = []
        while k >= 0 and lines[k].strip() and not lines[k].startswith("```"):
            para.insert(0, lines[k])
            k -= 1
        out.append(Block(str(path.relative_to(ROOT)), start + 1, m.group(1), "\n".join(lines[start + 1:j]) + "\n",
                         " ".join(para), marker))
        i = j + 1
    return out


def commands(block: Block) -> list[tuple[str, list[str]]]:
    """(command, expected output lines) of a bash or console block."""
    if block.lang == "bash":
        joined = block.text.replace("\\\n", " ")
        return [(c.strip(), []) for c in joined.split("\n") if c.strip() and not c.strip().startswith("#")]
    out: list[tuple[str, list[str]]] = []
    for line in block.text.replace("\\\n", " ").split("\n"):
        if line.startswith("$ "):
            out.append((line[2:].strip(), []))
        elif line.strip() and out:
            out[-1][1].append(line.strip())
    return out


def argv(command: str) -> list[str]:
    """The words of one command, environment assignments (``OMP_NUM_THREADS=1``) and comments left out."""
    words = shlex.split(command, comments=True)
    while words and re.match(r"^[A-Z_][A-Z0-9_]*=", words[0]):
        words.pop(0)
    return words


def parts(command: str) -> list[str]:
    """A ``a && b && c`` line split into its commands."""
    return [p.strip() for p in command.split("&&") if p.strip()]


# ---------------------------------------------------------------------------------------------- checks


def check_femcheck_parses(words: list[str]) -> None:
    """Parse ``femcheck ...`` with the CLI's own parser and validate its scene, keys, models and axes."""
    import click
    import typer

    from femcheck.cli import app
    from femcheck.runner import resolve_scene
    from femcheck.scene import parse_overrides

    group = typer.main.get_command(app)
    try:
        ctx = group.make_context("femcheck", words[1:])
    except (click.exceptions.Exit, typer.Exit):   # --version, --help: eager options that end the parse
        return
    name, sub, rest = group.resolve_command(ctx, ctx._protected_args + ctx.args)
    assert sub is not None, f"no command {name!r}"
    with sub.make_context(name, rest, parent=ctx) as sctx:
        p = sctx.params
    if name == "list" or "scene" not in p:
        return
    models = [m.strip() for m in p["models"].split(",")] if p.get("models") else None
    sc = resolve_scene(p["scene"], parse_overrides(p.get("set_") or []), models)
    if name == "map":
        from femcheck.validity_map import parse_axis

        parse_axis("--x", p["x"], sc)
        parse_axis("--y", p["y"], sc)


def check_not_run(command: str, expected: list[str] = (), written: set[str] = frozenset()) -> None:
    """A command that is shown but not run: it must at least parse. A ``femcheck`` command shown with a
    ``femcheck: error: ...`` line must be refused with that message."""
    for part in parts(command):
        words = argv(part)
        if not words or words[0] in (".", "source", "cd") or words[:3] == ["python3", "-m", "venv"]:
            continue
        if words[0] == "femcheck":
            errors = [e.removeprefix("femcheck: error: ") for e in expected if e.startswith("femcheck: error:")]
            if errors:
                from femcheck.errors import InputError

                try:
                    check_femcheck_parses(words)
                except InputError as err:
                    assert str(err) == errors[0], f"{part!r}: {err} (shown: {errors[0]})"
                else:
                    raise AssertionError(f"{part!r} was accepted; the page shows it refused")
            else:
                check_femcheck_parses(words)
        elif words[0] in ("python", "python3") and words[1].endswith(".py"):
            script = ROOT / words[1]
            assert script.is_file(), f"{words[1]} does not exist"
            compile(script.read_text(), str(script), "exec")
        elif words[0] == "pip" and words[1] == "install":
            declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
            for w in words[2:]:
                for extra in re.findall(r"\[([\w,]+)\]", w):
                    for e in extra.split(","):
                        assert e in declared, f"extra {e!r} is not declared in pyproject.toml"
        elif words[0] == "pytest":
            markers = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"]["ini_options"]["markers"]
            names = {m.split(":")[0] for m in markers}
            if "-m" in words:
                expr = words[words.index("-m") + 1]
                for w in re.findall(r"\w+", expr):
                    assert w in names | {"not", "and", "or"}, f"pytest marker {w!r} is not declared"
            for w in words[1:]:
                if w.startswith("tests/") and w.split("::")[0] not in written:      # written: the page's files
                    assert (ROOT / w.split("::")[0]).exists(), f"{w} does not exist"
        elif words[0] == "mkdocs":
            assert (ROOT / "mkdocs.yml").is_file()
        elif words[0] == "ccx":
            # a deck written by `femcheck export`: DIR/<scene>-L<level>-<element>, the scene a built-in one
            from femcheck.scene import builtin_scene_files

            assert words[1] == "-i" and len(words) == 3, f"{part!r}: shown as `ccx -i DECK`"
            m = re.fullmatch(r"(?:.*/)?(.+)-L(\d+)-(C3D4|C3D10|CPE3|CPE6)", words[2])
            assert m and m.group(1) in builtin_scene_files(), f"{words[2]!r} is not a deck femcheck export writes"
        else:
            raise AssertionError(f"no rule to check {part!r}: add one to tests/docs_blocks.py")


@dataclass
class PageRun:
    """Runs a page's blocks in order in ``workdir``. The stored references are read from a copy (a run that
    solves an FE reference stores it there, never in the source tree); ``femcheck`` is found next to the
    interpreter running the tests."""
    workdir: Path
    namespace: dict = field(default_factory=dict)
    ran: int = 0

    def __post_init__(self) -> None:
        refs = self.workdir / ".references"
        shutil.copytree(ROOT / "references", refs)
        self.env = {**os.environ, "FEMCHECK_REFERENCES": str(refs), "COLUMNS": "200",
                    "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}

    def run(self, block: Block) -> None:
        if block.file:
            target = self.workdir / block.file
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(block.text)
            return
        if block.lang == "toml":
            tomllib.loads(block.text)
            return
        if block.lang == "json":
            json.loads(block.text)
            return
        if block.lang == "python":
            cwd, env = os.getcwd(), dict(os.environ)
            os.chdir(self.workdir)
            os.environ.update(self.env)
            try:
                exec(compile(block.text, block.where(), "exec"), self.namespace)
            finally:
                os.chdir(cwd)
                os.environ.clear()
                os.environ.update(env)
            self.ran += 1
            return
        if block.lang not in ("bash", "console"):
            return
        for command, expected in commands(block):
            if block.not_run:
                check_not_run(command)
                continue
            self._shell(block, command, expected)

    def _shell(self, block: Block, command: str, expected: list[str]) -> None:
        words = argv(command)
        assert words and words[0] in ("femcheck", "pytest", "mkdocs"), \
            f"{block.where()}: {command!r} is not a command the tests run; say why it is not run"
        if words[0] == "mkdocs":
            command += f" --config-file {ROOT / 'mkdocs.yml'} --site-dir {self.workdir / 'site'}"
        if words[0] == "pytest":          # the page's own test files, never the project's suite
            assert any(w.startswith("tests/") for w in words[1:]) and (self.workdir / "tests").is_dir(), \
                f"{block.where()}: {command!r} would run the project's suite"
            command = command.replace("pytest", f"{sys.executable} -m pytest -p no:cacheprovider", 1)
        r = subprocess.run(command, shell=True, cwd=self.workdir, capture_output=True, text=True,
                           executable="/bin/bash", env=self.env)
        output = r.stdout + r.stderr
        want_code = 2 if any(e.startswith("femcheck: error:") for e in expected) else 0
        assert r.returncode == want_code, \
            f"{block.where()}: {command!r} exited {r.returncode} (expected {want_code})\n{output[-3000:]}"
        flat = " ".join(output.split())
        for e in expected:
            if e in ("...", "…"):
                continue
            e = e.removesuffix("...").rstrip()      # "PASS: ... in ..." shows the start of a line that goes on
            assert " ".join(e.split()) in flat, f"{block.where()}: {command!r}: {e!r} not in its output\n{output[-3000:]}"
        self.ran += 1
