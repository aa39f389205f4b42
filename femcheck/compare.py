"""Errors of every model against the reference models, and the verdict on each: scalar quantities and pressure
profiles.

Relative error |value - reference| / |reference| for scalars. Profiles are interpolated onto a common grid
x in [0, 1.2 s] (s: the scene's profile scale, e.g. the Hertz half-width) and compared in the L2 norm
||p - p_ref||_2 / ||p_ref||_2 and the max norm max|p - p_ref| / max p_ref.

Verdicts (:data:`femcheck.result.VERDICTS`). Every comparison is graded by ``tolerances.<model>.<quantity>``
(``<model>@finest`` for the finest level of a multi-level model):

- a candidate model within its tolerance is ``valid``; outside it, ``not valid here`` and the scene fails;
- a contrast model (``models.contrast``: shown because an engineer might reach for it, not expected to hold in
  this scene) is judged by the same key, its band: ``contrast`` within it, ``not valid here`` outside (shown,
  the scene does not fail);
- against (or, between two references, from) a reference quantity whose convergence certificate
  (``stats["certificates"][q]["certified"]``) is false: ``reference uncertified``, never a pass -- unless the
  error exceeds the tolerance plus the certificate's own error estimate: then ``not valid here`` whatever the
  reference's convergence;
- no tolerance: ``ungraded``, an error of the scene (built-in scenes have none; a test checks it).

What is not compared, and why:
- ``total_force*``: every model runs under load control and :mod:`femcheck.checks` already fails a model whose
  load balance is off by more than 1e-6; a comparison would repeat that check;
- a value bit-identical to the reference's, or to the same quantity of a model compared before it: the model
  took it from the same source (linear theory, FASTSIM and strip theory start from the Hertz semi-axes and
  pressure; a multi-level model's finest level equals its reported value when the levels do not extrapolate).
  It is compared once, for the model that computes it;
- a quantity that grows with refinement by nature (a pressure peak at a sharp edge): the kind declares it
  (``singular_quantities(scene)``) or the reference's certificate says so; a number that depends on the grid
  has no error to grade. It is listed in ``RunResult.not_compared``.
"""
from __future__ import annotations

from typing import Iterable

import numpy as np

from .result import Comparison, ModelResult
from .scene import Scene, did_you_mean

PROFILE_POINTS = 241
LOAD_QUANTITIES = "total_force"        # prefix: checked against the applied load, not against a reference


def profile_errors(x: np.ndarray, p: np.ndarray, x_ref: np.ndarray, p_ref: np.ndarray,
                   scale: float) -> dict[str, float]:
    """Relative L2 and max-norm differences of two pressure profiles on the common grid (see module doc)."""
    grid = np.linspace(0.0, 1.2 * scale, PROFILE_POINTS)
    a = np.interp(grid, x, p, left=0.0, right=0.0)
    b = np.interp(grid, x_ref, p_ref, left=0.0, right=0.0)
    return {"pressure_profile_l2": float(np.linalg.norm(a - b) / np.linalg.norm(b)),
            "pressure_profile_max": float(np.abs(a - b).max() / b.max())}


def roller_load_errors(loads: np.ndarray, ref_loads: np.ndarray) -> dict[str, float]:
    """Roller-by-roller difference of two load distributions (same rollers): max_j |Q_j - Q_j,ref| / max Q_ref."""
    return {"roller_loads_max": float(np.abs(loads - ref_loads).max() / np.abs(ref_loads).max())}


def slice_load_errors(loads: np.ndarray, ref_loads: np.ndarray) -> dict[str, float]:
    """Slice-by-slice difference (ISO/TS 16281 slices of every roller): max |q_jk - q_jk,ref| / max q_ref."""
    return {"slice_loads_max": float(np.abs(loads - ref_loads).max() / np.abs(ref_loads).max())}


def certificates(res: ModelResult | None) -> dict[str, dict]:
    """A result's convergence certificates (``stats["certificates"]``, format in the README). A multi-level result
    from before certificates existed has only ``stats["richardson"]``: a quantity there without an observed order
    (levels equal, oscillating, or an order outside [0.5, 4]) is read as not certified."""
    if res is None:
        return {}
    out = _own_certificates(res.stats)
    for part, sub in res.stats.items():       # a scene of several contacts (coatings): quantity_<part>
        if isinstance(sub, dict) and ("certificates" in sub or "richardson" in sub):
            out.update({f"{q}_{part}": c for q, c in _own_certificates(sub).items()})
    return out


def _own_certificates(stats: dict) -> dict[str, dict]:
    if "certificates" in stats:
        return dict(stats["certificates"] or {})
    return {q: {"certified": e.get("order") is not None, "value": e.get("value"), "finest": e.get("finest"),
                "order": e.get("order"),
                "error_estimate": abs(e["error_estimate"] / e["value"]) if e.get("value") else None,
                "note": "stats without a certificate; " + ("Richardson order %.2f" % e["order"]
                                                           if e.get("order") is not None else
                                                           "Richardson found no observed order")}
            for q, e in (stats.get("richardson") or {}).items()}


def certificate(res: ModelResult | None, quantity: str) -> dict | None:
    """The certificate of ``quantity``; a pressure profile (the finest level's) shares that of the peak pressure
    unless the result certifies the profile itself."""
    certs = certificates(res)
    if quantity in certs:
        return certs[quantity]
    if quantity.startswith("pressure_profile"):
        return next((c for q, c in certs.items() if q == "p_max" or q.startswith("p_max_")), None)
    return None


def is_singular(cert: dict | None) -> bool:
    """A certificate that says its quantity grows with refinement by nature (a peak at a sharp edge)."""
    return bool(cert) and (bool(cert.get("singular")) or
                           str(cert.get("note", "")).startswith("mesh-dependent by nature"))


class _Judge:
    """Grades comparisons of one scene run (see the module doc)."""

    def __init__(self, scene: Scene, results: dict[str, ModelResult], refs: list[str]):
        self.scene, self.results, self.refs = scene, results, refs
        self.contrast = set(scene.get("models.contrast", ()))
        self.seen: dict[tuple[str, str], list[float]] = {}      # (reference, quantity) -> values compared

    def duplicate(self, quantity: str, ref: str, value: float, ref_value: float) -> bool:
        if not np.isfinite(value):      # an infinite life equal to the reference's is an agreement, not a copy
            return False
        done = self.seen.setdefault((ref, quantity), [])
        if value == ref_value or value in done:
            return True
        done.append(value)
        return False

    def uncertified(self, model: str, ref: str, quantity: str) -> tuple[str, float | None]:
        """(note, relative error estimate) of a certificate saying certified: false, on the reference side (or
        on the model side when the model is a reference too); ('', None) when none does."""
        sides = [ref] + ([model] if model in self.refs else [])
        for side in sides:
            cert = certificate(self.results.get(side), quantity)
            if cert is not None and cert.get("certified") is False:
                note = f"{side} {quantity} not certified: {cert.get('note', '')}".rstrip(": ")
                est = cert.get("error_estimate")
                return note, (float(est) if est is not None and np.isfinite(est) else None)
        return "", None

    def __call__(self, quantity: str, model: str, ref: str, value: float, ref_value: float,
                 rel: float) -> Comparison:
        base = model.partition("@")[0]
        tol = self.scene.get(f"tolerances.{model}.{quantity}")
        contrast = base in self.contrast
        note, est = self.uncertified(base if base == model else "", ref, quantity)
        if tol is None:
            given = [k.split(".", 2)[2] for k in self.scene.params if k.startswith(f"tolerances.{model}.")]
            verdict, note = "ungraded", (f"the scene gives no tolerances.{model}.{quantity}"
                                         f"{did_you_mean(quantity, given)}")
        elif note and est is not None and rel > tol + est:
            # beyond its tolerance by more than the reference's own error bound: wrong whatever the reference's
            # certificate says
            verdict, note = "not valid here", note + f"; the error exceeds tolerance + its error estimate {est:.2g}"
        elif note:
            verdict = "reference uncertified"
        elif rel <= tol:
            verdict = "contrast" if contrast else "valid"
        else:
            verdict = "not valid here"
        return Comparison(quantity, model, ref, float(value), float(ref_value), float(rel), tol,
                          verdict == "valid", verdict, contrast, note)


def _scalar(judge: _Judge, model: str, q: dict[str, float], ref: str, qr: dict[str, float],
            skip: set[str]) -> list[Comparison]:
    out = []
    for name in q:
        if name in qr and qr[name] != 0 and not name.startswith(LOAD_QUANTITIES) and name not in skip:
            if judge.duplicate(name, ref, q[name], qr[name]):
                continue
            a, b = q[name], qr[name]      # equal infinite values (an infinite life) agree; one infinite does not
            rel = 0.0 if a == b else abs(a - b) / abs(b) if np.isfinite(a) and np.isfinite(b) else np.inf
            out.append(judge(name, model, ref, a, b, rel))
    return out


def singular_set(results: dict[str, ModelResult], refs: Iterable[str], declared: Iterable[str]) -> dict[str, str]:
    """Quantities not compared because they grow with refinement by nature -> the reason."""
    present = {q for r in results.values() if r.status == "ok" for q in r.quantities}
    out = {q: "grows with refinement by nature (a pressure peak at a sharp edge): not compared"
           for q in declared if q in present}
    for name in refs:
        res = results.get(name)
        for q, cert in certificates(res).items():
            if is_singular(cert):
                out.setdefault(q, f"{name}: {cert.get('note', 'mesh-dependent by nature')}; not compared")
    return out


def compare(scene: Scene, results: dict[str, ModelResult], scale: float,
            singular: Iterable[str] = ()) -> tuple[list[Comparison], dict[str, str]]:
    """All comparisons of the ok models against the ok references of ``models.references``, graded, and the
    quantities left out (``singular``: declared by the kind) with the reason.

    Each unordered pair of references is compared once (the later one against the earlier one). A model
    whose stats carry ``finest`` (FEM levels) is also compared at its finest level as ``<model>@finest``.
    """
    refs = [r for r in scene["models.references"] if r in results and results[r].status == "ok"]
    not_compared = singular_set(results, refs, singular)
    skip = set(not_compared)
    judge = _Judge(scene, results, refs)
    out: list[Comparison] = []
    for ref in refs:                      # references first: a copied value is charged to the one computing it
        for name, res in results.items():
            if res.status != "ok" or ref == name or (name in refs and refs.index(name) < refs.index(ref)):
                continue
            rres = results[ref]
            out += _scalar(judge, name, res.quantities, ref, rres.quantities, skip)
            if "finest" in res.stats:
                out += _scalar(judge, f"{name}@finest", res.stats["finest"], ref, rres.quantities, skip)
            if "pressure" in res.fields and "pressure" in rres.fields:
                errs = profile_errors(res.fields["x"], res.fields["pressure"], rres.fields["x"],
                                      rres.fields["pressure"], scale)
                for k, v in errs.items():
                    if not judge.duplicate(k, ref, v, 0.0):
                        out.append(judge(k, name, ref, v, 0.0, v))
            if "roller_loads" in res.fields and "roller_loads" in rres.fields and \
                    np.shape(res.fields["roller_loads"]) == np.shape(rres.fields["roller_loads"]):
                errs = roller_load_errors(res.fields["roller_loads"], rres.fields["roller_loads"])
                if np.shape(res.fields.get("slice_loads", ())) == np.shape(rres.fields.get("slice_loads", ())) != (0,):
                    errs.update(slice_load_errors(res.fields["slice_loads"], rres.fields["slice_loads"]))
                for k, v in errs.items():
                    if not judge.duplicate(k, ref, v, 0.0):
                        out.append(judge(k, name, ref, v, 0.0, v))
    order = {n: i for i, n in enumerate(results)}
    out.sort(key=lambda c: (order.get(c.model.partition("@")[0], 0), "@" in c.model, refs.index(c.reference)))
    return out, not_compared
