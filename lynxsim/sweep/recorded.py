"""A physics run recorded once, to judge many obstacle placements on its states.

The arm's physics does not depend on where an obstacle stands until something
touches it: an obstacle is a static world geom with zero collision margin, so
until the first contact with it MuJoCo's constraint set, and with it every
step, is that of the scene without it. So the run of a (task, trajectory type,
cube) without the swept obstacle is, state by state and bit for bit, the run
with the obstacle anywhere it is not touched; judged on the recorded states
(:mod:`lynxsim.sweep.placements`), each placement's verdict, first contact time
and, when clear, its clearance come out exactly as a run of its own would give
them. After a first contact the real run differs (the servos push against the
obstacle), but its verdict and first contact time are already determined.

:func:`record_run` plays the run as ``lynxsim play`` does
(:func:`~lynxsim.sim.arm.task.run_arm_trajectory`, whose report is kept) and
also records the unrecorded hold before the motion (the presettle), since an
obstacle touched there changes the run before its record begins. It checks
that the hold, replayed on its own, ends in the state the playback started
from, bit for bit, and raises otherwise: the claim above is tested each time.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.arm import tool_pose
from lynxsim.errors import LynxsimError
from lynxsim.scene import Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding
from lynxsim.sim.arm.task import pick_and_place_gripper, run_arm_trajectory
from lynxsim.sim.report import RunReport
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.traj import Trajectory

__all__ = ["RecordedRun", "ReplayMismatchError", "record_run"]

FloatArray = npt.NDArray[np.float64]

_PRESETTLE_S: float = inspect.signature(rollout).parameters["presettle_s"].default
"""The hold before the motion of every playback [s] (``rollout``'s own default)."""


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


def _hold_states(
    model: mujoco.MjModel, trajectory: Trajectory, gripper: bool
) -> tuple[FloatArray, int]:
    """The hold before the motion replayed as recorded steps: its states and its length.

    ``rollout`` with no hold, given the hold's commands (the first sample,
    repeated) before the trajectory's, steps the same physics from the same
    reset; its first H states are the hold's, its state H the playback's first.
    """
    dt = float(model.opt.timestep)
    # The whole grid sampled, as the playback samples it (one time alone may round otherwise).
    q_first = trajectory.sample(physics_grid(trajectory.duration, dt)).q[:1]
    hold = round(_PRESETTLE_S / dt)
    q_cmd = np.repeat(q_first, hold + 1, axis=0)
    schedule = pick_and_place_gripper(trajectory.duration)

    def gripper_at(t: float) -> float:  # step k of this run is step k - H of the playback
        return schedule((round(t / dt) - hold) * dt)

    log = rollout(
        model,
        mujoco.MjData(model),
        arm_binding(model),
        q_cmd,
        tool_pose(q_cmd).position,
        task="hold",
        trajectory=trajectory.kind.value,
        settle_s=0.0,
        presettle_s=0.0,
        gripper_cmd=gripper_at if gripper else None,
    )
    return log.qpos, hold


def record_run(trajectory: Trajectory, *, task: str, scene: Scene) -> RecordedRun:
    """Play a trajectory in a scene as ``lynxsim play`` does, keeping every state.

    Args:
        trajectory: The joint trajectory.
        task: Task name for the report.
        scene: The scene without the swept obstacle.

    Returns:
        The :class:`RecordedRun`.

    Raises:
        ReplayMismatchError: The replayed hold does not end in the playback's
            first state (the exactness this module relies on does not hold).
        LynxsimError: The trajectory cannot be played (see ``rollout``).
    """
    playback = run_arm_trajectory(trajectory, task=task, scene=scene)
    log = playback.log
    hold_qpos, hold = _hold_states(load_arm_scene(scene), trajectory, scene.cube is not None)
    if (
        len(log.qpos) == 0
        or len(hold_qpos) <= hold
        or not np.array_equal(hold_qpos[hold], log.qpos[0])
    ):
        raise ReplayMismatchError(
            f"{task} {trajectory.kind.value}: the hold replayed on its own does not end in the "
            "playback's first state; the sweep's replay of recorded states would not be exact"
        )
    return RecordedRun(
        report=playback.report,
        qpos=np.concatenate([hold_qpos[:hold], log.qpos]),
        hold_steps=hold,
        time_s=log.time_s.copy(),
        scene=scene,
    )
