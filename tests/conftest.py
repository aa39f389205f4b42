"""Test session set-up.

FEM results are cached in a fresh temporary directory per session, so tests never depend on results left on the
machine, while tests within the session reuse each other's FEM solves. Under pytest-xdist (``-n``) every worker of
one run shares that directory (keyed on the run's uid; cache entries are written atomically), so a solve made by one
worker is reused by the others.
"""
import os
import tempfile
from pathlib import Path

import pytest

_RUN_UID = os.environ.get("PYTEST_XDIST_TESTRUNUID")
if _RUN_UID:
    _cache = Path(tempfile.gettempdir()) / f"femcheck-test-cache-{_RUN_UID}"
    _cache.mkdir(exist_ok=True)
    os.environ["FEMCHECK_CACHE"] = str(_cache)
else:
    os.environ["FEMCHECK_CACHE"] = tempfile.mkdtemp(prefix="femcheck-test-cache-")

# The largest FE tests peak at about 5 GB; more workers than memory allows would swap.
_GB_PER_WORKER = 6


@pytest.hookimpl(optionalhook=True)          # pytest-xdist's hook; absent with -p no:xdist
def pytest_xdist_auto_num_workers(config):
    """``-n auto``: one worker per core, at most one per 6 GB of memory."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    try:
        mem_gb = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):
        return cores
    return max(1, min(cores, int(mem_gb // _GB_PER_WORKER)))
