"""Run independent cases (stress sweeps, validity maps, benchmarks) in local worker processes or on a
dask.distributed cluster, with progress.

Local processes are the default. ``scheduler`` (an address such as ``tcp://10.0.0.5:8786``) sends the cases
to a running dask.distributed cluster instead, for a user who outgrows one machine; dask is the optional
``dist`` extra, imported only then. Either way the results come back in the order of the cases and a case
that raises makes the whole sweep raise (the case functions catch what they expect themselves). A reference
builder whose levels are independent solves (the FE tables of a finite-body correction) reads the cluster of the
run it belongs to from :func:`current_scheduler`, set by :func:`remote` (``femcheck run --scheduler``); where
its levels run never enters a reference's key.

Stopping. Ctrl-C (SIGINT) or SIGTERM stops a local sweep at once: the workers ignore SIGINT (a terminal sends
it to the whole process group; only the parent acts on it), the parent cancels what has not started and
terminates (then kills) every worker, and :class:`Interrupted` reaches the caller, which prints one line. A
worker also dies with its parent (Linux: PR_SET_PDEATHSIG), so even a parent killed outright leaves none behind.
"""
from __future__ import annotations

import contextlib
import contextvars
import ctypes
import os
import signal
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, Callable, Iterable, Iterator

from .errors import InputError


class Interrupted(BaseException):
    """The user stopped the run (SIGINT / Ctrl-C, SIGTERM); ``signum`` says which. A BaseException, as
    KeyboardInterrupt, so that no ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int):
        self.signum = signum
        super().__init__(signal.Signals(signum).name)


def _raise_interrupted(signum, _frame):
    raise Interrupted(signum)


@contextlib.contextmanager
def stop_on_signals(signums: tuple[int, ...] = (signal.SIGTERM,)) -> Iterator[None]:
    """Within the block, these signals raise :class:`Interrupted` in the main thread (as Ctrl-C raises
    KeyboardInterrupt), so the same clean-up runs for all of them. Outside the main thread: no change."""
    try:
        previous = {s: signal.signal(s, _raise_interrupted) for s in signums}
    except ValueError:
        yield
        return
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


def _worker_init() -> None:
    """In each worker: ignore SIGINT (the parent stops the workers) and die with the parent."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)     # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):     # not Linux: the parent still terminates its workers itself
        pass


def _stop(pool: ProcessPoolExecutor) -> int:
    """Cancel what has not started and end every worker now (SIGTERM, then SIGKILL after 2 s); the number of
    workers stopped."""
    procs = list((getattr(pool, "_processes", None) or {}).values())   # private: the only handle on them
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=2.0)
        if p.is_alive():
            p.kill()
            p.join(timeout=1.0)
    return len(procs)


_SCHEDULER: contextvars.ContextVar[str | None] = contextvars.ContextVar("femcheck_scheduler", default=None)


@contextlib.contextmanager
def remote(scheduler: str | None) -> Iterator[None]:
    """Within the block, :func:`current_scheduler` is ``scheduler`` (None: everything runs here)."""
    token = _SCHEDULER.set(scheduler or None)
    try:
        yield
    finally:
        _SCHEDULER.reset(token)


def current_scheduler() -> str | None:
    """The dask scheduler address of the run in progress (:func:`remote`), or None."""
    return _SCHEDULER.get()


def check_scheduler(scheduler: str) -> None:
    """Connect once to ``scheduler`` (InputError naming ``--scheduler`` when dask is missing or nothing answers),
    so that a run fails at its start, not after its local work."""
    with _client(scheduler):
        pass


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
    pool = ProcessPoolExecutor(max_workers=workers, initializer=_worker_init)
    try:
        with stop_on_signals():
            futures = {pool.submit(fn, c): i for i, c in enumerate(cases)}
            for fut in as_completed(futures):
                i = futures[fut]
                out[i] = fut.result()
                if on_done:
                    on_done(i, out[i])
    except BaseException:            # Ctrl-C, SIGTERM, or a case that raised: no worker outlives the sweep
        _stop(pool)
        raise
    pool.shutdown(wait=True)
    return out
