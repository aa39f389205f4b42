"""Result cache for expensive models (FEM), keyed by a hash of everything that determines the result:
the scene kind, the model, the parameters it depends on, and the source code of the modules it runs (found from
the imports, :mod:`femcheck.provenance`) with the numerical libraries' versions.

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

from . import provenance
from .result import ModelResult, _jsonable

def cache_dir() -> Path:
    return Path(os.environ.get("FEMCHECK_CACHE", Path.home() / ".cache" / "femcheck"))


def key(kind: str, model: str, params: dict[str, Any], prefixes: tuple[str, ...], modules: tuple[str, ...]) -> str:
    """Content key of a model result: the kind, the model, the parameters under ``prefixes`` and
    :func:`femcheck.provenance.code_digest` of ``modules`` (the source of everything they import, transitively,
    and the numerical libraries' versions)."""
    relevant = {k: v for k, v in sorted(params.items()) if k.startswith(prefixes)}
    blob = json.dumps({"kind": kind, "model": model, "params": _jsonable(relevant),
                       "code": provenance.code_digest(modules)}, sort_keys=True)
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
                       # quantities stay floats: an infinite fatigue life must come back as inf, not None
                       "quantities": {k: float(v) for k, v in res.quantities.items()}, "stats": _jsonable(res.stats)})
    fd, tmp = tempfile.mkstemp(dir=d, suffix=".npz.tmp")
    with os.fdopen(fd, "wb") as fh:
        np.savez_compressed(fh, __meta__=np.array(meta), **res.fields)
    os.replace(tmp, d / f"{k}.npz")
