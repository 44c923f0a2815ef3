"""Minari's standard format (HDF5 storage), behind the optional extra ``lynxsim[datasets]``.

Minari is imported here only, when a Minari dataset is written: the rest of
lynxsim never needs it. The dataset's folder is ``ROOT/DATASET_ID`` with Minari's
``data/main_data.hdf5`` and ``data/metadata.json``; with ``MINARI_DATASETS_PATH=ROOT``,
``minari.load_dataset(DATASET_ID)`` finds it, and ``recover_environment()`` makes
the env from the spec stored in the metadata. Each namespace folder above it
gets Minari's ``namespace_metadata.json`` (an empty one) if it has none, as
``minari.create_namespace`` would write.

The HDF5 file holds no timestamp (h5py does not track object times by default):
the same episodes give the same bytes, as does ``metadata.json``.

HDF5 does not survive a failed write: on a full disk h5py reports errors it
cannot raise and the process may then crash (a segmentation fault). So the
HDF5 file is written by a process of its own (spawned; it dies with this one,
:func:`lynxsim.processes.die_with_parent`), which stops at the first failed
write; :class:`MinariWriter` waits for it to end, so that the file is closed,
and raises one :class:`DatasetWriteError` saying why, before the temporary
folder is removed.
"""

from __future__ import annotations

import contextlib
import json
import multiprocessing
import os
import re
import sys
from dataclasses import dataclass
from multiprocessing.connection import Connection
from pathlib import Path
from types import ModuleType, TracebackType
from typing import Any, NoReturn

import gymnasium as gym
from gymnasium.envs.registration import EnvSpec

from lynxsim.datasets.episode import Episode
from lynxsim.errors import LynxsimError
from lynxsim.fileio import write_json
from lynxsim.processes import die_with_parent

__all__ = [
    "DatasetWriteError",
    "MinariWriter",
    "MissingExtraError",
    "require_minari",
    "write_namespaces",
]

_STOP_S = 30.0
"""How long the writer process may take to end once asked [s]."""

_NAMESPACE_FILE = "namespace_metadata.json"
"""Minari's marker of a namespace folder."""


class MissingExtraError(LynxsimError, ImportError):
    """An optional dependency of lynxsim is not installed (the message says which extra)."""


class DatasetWriteError(LynxsimError, OSError):
    """The dataset could not be written (a full disk, a failed write); the message says why."""


def require_minari() -> ModuleType:
    """The ``minari`` module, with its HDF5 storage available.

    Raises:
        MissingExtraError: Minari or h5py is not installed.
    """
    try:
        import h5py  # noqa: F401  (Minari's HDF5 storage needs it)
        import minari
    except ImportError as exc:
        raise MissingExtraError(
            f"the Minari format needs the 'datasets' extra: pip install 'lynxsim[datasets]' "
            f"(or use --format npz) [{exc}]"
        ) from None
    module: ModuleType = minari
    return module


def write_namespaces(root: Path, dataset_id: str) -> None:
    """Mark each namespace folder of ``dataset_id`` under ``root`` as Minari does, if unmarked."""
    parts = dataset_id.split("/")[:-1]
    for depth in range(1, len(parts) + 1):
        marker = root.joinpath(*parts[:depth], _NAMESPACE_FILE)
        if not marker.exists():
            write_json(marker, {})


class _Store:
    """Minari's storage of one dataset, in the writer process (see :class:`MinariWriter`)."""

    def __init__(self, folder: Path, spaces: _Spaces, dataset_id: str, description: str) -> None:
        minari = require_minari()
        from minari.dataset.minari_storage import MinariStorage

        self._data = folder.resolve() / "data"  # Minari's size count fails on relative paths
        self._storage = MinariStorage.new(
            self._data,
            observation_space=spaces.observation,
            action_space=spaces.action,
            env_spec=spaces.spec,
            data_format="hdf5",
            jpeg_encoding=False,
        )
        self._storage.update_metadata(
            {
                "dataset_id": dataset_id,
                "minari_version": minari.__version__,
                "algorithm_name": "lynxsim scripted expert with Gaussian action noise",
                "description": description,
            }
        )
        self._episodes = 0
        self._steps = 0

    def add(self, episode: Episode) -> None:
        """Append an episode."""
        from minari.data_collector import EpisodeBuffer

        buffer = EpisodeBuffer(
            id=self._episodes,
            seed=episode.seed,
            observations=episode.observations,
            actions=episode.actions,
            rewards=episode.rewards,  # arrays work where Minari's annotation says list
            terminations=episode.terminations,
            truncations=episode.truncations,
            infos=episode.infos,
        )
        self._storage.update_episodes([buffer])
        self._episodes += 1
        self._steps += episode.steps

    def finish(self, metadata: dict[str, Any]) -> None:
        """Store lynxsim's metadata (under the key ``"lynxsim"``) and check the dataset loads.

        Raises:
            LynxsimError: Minari reads back other counts of episodes or steps.
        """
        import minari

        self._storage.update_metadata({"lynxsim": json.loads(json.dumps(metadata))})
        dataset = minari.MinariDataset(self._data)
        counts = (dataset.total_episodes, dataset.total_steps)
        if counts != (self._episodes, self._steps):
            raise LynxsimError(
                f"Minari reads back {counts[0]} episodes and {counts[1]} steps "
                f"of the {self._episodes} and {self._steps} written"
            )


@dataclass(frozen=True)
class _Spaces:
    """What Minari stores of the env: its spaces and spec (picklable, unlike the env)."""

    observation: gym.Space[Any]
    action: gym.Space[Any]
    spec: EnvSpec | None


_HDF5_REASON = re.compile(r"error message = '([^']*)'")


def _reason(exc: BaseException) -> str:
    """Why a write failed, in a few words: the system's message where there is one."""
    text = str(exc)
    found = _HDF5_REASON.search(text)
    if found:
        return found.group(1)
    if isinstance(exc, OSError) and exc.errno:
        return os.strerror(exc.errno)
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return f"{type(exc).__name__}: {lines[0]}" if lines else type(exc).__name__


def _serve(
    conn: Connection,
    parent: int,
    folder: Path,
    spaces: _Spaces,
    dataset_id: str,
    description: str,
) -> None:
    """The writer process: requests from ``conn``, one reply each; ends at the first failure."""
    die_with_parent(parent)
    os.dup2(os.open(os.devnull, os.O_WRONLY), 2)  # h5py's reports of a failure: one line instead

    def fail(exc: BaseException) -> NoReturn:
        conn.send(("error", _reason(exc)))
        os._exit(1)  # before HDF5, broken by the failed write, is used again

    sys.unraisablehook = lambda unraisable: fail(unraisable.exc_value or RuntimeError())
    try:
        store = _Store(folder, spaces, dataset_id, description)
    except Exception as exc:  # any failure of the writer ends it, reported in one line
        fail(exc)
    conn.send(("ok", ""))
    while True:
        op, arg = conn.recv()
        if op == "close":
            return
        try:
            if op == "add":
                store.add(arg)
            else:
                store.finish(arg)
        except LynxsimError as exc:
            conn.send(("lynxsim", str(exc)))
            continue
        except Exception as exc:  # any failure of the writer ends it, reported in one line
            fail(exc)
        conn.send(("ok", ""))


class MinariWriter:
    """Writes episodes into ``folder`` as a Minari dataset, one by one, in a process of its own.

    Use as a context manager (leaving it ends the writer process);
    :meth:`finish` completes and checks the dataset.

    Args:
        folder: An existing, empty folder (the temporary one of
            :func:`~lynxsim.fileio.atomic_folder`).
        env: The env the episodes come from (made by ``gym.make``: its spec is
            stored, for ``recover_environment()``).
        dataset_id: The dataset's Minari id.
        description: Free text stored in the metadata.

    Raises:
        MissingExtraError: Minari is not installed.
        DatasetWriteError: The dataset cannot be created there.
    """

    def __init__(
        self, folder: Path, env: gym.Env[Any, Any], dataset_id: str, description: str
    ) -> None:
        require_minari()
        context = multiprocessing.get_context("spawn")  # no forked MuJoCo or HDF5 state
        self._conn, child = context.Pipe()
        spaces = _Spaces(env.observation_space, env.action_space, env.spec)
        self._process = context.Process(
            target=_serve,
            args=(child, os.getpid(), folder, spaces, dataset_id, description),
            name="minari-writer",
            daemon=True,
        )
        self._process.start()
        child.close()
        self._call("", None)

    def __enter__(self) -> MinariWriter:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        """End the writer process (its HDF5 file closed) before anything else happens."""
        self._stop()

    def add(self, episode: Episode) -> None:
        """Append an episode.

        Raises:
            DatasetWriteError: It could not be written.
        """
        self._call("add", episode)

    def finish(self, metadata: dict[str, Any]) -> None:
        """Store lynxsim's metadata (under the key ``"lynxsim"``) and check the dataset loads.

        Raises:
            LynxsimError: Minari reads back other counts of episodes or steps.
            DatasetWriteError: It could not be written.
        """
        self._call("finish", metadata)

    def _call(self, op: str, arg: object) -> None:
        """Send a request (none for ``op == ""``) and wait for its reply."""
        try:
            if op:
                self._conn.send((op, arg))
            kind, message = self._conn.recv()
        except (EOFError, OSError):
            kind, message = "error", "the writer process ended"
        if kind == "ok":
            return
        if kind == "lynxsim":
            raise LynxsimError(message)
        self._stop()
        raise DatasetWriteError(f"cannot write the Minari dataset: {message}")

    def _stop(self) -> None:
        if self._process.is_alive():
            with contextlib.suppress(OSError):  # it ended meanwhile
                self._conn.send(("close", None))
            self._process.join(_STOP_S)
        if self._process.is_alive():
            self._process.kill()
            self._process.join()
        self._conn.close()
