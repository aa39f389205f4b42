"""FE relative compliance tables (:class:`femcheck.fem.rolling_contact.RelativeCompliance`) on disk: one ``.npz``
per set of tables, written atomically, read back onto the grids they were computed on (the grids are not stored:
the caller rebuilds them from the same inputs and its key must say so)."""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import numpy as np

from .rolling_contact import RelativeCompliance


def save(path: Path, t: RelativeCompliance) -> None:
    """Tables, lags and FE stats of ``t`` to ``path`` (``.npz``)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    arrays = {f"T|{r}|{s}": v for (r, s), v in t.tables.items()}
    arrays.update({f"L|{r}|{s}": np.array(v) for (r, s), v in t.lag0.items()})
    fd, tmp = tempfile.mkstemp(suffix=".npz", dir=path.parent)
    os.close(fd)
    try:
        np.savez(tmp, **arrays, stats=json.dumps(t.stats, default=str))
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def load(path: Path, grids: dict) -> RelativeCompliance | None:
    """The tables stored at ``path`` on ``grids``; None when the file is missing or damaged."""
    try:
        with np.load(path) as z:
            tables = {tuple(k.split("|")[1:]): z[k] for k in z.files if k.startswith("T|")}
            lag0 = {tuple(k.split("|")[1:]): float(z[k]) for k in z.files if k.startswith("L|")}
            stats = json.loads(str(z["stats"]))
    except (OSError, ValueError, KeyError):
        return None
    return RelativeCompliance(dict(grids), tables, lag0, stats)
