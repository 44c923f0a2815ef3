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
"""

from __future__ import annotations

import json
from pathlib import Path
from types import ModuleType, TracebackType
from typing import Any

import gymnasium as gym

from lynxsim.datasets.episode import Episode
from lynxsim.errors import LynxsimError
from lynxsim.fileio import write_json

__all__ = ["MinariWriter", "MissingExtraError", "require_minari", "write_namespaces"]

_NAMESPACE_FILE = "namespace_metadata.json"
"""Minari's marker of a namespace folder."""


class MissingExtraError(LynxsimError, ImportError):
    """An optional dependency of lynxsim is not installed (the message says which extra)."""


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


class MinariWriter:
    """Writes episodes into ``folder`` as a Minari dataset, one by one.

    Use as a context manager; :meth:`finish` completes and checks the dataset.

    Args:
        folder: An existing, empty folder (the temporary one of
            :func:`~lynxsim.fileio.atomic_folder`).
        env: The env the episodes come from (made by ``gym.make``: its spec is
            stored, for ``recover_environment()``).
        dataset_id: The dataset's Minari id.
        description: Free text stored in the metadata.

    Raises:
        MissingExtraError: Minari is not installed.
    """

    def __init__(
        self, folder: Path, env: gym.Env[Any, Any], dataset_id: str, description: str
    ) -> None:
        minari = require_minari()
        from minari.dataset.minari_storage import MinariStorage

        self._data = folder.resolve() / "data"  # Minari's size count fails on relative paths
        self._storage = MinariStorage.new(
            self._data,
            observation_space=env.observation_space,
            action_space=env.action_space,
            env_spec=env.spec,
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

    def __enter__(self) -> MinariWriter:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        """Nothing to close: the storage opens its HDF5 file for each write."""

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
