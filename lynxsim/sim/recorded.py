"""A physics run recorded once, to judge many obstacle placements on its states.

A robot's physics does not depend on where an obstacle stands until something
touches it: an obstacle is a static world geom with zero collision margin, so
until the first contact with it MuJoCo's constraint set, and with it every
step, is that of the scene without it. So the run of a (task, trajectory type,
cube) without the swept obstacle is, state by state and bit for bit, the run
with the obstacle anywhere it is not touched; judged on the recorded states
(:mod:`lynxsim.sim.sweep_judge`), each placement's verdict, first contact time
and, when clear, its clearance come out exactly as a run of its own would give
them. After a first contact the real run differs (the robot pushes against the
obstacle), but its verdict and first contact time are already determined.

A robot records its runs (the arm: :func:`lynxsim.sim.arm.recorded.record_run`)
with the unrecorded hold before the motion (the presettle), since an obstacle
touched there changes the run before its record begins, and
:func:`recorded_run` checks that the hold, replayed on its own, ends in the
state the playback started from, bit for bit, and raises otherwise: the claim
above is tested each time.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import LynxsimError
from lynxsim.scene import Scene
from lynxsim.sim.report import RunReport
from lynxsim.sim.stepping.log import PlaybackLog

__all__ = ["RecordedRun", "ReplayMismatchError", "recorded_run"]

FloatArray = npt.NDArray[np.float64]


class ReplayMismatchError(LynxsimError):
    """The recorded hold does not reproduce the playback's start: the sweep cannot be exact."""


@dataclass(frozen=True)
class RecordedRun:
    """The states of one run in a scene without the swept obstacle.

    Attributes:
        report: The run's report, as ``lynxsim play`` gives it in that scene.
        qpos: Whole states: the hold's steps, then the recorded steps, (H + S, nq).
        hold_steps: H, the number of hold (presettle) states at the start of ``qpos``.
        time_s: Time stamp of each recorded step, (S,) [s] (the playback's).
        scene: The scene it ran in (the swept obstacle removed).
    """

    report: RunReport
    qpos: FloatArray
    hold_steps: int
    time_s: FloatArray
    scene: Scene

    @property
    def steps(self) -> int:
        """S, the recorded steps."""
        return len(self.time_s)


def recorded_run(
    report: RunReport,
    log: PlaybackLog,
    hold_qpos: FloatArray,
    hold_steps: int,
    scene: Scene,
    *,
    label: str,
) -> RecordedRun:
    """A playback and its hold replayed on their own, checked to join, as one recorded run.

    Args:
        report: The playback's report.
        log: Its log.
        hold_qpos: The hold replayed as recorded steps: its states, then (at
            index ``hold_steps``) the state it ends in, (H + 1 + ..., nq).
        hold_steps: H, the hold's length in steps.
        scene: The scene of the run (the swept obstacle removed).
        label: Names the run in the error (task and trajectory type).

    Raises:
        ReplayMismatchError: The replayed hold does not end in the playback's
            first state (the exactness this module relies on does not hold).
    """
    if (
        len(log.qpos) == 0
        or len(hold_qpos) <= hold_steps
        or not np.array_equal(hold_qpos[hold_steps], log.qpos[0])
    ):
        raise ReplayMismatchError(
            f"{label}: the hold replayed on its own does not end in the "
            "playback's first state; the sweep's replay of recorded states would not be exact"
        )
    return RecordedRun(
        report=report,
        qpos=np.concatenate([hold_qpos[:hold_steps], log.qpos]),
        hold_steps=hold_steps,
        time_s=log.time_s.copy(),
        scene=scene,
    )
