"""Sources cited by author and year in reports (scene files and notes may use the project's short names for
the four source papers: "seed 000" ... "seed 004")."""
from __future__ import annotations

import re

SEEDS = {
    "000": "Blanco-Lorenzo et al. 2022",     # Frictional contact analysis in a spherical roller bearing
    "001": "Johns-Rahnejat et al. 2023",     # Contact mechanics of highly loaded counterformal finite line contacts
    "003": "Yang et al. 2016",               # Bearing boundary element method, geometrically similar rollers
    "004": "Biboulet 2008",                  # Influence of indentations on rolling bearing life (thesis)
}
_SEED = re.compile(r"\b[Ss]eed (00[0-4])('s)?(?: \(([^()]*?)\))?")
_ISSUE = r"issue \d+(?: (?:item|finding) \d+)?"


def cite(text: str) -> str:
    """``text`` with "seed 00N" replaced by the author and year of that source (an author-year already given in
    parentheses after it is kept once) and the project's issue numbers removed."""
    def seed(m: re.Match) -> str:
        who = SEEDS.get(m.group(1), f"source {m.group(1)}")
        extra = m.group(3)
        if extra and extra.startswith(who.split()[0]):
            extra = extra[len(who.split()[0]):].lstrip(" ,").replace("et al.", "").lstrip(" ,")
            extra = re.sub(r"^\d{4}\s*,?\s*", "", extra)
        return who + ("'s" if m.group(2) else "") + (f" ({extra})" if extra else "")

    text = _SEED.sub(seed, text)
    # "(issue 5: within 5 %)" -> "(within 5 %)"; "(issue 4)" -> ""; "issue 3: centre ..." -> "centre ..."
    text = re.sub(rf"\({_ISSUE}:\s*", "(", text)
    text = re.sub(rf"\s*\({_ISSUE}\)", "", text)
    return re.sub(rf"\b{_ISSUE}:?\s*", "", text)
