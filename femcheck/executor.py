"""Run independent cases (stress sweeps, suites) in local worker processes, with progress."""
from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, Callable, Iterable


def default_workers() -> int:
    return max(1, min(len(os.sched_getaffinity(0)), 8))


def map_cases(fn: Callable[[Any], Any], cases: Iterable[Any], workers: int | None = None,
              on_done: Callable[[int, Any], None] | None = None) -> list[Any]:
    """``[fn(c) for c in cases]`` in ``workers`` processes (1: in this process); order preserved.
    ``fn`` must be a module-level function (picklable)."""
    cases = list(cases)
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
