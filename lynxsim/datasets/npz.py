"""The plain NumPy format: one ``episodes.npz`` and a ``metadata.json`` in the dataset's folder.

``episodes.npz`` is a zip of ``.npy`` arrays (``np.load`` reads it) named as in
Minari's HDF5 files, for episode ``i`` from 0 (``T`` its steps)::

    episode_{i}/observations/observation      (T + 1, n_obs) float64
    episode_{i}/observations/achieved_goal    (T + 1, 3) float64 [m]
    episode_{i}/observations/desired_goal     (T + 1, 3) float64 [m]
    episode_{i}/actions                       (T, n_act) float32, as stepped (noise included)
    episode_{i}/rewards                       (T,) float64
    episode_{i}/terminations                  (T,) bool
    episode_{i}/truncations                   (T,) bool
    episode_{i}/infos/{key}                   (T + 1,) or (T + 1, n_act): row 0 from the reset
    episode_{i}/seed                          () int64, the seed of its reset

(see :class:`~lynxsim.datasets.Episode` for what each holds). Every zip entry
carries the same fixed timestamp (1980-01-01 00:00), unlike :func:`numpy.savez`
which stores the current time: the same data give the same bytes.
"""

from __future__ import annotations

import json
import os
import zipfile
from collections.abc import Iterator
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.datasets.episode import Episode
from lynxsim.errors import InvalidInputError, LynxsimError

__all__ = ["METADATA_FILE", "NPZ_FILE", "NpzWriter", "read_npz"]

NPZ_FILE = "episodes.npz"
"""The arrays' file inside a dataset's folder."""
METADATA_FILE = "metadata.json"
"""The metadata's file inside a dataset's folder."""

_ZIP_TIME = (1980, 1, 1, 0, 0, 0)
"""Timestamp of every zip entry: the earliest a zip can hold."""


def _arrays(episode: Episode, index: int) -> Iterator[tuple[str, npt.NDArray[Any]]]:
    """The entries of one episode: (name without ``.npy``, array)."""
    p = f"episode_{index}"
    for key, obs in episode.observations.items():
        yield f"{p}/observations/{key}", obs
    yield f"{p}/actions", episode.actions
    yield f"{p}/rewards", episode.rewards
    yield f"{p}/terminations", episode.terminations
    yield f"{p}/truncations", episode.truncations
    for key, info in episode.infos.items():
        yield f"{p}/infos/{key}", info
    yield f"{p}/seed", np.array(episode.seed, dtype=np.int64)


class NpzWriter:
    """Writes episodes into ``folder`` one by one (memory holds one episode).

    Use as a context manager; :meth:`finish` completes and checks the dataset.

    Args:
        folder: An existing, empty folder (the temporary one of
            :func:`~lynxsim.fileio.atomic_folder`).
    """

    def __init__(self, folder: Path) -> None:
        self._folder = folder
        self._zip = zipfile.ZipFile(folder / NPZ_FILE, "w", allowZip64=True)
        self._entries = 0
        self._episodes = 0

    def __enter__(self) -> NpzWriter:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self._zip.close()

    def add(self, episode: Episode) -> None:
        """Append an episode."""
        for name, array in _arrays(episode, self._episodes):
            info = zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            with self._zip.open(info, "w", force_zip64=True) as f:
                np.lib.format.write_array(f, array, allow_pickle=False)
            self._entries += 1
        self._episodes += 1

    def finish(self, metadata: dict[str, Any]) -> None:
        """Close the arrays' file, write ``metadata.json``, and check the arrays read back.

        Raises:
            LynxsimError: The file does not read back whole (a bad CRC, entries missing).
        """
        self._zip.close()
        path = self._folder / NPZ_FILE
        with zipfile.ZipFile(path) as z:
            bad = z.testzip()
            entries = len(z.namelist())
        if bad is not None or entries != self._entries:
            raise LynxsimError(
                f"{path} does not read back: {entries} of {self._entries} entries, "
                f"first bad entry {bad}"
            )
        text = json.dumps(metadata, indent=2) + "\n"
        (self._folder / METADATA_FILE).write_text(text, encoding="utf-8")


def read_npz(folder: str | os.PathLike[str]) -> tuple[Episode, ...]:
    """The episodes of an NPZ dataset, in order.

    Args:
        folder: The dataset's folder (``OUT/DATASET_ID``).

    Returns:
        One :class:`~lynxsim.datasets.Episode` per episode.

    Raises:
        InvalidInputError: Not an NPZ dataset of this layout.
    """
    folder = Path(folder)
    try:
        metadata = json.loads((folder / METADATA_FILE).read_text(encoding="utf-8"))
        count = int(metadata["total_episodes"])
        with np.load(folder / NPZ_FILE, allow_pickle=False) as z:
            names: dict[str, list[str]] = {}
            for name in z.files:  # in the order written
                names.setdefault(name.split("/", 1)[0], []).append(name)
            return tuple(_episode(z, names[f"episode_{i}"], i) for i in range(count))
    except (OSError, ValueError, KeyError, TypeError, zipfile.BadZipFile) as exc:
        raise InvalidInputError(f"{folder} is not a lynxsim NPZ dataset: {exc}") from None


def _episode(z: Any, names: list[str], index: int) -> Episode:
    p = f"episode_{index}/"

    def group(sub: str) -> dict[str, npt.NDArray[Any]]:
        start = p + sub
        return {n[len(start) :]: z[n] for n in names if n.startswith(start)}

    return Episode(
        seed=int(z[p + "seed"]),
        observations=group("observations/"),
        actions=z[p + "actions"],
        rewards=z[p + "rewards"],
        terminations=z[p + "terminations"],
        truncations=z[p + "truncations"],
        infos=group("infos/"),
    )
