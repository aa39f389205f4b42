"""Problem kinds: each module declares its scene schema (SCHEMA, DEFAULTS, REQUIRED), cross-key checks
(``validate``) and its models (MODELS: name -> function(scene, progress) -> ModelResult).

A scene's ``kind`` selects the module; adding a kind means adding a module here and listing it below.
"""
from __future__ import annotations

from importlib import import_module
from types import ModuleType

from ..errors import InputError

KINDS = {"line_contact": "line_contact", "point_contact": "point_contact", "roller_contact": "roller_contact",
         "indent_contact": "indent_contact", "srb_contact": "srb_contact",
         "line_tangential": "line_tangential", "point_tangential": "point_tangential",
         "layer_contact": "layer_contact", "groove_rolling": "groove_rolling"}


def problem(kind: str) -> ModuleType:
    if kind not in KINDS:
        raise InputError("kind", f"{kind!r} is not a problem kind; allowed: {', '.join(sorted(KINDS))}")
    return import_module(f"{__name__}.{KINDS[kind]}")
