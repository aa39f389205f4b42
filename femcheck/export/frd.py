"""A small reader of CalculiX results: the ASCII ``.frd`` file (nodes and nodal result blocks) and the ``.dat``
file (``*NODE PRINT`` tables).

``.frd`` (CalculiX manual, "Result file format"): a node block opens with ``    2C``, its lines are
``(1X,'-1',I10,3E12.5)``, it closes with `` -3``; a result block opens with ``  100CL`` (its 4th field the
time), names itself in a `` -4  NAME  ncomp`` line, lists components in `` -5`` lines, then holds
``(1X,'-1',I10,6E12.5)`` lines (`` -2`` continuation lines past 6 values) and closes with `` -3``. Values carry
6 significant digits (5 after the point: relative resolution 1e-5).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np


@dataclass
class Block:
    """One nodal result block: ``name`` (DISP, STRESS, CONTACT, ...), ``time`` (s of the analysis), component
    names, node ids (N,) and values (N, ncomp)."""

    name: str
    time: float
    components: list[str]
    nodes: np.ndarray
    values: np.ndarray

    def column(self, component: str) -> np.ndarray:
        return self.values[:, self.components.index(component)]


@dataclass
class Frd:
    nodes: np.ndarray                 # node ids (N,)
    coords: np.ndarray                # (N, 3) m
    blocks: list[Block] = field(default_factory=list)

    @cached_property
    def _row(self) -> dict[int, int]:
        return {int(n): i for i, n in enumerate(self.nodes)}

    def coords_of(self, nodes) -> np.ndarray:
        """(3, n) undeformed coordinates (m) of the node ids ``nodes``."""
        return self.coords[[self._row[int(n)] for n in nodes]].T

    def last(self, name: str) -> Block:
        """The last block called ``name`` (the end of the last step)."""
        for b in reversed(self.blocks):
            if b.name == name:
                return b
        raise KeyError(f"no {name} block in the .frd file (was it requested?)")


def _values(line: str, start: int = 13, width: int = 12) -> list[float]:
    rest = line[start:].rstrip("\n")
    return [float(rest[i:i + width]) for i in range(0, len(rest) - width + 1, width)]


def read_frd(path: Path) -> Frd:
    lines = Path(path).read_text().splitlines()
    i, n = 0, len(lines)
    node_ids: list[int] = []
    coords: list[list[float]] = []
    blocks: list[Block] = []
    time = float("nan")
    while i < n:
        line = lines[i]
        if line.startswith("    2C"):
            i += 1
            while not lines[i].startswith(" -3"):
                node_ids.append(int(lines[i][3:13]))
                coords.append(_values(lines[i]))
                i += 1
        elif line.startswith("  100C"):
            time = float(line[12:24])
            i += 1
            name = lines[i][5:13].strip()
            comps, ids, vals = [], [], []
            i += 1
            while lines[i].startswith(" -5"):
                comps.append(lines[i][5:13].strip())
                i += 1
            while not lines[i].startswith(" -3"):
                if lines[i].startswith(" -1"):
                    ids.append(int(lines[i][3:13]))
                    vals.append(_values(lines[i]))
                elif lines[i].startswith(" -2"):
                    vals[-1] += _values(lines[i])
                i += 1
            comps = [c for c in comps if c != "ALL"]
            blocks.append(Block(name, time, comps, np.array(ids, dtype=np.int64),
                                np.array(vals, dtype=float).reshape(len(ids), -1)[:, :len(comps)]))
        i += 1
    return Frd(np.array(node_ids, dtype=np.int64), np.array(coords, dtype=float).reshape(-1, 3), blocks)


_TABLE = re.compile(r"^\s*(displacements|total force|forces)\b.*for set (\S+) and time\s+(\S+)")


def read_dat(path: Path) -> dict[tuple[str, str], np.ndarray]:
    """``*NODE PRINT`` tables of a ``.dat`` file: {(quantity, set): rows} with quantity 'displacements',
    'forces' or 'total force' and rows (k, 1 + ncomp) = node id and values (the total's row has no id: its
    first column is NaN); the last table of each kind wins (the end of the last step)."""
    out: dict[tuple[str, str], np.ndarray] = {}
    lines = Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        m = _TABLE.match(lines[i])
        i += 1
        if not m:
            continue
        rows = []
        while i < len(lines) and not lines[i].strip():
            i += 1
        while i < len(lines) and lines[i].strip():
            f = [float(v) for v in lines[i].split()]
            rows.append(f if m.group(1) != "total force" else [float("nan"), *f])
            i += 1
        out[(m.group(1), m.group(2))] = np.array(rows)
    return out
