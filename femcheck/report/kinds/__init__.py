"""Per-kind report sections: tables and figures a problem kind needs beyond the generic ones (a bearing's
Table 2, roller-load polar plots, film maps...).

A kind ``K`` adds them by defining ``femcheck/report/kinds/K.py`` with

    def section(run: RunResult, outdir: Path, prefix: str) -> KindSection

which reads the run's fields and stats (it never runs a model) and writes its figures into ``outdir`` with file
names starting with ``prefix``. :func:`section` returns an empty section for kinds without such a module.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from importlib import import_module
from importlib.util import find_spec
from pathlib import Path

from ...result import RunResult


@dataclass
class Table:
    """A table in the report: ``header`` labels, ``rows`` of cells (numbers are formatted by the template),
    ``note`` a sentence under it (sources, units, what a blank cell means)."""

    title: str
    header: list[str]
    rows: list[list]
    note: str = ""


@dataclass
class Figure:
    file: str                  # name inside the report directory
    caption: str               # what it shows: which contact, which level, units


@dataclass
class KindSection:
    tables: list[Table] = field(default_factory=list)
    figures: list[Figure] = field(default_factory=list)


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    name = f"{__name__}.{run.kind}"
    if not run.kind or find_spec(name) is None:
        return KindSection()
    return import_module(name).section(run, outdir, prefix)
