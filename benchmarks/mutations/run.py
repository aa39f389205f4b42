"""Mutation suite of femcheck's physics: break the physics on purpose, one mutation at a time, in a scratch copy of
the repository, and check that the tests named for it fail.

    python benchmarks/mutations/run.py --list
    python benchmarks/mutations/run.py ehl-cel-inverted iso-l10r-rotating-exponent     # some ids
    python benchmarks/mutations/run.py --all [--jobs 1] [--no-baseline] [--keep]
    python benchmarks/mutations/run.py --all --check        # every pattern still applies (no tests run)

Independent of femcheck's own code (standard library, git and the interpreter only), so that a mutation of
femcheck cannot break the harness that judges it. Per mutation (``mutations.toml``):

1. a scratch copy: ``git archive HEAD`` of the repository, overlaid with the working tree's current (also
   uncommitted and untracked) files under femcheck/, tests/ and references/ - the suite judges the code as it is
   on disk, not the last commit;
2. the mutation: ``pattern`` must occur exactly once in ``file`` (otherwise the mutation is reported as a
   pattern error and nothing runs: a stale pattern must be fixed, never silently skipped), replaced by
   ``replacement``; the mutated file must still compile;
3. ``python -m pytest -x -q <tests>`` with the same interpreter, the scratch copy first on ``sys.path``
   (``femcheck`` imported from the copy is checked), ``FEMCHECK_CACHE`` in a fresh scratch folder (no stale
   cached result can hide a mutation), the stored references read from the copy's references/ as usual;
4. the outcome: ``caught`` (a named test failed: its node id and message are recorded), ``survived`` (all
   passed), ``error`` (pytest could not collect or run: import error, usage error), ``timeout``.

Baseline: each distinct set of tests is first run once on the unmutated copy; when that fails, the mutation's
outcome is ``baseline-fails`` (a failing test cannot judge a mutation). ``--no-baseline`` skips it.

Results: merged by id into ``results.json`` (so the list can be run in chunks) and written as the Markdown table
``RESULTS.md`` beside this script. Exit code 0 when every mutation run was caught, 1 otherwise, 2 on bad input.
Not in CI: the whole list takes tens of minutes (CPU heavy: on a shared machine wrap it in the machine's lock).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import datetime
import json
import os
import py_compile
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
OVERLAY = ("femcheck", "tests", "references")      # working-tree folders copied over the HEAD snapshot
OUTCOMES = ("caught", "survived", "error", "timeout", "baseline-fails", "pattern-error")


# -- the list -----------------------------------------------------------------------------------------------------
def load_mutations(path: Path) -> list[dict]:
    data = tomllib.loads(path.read_text())
    muts = data.get("mutation", [])
    seen = set()
    for m in muts:
        for key in ("id", "file", "pattern", "replacement", "why", "tests"):
            if key not in m:
                raise SystemExit(f"{path}: mutation {m.get('id', '?')!r} lacks '{key}'")
        if m["id"] in seen:
            raise SystemExit(f"{path}: duplicate mutation id {m['id']!r}")
        if m["pattern"] == m["replacement"]:
            raise SystemExit(f"{path}: mutation {m['id']!r}: replacement equals the pattern")
        seen.add(m["id"])
    return muts


# -- scratch copies ---------------------------------------------------------------------------------------------
def _git(repo: Path, *args: str) -> bytes:
    return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True).stdout


def snapshot(repo: Path, dest: Path) -> None:
    """HEAD's tracked files, then the working tree's tracked-and-modified and untracked (not ignored) files under
    OVERLAY, into ``dest``; files deleted in the working tree are deleted from the copy too."""
    dest.mkdir(parents=True)
    archive = dest / ".head.tar"
    archive.write_bytes(_git(repo, "archive", "--format=tar", "HEAD"))
    with tarfile.open(archive) as tar:
        tar.extractall(dest, filter="data")
    archive.unlink()
    listed = _git(repo, "ls-files", "-z", "--cached", "--others", "--exclude-standard", "--", *OVERLAY)
    for rel in filter(None, listed.decode().split("\0")):
        src, dst = repo / rel, dest / rel
        if src.is_file():
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
        elif dst.exists():
            dst.unlink()


def apply(copy: Path, m: dict) -> str | None:
    """Apply mutation ``m`` inside ``copy``; None on success, else the reason it could not be applied."""
    target = copy / m["file"]
    if not target.is_file():
        return f"{m['file']} does not exist"
    text = target.read_text()
    n = text.count(m["pattern"])
    if n != 1:
        return f"pattern found {n} times in {m['file']} (must be exactly once)"
    target.write_text(text.replace(m["pattern"], m["replacement"]))
    if target.suffix == ".py":
        try:
            py_compile.compile(str(target), doraise=True, cfile=str(copy / ".pyc-check"))
        except py_compile.PyCompileError as err:
            return f"the mutated {m['file']} does not compile: {err.msg.strip().splitlines()[-1]}"
    return None


# -- running tests ------------------------------------------------------------------------------------------------
FAILED = re.compile(r"^(FAILED|ERROR) (\S+)(?: - (.*))?$", re.M)


LOCK: list[str] = []       # ["flock", PATH] with --lock: each test run takes the machine's CPU lock


def run_tests(copy: Path, tests: list[str], timeout: float, marker: str = "not slow") -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(copy) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["FEMCHECK_CACHE"] = tempfile.mkdtemp(prefix="cache-", dir=copy)
    env.pop("FEMCHECK_REFERENCES", None)
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env["COLUMNS"] = "400"           # pytest cuts the summary lines (and the failure message) to the width
    probe = subprocess.run([sys.executable, "-c", "import femcheck; print(femcheck.__file__)"], cwd=copy, env=env,
                           capture_output=True, text=True)
    where = probe.stdout.strip()
    if probe.returncode or not Path(where).resolve().is_relative_to(copy.resolve()):
        return {"outcome": "error", "detail": f"femcheck imported from {where or probe.stderr.strip()[-300:]}, "
                                              f"not from the scratch copy", "time_s": 0.0}
    cmd = [*LOCK, sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "-o", "addopts=-rfE",
           *(["-m", marker] if marker else []), *tests]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, cwd=copy, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"outcome": "timeout", "detail": f"no result within {timeout:g} s", "time_s": timeout}
    out = p.stdout + p.stderr
    took = re.findall(r" in (\d+(?:\.\d+)?)s", out)
    dt = float(took[-1]) if took else time.perf_counter() - t0     # pytest's own time: no lock wait in it
    tail = " | ".join(line for line in out.strip().splitlines()[-3:])
    if p.returncode == 0:
        return {"outcome": "passed", "detail": tail[-300:], "time_s": dt}
    if p.returncode == 5:
        return {"outcome": "error", "detail": "no test selected (check the node ids and the marker)", "time_s": dt}
    if p.returncode == 1:
        hit = FAILED.search(out)
        node, msg = (hit.group(2), (hit.group(3) or "").strip()) if hit else ("?", tail)
        return {"outcome": "failed", "test": node, "detail": msg[:400], "time_s": dt}
    return {"outcome": "error", "detail": f"pytest exit code {p.returncode}: {tail[-400:]}", "time_s": dt}


class Baselines:
    """Unmutated runs per distinct test set (computed once, shared between threads)."""

    def __init__(self, base: Path, timeout: float, marker: str):
        self.base, self.timeout, self.marker = base, timeout, marker
        self.lock = threading.Lock()
        self.done: dict[tuple, dict] = {}
        self.events: dict[tuple, threading.Event] = {}

    def get(self, tests: list[str], marker: str) -> dict:
        key = (marker, *tests)
        with self.lock:
            ev = self.events.get(key)
            owner = ev is None
            if owner:
                ev = self.events[key] = threading.Event()
        if owner:
            work = Path(tempfile.mkdtemp(prefix="baseline-", dir=self.base.parent))
            shutil.rmtree(work)
            shutil.copytree(self.base, work, symlinks=True)
            try:
                self.done[key] = run_tests(work, tests, self.timeout, marker)
            finally:
                shutil.rmtree(work, ignore_errors=True)
                ev.set()
        ev.wait()
        return self.done[key]


def one(m: dict, base: Path, baselines: Baselines | None, timeout: float, keep: bool, marker: str) -> dict:
    t0 = time.perf_counter()
    rec = {"id": m["id"], "file": m["file"], "tests": m["tests"], "when": datetime.datetime.now().isoformat(
        timespec="seconds")}
    marker = m.get("marker", marker)
    if baselines is not None:
        b = baselines.get(m["tests"], marker)
        if b["outcome"] != "passed":
            rec.update(outcome="baseline-fails", detail=f"unmutated: {b['outcome']} {b.get('test', '')} "
                                                        f"{b.get('detail', '')}"[:400], time_s=0.0)
            return rec
        rec["baseline_s"] = round(b["time_s"], 1)
    work = Path(tempfile.mkdtemp(prefix=f"{m['id']}-", dir=base.parent))
    shutil.rmtree(work)
    shutil.copytree(base, work, symlinks=True)
    try:
        why = apply(work, m)
        if why is not None:
            rec.update(outcome="pattern-error", detail=why, time_s=0.0)
            return rec
        r = run_tests(work, m["tests"], timeout, marker)
        outcome = {"failed": "caught", "passed": "survived"}.get(r["outcome"], r["outcome"])
        rec.update(outcome=outcome, test=r.get("test"), detail=r.get("detail", ""), time_s=round(r["time_s"], 1))
        return rec
    finally:
        if keep:
            rec["copy"] = str(work)
        else:
            shutil.rmtree(work, ignore_errors=True)
        rec["wall_s"] = round(time.perf_counter() - t0, 1)


# -- results ------------------------------------------------------------------------------------------------------
def write_results(results: dict, muts: list[dict], json_path: Path, md_path: Path, commit: str) -> None:
    json_path.parent.mkdir(parents=True, exist_ok=True)
    md_path.parent.mkdir(parents=True, exist_ok=True)
    tmp = json_path.with_suffix(".tmp")
    tmp.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")
    tmp.replace(json_path)
    order = {m["id"]: m for m in muts}
    lines = ["# Mutation suite: results", "",
             f"Written by `benchmarks/mutations/run.py` from `results.json` (last run on {commit}). One row per "
             "mutation of `mutations.toml`: the outcome of the named fast tests on a scratch copy with the "
             "mutation applied; *caught by* is the first test that failed and its message, *time* the test run "
             "on the mutated copy (s). How to run: docs/notes/mutation-suite.md.", ""]
    counts = {k: 0 for k in OUTCOMES}
    for mid in order:
        if mid in results:
            counts[results[mid]["outcome"]] = counts.get(results[mid]["outcome"], 0) + 1
    lines.append("Totals: " + ", ".join(f"{k} {v}" for k, v in counts.items() if v) +
                 f"; not run {sum(1 for mid in order if mid not in results)} of {len(order)}.")
    lines += ["", "| id | mutation | outcome | caught by | time (s) | note |", "|---|---|---|---|---|---|"]

    def cell(s: str) -> str:
        return str(s).replace("|", "\\|").replace("\n", " ")

    for mid, m in order.items():
        r = results.get(mid)
        what = f"`{m['file']}`: {m['why']}"
        if r is None:
            lines.append(f"| {mid} | {cell(what)} | not run | | | {cell(m.get('note', ''))} |")
            continue
        by = r.get("test") or ""
        if r.get("detail") and r["outcome"] in ("caught", "error", "baseline-fails", "pattern-error", "timeout"):
            by = f"{by} ({r['detail'][:160]})" if by else r["detail"][:200]
        lines.append(f"| {mid} | {cell(what)} | **{r['outcome']}** | {cell(by)} | {r.get('time_s', '')} | "
                     f"{cell(m.get('note', ''))} |")
    tmp = md_path.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    tmp.replace(md_path)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("ids", nargs="*", help="mutation ids to run (default: none; see --all)")
    ap.add_argument("--all", action="store_true", help="run every mutation of the list")
    ap.add_argument("--list", action="store_true", help="print the ids and exit")
    ap.add_argument("--check", action="store_true",
                    help="only check that every chosen mutation applies (pattern found once, file compiles)")
    ap.add_argument("--mutations", type=Path, default=HERE / "mutations.toml")
    ap.add_argument("--repo", type=Path, default=HERE.parents[1])
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=1800.0, help="seconds per test run")
    ap.add_argument("--no-baseline", action="store_true", help="do not run the tests unmutated first")
    ap.add_argument("--marker", default="not slow",
                    help="pytest -m expression for every run (default 'not slow'; a mutation's 'marker' overrides it)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch copies (paths in results.json)")
    ap.add_argument("--lock", type=Path, default=None,
                    help="take this flock(1) lock file around each test run (a shared machine's CPU lock)")
    ap.add_argument("--scratch", type=Path, default=None, help="parent folder of the scratch copies")
    ap.add_argument("--out", type=Path, default=HERE, help="folder of results.json and RESULTS.md")
    args = ap.parse_args(argv)
    muts = load_mutations(args.mutations)
    if args.lock is not None:
        LOCK[:] = ["flock", str(args.lock)]
    if args.list:
        for m in muts:
            print(f"{m['id']:40s} {m['file']}  ->  {' '.join(m['tests'])}")
        return 0
    ids = [m["id"] for m in muts] if args.all else args.ids
    unknown = [i for i in ids if i not in {m["id"] for m in muts}]
    if unknown or not ids:
        print(f"unknown mutation ids: {', '.join(unknown)}" if unknown else "give mutation ids or --all",
              file=sys.stderr)
        return 2
    chosen = [m for m in muts if m["id"] in ids]
    repo = args.repo.resolve()
    if args.check:
        with tempfile.TemporaryDirectory(dir=args.scratch) as tmp:
            base = Path(tmp) / "base"
            snapshot(repo, base)
            bad = 0
            for m in chosen:
                target = base / m["file"]
                original = target.read_text() if target.is_file() else None
                why = apply(base, m)
                if original is not None:
                    target.write_text(original)
                print(f"{m['id']:40s} {why or 'ok'}")
                bad += why is not None
        return 1 if bad else 0
    commit = _git(repo, "rev-parse", "--short", "HEAD").decode().strip()
    root = Path(tempfile.mkdtemp(prefix="femcheck-mutations-", dir=args.scratch))
    base = root / "base"
    snapshot(repo, base)
    baselines = None if args.no_baseline else Baselines(base, args.timeout, args.marker)
    json_path, md_path = args.out / "results.json", args.out / "RESULTS.md"
    results = json.loads(json_path.read_text()) if json_path.is_file() else {}
    lock = threading.Lock()
    print(f"{len(chosen)} mutation(s), scratch {root}, HEAD {commit} + working tree", flush=True)
    try:
        with cf.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            futs = {pool.submit(one, m, base, baselines, args.timeout, args.keep, args.marker): m for m in chosen}
            for f in cf.as_completed(futs):
                rec = f.result()
                rec["commit"] = commit
                with lock:
                    results[rec["id"]] = rec
                    write_results(results, muts, json_path, md_path, commit)
                print(f"{rec['id']:40s} {rec['outcome']:15s} {rec.get('time_s', 0):7.1f} s  "
                      f"{rec.get('test') or ''} {rec.get('detail', '')[:120]}", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)
    return 0 if all(results[m["id"]]["outcome"] == "caught" for m in chosen) else 1


if __name__ == "__main__":
    sys.exit(main())
