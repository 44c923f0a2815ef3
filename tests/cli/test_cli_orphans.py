"""A command killed with SIGKILL leaves no process behind: its pool's workers die with it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

GONE_AFTER_S = 5.0
"""How long the workers may outlive their killed parent [s] (the issue's bound)."""

STARTUP_S = 120.0
"""How long the command may take to start its workers on a loaded machine [s]."""

LONG_SWEEP = """
name = "long"
tasks = ["{tasks}/obstacle_avoidance.toml", "{tasks}/pick_and_place.toml"]
types = ["planned", "line"]
planner_seeds = [0, 1, 2, 3]
rows_per_shard = 1
[obstacle]
name = "cylinder"
[obstacle.grid]
step_mm = 20.0
"""


def _stat(pid: int) -> tuple[int, int, int] | None:
    """(parent, session, start time) of a process, or None once it is gone (zombies too)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2 :].split()
    if fields[0] == "Z":
        return None
    return int(fields[1]), int(fields[3]), int(fields[19])


def _processes() -> dict[int, tuple[int, int, int]]:
    out = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit() and (stat := _stat(int(entry))) is not None:
            out[int(entry)] = stat
    return out


def _descendants(root: int) -> dict[int, int]:
    """Every process below ``root`` or in its session: pid to start time."""
    table = _processes()
    found = {pid: s[2] for pid, s in table.items() if s[1] == root and pid != root}
    grew = True
    while grew:
        grew = False
        for pid, (parent, _, start) in table.items():
            if pid not in found and (parent == root or parent in found):
                found[pid] = start
                grew = True
    return found


def _alive(processes: dict[int, int]) -> list[int]:
    return [pid for pid, start in processes.items() if (s := _stat(pid)) and s[2] == start]


def _kill_and_check(argv: list[str], workers: int, tmp_path: Path) -> None:
    """Start ``lynxsim ARGV``, wait for its workers, SIGKILL it, and find none of them left."""
    proc = subprocess.Popen(
        [sys.executable, "-c", "from lynxsim.cli import run; run()", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
        cwd=tmp_path,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    children: dict[int, int] = {}
    try:
        deadline = time.monotonic() + STARTUP_S
        while len(children) < workers + 1 and time.monotonic() < deadline:  # + resource tracker
            assert proc.poll() is None, proc.communicate()
            time.sleep(0.2)
            children = _descendants(proc.pid)
        assert len(children) >= workers + 1, children
        time.sleep(1.0)  # the workers busy with their first job
        children = _descendants(proc.pid)
        proc.send_signal(signal.SIGKILL)
        killed = time.monotonic()
        proc.communicate(timeout=GONE_AFTER_S)  # end of file: nothing holds its pipes
        while _alive(children) and time.monotonic() < killed + GONE_AFTER_S:
            time.sleep(0.1)
        assert _alive(children) == [], "processes outlived their killed parent"
    finally:
        for pid in _alive(children):  # what this test started, by id
            os.kill(pid, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()
            proc.wait()


@pytest.mark.slow
def test_a_killed_sweep_leaves_no_worker(tmp_path):
    sweep = tmp_path / "long.toml"
    sweep.write_text(LONG_SWEEP.format(tasks=ROOT / "tasks"))
    argv = ["sweep", str(sweep), "--jobs", "2", "--out-dir", str(tmp_path / "out"), "--quiet"]
    _kill_and_check(argv, 2, tmp_path)


@pytest.mark.slow
def test_a_killed_demo_leaves_no_worker(tmp_path):
    argv = ["demo", "--jobs", "2", "--out-dir", str(tmp_path / "out"), "--quiet"]
    argv += ["--tasks", str(ROOT / "tasks")]
    _kill_and_check(argv, 2, tmp_path)
