"""Stored indent-population risk maps (seed 004 §4.3, Figs 4.10-4.11) with provenance keyed on inputs and code.

The map I_D/I_S over indent diameter Phi and slope D/Phi, dry and lubricated, costs 15 transient EHL runs and
15 dry BEM passes (13 min on 129^2 nodes, two refused cells 11 min each on 257^2), so no suite computes it:
``benchmarks/life_population.py --store`` writes it once under ``references/indent_population/`` and the report
shows it (:mod:`femcheck.report.population`) only while it is current. Current means: its key, recomputed from
the inputs stored with it and today's code, equals the stored key. The code is the source (docstrings and
comments dropped, :func:`femcheck.provenance.code_text`) of the benchmark scripts that computed it and of every
femcheck module they import, transitively (:func:`femcheck.provenance.code_digest`, numerical libraries'
versions included). Change a statement in any of them and the stored map is reported stale, never shown as
current.

A stored entry is one JSON file ``life_population-<key16>.json``: ``{"provenance": {"key", "inputs",
"scripts", "created", "machine"}, "result": {...}}``; ``result`` holds the maps (``maps[name][i][j]`` at
``phis[i]`` x ``slopes[j]``, null where a cell was refused), the population numbers and the fatigue limit.
"""
from __future__ import annotations

import datetime
import hashlib
import json
import os
import platform
import tempfile
from pathlib import Path
from typing import Any

from . import provenance
from .references import reference_dir

KIND = "indent_population"
NAME = "life_population"
# the scripts that compute the map, relative to the source checkout (life_population.py runs ehl_life.py's code)
SCRIPTS = ("benchmarks/life_population.py", "benchmarks/ehl_life.py")


def checkout() -> Path:
    """The source checkout holding ``benchmarks/`` (absent in an installed package)."""
    return Path(__file__).resolve().parent.parent


def script_digest(scripts: tuple[str, ...] = SCRIPTS, root: Path | None = None) -> str:
    """sha256 over the scripts' code text and :func:`femcheck.provenance.code_digest` of the femcheck modules
    they import; FileNotFoundError when a script is missing."""
    root = checkout() if root is None else Path(root)
    modules = provenance.module_files()
    h = hashlib.sha256()
    imported: set[str] = set()
    for rel in scripts:
        path = root / rel
        h.update(rel.encode())
        h.update(provenance.code_text(path.read_text(encoding="utf-8")).encode())
        imported |= provenance._imports(f"benchmarks.{path.stem}", path, modules)
    h.update(provenance.code_digest(sorted(imported)).encode())
    return h.hexdigest()


def key(inputs: dict[str, Any], scripts: tuple[str, ...] = SCRIPTS, root: Path | None = None) -> str:
    """Content key of a population map: its inputs (operating point, grid, map axes, life constants, the
    population) and :func:`script_digest`."""
    blob = json.dumps({"kind": KIND, "inputs": inputs, "code": script_digest(scripts, root)}, sort_keys=True,
                      default=float)
    return hashlib.sha256(blob.encode()).hexdigest()[:32]


def _dir(refs: Path | None) -> Path:
    return (reference_dir() if refs is None else Path(refs)) / KIND


def store(result: dict[str, Any], inputs: dict[str, Any], refs: Path | None = None, root: Path | None = None,
          run_time_s: float | None = None) -> Path:
    """Write ``result`` under its key (temp file and rename); returns the path."""
    k = key(inputs, SCRIPTS, root)
    folder = _dir(refs)
    folder.mkdir(parents=True, exist_ok=True)
    doc = {"provenance": {"key": k, "inputs": inputs, "scripts": list(SCRIPTS),
                          "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                          "machine": {"platform": platform.platform(), "cpus": os.cpu_count()},
                          "run_time_s": run_time_s},
           "result": result}
    path = folder / f"{NAME}-{k[:16]}.json"
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".tmp")
    with os.fdopen(fd, "w") as fh:
        fh.write(json.dumps(doc, indent=1, default=float))
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
    return path


def load_current(refs: Path | None = None, root: Path | None = None) -> tuple[dict | None, str]:
    """The stored map whose key matches today's code, and a status line: ``current`` (the doc returned),
    ``stale`` (maps stored, none computed by today's code), ``missing`` (none stored) or ``unchecked`` (the
    scripts are not there to key against: an installed package)."""
    files = sorted(_dir(refs).glob(f"{NAME}-*.json"))
    if not files:
        return None, "missing"
    try:
        digest_ok = script_digest(SCRIPTS, root) is not None
    except FileNotFoundError:
        digest_ok = False
    if not digest_ok:
        return None, "unchecked"
    for path in files:
        try:
            doc = json.loads(path.read_text())
            stored = doc["provenance"]["key"]
            inputs = doc["provenance"]["inputs"]
        except (OSError, ValueError, KeyError):
            continue
        if key(inputs, SCRIPTS, root) == stored:
            return doc, "current"
    return None, "stale"
