"""Result cache for expensive models (FEM), keyed by a hash of everything that determines the result:
the scene kind, the model, the parameters it depends on, and the source code of the modules it runs.

Location: ``$FEMCHECK_CACHE`` or ``~/.cache/femcheck``. Entries are single ``.npz`` files written atomically.
"""
from __future__ import annotations

import hashlib
import json
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from .result import ModelResult, _jsonable

PACKAGE = Path(__file__).parent


def cache_dir() -> Path:
    return Path(os.environ.get("FEMCHECK_CACHE", Path.home() / ".cache" / "femcheck"))


def code_digest(paths: tuple[str, ...]) -> str:
    """Hash of the package source files (relative to the package; directories mean their *.py files)."""
    h = hashlib.sha256()
    for rel in sorted(paths):
        p = PACKAGE / rel
        files = sorted(p.rglob("*.py")) if p.is_dir() else [p]
        for f in files:
            h.update(str(f.relative_to(PACKAGE)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()


def key(kind: str, model: str, params: dict[str, Any], prefixes: tuple[str, ...], code: tuple[str, ...]) -> str:
    relevant = {k: v for k, v in sorted(params.items()) if k.startswith(prefixes)}
    blob = json.dumps({"kind": kind, "model": model, "params": _jsonable(relevant), "code": code_digest(code)},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:32]


def load(k: str) -> ModelResult | None:
    path = cache_dir() / f"{k}.npz"
    if not path.is_file():
        return None
    try:
        with np.load(path, allow_pickle=False) as data:
            meta = json.loads(str(data["__meta__"]))
            fields = {name: data[name] for name in data.files if name != "__meta__"}
    except (OSError, ValueError, KeyError):
        return None   # a damaged entry is recomputed
    return ModelResult(meta["model"], meta["status"], meta["time_s"], meta["quantities"], meta["stats"], fields,
                       cached=True)


def store(k: str, res: ModelResult) -> None:
    d = cache_dir()
    d.mkdir(parents=True, exist_ok=True)
    meta = json.dumps({"model": res.model, "status": res.status, "time_s": res.time_s,
                       "quantities": _jsonable(res.quantities), "stats": _jsonable(res.stats)})
    fd, tmp = tempfile.mkstemp(dir=d, suffix=".npz.tmp")
    with os.fdopen(fd, "wb") as fh:
        np.savez_compressed(fh, __meta__=np.array(meta), **res.fields)
    os.replace(tmp, d / f"{k}.npz")
