"""Every band in a built-in scene file says where it comes from (project rule; docs/user-guide/verdicts.md).

A ``[tolerances.<model>]`` table (``[tolerances.exceptions]`` aside: its values are the reasons) needs either a
comment block directly above its header (consecutive ``#`` lines ending on the line before it; a blank line in
between detaches the block) or an inline comment on every key line. Whether the comment names a sound source is a
matter of review; this test only makes a silent table fail. No comment in a scene file may cite an issue number
(``issue 12``): the scene must carry the basis itself, not a pointer into a tracker.
"""
from __future__ import annotations

import re

import pytest

from femcheck.scene import builtin_scene_files

HEADER = re.compile(r"^\s*\[\s*tolerances\s*\.\s*(?P<model>\"[^\"]*\"|'[^']*'|[A-Za-z0-9_@-]+)\s*\]\s*(#.*)?$")
TABLE = re.compile(r"^\s*\[")
ISSUE = re.compile(r"issue\s*\d", re.IGNORECASE)


def _split(line: str, in_string: str | None) -> tuple[str, str | None, str | None]:
    """Split one physical line into (code, comment or None, open multi-line string delimiter or None), given the
    multi-line string (``\"\"\"`` or ``'''``) open at its start. Quotes of basic and literal strings are honoured."""
    i, code = 0, []
    while i < len(line):
        if in_string:
            end = line.find(in_string, i)
            while in_string == '"""' and end > 0 and _escaped(line, end):
                end = line.find(in_string, end + 1)
            if end < 0:
                return "".join(code), None, in_string
            i, in_string = end + 3, None
            continue
        ch = line[i]
        if ch == "#":
            return "".join(code), line[i:], None
        if line.startswith('"""', i) or line.startswith("'''", i):
            in_string = line[i:i + 3]
            code.append(in_string)
            i += 3
            continue
        if ch in "\"'":
            j = i + 1
            while j < len(line) and (line[j] != ch or (ch == '"' and _escaped(line, j))):
                j += 1
            code.append(line[i:j + 1])
            i = j + 1
            continue
        code.append(ch)
        i += 1
    return "".join(code), None, None


def _escaped(line: str, pos: int) -> bool:
    n = 0
    while pos - 1 - n >= 0 and line[pos - 1 - n] == "\\":
        n += 1
    return n % 2 == 1


def _lines(text: str) -> list[tuple[str, str | None, bool]]:
    """(code, comment, starts inside a multi-line string) for every line of ``text``."""
    out, open_ = [], None
    for line in text.splitlines():
        inside = open_ is not None
        code, comment, open_ = _split(line, open_)
        out.append((code, comment, inside))
    return out


def uncommented_tables(text: str) -> list[str]:
    """The ``[tolerances.<model>]`` tables of a scene's TOML text (exceptions aside) that have neither a comment
    block directly above their header nor an inline comment on every key line."""
    lines = _lines(text)
    bad = []
    for i, (code, _comment, inside) in enumerate(lines):
        m = None if inside else HEADER.match(code)
        if m is None:
            continue
        model = m.group("model").strip("\"'")
        if model == "exceptions":
            continue
        above = lines[i - 1] if i > 0 else None
        if above is not None and not above[2] and above[0].strip() == "" and above[1] is not None:
            continue                                         # a comment line right above the header
        keys = []
        for code2, comment2, inside2 in lines[i + 1:]:
            if not inside2 and TABLE.match(code2):
                break
            if inside2 or code2.strip() == "":
                continue                                     # a string's continuation, blank or comment-only line
            keys.append(comment2 is not None)
        if not keys or not all(keys):
            bad.append(model)
    return bad


def issue_citations(text: str) -> list[str]:
    """The comments of a scene's TOML text that cite an issue number."""
    return [c for _code, c, _inside in _lines(text) if c is not None and ISSUE.search(c)]


SCENES = builtin_scene_files()


def test_checker_flags_an_uncommented_table():
    text = '''name = "x"
# the bem's band: a resolution bound
[tolerances.bem]
p_max = 0.01

[tolerances.fem]
p_max = 0.01
half_width = 0.01   # one element

# detached by the blank line below

[tolerances."fem@finest"]
p_max = 0.03

[tolerances.exceptions]
"fem.p_max" = """a reason # not a comment
[tolerances.inside_a_string]
p_max = 1"""
'''
    assert uncommented_tables(text) == ["fem", "fem@finest"]


def test_checker_accepts_block_or_inline_comments():
    text = '''# two lines of source,
# directly above
[tolerances.bem]
p_max = 0.01

[tolerances.fem]
p_max = 0.01        # Hertz-edge bound
"half_width" = 0.01 # one element: "a" # quoted hashes are not comments
'''
    assert uncommented_tables(text) == []
    assert uncommented_tables('[tolerances.bem]\nname = "a # b"\n') == ["bem"]   # a '#' inside a string
    assert uncommented_tables("[tolerances.bem]\n") == ["bem"]                     # no keys, no comment


def test_checker_finds_issue_citations():
    text = 'p_max = 0.01   # see Issue 12\n# issue#3 is not a number\n# (issue7)\nx = "issue 4"\n'
    assert issue_citations(text) == ["# see Issue 12", "# (issue7)"]
    assert issue_citations("# measured on this scene's grid\n") == []


def test_builtin_scenes_exist():
    assert len(SCENES) >= 20


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_band_states_its_source(name):
    text = SCENES[name].read_text()
    assert uncommented_tables(text) == [], f"{name}: [tolerances.<model>] tables without a comment on their source"
    assert issue_citations(text) == [], f"{name}: comments citing an issue number"
