"""Report section of the roller_contact kind: the fatigue-life output (:mod:`femcheck.report.life`), when a model has it."""
from __future__ import annotations

from pathlib import Path

from ...result import RunResult
from .. import life
from . import KindSection


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    return life.section(run, outdir, prefix)
