"""The Ray backend: a sweep's shards as Ray tasks, on this machine or a cluster.

Ray is optional (``pip install "lynxsim[cluster]"``); nothing else in lynxsim
imports it, and this module imports it only when a sweep runs. Each shard is
one task (:func:`lynxsim.sweep.runner.compute_shard`, one CPU); its rows come
back to this process, which saves the shard at once, so a worker, or a node,
lost mid-shard loses only that shard, which Ray runs again
(:attr:`RayBackend.max_retries`). The table is the same, bit for bit, as the
local backend's where the workers run the same build of lynxsim and MuJoCo.

On a cluster every node needs the same lynxsim, MuJoCo and Ray installed (a
shared environment or image); only the task files travel, inside the sweep.
An address (``HOST:PORT`` or Ray Client's ``ray://HOST:PORT``, which the
``cluster`` extra installs) is tried first with a plain TCP connection that
must answer within :attr:`RayBackend.connect_timeout_s`: nothing listening
there is one clear error at once, not Ray retrying for minutes. Ray's own log
lines stay off stderr unless :attr:`RayBackend.verbose`.
"""

from __future__ import annotations

import logging
import os
import socket
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.sweep.runner import Shard, ShardHook, compute_shard
from lynxsim.sweep.spec import SweepSpec
from lynxsim.sweep.table import Table

__all__ = ["CONNECT_TIMEOUT_S", "RayBackend", "RayUnavailableError", "require_ray"]

CONNECT_TIMEOUT_S = 10.0
"""How long the address may take to accept a connection [s]."""

_GCS_WAIT_S = "5"
"""Ray's budget for reaching a cluster's GCS once its port answers [s] (its default is minutes)."""


class RayUnavailableError(LynxsimError):
    """Ray is not installed, or no Ray instance could be reached."""


def require_ray() -> Any:
    """The ``ray`` module.

    Raises:
        RayUnavailableError: Ray is not installed (says how to install it).
    """
    try:
        import ray
    except ImportError:
        raise RayUnavailableError(
            "--backend ray needs Ray, which is not installed: pip install 'lynxsim[cluster]'"
        ) from None
    return ray


@dataclass(frozen=True)
class RayBackend:
    """Shards as Ray tasks.

    Attributes:
        address: The Ray cluster's address (``ray://HOST:10001`` or
            ``HOST:6379``; ``"auto"`` for the one this machine belongs to), or None:
            the instance this process already started (``ray.init``), else a new
            local one.
        max_retries: How often Ray runs a shard again whose worker died.
        max_in_flight: Shards submitted at a time (0: all at once).
        connect_timeout_s: How long the address may take to accept a TCP
            connection [s].
        verbose: Ray's own log lines on stderr (else only its errors).
    """

    address: str | None = None
    max_retries: int = 3
    max_in_flight: int = 0
    connect_timeout_s: float = CONNECT_TIMEOUT_S
    verbose: bool = False

    def __post_init__(self) -> None:
        if self.address is not None:
            _host_port(self.address)  # a malformed address is refused before any work starts

    def run(
        self,
        spec: SweepSpec,
        todo: list[Shard],
        done: Callable[[Shard, Table], None],
        hook: ShardHook | None = None,
    ) -> None:
        """Compute the shards as Ray tasks; ``done`` runs here as each result arrives.

        Raises:
            RayUnavailableError: Ray is missing or the address cannot be reached.
        """
        ray = require_ray()
        started = False
        if not ray.is_initialized():
            if self.address is not None:
                _probe(self.address, self.connect_timeout_s)
                os.environ.setdefault("RAY_gcs_server_port_wait_time_s", _GCS_WAIT_S)
            try:
                with warnings.catch_warnings():
                    if not self.verbose:  # Ray Client warns before it fails
                        warnings.simplefilter("ignore")
                    ray.init(
                        address=self.address,
                        log_to_driver=self.verbose,
                        logging_level=logging.INFO if self.verbose else logging.ERROR,
                    )
            except (ConnectionError, RuntimeError, ValueError) as exc:
                where = self.address or "a new local instance"
                raise RayUnavailableError(f"cannot reach Ray at {where}: {exc}") from None
            started = True
        try:
            remote = ray.remote(num_cpus=1, max_retries=self.max_retries)(compute_shard)
            spec_ref = ray.put(spec)
            queue = list(todo)
            limit = self.max_in_flight or len(queue)
            pending: dict[Any, Shard] = {}
            while queue or pending:
                while queue and len(pending) < limit:
                    shard = queue.pop(0)
                    pending[remote.remote(spec_ref, shard, hook)] = shard
                ready, _ = ray.wait(list(pending), num_returns=1)
                for ref in ready:
                    shard = pending.pop(ref)
                    try:
                        rows = ray.get(ref)
                    except LynxsimError:
                        raise
                    except ray.exceptions.RayError as exc:
                        raise RayUnavailableError(
                            f"shard {shard.index} failed on Ray: {str(exc).splitlines()[0]}"
                        ) from None
                    done(shard, rows)
        finally:
            if started:
                ray.shutdown()


def _host_port(address: str) -> tuple[str, int] | None:
    """The host and port of ``address``; None for ``auto`` and ``local`` (left to Ray).

    Raises:
        InvalidInputError: The address is not ``HOST:PORT``, ``ray://HOST:PORT``, ``auto`` or
            ``local``.
    """
    if address in ("auto", "local"):
        return None
    host, _, port = address.removeprefix("ray://").rpartition(":")
    host = host.strip("[]")
    if not host or not port.isdigit() or not 1 <= int(port) <= 65535:
        raise InvalidInputError(
            f"--address {address!r}: expected HOST:PORT, ray://HOST:PORT or auto"
        )
    return host, int(port)


def _probe(address: str, timeout_s: float) -> None:
    """Check that ``address`` (``HOST:PORT`` or ``ray://HOST:PORT``) accepts a TCP connection.

    ``auto`` and ``local`` are left to Ray (it finds or starts the instance itself).

    Raises:
        InvalidInputError: The address is not of that form.
        RayUnavailableError: Nothing accepts a connection there within ``timeout_s``.
    """
    where = _host_port(address)
    if where is None:
        return
    try:
        socket.create_connection(where, timeout=timeout_s).close()
    except OSError as exc:
        why = exc.strerror or str(exc) or type(exc).__name__
        raise RayUnavailableError(
            f"cannot reach Ray at {address}: no answer within {timeout_s:g} s ({why})"
        ) from None
