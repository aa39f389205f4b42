"""Run independent cases (stress sweeps, validity maps, benchmarks) in local worker processes or on a
dask.distributed cluster, with progress.

Local processes are the default. ``scheduler`` (an address such as ``tcp://10.0.0.5:8786``) sends the cases
to a running dask.distributed cluster instead, for a user who outgrows one machine; dask is the optional
``dist`` extra, imported only then. Either way the results come back in the order of the cases and a case
that raises makes the whole sweep raise (the case functions catch what they expect themselves).
"""
from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, Callable, Iterable

from .errors import InputError


def default_workers() -> int:
    return max(1, min(len(os.sched_getaffinity(0)), 8))


def _client(scheduler: str):
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--scheduler", "needs dask.distributed: pip install 'femcheck[dist]'") from None
    try:
        return Client(scheduler, timeout="10s")
    except (OSError, TimeoutError) as err:
        raise InputError("--scheduler", f"no dask scheduler reachable at {scheduler!r} ({err}); "
                         "allowed: the address of a running scheduler, e.g. tcp://host:8786") from None


def _map_dask(fn: Callable[[Any], Any], cases: list[Any], scheduler: str,
              on_done: Callable[[int, Any], None] | None) -> list[Any]:
    from distributed import as_completed as dask_completed

    out: list[Any] = [None] * len(cases)
    with _client(scheduler) as client:
        # pure=False: two equal cases (e.g. repeated timings) must both run
        futures = client.map(fn, cases, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        for fut in dask_completed(futures):
            i = index[fut.key]
            out[i] = fut.result()
            if on_done:
                on_done(i, out[i])
    return out


def map_cases(fn: Callable[[Any], Any], cases: Iterable[Any], workers: int | None = None,
              on_done: Callable[[int, Any], None] | None = None, scheduler: str | None = None) -> list[Any]:
    """``[fn(c) for c in cases]`` in ``workers`` local processes (1: in this process) or, with ``scheduler``,
    on that dask.distributed cluster; order preserved. ``fn`` must be a module-level function (picklable)."""
    cases = list(cases)
    if scheduler:
        return _map_dask(fn, cases, scheduler, on_done)
    workers = default_workers() if workers is None else workers
    out: list[Any] = [None] * len(cases)
    if workers <= 1 or len(cases) <= 1:
        for i, c in enumerate(cases):
            out[i] = fn(c)
            if on_done:
                on_done(i, out[i])
        return out
    with ProcessPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(fn, c): i for i, c in enumerate(cases)}
        for fut in as_completed(futures):
            i = futures[fut]
            out[i] = fut.result()
            if on_done:
                on_done(i, out[i])
    return out
