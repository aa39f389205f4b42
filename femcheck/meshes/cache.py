"""Content-keyed mesh cache: ``<cache>/meshes/<kind>-<key>.<ext>``.

A mesh is determined by its spec (a dataclass of lengths and counts), by the builder's source and everything it
imports (:func:`femcheck.provenance.code_digest`) and by the Gmsh version (in the same digest), so a change
to a size field or a meshing algorithm gives a new key and a fresh mesh. Inside :func:`rebuilding` (``--rebuild``)
every mesh is built again and the cache entry replaced. Entries are written to a temporary file and renamed.
"""
from __future__ import annotations

import contextlib
import contextvars
import hashlib
import json
import os
import tempfile
from dataclasses import asdict
from pathlib import Path
from typing import Callable, Iterator, TypeVar

from .. import provenance
from ..cache import cache_dir

M = TypeVar("M")
_REBUILD: contextvars.ContextVar[bool] = contextvars.ContextVar("femcheck_rebuild_meshes", default=False)


def mesh_cache_dir() -> Path:
    return cache_dir() / "meshes"


@contextlib.contextmanager
def rebuilding(active: bool = True) -> Iterator[None]:
    """Within this block every cached mesh is built again (and stored anew)."""
    token = _REBUILD.set(active)
    try:
        yield
    finally:
        _REBUILD.reset(token)


def mesh_key(kind: str, spec, builder_module: str) -> str:
    blob = json.dumps({"kind": kind, "spec": asdict(spec), "code": provenance.code_digest((builder_module,))},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def cached(kind: str, spec, builder_module: str, suffix: str, build: Callable[[], M],
           read: Callable[[Path], M], write: Callable[[M, str], None]) -> M:
    """``build()`` once per (kind, spec, builder code, Gmsh version); later calls ``read`` the stored copy.
    A damaged entry is built again."""
    path = mesh_cache_dir() / f"{kind}-{mesh_key(kind, spec, builder_module)}{suffix}"
    if path.is_file() and not _REBUILD.get():
        try:
            return read(path)
        except (OSError, KeyError, ValueError):
            pass
    mesh = build()
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=suffix)
    os.close(fd)
    write(mesh, tmp)
    os.replace(tmp, path)
    return mesh
