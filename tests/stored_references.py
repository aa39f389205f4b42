"""Test helper: run built-in scenes with their stored FE references standing in for the FE solves, whatever
their code key (tests must never re-solve a fine FE level; the gradedness and the layout of a report do not
depend on the FE code version)."""
from __future__ import annotations

import json

import pytest

from femcheck import references, runner
from femcheck.problems import problem
from femcheck.result import ModelResult, _jsonable


def stored(kind: str, model: str, params: dict) -> ModelResult | None:
    """The newest stored reference of (kind, model) computed for these parameters."""
    best = None
    for path in (references.reference_dir() / kind).glob(f"{model}-*.json"):
        meta = json.loads(path.read_text())
        if meta["model"] == model and meta["provenance"]["params"] == params:
            if best is None or meta["provenance"]["created"] > best["provenance"]["created"]:
                best = meta
    return None if best is None else references.load(kind, model, best["provenance"]["key"])


def use_stored_references(monkeypatch) -> None:
    """Make runner.run take every stored-reference model (the kind's DEPENDS with reference=True) from the
    stored files; fail the test when one is missing (a built-in scene ships its references: `femcheck run SCENE`
    stores them)."""
    plain = runner.run_model

    def run_model(scene, model, *args, **kwargs):
        dep = problem(scene.kind).DEPENDS.get(model)
        if dep and dep.get("reference"):
            rel = _jsonable({k: v for k, v in scene.params.items() if k.startswith(dep["params"])})
            res = stored(scene.kind, model, rel)
            if res is None:
                pytest.fail(f"{scene.name}: no stored {model} reference for these parameters; store it with "
                            f"`femcheck run {scene.name}`")
            return res
        return plain(scene, model, *args, **kwargs)

    monkeypatch.setattr(runner, "run_model", run_model)
