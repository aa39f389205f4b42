"""Running CalculiX (``ccx``) on an exported deck: a full solve, or a start-up check that stops at the first
contact evaluation (the deck is read, every keyword accepted, the matrix structure set up and the contact pair
found), for decks whose full solve takes minutes.

``ccx`` runs single-threaded by default (OMP_NUM_THREADS=1: fair in timings), in the deck's folder, with a clean
PATH; ``threads`` > 1 lets its matrix set-up, SPOOLES solve and stress recovery use that many CPUs (srb-normal's
68k-DOF deck: 97 s on 2 instead of 136 s on 1; the solution changes by round-off only). A run is successful when ccx exits 0, prints "Job finished" and no ``*ERROR``.
"""
from __future__ import annotations

import os
import re
import resource
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

MISSING = "ccx not installed (apt-get install calculix-ccx)"
_SPRINGS = re.compile(r"Number of contact spring elements=\s*(\d+)")


def ccx() -> str | None:
    """Path of the CalculiX executable, None where it is not installed."""
    return shutil.which("ccx")


@dataclass
class CcxRun:
    """What a ccx run printed: ``finished`` ("Job finished" and no ``*ERROR``), ``errors`` the ``*ERROR`` lines,
    ``springs`` the contact-element count of each Newton iteration, ``iterations``, CPU (s, user + system of ccx)
    and wall time (s), ``stopped``: a start-up check ended the run on purpose."""

    returncode: int
    finished: bool
    errors: list[str] = field(default_factory=list)
    springs: list[int] = field(default_factory=list)
    iterations: int = 0
    cpu_s: float = 0.0
    wall_s: float = 0.0
    stopped: bool = False
    tail: str = ""


def _env(threads: int = 1) -> dict[str, str]:
    n = str(int(threads))
    return {"OMP_NUM_THREADS": n, "CCX_NPROC_EQUATION_SOLVER": n, "CCX_NPROC_RESULTS": n,
            "PATH": "/usr/bin:/bin:/usr/local/bin", "HOME": os.environ.get("HOME", "/tmp")}


def run(deck: Path, timeout: float = 600.0, stop_at_contact: bool = False, threads: int = 1) -> CcxRun:
    """Run ccx on ``deck`` (``.inp``); with ``stop_at_contact`` end it after the first contact evaluation;
    ``threads``: CPUs ccx may use (module docstring)."""
    exe = ccx()
    if exe is None:
        raise FileNotFoundError(MISSING)
    deck = Path(deck)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen([exe, "-i", deck.with_suffix("").name], cwd=deck.parent, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=_env(threads))
    errors, springs, lines = [], [], []
    iterations, stopped = 0, False
    try:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.append(line)
            if len(lines) > 400:
                del lines[:200]
            if "*ERROR" in line:
                errors.append(line.strip())
            elif line.startswith(" iteration"):
                iterations += 1
            m = _SPRINGS.search(line)
            if m:
                springs.append(int(m.group(1)))
                if stop_at_contact:
                    stopped = True
                    proc.terminate()
                    break
            if time.perf_counter() - t0 > timeout:
                proc.kill()
                errors.append(f"timeout after {timeout:g} s")
                break
    finally:
        rc = proc.wait()
        if proc.stdout is not None:
            proc.stdout.close()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    text = "".join(lines)
    finished = (not stopped) and rc == 0 and "Job finished" in text and not errors
    return CcxRun(rc, finished, errors, springs, iterations, cpu, time.perf_counter() - t0, stopped, text[-3000:])
