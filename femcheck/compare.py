"""Errors of every model against the reference models: scalar quantities and pressure profiles.

Relative error |value - reference| / |reference| for scalars. Profiles are interpolated onto a common grid
x in [0, 1.2 s] (s: the scene's profile scale, e.g. the Hertz half-width) and compared in the L2 norm
||p - p_ref||_2 / ||p_ref||_2 and the max norm max|p - p_ref| / max p_ref.
A comparison passes when the scene gives a tolerance ``tolerances.<model>.<quantity>`` and the error is within
it; without a tolerance it is listed with ``pass = null``.
"""
from __future__ import annotations

import numpy as np

from .result import Comparison, ModelResult
from .scene import Scene

PROFILE_POINTS = 241


def profile_errors(x: np.ndarray, p: np.ndarray, x_ref: np.ndarray, p_ref: np.ndarray,
                   scale: float) -> dict[str, float]:
    """Relative L2 and max-norm differences of two pressure profiles on the common grid (see module doc)."""
    grid = np.linspace(0.0, 1.2 * scale, PROFILE_POINTS)
    a = np.interp(grid, x, p, left=0.0, right=0.0)
    b = np.interp(grid, x_ref, p_ref, left=0.0, right=0.0)
    return {"pressure_profile_l2": float(np.linalg.norm(a - b) / np.linalg.norm(b)),
            "pressure_profile_max": float(np.abs(a - b).max() / b.max())}


def _judge(quantity: str, model: str, ref: str, value: float, ref_value: float, rel: float,
           scene: Scene) -> Comparison:
    tol = scene.get(f"tolerances.{model}.{quantity}")
    return Comparison(quantity, model, ref, float(value), float(ref_value), float(rel), tol,
                      None if tol is None else bool(rel <= tol))


def _scalar(model: str, q: dict[str, float], ref: str, qr: dict[str, float], scene: Scene) -> list[Comparison]:
    out = []
    for name in q:
        if name in qr and qr[name] != 0:
            a, b = q[name], qr[name]      # equal infinite values (an infinite life) agree; one infinite does not
            rel = 0.0 if a == b else abs(a - b) / abs(b) if np.isfinite(a) and np.isfinite(b) else np.inf
            out.append(_judge(name, model, ref, q[name], qr[name], rel, scene))
    return out


def compare(scene: Scene, results: dict[str, ModelResult], scale: float) -> list[Comparison]:
    """All comparisons of the ok models against the ok references of ``models.references``.

    Each unordered pair of references is compared once (the later one against the earlier one). A model
    whose stats carry ``finest`` (FEM levels) is also compared at its finest level as ``<model>@finest``.
    """
    refs = [r for r in scene["models.references"] if r in results and results[r].status == "ok"]
    out: list[Comparison] = []
    for name, res in results.items():
        if res.status != "ok":
            continue
        for ref in refs:
            if ref == name or (name in refs and refs.index(name) < refs.index(ref)):
                continue
            rres = results[ref]
            out += _scalar(name, res.quantities, ref, rres.quantities, scene)
            if "finest" in res.stats:
                out += _scalar(f"{name}@finest", res.stats["finest"], ref, rres.quantities, scene)
            if "pressure" in res.fields and "pressure" in rres.fields:
                errs = profile_errors(res.fields["x"], res.fields["pressure"], rres.fields["x"],
                                      rres.fields["pressure"], scale)
                out += [_judge(k, name, ref, v, 0.0, v, scene) for k, v in errs.items()]
    return out
