"""The entry point of ``femcheck export``: check the options, build the scene's deck, write it."""
from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from . import deck, scenes

FORMATS = ("calculix", "abaqus")
ORDERS = (1, 2)


def export(scene, fmt: str, level: int, order: int, out) -> dict:
    """Write ``<scene>-L<level>-<element>.inp`` for ``scene`` (a validated Scene) into directory ``out`` and
    return a summary: the path, element, mesh level, node / DOF counts and the Hertz values to compare with.
    Bad input raises :class:`femcheck.errors.InputError` before anything is written."""
    if fmt not in FORMATS:
        raise InputError("--format", f"{fmt!r}; allowed: {', '.join(FORMATS)}")
    if order not in ORDERS:
        raise InputError("--order", f"{order}; allowed 1 (linear) or 2 (quadratic)")
    d = scenes.build(scene, level, order)
    path = deck.write_deck(d, fmt, Path(out) / f"{scene.name}-L{level}-{d.info['element']}.inp")
    return {"deck": str(path), "format": fmt, "nodes": d.n_nodes, **d.info}
