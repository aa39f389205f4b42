"""A reader of the keyword decks this package writes (the Abaqus/CalculiX ``.inp`` language): keyword lines
``*NAME, PARAM=VALUE, ...``, data lines of comma-separated fields, ``**`` comments. Enough to check a deck
against the format (:func:`check`) and to find its node sets again when reading results."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .elements import NODES_PER_ELEMENT


@dataclass
class Card:
    keyword: str                 # upper case, without '*'
    params: dict[str, str]       # upper-case names; a flag without '=' maps to ''
    data: list[list[str]] = field(default_factory=list)
    line: int = 0                # 1-based line number of the keyword


def parse(text: str) -> list[Card]:
    cards: list[Card] = []
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            parts = [p.strip() for p in line[1:].split(",")]
            params = {}
            for p in parts[1:]:
                k, _, v = p.partition("=")
                params[k.strip().upper()] = v.strip()
            cards.append(Card(parts[0].upper(), params, line=n))
        elif cards:
            cards[-1].data.append([f.strip() for f in line.rstrip(",").split(",")])
        else:
            raise ValueError(f"line {n}: data before the first keyword")
    return cards


def node_sets(cards: list[Card]) -> dict[str, np.ndarray]:
    """Node sets (deck ids) by upper-case name."""
    out: dict[str, list[int]] = {}
    for c in cards:
        if c.keyword == "NSET":
            out.setdefault(c.params["NSET"].upper(), []).extend(int(v) for row in c.data for v in row if v)
        elif c.keyword == "NODE" and "NSET" in c.params:
            out.setdefault(c.params["NSET"].upper(), []).extend(int(row[0]) for row in c.data)
    return {k: np.array(v, dtype=np.int64) for k, v in out.items()}


def element_types(cards: list[Card]) -> dict[str, str]:
    """{ELSET: element type} of the *ELEMENT cards."""
    return {c.params.get("ELSET", "").upper(): c.params["TYPE"].upper() for c in cards if c.keyword == "ELEMENT"}


# keyword -> allowed field counts of each data line (None: any count up to 16; a keyword absent here is unknown)
HEADING_TEXT = -1
_FIELDS = {
    "HEADING": HEADING_TEXT, "NODE": {3, 4}, "ELEMENT": None, "NSET": None, "ELSET": None, "SURFACE": {2},
    "MATERIAL": set(), "ELASTIC": {2}, "SOLID SECTION": {1}, "SPRING": {1, 2}, "MODEL CHANGE": None, "CONTROLS": None, "RIGID BODY": set(), "AMPLITUDE": None,
    "SURFACE INTERACTION": set(), "SURFACE BEHAVIOR": {1, 2, 3}, "FRICTION": {1, 2}, "EQUATION": None, "CONTACT PAIR": {2}, "STEP": set(),
    "STATIC": {1, 2, 3, 4}, "BOUNDARY": {3, 4}, "CLOAD": {3}, "END STEP": set(), "OUTPUT": set(),
    "NODE OUTPUT": None, "ELEMENT OUTPUT": None, "CONTACT OUTPUT": None, "NODE PRINT": None, "NODE FILE": None,
    "EL FILE": None, "CONTACT FILE": None,
}


def check(text: str) -> list[str]:
    """Problems of a deck against the keyword format: unknown keywords, data lines with the wrong number of
    fields (an *ELEMENT line: 1 + the type's node count; at most 16 fields a line), node and element ids
    referenced but not defined, node / element sets and surfaces referenced but not defined, and whether every
    step ends. An empty list is a deck that passes."""
    cards = parse(text)
    problems: list[str] = []
    nodes: set[int] = set()
    elems: set[int] = set()
    nsets = set(node_sets(cards))
    elsets = {c.params["ELSET"].upper() for c in cards if c.keyword in ("ELEMENT", "ELSET") and "ELSET" in c.params}
    surfaces = {c.params["NAME"].upper() for c in cards if c.keyword == "SURFACE"}
    materials = {c.params["NAME"].upper() for c in cards if c.keyword == "MATERIAL"}
    interactions = {c.params["NAME"].upper() for c in cards if c.keyword == "SURFACE INTERACTION"}
    amplitudes = {c.params["NAME"].upper() for c in cards if c.keyword == "AMPLITUDE"}
    for c in cards:
        if c.keyword == "NODE":
            nodes.update(int(r[0]) for r in c.data)
        elif c.keyword == "ELEMENT":
            elems.update(int(r[0]) for r in c.data)
    open_step = False
    for c in cards:
        where = f"line {c.line} *{c.keyword}"
        if c.keyword not in _FIELDS:
            problems.append(f"{where}: unknown keyword")
            continue
        allowed = _FIELDS[c.keyword]
        if c.keyword == "ELEMENT":
            t = c.params.get("TYPE", "").upper()
            if t not in NODES_PER_ELEMENT:
                problems.append(f"{where}: unknown element type {t!r}")
                continue
            allowed = {1 + NODES_PER_ELEMENT[t]}
            for r in c.data:
                bad = [v for v in r[1:] if int(v) not in nodes]
                if bad:
                    problems.append(f"{where}: element {r[0]} uses undefined nodes {bad[:3]}")
        if allowed != HEADING_TEXT:
            for r in c.data:
                if len(r) > 16 or (allowed is not None and len(r) not in allowed):
                    problems.append(f"{where}: a data line has {len(r)} fields ({','.join(r)[:60]})")
                    break
        refs = [("NSET", nsets), ("TIE NSET", nsets), ("ELSET", elsets), ("MATERIAL", materials), ("INTERACTION", interactions),
                ("AMPLITUDE", amplitudes)]
        for key, known in refs:
            if key in c.params and c.keyword not in ("NSET", "NODE", "ELEMENT", "ELSET") \
                    and c.params[key].upper() not in known:
                problems.append(f"{where}: {key}={c.params[key]} is not defined")
        for key in ("REF NODE", "ROT NODE"):
            if key in c.params and int(c.params[key]) not in nodes:
                problems.append(f"{where}: {key}={c.params[key]} is not a node")
        if c.keyword == "NSET":
            bad = [v for r in c.data for v in r if int(v) not in nodes]
            if bad:
                problems.append(f"{where}: undefined nodes {bad[:3]}")
        if c.keyword == "SURFACE":
            for r in c.data:
                if int(r[0]) not in elems or not r[1].upper().startswith("S"):
                    problems.append(f"{where}: bad face {r}")
                    break
        if c.keyword == "CONTACT PAIR":
            for name in c.data[0]:
                if name.upper() not in surfaces:
                    problems.append(f"{where}: surface {name} is not defined")
        if c.keyword in ("BOUNDARY", "CLOAD"):
            for r in c.data:
                target = r[0]
                if not (target.isdigit() and int(target) in nodes) and target.upper() not in nsets:
                    problems.append(f"{where}: {target} is neither a node nor a node set")
        if c.keyword == "STEP":
            if open_step:
                problems.append(f"{where}: a step opens inside a step")
            open_step = True
        if c.keyword == "END STEP":
            open_step = False
    if open_step:
        problems.append("the last step has no *END STEP")
    return problems
