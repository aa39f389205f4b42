"""Report section of the indent_contact kind: the fatigue-life output (:mod:`femcheck.report.life`), when a model has it,
and then the stored risk map of an indent population (:mod:`femcheck.report.population`: seed 004 Figs 4.10-4.11,
shown while it is current for today's code)."""
from __future__ import annotations

from pathlib import Path

from ...result import RunResult
from .. import life, population
from . import KindSection


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    sec = life.section(run, outdir, prefix)
    if sec.tables:
        pop = population.section(outdir, prefix)
        sec.tables += pop.tables
        sec.figures += pop.figures
    return sec
