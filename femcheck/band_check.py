"""Bands that cannot fail: every tolerance of a scene must be narrower than what its quantity moves over the
scene's own stress sweep (:func:`femcheck.problems.<kind>.stress_cases`), or the scene says why not.

A relative tolerance t on a quantity Q (``tolerances.<model>.<Q>``, :mod:`femcheck.compare`) is judged against
the reference values v_i of Q at the scene's nominal point and at every case of its stress sweep where the
reference runs (refused inputs, failures, non-finite values and zeros -- which :mod:`femcheck.compare` never
divides by -- are left out). The measure is the blind error

    e_blind = min_c max_i |c - v_i| / |v_i|,

the worst relative error over the sweep of the best model blind to every input the sweep moves (one constant c):
(max|v| - min|v|) / (max|v| + min|v|) = s / (2 + s), s = max|v| / min|v| - 1, for values of one sign; 1 for
values of both signs (c = 0 is then best). A band t >= e_blind lets that constant pass at every point of the
scene's own operating range: the band cannot tell a right model from one that ignores the physics.

Criterion: t < FRACTION e_blind with FRACTION = 1/2. A model that follows only half of the quantity's response
(v' = sqrt(v v0), half the logarithmic change, best v0) misses by tanh(L/4) somewhere, L = ln(max|v| / min|v|),
while e_blind = tanh(L/2) <= 2 tanh(L/4): a band below e_blind / 2 fails such a half-right model, whatever the
spread. For the small spreads where the check bites (a few tens of per cent) tanh(L/4) is e_blind / 2 to within
L^2/16 relative, so a band at the limit lets the half-right model pass: the limit is tight there, not a margin.

Which values: those of the scene's references (``models.references``) that are fast, in their order; where none
gives Q at two points or more (a stored / cached reference such as an FE model, minutes per case, is not run over
the sweep; a published column exists at the nominal point only), a stand-in: the candidate (else the contrast)
with the narrowest band on Q (``source`` names it). It agrees with the reference at the nominal point within that
band, and what is measured is how far Q moves, not an error.

What it can see: loads over decades make e_blind close to 1 for every dimensional quantity, so there only a band
of about 0.5 or more fails; the check is sharp for quantities the sweep hardly moves (normalised forces, speeds
near their kinematic values, positions fixed by the geometry), where a wide band admits a model without the
physics.
Profile norms (``pressure_profile_*``) and roller-by-roller norms (``roller_loads_max``) are
differences relative to the reference's own norm, with no reference value to spread: not judged here (listed).
``total_force*`` is never compared (load control, :mod:`femcheck.compare`): a tolerance on it is never evaluated, a
defect as well (``unused``).

A deliberate exception is written in the scene, ``[tolerances.exceptions]`` with ``"model.quantity" = "why"``
(:attr:`femcheck.scene.Scene.band_exceptions`); it is reported with its reason instead of failing.

Cost: only the reference (or stand-in) models run, on the nominal point and each case (``Sweep.time_s``); a sweep
too expensive to repeat is stored once (:func:`save_sweep`, ``python -m femcheck.band_check --store DIR SCENE``)
and judged from the file (:func:`check_scene` with ``stored``), which must have the current sweep's cases.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

from .compare import LOAD_QUANTITIES
from .errors import InputError
from .executor import map_cases
from .problems import problem
from .runner import run_model
from .scene import Scene, load_scene

FRACTION = 0.5
NORM_QUANTITIES = ("pressure_profile_l2", "pressure_profile_max", "roller_loads_max", "slice_loads_max")
# finding status, from the worst
STATUSES = ("vacuous", "unmeasured", "excepted", "unused", "norm", "ok")


@dataclass
class BandFinding:
    """One tolerance ``tolerances.<model>.<quantity>`` of a scene, judged against the spread of ``source``'s
    values of ``quantity`` over the sweep (``values``: case label -> value). ``limit`` = FRACTION x e_blind."""

    key: str
    tolerance: float
    status: str = "ok"
    source: str = ""
    values: dict[str, float] = field(default_factory=dict)
    spread: float = math.nan          # max|v| / min|v| - 1
    blind_error: float = math.nan
    limit: float = math.nan
    note: str = ""

    def line(self) -> str:
        if self.status in ("ok", "vacuous", "excepted"):
            tail = (f"band {self.tolerance:.3g} vs limit {self.limit:.3g} (= {FRACTION:g} x blind error "
                    f"{self.blind_error:.3g}; spread {self.spread:.3g} of {self.source}'s values over "
                    f"{len(self.values)} points)")
        else:
            tail = f"band {self.tolerance:.3g}"
        return f"{self.status:10s} {self.key}: {tail}" + (f"; {self.note}" if self.note else "")


@dataclass
class BandReport:
    scene: str
    findings: list[BandFinding]
    points: list[str]              # the nominal point and the sweep's case labels
    refused: dict[str, str]        # case label -> why its inputs were refused (by a source model)
    time_s: float = 0.0            # the sweep's run time (0 for a stored sweep)
    stored: bool = False

    def failing(self) -> list[BandFinding]:
        """Findings that are defects: a vacuous band, a band whose quantity could not be measured, or one that is
        never evaluated (on the imposed load) -- none of them can fail a model."""
        return [f for f in self.findings if f.status in ("vacuous", "unmeasured", "unused")]


def blind_error(values) -> float:
    """min_c max_i |c - v_i| / |v_i| over non-zero finite values (module doc); NaN for fewer than two."""
    v = [abs(x) for x in values if math.isfinite(x) and x != 0.0]
    if len(v) < 2:
        return math.nan
    signs = {x > 0 for x in values if math.isfinite(x) and x != 0.0}
    if len(signs) > 1:
        return 1.0
    return (max(v) - min(v)) / (max(v) + min(v))


def _spread(values) -> float:
    v = [abs(x) for x in values if math.isfinite(x) and x != 0.0]
    return max(v) / min(v) - 1.0 if len(v) >= 2 else math.nan


def tolerance_keys(scene: Scene) -> list[tuple[str, str, float]]:
    """(model or model@finest, quantity, tolerance) of every ``tolerances.*.*`` key of ``scene``."""
    out = []
    for key, tol in scene.params.items():
        if key.startswith("tolerances.") and key.count(".") >= 2:
            _, model, quantity = key.split(".", 2)
            out.append((model.strip('"'), quantity, float(tol)))
    return out


def references_fast(scene: Scene) -> list[str]:
    """The scene's references (``models.references``) that are not stored / cached models (the kind's DEPENDS)."""
    expensive = set(problem(scene.kind).DEPENDS)
    return [r for r in scene["models.references"] if r not in expensive]


def stand_in(scene: Scene, quantity: str) -> str | None:
    """The fast model that stands in for the references on ``quantity`` (module doc): the candidate (not a
    contrast) with the narrowest band on it, else the contrast with the narrowest band; None when no fast model
    has a band on it."""
    expensive = set(problem(scene.kind).DEPENDS)
    contrast = set(scene.get("models.contrast", ()))
    bands = [(m.partition("@")[0] in contrast, tol, m.partition("@")[0]) for m, q, tol in tolerance_keys(scene)
             if q == quantity and m.partition("@")[0] not in expensive]
    return min(bands)[2] if bands else None


def judged(scene: Scene) -> list[str]:
    """The quantities whose bands are judged against a spread (not norms, not the imposed load)."""
    return sorted({q for _, q, _ in tolerance_keys(scene)
                   if q not in NORM_QUANTITIES and not q.startswith(LOAD_QUANTITIES)})


@dataclass
class Sweep:
    """Quantities of ``models`` at the nominal point and at every case of the scene's stress sweep:
    ``values[label][model]`` (models that ran ok), ``refused[label]`` (why a point's inputs were refused)."""

    scene: str
    models: list[str]
    labels: list[str]
    values: dict[str, dict[str, dict[str, float]]]
    refused: dict[str, str]
    time_s: float = 0.0

    def to_json(self) -> dict[str, Any]:
        return {"scene": self.scene, "models": self.models, "labels": self.labels, "values": self.values,
                "refused": self.refused, "time_s": self.time_s}

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> "Sweep":
        return cls(d["scene"], list(d["models"]), list(d["labels"]), d["values"], d["refused"], d.get("time_s", 0.0))


def _point(args: tuple) -> tuple[str, dict[str, dict[str, float]], str]:
    """Run ``models`` at one point: (label, {model: quantities}, why refused or '')."""
    scene, label, overrides, models = args
    try:
        sc = scene.with_overrides(overrides) if overrides else scene
    except InputError as err:
        return label, {}, str(err)
    own = overrides.get("models.run")
    out = {}
    for m in models:
        if own and m not in own:
            continue
        try:
            res = run_model(sc, m, use_cache=False)
        except InputError as err:
            return label, out, str(err)
        if res.status == "ok":
            out[m] = {k: float(v) for k, v in res.quantities.items()
                      if isinstance(v, (int, float)) and not isinstance(v, bool)}
    return label, out, ""


def sweep(scene: Scene | str, models: list[str] | None = None, workers: int | None = None) -> Sweep:
    """Run ``models`` at the nominal point and at every case of the kind's ``stress_cases(scene)`` (``workers``
    processes, default the machine's cores). Default: the fast references (:func:`references_fast`), then the
    stand-ins (:func:`stand_in`) of the quantities that the references do not give at two points or more."""
    t0 = time.perf_counter()
    sc = load_scene(scene) if isinstance(scene, str) else scene
    points = [("nominal", {})] + [(c.label, dict(c.overrides)) for c in problem(sc.kind).stress_cases(sc)]

    def run(names: list[str]) -> list[tuple]:
        return map_cases(_point, [(sc, label, over, names) for label, over in points], workers) if names else []

    names = list(models) if models is not None else references_fast(sc)
    runs = run(names)
    out = Sweep(sc.name, names, [p[0] for p in points], {label: got for label, got, _ in runs},
                {label: why for label, _, why in runs if why})
    if models is None:
        if not runs:
            out.values = {label: {} for label, _ in points}
        missing = [q for q in judged(sc) if not any(len(_usable(out, m, q)) >= 2 for m in names)]
        extra = sorted({m for q in missing if (m := stand_in(sc, q)) is not None} - set(names))
        for label, got, why in run(extra):
            out.values[label].update(got)
            if why:
                out.refused.setdefault(label, why)
        out.models = names + extra
    out.time_s = time.perf_counter() - t0
    return out


def case_labels(scene: Scene | str) -> list[str]:
    """The labels of the points :func:`sweep` runs (a stored sweep must have the same)."""
    sc = load_scene(scene) if isinstance(scene, str) else scene
    return ["nominal"] + [c.label for c in problem(sc.kind).stress_cases(sc)]


def _usable(sw: Sweep, model: str, q: str) -> dict[str, float]:
    return {label: got[model][q] for label, got in sw.values.items()
            if model in got and q in got[model] and math.isfinite(got[model][q]) and got[model][q] != 0.0}


def check_scene(scene: Scene | str, fraction: float = FRACTION, workers: int | None = None,
                stored: Sweep | None = None) -> BandReport:
    """Judge every tolerance of ``scene`` against the spread of its quantity over the scene's stress sweep
    (module doc): the sweep is run (:func:`sweep`), or ``stored`` is used (an expensive sweep run once; its
    labels must be those of the current sweep). The source of a quantity is the first of :func:`sources` that
    gives it at two points or more."""
    sc = load_scene(scene) if isinstance(scene, str) else scene
    if stored is not None and stored.labels != case_labels(sc):
        raise InputError("stored", f"the stored sweep of {sc.name} has other cases than the scene's stress sweep "
                                   f"now ({len(stored.labels)} vs {len(case_labels(sc))}): run it again")
    sw = stored if stored is not None else sweep(sc, workers=workers)
    exceptions = dict(sc.band_exceptions)
    findings = []
    for model, q, tol in tolerance_keys(sc):
        f = BandFinding(f"{model}.{q}", tol)
        findings.append(f)
        if q.startswith(LOAD_QUANTITIES):
            f.status, f.note = "unused", "total force is imposed (load control) and never compared"
            continue
        if q in NORM_QUANTITIES:
            f.status, f.note = "norm", "a profile / roller-by-roller norm: no reference value to spread"
            continue
        tried = []
        for src in [m for m in references_fast(sc) if m in sw.models] + [stand_in(sc, q)]:
            vals = _usable(sw, src, q) if src in sw.models else {}
            tried.append(f"{src}: {len(vals)}")
            if len(vals) >= 2:
                f.source, f.values = src, vals
                break
        f.blind_error, f.spread = blind_error(f.values.values()), _spread(f.values.values())
        f.limit = fraction * f.blind_error
        why = exceptions.get(f.key)
        if not f.source:
            f.status, f.note = "unmeasured", "usable values over the sweep: " + (", ".join(tried) or "no model")
        elif tol < f.limit:
            f.status = "ok"
        else:
            f.status = "vacuous"
        if why:
            if f.status in ("vacuous", "unmeasured"):
                f.status, f.note = "excepted", why
            else:
                f.note = "an exception is written for it but the band passes"
    order = {s: i for i, s in enumerate(STATUSES)}
    findings.sort(key=lambda f: (order[f.status], f.key))
    return BandReport(sc.name, findings, sw.labels, sw.refused, sw.time_s if stored is None else 0.0,
                      stored is not None)


def save_sweep(sw: Sweep, path) -> None:
    """Write a sweep as JSON (temp file and rename: never half-written), with how to run it again."""
    import datetime
    import json
    import os
    import tempfile
    from pathlib import Path

    from . import __version__

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    d = {**sw.to_json(), "femcheck_version": __version__,
         "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
         "command": f"python -m femcheck.band_check --store {path.parent} {sw.scene}"}
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    with os.fdopen(fd, "w") as fh:
        json.dump(d, fh, indent=1)
    os.replace(tmp, path)


def load_sweep(path) -> Sweep:
    import json
    from pathlib import Path

    return Sweep.from_json(json.loads(Path(path).read_text()))


def main(argv: list[str] | None = None) -> int:
    """``python -m femcheck.band_check [--store DIR] [SCENE ...]``: print every built-in scene's findings (or the
    named scenes'); with ``--store DIR`` also write each sweep to DIR/SCENE.json. Exit status 1 when any band is a
    defect (vacuous, or unmeasured without an exception)."""
    import argparse
    import sys

    from .scene import builtin_scene_files

    ap = argparse.ArgumentParser(prog="python -m femcheck.band_check", description=main.__doc__)
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--store", default=None, help="write each scene's sweep to STORE/SCENE.json")
    ap.add_argument("--workers", type=int, default=None)
    args = ap.parse_args(argv)
    bad = 0
    for name in args.scenes or list(builtin_scene_files()):
        sc = load_scene(name)
        sw = sweep(sc, workers=args.workers)
        if args.store:
            save_sweep(sw, f"{args.store}/{sc.name}.json")
        rep = check_scene(sc, stored=sw)
        print(f"== {name}: {len(rep.points)} points, {len(rep.refused)} refused, sweep {sw.time_s:.1f} s "
              f"({', '.join(sw.models)})")
        for f in rep.findings:
            print("   " + f.line())
        bad += len(rep.failing())
        sys.stdout.flush()
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
