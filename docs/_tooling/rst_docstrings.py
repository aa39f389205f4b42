"""Griffe extension: render femcheck's plain-text docstrings faithfully in Markdown.

femcheck's docstrings are written as plain text with reStructuredText habits: ``double backticks`` for code
(Markdown reads them as code too), ``:func:`name``` roles for cross-references, and equations such as
``[(2 - nu1)/G1 + (2 - nu2)/G2] [1 - (Q/(mu P))^(2/3)]`` whose square brackets Markdown would take for links.
This extension rewrites them for display only (the source files are not touched, so the stored references'
keys, which hash the source of every module a model imports, do not change):

- a role ``:func:`femcheck.runner.run``` becomes an optional cross-reference: a link where the target is
  documented on the site, plain code where it is not (no warning either way);
- square brackets outside code are escaped, so an equation never turns into a link;
- a paragraph ending in ``::`` (an rST literal block follows) ends in ``:``;
- a parenthesised tracker reference such as ``(issue N, finding M)`` is left out: it means nothing to a user.
"""
from __future__ import annotations

import html
import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:func|class|mod|meth|attr|data|obj|exc|const):`~?([^`<>]+?)`")
_TRACKER = re.compile(r"\s*\([Ii]ssue \d+[^()]*\)")   # "(issue N, finding M)": for developers, not users
_CODE = re.compile(r"(``.+?``|`[^`\n]+`)", re.S)


def _autoref(match: re.Match) -> str:
    target = match.group(1).strip()
    text = html.escape(target)
    return f'<autoref identifier="{text}" optional><code>{text}</code></autoref>'


def _escape_brackets(text: str) -> str:
    parts = _CODE.split(text)
    for i in range(0, len(parts), 2):           # even parts are outside code spans
        parts[i] = parts[i].replace("[", r"\[").replace("]", r"\]")
    return "".join(parts)


def _indented_block(lines: list[str], i: int) -> bool:
    return i < len(lines) and (lines[i].startswith("    ") or not lines[i].strip())


def render(text: str) -> str:
    """The docstring ``text`` as Markdown that shows what its author wrote."""
    out: list[str] = []
    lines = text.split("\n")
    in_block = False
    for i, line in enumerate(lines):
        if in_block:                              # indented literal block: leave verbatim
            if line.strip() and not line.startswith("    "):
                in_block = False
            else:
                out.append(line)
                continue
        if line.rstrip().endswith("::"):
            line = line.rstrip()[:-1]
            in_block = _indented_block(lines, i + 1)
        out.append(_escape_brackets(_ROLE.sub(_autoref, line)) if "`" in line or "[" in line else line)
    return _TRACKER.sub("", "\n".join(out))


class PlainDocstrings(griffe.Extension):
    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = render(obj.docstring.value)
