"""MkDocs hooks: tables that are generated from the code at build time, so the pages cannot drift from it.

Markers in a page (HTML comments, invisible when the page is read as plain Markdown):

- ``<!-- keys: KIND -->``: the kind's scene keys (from ``femcheck.problems.KIND.SCHEMA`` and ``DEFAULTS``):
  key, unit, meaning, allowed values, default.
- ``<!-- scenes -->``: the built-in scenes (name, kind, suites, description) from ``femcheck/scenes/*.toml``.
- ``<!-- include: PATH -->``: a Markdown file of the repository (a benchmark's result table) without its title,
  its other headings moved two levels down so that they sit under the page's own.
"""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_ISSUE = re.compile(r"\b[Ii]ssue \d+:? *")   # tracker numbers in a scene description are not for users
_MARKER = re.compile(r"<!-- (keys|include|scenes)(?:: *([a-z_][\w./-]*))? *-->")   # lower case: KIND is prose


def _cell(value) -> str:
    if isinstance(value, bool):
        text = str(value).lower()
    elif isinstance(value, float):
        text = f"{value:g}"
    elif isinstance(value, (list, tuple)):
        text = ", ".join(_cell(v) for v in value) if value else "(empty)"
    else:
        text = str(value)
    return text.replace("|", r"\|").replace("\n", " ")


def keys_table(kind: str) -> str:
    """The scene keys of ``kind`` as a Markdown table."""
    from femcheck.problems import problem

    prob = problem(kind)
    defaults = getattr(prob, "DEFAULTS", {})
    required = set(getattr(prob, "REQUIRED", ()))
    rows = ["| key | unit | meaning | allowed | default |", "|---|---|---|---|---|"]
    for name, key in prob.SCHEMA.items():
        default = "required" if name in required else (_cell(defaults[name]) if name in defaults else "")
        rows.append(f"| `{name}` | {_cell(key.unit)} | {_cell(key.doc)} | {_cell(key.allowed())} | {default} |")
    return "\n".join(rows)


def scenes_table() -> str:
    rows = ["| scene | kind | suites | description |", "|---|---|---|---|"]
    for path in sorted((ROOT / "femcheck" / "scenes").glob("*.toml")):
        data = tomllib.loads(path.read_text())
        rows.append(f"| `{path.stem}` | [{data['kind']}](kinds/{_kind_page(data['kind'])}.md) | "
                    f"{_cell(data.get('tags', []))} | {_cell(_ISSUE.sub('', data.get('description', '')))} |")
    return "\n".join(rows)


def _kind_page(kind: str) -> str:
    return "tangential" if kind in ("line_tangential", "point_tangential") else kind


def include(path: str) -> str:
    """The file's text without its title (the page gives its own heading), lower headings demoted by two."""
    text = re.sub(r"\A# [^\n]*\n", "", (ROOT / path).read_text())
    return re.sub(r"^(#+) ", lambda m: "#" * min(len(m.group(1)) + 2, 6) + " ", text, flags=re.M)


def expand(markdown: str, page_path: str) -> str:
    """``markdown`` with every marker replaced; ``page_path`` (relative to docs/) fixes relative links."""
    def repl(m: re.Match) -> str:
        what, arg = m.group(1), m.group(2)
        if what == "keys":
            return keys_table(arg)
        if what == "include":
            return include(arg)
        table = scenes_table()
        depth = page_path.count("/")
        return table.replace("](kinds/", "](" + "../" * depth + "kinds/")
    return _MARKER.sub(repl, markdown)


def on_page_markdown(markdown, page, config, files, **kwargs):
    return expand(markdown, page.file.src_uri)
