"""Feature statistics of a LeRobot dataset: the episodes' ``stats/`` columns, ``meta/stats.json``.

LeRobot keeps, for every feature but strings, ``min``, ``max``, ``mean``, ``std``
(population), ``count`` (frames) and the quantiles ``q01``, ``q10``, ``q50``,
``q90``, ``q99`` (its normalisers read them). Per episode they are exact here
(quantiles by linear interpolation, as :func:`numpy.quantile`); images are
reduced per channel, in [0, 1] (uint8 / 255), shape (3, 1, 1), from the
frames' histograms (exact for uint8, and memory-light). The dataset's
statistics aggregate the episodes' as LeRobot's own writer does: min and max
of the episodes', mean and std of all frames (merged with Chan's update), and
for the quantiles a bound over the episodes (the least of ``q01``..``q50``, the
largest of ``q90`` and ``q99``), not the quantile of all frames.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["QUANTILES", "RunningStats", "Stats", "feature_stats", "image_stats"]

FloatArray = npt.NDArray[np.float64]
Stats = dict[str, FloatArray]
"""One feature's statistics: name (``"min"``, ..., ``"q99"``) to an array of the feature's shape
(``count``: shape (1,))."""

QUANTILES: dict[str, float] = {"q01": 0.01, "q10": 0.10, "q50": 0.50, "q90": 0.90, "q99": 0.99}
"""LeRobot's quantile names and levels."""

_UINT8_LEVELS = 256


def feature_stats(values: npt.ArrayLike) -> Stats:
    """Statistics of one episode's frames of a numeric feature.

    Args:
        values: Shape (N, *shape) with N >= 1 frames; bools count as 0 and 1.

    Returns:
        The :data:`Stats`, each of shape ``shape`` (``count``: (1,), N).
    """
    x = np.asarray(values).astype(np.float64)
    stats: Stats = {
        "min": x.min(axis=0),
        "max": x.max(axis=0),
        "mean": x.mean(axis=0),
        "std": x.std(axis=0),
        "count": np.array([x.shape[0]], dtype=np.float64),
    }
    levels = np.quantile(x, list(QUANTILES.values()), axis=0)
    for i, name in enumerate(QUANTILES):
        stats[name] = levels[i]
    return stats


def _histogram_quantile(cumulative: npt.NDArray[np.int64], q: float) -> float:
    """``np.quantile`` (linear) of the values 0..255 counted by ``cumulative`` (their cumsum)."""
    position = q * (int(cumulative[-1]) - 1)
    low = int(np.floor(position))
    below = int(np.searchsorted(cumulative, low, side="right"))
    above = int(np.searchsorted(cumulative, min(low + 1, int(cumulative[-1]) - 1), side="right"))
    return float(below + (position - low) * (above - below))


def image_stats(frames: npt.NDArray[np.uint8]) -> Stats:
    """Per-channel statistics of one episode's RGB frames, in [0, 1].

    Args:
        frames: Shape (N, H, W, C), uint8.

    Returns:
        The :data:`Stats`, each of shape (C, 1, 1) (``count``: (1,), N).
    """
    channels = frames.shape[-1]
    names = ["min", "max", "mean", "std", *QUANTILES]
    out = {name: np.empty(channels) for name in names}
    levels = np.arange(_UINT8_LEVELS, dtype=np.float64)
    for c in range(channels):
        hist = np.bincount(frames[..., c].ravel(), minlength=_UINT8_LEVELS)
        present = np.flatnonzero(hist)
        n = int(hist.sum())
        mean = float(hist @ levels) / n
        out["min"][c], out["max"][c] = present[0], present[-1]
        out["mean"][c] = mean
        out["std"][c] = np.sqrt(float(hist @ (levels - mean) ** 2) / n)
        cumulative = np.cumsum(hist)
        for name, q in QUANTILES.items():
            out[name][c] = _histogram_quantile(cumulative, q)
    stats: Stats = {k: (v / (_UINT8_LEVELS - 1)).reshape(channels, 1, 1) for k, v in out.items()}
    stats["count"] = np.array([frames.shape[0]], dtype=np.float64)
    return {k: stats[k] for k in ["min", "max", "mean", "std", "count", *QUANTILES]}


@dataclass
class RunningStats:
    """The dataset's statistics of one feature, merged episode by episode.

    Attributes:
        stats: The merge so far (None before the first episode).
        m2: Sum of squared deviations from ``stats["mean"]`` over all frames.
    """

    stats: Stats | None = None
    m2: FloatArray | None = None

    def add(self, episode: Stats) -> None:
        """Merge one episode's statistics."""
        nb = float(episode["count"][0])
        m2b = episode["std"] ** 2 * nb
        if self.stats is None or self.m2 is None:
            self.stats = {k: v.copy() for k, v in episode.items()}
            self.m2 = m2b
            return
        s = self.stats
        na = float(s["count"][0])
        n = na + nb
        delta = episode["mean"] - s["mean"]
        s["mean"] = s["mean"] + delta * (nb / n)
        self.m2 = self.m2 + m2b + delta**2 * (na * nb / n)
        s["std"] = np.sqrt(self.m2 / n)
        s["count"] = np.array([n])
        s["min"] = np.minimum(s["min"], episode["min"])
        s["max"] = np.maximum(s["max"], episode["max"])
        for name, q in QUANTILES.items():
            pick = np.minimum if q <= 0.5 else np.maximum
            s[name] = pick(s[name], episode[name])
