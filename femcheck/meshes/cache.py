"""Content-keyed mesh cache: ``<cache>/meshes/<kind>-<key>.<ext>``.

A mesh is determined by its spec (a dataclass of lengths and counts), by the builder's source and everything it
imports (:func:`femcheck.provenance.code_digest`) and by the Gmsh version (in the same digest), so a change
to a size field or a meshing algorithm gives a new key and a fresh mesh. Inside :func:`rebuilding` (``--rebuild``)
every mesh is built again and the cache entry replaced. Entries are written to a temporary file and renamed.

Every mesh a model uses passes through :func:`cached` (builders without a reader of their own through
:func:`cached_builder`), which is where a stored reference's coarse-level meshes are recorded and replayed
(:mod:`femcheck.replay`): Gmsh's output for one spec depends on the CPU, so a reference is re-solved on the
meshes it was computed on.
"""
from __future__ import annotations

import contextlib
import contextvars
import functools
import hashlib
import importlib
import inspect
import json
import os
import tempfile
from dataclasses import asdict, fields, is_dataclass
from pathlib import Path
from typing import Any, Callable, Iterator, TypeVar

import numpy as np

from .. import provenance, replay
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


def _spec_dict(spec) -> dict:
    return asdict(spec) if is_dataclass(spec) else dict(spec)


def mesh_key(kind: str, spec, builder_module: str) -> str:
    blob = json.dumps({"kind": kind, "spec": _spec_dict(spec), "code": provenance.code_digest((builder_module,))},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def cached(kind: str, spec, builder_module: str, suffix: str, build: Callable[[], M],
           read: Callable[[Path], M], write: Callable[[M, str], None]) -> M:
    """``build()`` once per (kind, spec, builder code, Gmsh version); later calls ``read`` the stored copy.
    ``spec``: a dataclass or a dict of JSON values. A damaged entry is built again. While a reference's inputs
    are replayed (:func:`femcheck.replay.replaying`) the recorded mesh of the same kind and spec is read instead;
    while they are recorded, the file used is noted."""
    spec_dict = _spec_dict(spec)
    if (stored := replay.recorded_mesh(kind, spec_dict)) is not None:
        return read(stored)
    path = mesh_cache_dir() / f"{kind}-{mesh_key(kind, spec_dict, builder_module)}{suffix}"
    if path.is_file() and not _REBUILD.get():
        try:
            mesh = read(path)
            replay.mesh_used(kind, spec_dict, path)
            return mesh
        except (OSError, KeyError, ValueError):
            pass
    mesh = build()
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=suffix)
    os.close(fd)
    write(mesh, tmp)
    os.replace(tmp, path)
    replay.mesh_used(kind, spec_dict, path)
    return mesh


# Generic storage of a builder's result: a dataclass whose fields are arrays, numbers, strings, None, tuples of
# them, dicts of arrays, or nested dataclasses (TriMesh inside LayeredTriMesh, BlockSpec inside TetMesh).

def _pack(obj: Any, prefix: str, arrays: dict[str, np.ndarray]) -> Any:
    if is_dataclass(obj):
        return {"__class__": f"{type(obj).__module__}:{type(obj).__qualname__}",
                **{f.name: _pack(getattr(obj, f.name), f"{prefix}{f.name}.", arrays) for f in fields(obj)}}
    if isinstance(obj, np.ndarray):
        arrays[prefix] = obj
        return {"__array__": prefix}
    if isinstance(obj, dict):
        return {"__dict__": {k: _pack(v, f"{prefix}{k}.", arrays) for k, v in obj.items()}}
    if isinstance(obj, (list, tuple)):
        return {"__tuple__": [_pack(v, f"{prefix}{i}.", arrays) for i, v in enumerate(obj)]}
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def _unpack(meta: Any, arrays) -> Any:
    if not isinstance(meta, dict):
        return meta
    if "__array__" in meta:
        return arrays[meta["__array__"]]
    if "__dict__" in meta:
        return {k: _unpack(v, arrays) for k, v in meta["__dict__"].items()}
    if "__tuple__" in meta:
        return tuple(_unpack(v, arrays) for v in meta["__tuple__"])
    module, _, name = meta["__class__"].partition(":")
    cls = getattr(importlib.import_module(module), name)
    return cls(**{k: _unpack(v, arrays) for k, v in meta.items() if k != "__class__"})


def _write_npz(obj: Any, path: str) -> None:
    arrays: dict[str, np.ndarray] = {}
    meta = _pack(obj, "", arrays)
    with open(path, "wb") as fh:
        np.savez_compressed(fh, __meta__=np.array(json.dumps(meta)), **arrays)


def _read_npz(path: Path) -> Any:
    with np.load(path, allow_pickle=False) as z:
        meta = json.loads(str(z["__meta__"]))
        arrays = {name: z[name] for name in z.files if name != "__meta__"}
    return _unpack(meta, arrays)


def _argument(value: Any) -> Any:
    if is_dataclass(value):
        return asdict(value)
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def cached_builder(kind: str) -> Callable[[Callable[..., M]], Callable[..., M]]:
    """Decorate a Gmsh builder so that its meshes go through :func:`cached` (kind ``kind``, spec = its bound
    arguments, stored as ``.npz``), like the builders that have a reader of their own."""
    def decorate(build: Callable[..., M]) -> Callable[..., M]:
        signature = inspect.signature(build)

        @functools.wraps(build)
        def wrapper(*args, **kwargs) -> M:
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            spec = {k: _argument(v) for k, v in bound.arguments.items()}
            return cached(kind, spec, build.__module__, ".npz", lambda: build(*args, **kwargs), _read_npz, _write_npz)
        return wrapper
    return decorate
