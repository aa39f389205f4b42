"""Recorded inputs of a stored reference: the meshes and the derived inputs of its coarsest level.

A stored reference (:mod:`femcheck.references`) is proved current by re-solving its coarsest level
(:mod:`femcheck.reference_check`). Two kinds of input of that level are not fixed by the code and the scene alone
but by the machine that computed them:

* **meshes**: Gmsh evaluates sizes and curved boundaries with the C library's ``exp``/``sin``/``pow``, whose
  implementation glibc picks by CPU (FMA, AVX2, AVX-512 variants), so one mesh spec can give a different mesh on
  another CPU (measured: the srb-normal ring segment with FMA/AVX2 masked in glibc, 1e-4 of its DOFs);
* **derived inputs**: numbers computed by the model before it meshes, such as a contact width from pilot solves
  that scales the mesh family, or the CECT pose the FE is solved at. numpy's transcendental functions are
  SIMD-dispatched too (AVX-512 and AVX2 results differ in the last bits), and an iterative solve amplifies such
  bits up to its own tolerance (measured: layer-line's mesh scale moved enough to change 8 of 3092 DOFs with
  numpy's AVX-512 paths disabled; the srb-rolling CECT pose moved within its equilibrium tolerance, which moves
  the FE's lateral force by 7e-4).

Within :func:`recording` every mesh a model obtains through :func:`femcheck.meshes.cache.cached` and every value
it passes through :func:`derived` is recorded; :func:`save` writes the record next to the reference. Within
:func:`replaying` the model gets the recorded meshes and values back instead, so the re-solve runs on exactly the
inputs the stored numbers came from and may be compared to round-off. A mesh is served when the code asks for a
mesh of the same kind whose spec matches the recorded one to ``SPEC_RTOL`` (a spec computed from replayed values
may still differ in its last bits); a request that matches nothing is built as usual and listed in
``Record.unmatched`` (the code asks for a mesh the reference did not use: the check reports it).
"""
from __future__ import annotations

import contextlib
import contextvars
import json
import shutil
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, TypeVar

import numpy as np

T = TypeVar("T")
SPEC_RTOL = 1e-9          # spec numbers computed from replayed inputs: round-off apart, never a different mesh
INDEX = "index.json"


@dataclass
class Record:
    """``meshes``: [{"kind", "spec", "file"}] in the order the model asked for them (``file`` relative to
    ``folder``); ``values``: derived inputs by name (JSON: numbers, lists, dicts); ``folder`` holds the mesh files
    (None while recording: the files are still in the mesh cache, ``sources``); ``used`` / ``unmatched``: what a
    replay served and which mesh requests it could not serve."""

    meshes: list[dict] = field(default_factory=list)
    values: dict[str, Any] = field(default_factory=dict)
    folder: Path | None = None
    sources: list[Path] = field(default_factory=list)
    used: set[int] = field(default_factory=set)
    unmatched: list[str] = field(default_factory=list)


_ACTIVE: contextvars.ContextVar[tuple[str, Record] | None] = contextvars.ContextVar("femcheck_replay", default=None)


@contextlib.contextmanager
def recording() -> Iterator[Record]:
    """Record the meshes and derived inputs of everything run inside the block."""
    rec = Record()
    token = _ACTIVE.set(("record", rec))
    try:
        yield rec
    finally:
        _ACTIVE.reset(token)


@contextlib.contextmanager
def replaying(rec: Record) -> Iterator[Record]:
    """Serve the recorded meshes and derived inputs of ``rec`` to everything run inside the block."""
    rec.used, rec.unmatched = set(), []
    token = _ACTIVE.set(("replay", rec))
    try:
        yield rec
    finally:
        _ACTIVE.reset(token)


def derived(name: str, compute: Callable[[], T]) -> T:
    """A model input that the model computes itself (``compute()``, e.g. from pilot solves) and that fixes what
    follows (mesh scale, pose): recorded under ``name`` while recording, returned from the record (without calling
    ``compute``) while replaying. The value must be JSON (numbers, lists, dicts of them); it is returned as JSON
    gives it back in every mode, so the caller sees the same types whether it was computed or replayed."""
    active = _ACTIVE.get()
    if active is not None and active[0] == "replay":
        if name in active[1].values:
            return active[1].values[name]
        active[1].unmatched.append(f"value {name}")
    value = json.loads(json.dumps(compute()))    # the same types whether computed or replayed
    if active is not None and active[0] == "record":
        active[1].values[name] = value
    return value


def _close(a: Any, b: Any) -> bool:
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) or not isinstance(b, (int, float)):
        return a == b
    return abs(a - b) <= SPEC_RTOL * max(abs(a), abs(b))


def recorded_mesh(kind: str, spec: dict) -> Path | None:
    """While replaying: the file of the first unused recorded mesh of ``kind`` whose spec matches ``spec`` (None
    when none does, or when not replaying)."""
    active = _ACTIVE.get()
    if active is None or active[0] != "replay":
        return None
    rec = active[1]
    for i, m in enumerate(rec.meshes):
        if i not in rec.used and m["kind"] == kind and _close(m["spec"], spec):
            rec.used.add(i)
            return rec.folder / m["file"]
    rec.unmatched.append(f"mesh {kind}")
    return None


def mesh_used(kind: str, spec: dict, path: Path) -> None:
    """While recording: note that the model used the mesh stored at ``path`` (a mesh-cache file)."""
    active = _ACTIVE.get()
    if active is not None and active[0] == "record":
        rec = active[1]
        rec.meshes.append({"kind": kind, "spec": json.loads(json.dumps(spec)), "file": Path(path).name})
        rec.sources.append(Path(path))


def save(rec: Record, folder: Path) -> None:
    """Write ``rec`` to ``folder`` (mesh files and ``index.json``), replacing what was there; written to a
    sibling temporary folder and renamed, so a reader never sees half of it."""
    folder = Path(folder)
    tmp = folder.with_name(folder.name + ".tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    for src in dict.fromkeys(rec.sources):                 # one copy of a mesh the model used twice
        shutil.copyfile(src, tmp / src.name)
        (tmp / src.name).chmod(0o644)
    (tmp / INDEX).write_text(json.dumps({"meshes": rec.meshes, "values": rec.values}, indent=1))
    (tmp / INDEX).chmod(0o644)
    old = folder.with_name(folder.name + ".old")
    shutil.rmtree(old, ignore_errors=True)
    if folder.exists():
        folder.rename(old)
    tmp.rename(folder)
    shutil.rmtree(old, ignore_errors=True)


def load(folder: Path) -> Record | None:
    """The record saved in ``folder``, or None when there is none."""
    path = Path(folder) / INDEX
    if not path.is_file():
        return None
    data = json.loads(path.read_text())
    return Record(data["meshes"], data["values"], Path(folder))


def as_array(value: Any) -> np.ndarray:
    """A recorded list back as a float array."""
    return np.asarray(value, dtype=float)
