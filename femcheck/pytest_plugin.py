"""pytest plugin (entry point ``pytest11``): verify contact-model agreement in your own test suite.

    def test_my_roller(femcheck_run, femcheck_assert_agree):
        res = femcheck_run("my-scene.toml", {"load.per_length": 2e6}, models=["analytic", "bem"])
        femcheck_assert_agree(res, "p_max", "bem", "analytic", rtol=0.01)

``femcheck_run`` runs a scene once per session for a given (scene, overrides, models) and reuses the result;
FEM results are additionally cached on disk by content hash (``FEMCHECK_CACHE``).
"""
from __future__ import annotations

import pytest

from .testing import assert_agree


@pytest.fixture(scope="session")
def femcheck_run():
    from .runner import run

    memo: dict = {}

    def _run(scene, overrides: dict | None = None, models: list[str] | None = None):
        key = (str(scene), tuple(sorted((overrides or {}).items())), tuple(models or ()))
        if key not in memo:
            memo[key] = run(scene, overrides, models)
        return memo[key]

    return _run


@pytest.fixture
def femcheck_assert_agree():
    return assert_agree
