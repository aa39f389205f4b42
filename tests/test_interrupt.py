"""Ctrl-C and SIGTERM stop a sweep at once (issue 16 item 3): one line on stderr, a non-zero exit, no traceback,
no worker left behind, nothing written."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

CLI = [sys.executable, "-m", "femcheck.cli"]


def _session_pids(sid: int) -> list[int]:
    """Live processes of session ``sid`` (the sweep was started in a session of its own)."""
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rpartition(")")[2].split()
            except OSError:
                continue
            if int(fields[3]) == sid and fields[0] != "Z":          # session id; zombies are gone already
                out.append(int(d.name))
    return out


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
@pytest.mark.parametrize("signum,group", [(signal.SIGINT, True), (signal.SIGINT, False), (signal.SIGTERM, False)])
def test_signal_stops_sweep_and_every_worker(tmp_path, signum, group):
    # a sweep slow enough to be interrupted mid-way: 16 BEM cases on a fine grid, two workers
    out = tmp_path / "stress"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen([*CLI, "stress", "hertz-point", "--set", "numerics.bem_cells=193", "--workers", "2",
                             "--out", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, env=env)
    try:
        line = proc.stdout.readline()               # "stress hertz-point: 16 cases, ..." once the sweep starts
        assert "16 cases" in line, line
        time.sleep(2.0)                             # the workers are busy with their first cases
        assert len(_session_pids(proc.pid)) >= 3, "expected the parent and two workers"
        (os.killpg if group else os.kill)(proc.pid, signum)    # group: what a terminal's Ctrl-C does
        t0 = time.monotonic()
        stdout, stderr = proc.communicate(timeout=10)
        deadline = t0 + 5.0
        while _session_pids(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _session_pids(proc.pid) == [], "worker processes left behind"
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 128 + signum
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and "interrupted" in lines[0] and signal.Signals(signum).name in lines[0], stderr
    assert "Traceback" not in stderr + stdout
    assert not out.exists()
