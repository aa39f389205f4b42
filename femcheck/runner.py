"""Scene -> models -> comparisons. Decides what a scene needs, runs it, caches expensive results."""
from __future__ import annotations

import time
from pathlib import Path
from typing import Any, Callable

from . import cache, references, replay
from .checks import physical_violations
from .compare import compare
from .errors import ConvergenceError, InputError
from .meshes.cache import rebuilding
from .problems import problem
from .result import ModelResult, RunResult
from .scene import Scene, load_scene

Progress = Callable[[str], None]


def resolve_scene(scene: Scene | str | Path, overrides: dict[str, Any] | None = None,
                  models: list[str] | None = None) -> Scene:
    """The validated scene with ``overrides``; ``models`` (the ``--models`` option) replaces ``models.run``
    *before* validation, so a scene whose ``models.run`` lists a model the overrides make inapplicable (e.g.
    uncoated Hertz on a rigid substrate) runs with the models asked for."""
    if models:
        overrides = {**(overrides or {}), "models.run": list(models)}
    try:
        if isinstance(scene, Scene):
            return scene.with_overrides(overrides) if overrides else scene
        return load_scene(scene, overrides)
    except InputError as err:
        if models and err.key == "models.run":        # the user typed --models, not models.run
            raise InputError("--models", str(err).partition(": ")[2]) from None
        raise


def _store_reference(scene: Scene, name: str, key: str, res: ModelResult, dep: dict, root: Path | None) -> None:
    relevant = {p: v for p, v in scene.params.items() if p.startswith(dep["params"])}
    if references.store(scene.kind, name, key, res, scene.name, relevant, root) is not None and "coarse" in dep:
        record_coarse_inputs(scene, name, key, dep, root)


def record_coarse_inputs(scene: Scene, name: str, key: str, dep: dict, root: Path | None) -> None:
    """Solve the coarsest level of reference ``name`` (the kind's ``DEPENDS[name]["coarse"]`` overrides) once
    more while recording its meshes and derived inputs, and store them beside the reference
    (:func:`femcheck.references.inputs_dir`): the re-solve that proves the stored numbers current then runs on
    them (:mod:`femcheck.replay`, :mod:`femcheck.reference_check`). Meshes come from the mesh cache, so they are
    the very meshes the reference was just solved on."""
    coarse = scene.with_overrides(dep["coarse"])
    with replay.recording() as rec:
        res = problem(scene.kind).MODELS[name](coarse, None)
    if res.status == "ok":
        replay.save(rec, references.inputs_dir(scene.kind, name, key, root))


def _stored(scene: Scene, name: str, key: str, root: Path | None) -> ModelResult | None:
    """A stored reference: in the user's directory ``root`` first, then among the built-in references."""
    for where in ([root] if root is not None else []) + [None]:
        if (ref := references.load(scene.kind, name, key, where)) is not None:
            return ref
    return None


def model_modules(scene: Scene, name: str) -> tuple[str, ...]:
    """The modules whose source (with everything they import) determines model ``name`` of ``scene``'s kind:
    the kind's adapter and the module defining the model function."""
    prob = problem(scene.kind)
    return tuple(sorted({prob.__name__, prob.MODELS[name].__module__}))


def model_key(scene: Scene, name: str) -> str:
    """Cache / reference key of model ``name`` (declared in the kind's DEPENDS) for ``scene``."""
    dep = problem(scene.kind).DEPENDS[name]
    return cache.key(scene.kind, name, scene.params, dep["params"], model_modules(scene, name))


def run_model(scene: Scene, name: str, use_cache: bool = True, rebuild: bool = False,
              progress: Progress | None = None, store_references: bool = False,
              references_dir: Path | None = None) -> ModelResult:
    """Run one model; failures become ``status='failed'`` with the reason, never an exception (bad input
    still raises InputError). Results of models listed in the kind's DEPENDS are cached; those marked as
    references are first looked up in the stored references (:mod:`femcheck.references`: ``references_dir``
    first, then the built-in ones) and, with ``store_references``, stored after a solve: in ``references_dir``
    when given, else with the built-in references."""
    prob = problem(scene.kind)
    dep = prob.DEPENDS.get(name)
    k = None
    is_reference = bool(dep and dep.get("reference"))
    if dep is not None and use_cache:
        k = model_key(scene, name)
        if not rebuild and is_reference and (ref := _stored(scene, name, k, references_dir)) is not None:
            return ref
        if not rebuild and (hit := cache.load(k)) is not None:
            if is_reference and store_references:       # solved earlier under --set: keep it as the reference
                _store_reference(scene, name, k, hit, dep, references_dir)
            return hit
    t0 = time.perf_counter()
    try:
        with rebuilding(rebuild):                   # --rebuild meshes too, not only the solve
            res = prob.MODELS[name](scene, progress)
    except InputError:
        raise
    except ConvergenceError as err:
        return ModelResult(name, "failed", time.perf_counter() - t0, error=str(err))
    except (ArithmeticError, ValueError, RuntimeError, MemoryError, KeyError) as err:
        return ModelResult(name, "failed", time.perf_counter() - t0, error=f"{type(err).__name__}: {err}")
    res.time_s = time.perf_counter() - t0
    issues = physical_violations(res, prob.load_of(scene))
    if issues:
        res.status, res.error = "failed", "; ".join(issues)
    elif k is not None:
        cache.store(k, res)
        if is_reference and store_references:
            _store_reference(scene, name, k, res, dep, references_dir)
    return res


def run(scene: Scene | str | Path, overrides: dict[str, Any] | None = None, models: list[str] | None = None,
        use_cache: bool = True, rebuild: bool = False, progress: Progress | None = None,
        store_references: bool = False, references_dir: Path | None = None) -> RunResult:
    """Run ``models`` (default: the scene's ``models.run``; see :func:`resolve_scene`) and compare them with
    the scene's references."""
    sc = resolve_scene(scene, overrides, models)
    prob = problem(sc.kind)
    names = list(sc["models.run"])
    results = {}
    for n in names:
        if progress:
            progress(f"{sc.name}: {n}")
        results[n] = run_model(sc, n, use_cache, rebuild, progress, store_references, references_dir)
    singular = prob.singular_quantities(sc) if hasattr(prob, "singular_quantities") else ()
    comparisons, not_compared = compare(sc, results, prob.profile_scale(sc), singular)
    return RunResult(sc.name, dict(sc.params), results, comparisons, sc.kind, sc.description, not_compared)
