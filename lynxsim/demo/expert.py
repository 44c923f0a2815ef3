"""The environment part of the main job: one episode of the scripted pick-and-place expert."""

from __future__ import annotations

import functools
from pathlib import Path

from lynxsim.demo.jobs import Job
from lynxsim.envs.evaluation import EpisodeStats, record_expert_episode
from lynxsim.envs.registration import PICK_AND_PLACE_ID
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import Quality

__all__ = ["EXPERT_SEED", "EXPERT_VIDEO", "expert_job"]

EXPERT_VIDEO = f"{PICK_AND_PLACE_ID}_expert.mp4"
"""Name of the episode's video in the output folder."""
EXPERT_SEED = 0
"""Seed of the recorded episode."""
_EXPERT_COST = 300.0
"""Cost of the episode (200 frames and its physics), in frames (see :class:`Job`)."""


def _record(dest: Path, quality: Quality, progress: ProgressFn | None) -> EpisodeStats:
    stats = record_expert_episode(dest, seed=EXPERT_SEED, quality=quality.value)
    if progress is not None:
        progress(1.0)
    return stats


def expert_job(out: Path, quality: Quality) -> Job[EpisodeStats]:
    """Record the expert's episode (seed :data:`EXPERT_SEED`) into ``out/EXPERT_VIDEO``."""
    return Job(EXPERT_VIDEO, _EXPERT_COST, functools.partial(_record, out / EXPERT_VIDEO, quality))
