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
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from lynxsim.errors import LynxsimError
from lynxsim.sweep.runner import Shard, ShardHook, compute_shard
from lynxsim.sweep.spec import SweepSpec
from lynxsim.sweep.table import Table

__all__ = ["RayBackend", "RayUnavailableError", "require_ray"]


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
    """

    address: str | None = None
    max_retries: int = 3
    max_in_flight: int = 0

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
            try:
                ray.init(address=self.address, log_to_driver=False)
            except (ConnectionError, RuntimeError, ValueError) as exc:
                raise RayUnavailableError(
                    f"cannot reach Ray at {self.address or 'a new local instance'}: {exc}"
                ) from None
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
