"""``lynxsim sweep --backend ray`` as a user runs it: a real local Ray instance, a real head.

An address where nothing listens ends in one line within a bounded time; a
successful run keeps Ray's own log lines off stderr unless ``--verbose``; the
``ray://`` form of the README works with the ``cluster`` extra (Ray Client),
against a head started here with ``ray start --head --block`` and stopped by
its process id.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from tests.cli.test_cli_sweep import SMALL

pytest.importorskip("ray")

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]

UNREACHABLE_BOUND_S = 60.0
"""The longest an unreachable address may keep the command waiting [s] (the deadline
is shorter; this bound leaves room for Python, Ray's import and a loaded machine)."""


TOKEN = {"RAY_AUTH_MODE": "token", "RAY_AUTH_TOKEN": secrets.token_hex(16)}
"""Ray's token authentication for the head started here and its clients (Ray Client sends
the token only where ``RAY_AUTH_MODE=token``)."""


def _lynxsim(
    *argv: str, cwd: Path, timeout: float = 300.0, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", "from lynxsim.cli import run; run()", *argv],
        capture_output=True,
        text=True,
        timeout=timeout,
        cwd=cwd,
        env={**os.environ, "MUJOCO_GL": "egl", **(env or {})},
    )


@pytest.fixture
def small(tmp_path: Path) -> Path:
    path = tmp_path / "small.toml"
    path.write_text(SMALL.format(tasks=ROOT / "tasks"))
    return path


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.mark.parametrize("address", ["127.0.0.1:1", "ray://127.0.0.1:1"])
def test_an_address_where_nothing_listens_is_one_line_within_a_bound(small, tmp_path, address):
    result = _lynxsim(
        "sweep", str(small), "--backend", "ray", "--address", address, "--quiet",
        "--out-dir", str(tmp_path / "out"), cwd=tmp_path, timeout=UNREACHABLE_BOUND_S,
    )  # fmt: skip
    assert result.returncode == 1
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"lynxsim: error: cannot reach Ray at {address}")
    assert not (tmp_path / "out").exists()


def test_a_local_ray_run_keeps_rays_log_lines_off_stderr_unless_verbose(small, tmp_path):
    quiet = _lynxsim(
        "sweep", str(small), "--backend", "ray", "--quiet", "--json", "--no-maps",
        "--out-dir", str(tmp_path / "quiet"), cwd=tmp_path,
    )  # fmt: skip
    assert quiet.returncode == 0, quiet.stderr
    assert json.loads(quiet.stdout)["runs"] == 20
    assert quiet.stderr == ""
    verbose = _lynxsim(
        "sweep", str(small), "--backend", "ray", "--quiet", "--json", "--no-maps", "--verbose",
        "--out-dir", str(tmp_path / "verbose"), cwd=tmp_path,
    )  # fmt: skip
    assert verbose.returncode == 0, verbose.stderr
    assert "Ray" in verbose.stderr


@pytest.fixture
def ray_head():
    """A Ray head on this machine with its Ray Client server; yields the client port.

    Its temporary folder is its own and short (Ray's socket paths must fit in 107
    bytes), so that no other Ray instance of this machine finds it or is found.
    ``GRPC_ENABLE_FORK_SUPPORT=0``, as docs/sweeps.md tells users: the Ray Client proxy forks
    each client's server while gRPC threads run, and with gRPC's fork handlers that child
    died at once in 4 of 8 tries here ("Starting Ray client server failed"); 0 of 14 without.
    """
    port, client = _free_port(), _free_port()
    temp = Path(tempfile.mkdtemp(prefix="lxray", dir="/tmp"))
    ray_bin = Path(sys.executable).parent / "ray"
    log = temp / "head.log"
    with log.open("wb") as out:
        head = subprocess.Popen(
            [
                str(ray_bin), "start", "--head", "--block", f"--port={port}",
                f"--ray-client-server-port={client}", "--num-cpus=1", "--include-dashboard=false",
                f"--temp-dir={temp}", "--disable-usage-stats",
            ],
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
            env={**os.environ, **TOKEN, "GRPC_ENABLE_FORK_SUPPORT": "0"},
        )  # fmt: skip
    try:
        deadline = time.monotonic() + 180.0
        while "Ray runtime started" not in log.read_text(errors="replace"):
            assert head.poll() is None, log.read_text(errors="replace")
            assert time.monotonic() < deadline, log.read_text(errors="replace")
            time.sleep(0.5)
        yield client
    finally:
        head.send_signal(signal.SIGTERM)  # --block: it stops what it started
        try:
            head.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(head.pid, signal.SIGKILL)
            head.wait()
        shutil.rmtree(temp, ignore_errors=True)


def test_the_ray_client_form_of_the_readme_runs_a_sweep(small, tmp_path, ray_head):
    result = _lynxsim(
        "sweep", str(small), "--backend", "ray", "--address", f"ray://127.0.0.1:{ray_head}",
        "--quiet", "--json", "--no-maps", "--out-dir", str(tmp_path / "out"), cwd=tmp_path,
        env=TOKEN,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    assert summary["runs"] == 20
    assert summary["shards_computed"] == 1
