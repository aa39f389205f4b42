"""Problem kinds: each module declares its scene schema (SCHEMA, DEFAULTS, REQUIRED), cross-key checks
(``validate``) and its models (MODELS: name -> function(scene, progress) -> ModelResult).

A scene's ``kind`` is the name of a module of this package (modules starting with ``_`` are shared helpers of
several kinds, not kinds); adding a kind means adding a module here, nothing
else (the kinds are found by listing the package, so this file, which every model's key covers, never changes
when a kind is added).
"""
from __future__ import annotations

import pkgutil
from importlib import import_module
from pathlib import Path
from types import ModuleType

from ..errors import InputError

KINDS = tuple(sorted(m.name for m in pkgutil.iter_modules([str(Path(__file__).parent)]) if not m.ispkg and not m.name.startswith("_")))


def problem(kind: str) -> ModuleType:
    if kind not in KINDS:
        raise InputError("kind", f"{kind!r} is not a problem kind; allowed: {', '.join(KINDS)}")
    return import_module(f"{__name__}.{kind}")
