"""pytest plugin (entry point ``pytest11``): verify contact-model agreement in your own test suite.

    def test_my_roller(femcheck_run, femcheck_assert_agree):
        res = femcheck_run("scenes/my-roller.toml", {"load.per_length": 4e4}, models=["analytic", "bem"])
        femcheck_assert_agree(res, "p_max", "bem", "analytic", rtol=0.01)

``femcheck_run(scene, overrides, models)`` takes a built-in scene name or a TOML path; a relative path is read
from the directory of the test file that calls it (not from wherever pytest was started). It runs a scene once
per session for a given (scene, overrides, models) and reuses the result; FE results are additionally cached on
disk by content hash (``FEMCHECK_CACHE``). A user's scene never writes into femcheck's package or references.
"""
from __future__ import annotations

import inspect
from pathlib import Path

import pytest

from .testing import assert_agree


def resolve_scene_path(scene, test_dir: Path):
    """A built-in scene name stays a name; a relative path (anything with a separator or a ``.toml`` suffix) is
    taken relative to ``test_dir``."""
    if not isinstance(scene, (str, Path)):
        return scene
    text = str(scene)
    if isinstance(scene, str) and "/" not in text and "\\" not in text and not text.endswith(".toml"):
        return scene                               # a built-in scene name
    path = Path(scene).expanduser()
    return path if path.is_absolute() else (test_dir / path)


@pytest.fixture(scope="session")
def femcheck_run():
    """``run(scene, overrides=None, models=None)``, memoised for the session. A relative scene path is read from
    the directory of the file whose code calls it (the test file, or the conftest / fixture that does)."""
    from .runner import run

    memo: dict = {}

    def _run(scene, overrides: dict | None = None, models: list[str] | None = None):
        caller = Path(inspect.stack(context=0)[1].filename).resolve().parent
        scene = resolve_scene_path(scene, caller)
        key = (str(scene), tuple(sorted((overrides or {}).items())), tuple(models or ()))
        if key not in memo:
            memo[key] = run(scene, overrides, models)
        return memo[key]

    return _run


@pytest.fixture
def femcheck_assert_agree():
    return assert_agree
