"""Stored reference solutions (certified FEM results) with provenance, committed under ``references/``.

A reference is looked up by the same content key as the cache (scene kind, model, the parameters the model
depends on, and the digest of the source it runs), so a stored reference is used exactly when it would be
reproduced: change an input or the FEM code and the key changes, the suite solves again (and, when allowed,
stores the new reference next to the old one). Each entry is a JSON file (quantities, stats, provenance) and an
``.npz`` of its fields, small enough to commit.

Location: ``$FEMCHECK_REFERENCES`` or the ``references/`` directory of the source checkout.
"""
from __future__ import annotations

import datetime
import json
import os
import platform
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from .result import ModelResult, _jsonable


def reference_dir() -> Path:
    env = os.environ.get("FEMCHECK_REFERENCES")
    return Path(env) if env else Path(__file__).resolve().parent.parent / "references"


def _paths(kind: str, model: str, key: str, root: Path | None = None) -> tuple[Path, Path]:
    base = (reference_dir() if root is None else Path(root)) / kind / f"{model}-{key[:16]}"
    return base.with_suffix(".json"), base.with_suffix(".npz")


def inputs_dir(kind: str, model: str, key: str, root: Path | None = None) -> Path:
    """The folder of the recorded coarse-level inputs (meshes, derived values; :mod:`femcheck.replay`) of the
    reference ``key``: ``<kind>/<model>-<key16>.inputs`` beside its JSON."""
    return _paths(kind, model, key, root)[0].with_suffix(".inputs")


def load(kind: str, model: str, key: str, root: Path | None = None) -> ModelResult | None:
    """The stored reference for ``key`` under ``root`` (default :func:`reference_dir`), or None."""
    meta_path, field_path = _paths(kind, model, key, root)
    if not meta_path.is_file():
        return None
    try:
        meta = json.loads(meta_path.read_text())
        if meta["provenance"]["key"] != key:
            return None
        fields = {}
        if field_path.is_file():
            with np.load(field_path, allow_pickle=False) as data:
                fields = {name: data[name] for name in data.files}
    except (OSError, ValueError, KeyError):
        return None
    stats = {**meta["stats"], "reference": meta["provenance"]}
    return ModelResult(meta["model"], "ok", meta["time_s"], meta["quantities"], stats, fields, cached=True)


def store(kind: str, model: str, key: str, res: ModelResult, scene_name: str, params: dict[str, Any],
          root: Path | None = None) -> Path | None:
    """Write ``res`` as the reference for ``key`` under ``root`` (default :func:`reference_dir`: the built-in
    scenes' references; a user's scene stores only where the user says); returns the JSON path, or None when
    the directory is not writable (an installed package without a checkout)."""
    from . import __version__

    meta_path, field_path = _paths(kind, model, key, root)
    try:
        meta_path.parent.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    if not os.access(meta_path.parent, os.W_OK):
        return None
    provenance = {"key": key, "scene": scene_name, "kind": kind, "model": model, "params": _jsonable(params),
                  "femcheck_version": __version__, "created": datetime.datetime.now(datetime.timezone.utc)
                  .isoformat(timespec="seconds"), "machine": {"platform": platform.platform(),
                                                              "cpus": os.cpu_count()},
                  "run_time_s": res.time_s}
    meta = {"model": res.model, "time_s": res.time_s, "quantities": {k: float(v) for k, v in res.quantities.items()},
            "stats": _jsonable(res.stats), "provenance": provenance}
    for path, write in ((field_path, lambda fh: np.savez_compressed(fh, **res.fields)),
                        (meta_path, lambda fh: fh.write(json.dumps(meta, indent=1).encode()))):
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        os.chmod(tmp, 0o644)                   # mkstemp makes it private; a reference is meant to be shared
        os.replace(tmp, path)
    return meta_path
