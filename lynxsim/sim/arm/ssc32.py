"""The digital twin: an arm trajectory played through the SSC-32U the real arm would have.

The trajectory becomes the board's command stream (:mod:`lynxsim.real.stream`);
the emulated board plays it (:func:`lynxsim.real.deviation.board_motion`): a
pulse per channel every 20 ms, 1 us steps. Each servo passes its pulse
through its dead band (a servo does not move for a pulse change inside its
dead band: its target follows the pulse with a play of half the band either
way), and the MuJoCo position servo of the joint receives the angle of that
pulse (through the calibration), held for the 20 ms frame. The commanded tool
point stays the ideal trajectory's, so the run report's tracking error is the
distance from the intended motion; the ideal playback of the same trajectory
runs beside it and :class:`TwinComparison` gives the difference.
"""

from __future__ import annotations

import os

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, tool_pose
from lynxsim.arm.motion import tool_poses
from lynxsim.inputs import instance
from lynxsim.real.arm import arm_tool_points, load_arm_calibration
from lynxsim.real.calibration import Calibration
from lynxsim.real.deviation import BoardMotion, board_motion, stream_deviation
from lynxsim.real.stream import StreamOptions, command_stream
from lynxsim.sim.adapter import RealBackend
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.recording import ProgressFn, render_log
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.sim.summary import Playback, summarize
from lynxsim.sim.twin import TwinComparison, TwinRun
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory
from lynxsim.traj.motion import Motion

__all__ = [
    "BACKEND",
    "ArmSsc32",
    "TwinComparison",
    "TwinRun",
    "dead_band",
    "run_twin",
    "servo_targets",
]

FloatArray = npt.NDArray[np.float64]


def dead_band(pulses_us: npt.ArrayLike, width_us: npt.ArrayLike) -> FloatArray:
    """The pulse each servo acts on, given the pulses it receives: a play of half the band.

    Args:
        pulses_us: Received pulses, (F, n) [us].
        width_us: Dead band width per servo, (n,) [us].

    Returns:
        (F, n) [us]: the first row as received; then each row moves only as far
        as needed to stay within half the band of the received pulse.
    """
    p = np.asarray(pulses_us, dtype=float)
    half = np.asarray(width_us, dtype=float) / 2.0
    out = np.empty_like(p)
    held = p[0].copy()
    for k in range(len(p)):
        held = np.clip(held, p[k] - half, p[k] + half)
        out[k] = held
    return out


def servo_targets(motion: BoardMotion, calibration: Calibration, t: FloatArray) -> FloatArray:
    """The joint targets the MuJoCo servos get at times ``t`` on the motion's clock, (T, n) [rad].

    Each time takes the frame being sent then (zero-order hold), after the dead
    band, clipped into the model's joint ranges (a servo stops at its end).
    """
    acted = dead_band(motion.pulses_us, [j.dead_band_us for j in calibration.joints])
    q = np.clip(calibration.angles_rad(acted), LYNX_ARM.q_min, LYNX_ARM.q_max)
    k = np.searchsorted(motion.time_s, t + 1e-9, side="right") - 1
    result: FloatArray = q[np.clip(k, 0, len(q) - 1)]
    return result


def run_twin(
    task: Task,
    trajectory: Trajectory,
    calibration: Calibration,
    options: StreamOptions | None = None,
    *,
    settle_s: float = 0.5,
    video: str | os.PathLike[str] | None = None,
    render: RenderSettings | None = None,
    progress: ProgressFn | None = None,
) -> TwinRun:
    """Play an arm task's trajectory ideally and through the board, in the task's scene.

    Args:
        task: The arm task (its scene, its name).
        trajectory: The trajectory (any type).
        calibration: The arm's calibration.
        options: How the stream is made (defaults if None).
        settle_s: Hold after the motion [s].
        video: MP4 of the twin's run, or None.
        render: Video settings (defaults if None).
        progress: Called with the fraction done.

    Returns:
        The :class:`TwinRun`.

    Raises:
        CommandLimitError: The stream leaves a calibrated pulse range or a speed limit.
    """
    grip = task.scene.cube is not None
    stream = command_stream(trajectory, calibration, options, grip=grip)
    motion = board_motion(stream, calibration)
    deviation = stream_deviation(trajectory, stream, calibration, arm_tool_points, motion)
    model = load_arm_scene(task.scene)
    gripper = pick_and_place_gripper(trajectory.duration) if grip else None
    ideal = play_arm(model, trajectory, task=task.name, settle_s=settle_s, gripper_cmd=gripper)
    if progress is not None:
        progress(0.4)
    t = physics_grid(trajectory.duration, float(model.opt.timestep))
    log = rollout(
        model,
        mujoco.MjData(model),
        arm_binding(model),
        servo_targets(motion, calibration, t),
        tool_pose(trajectory.sample(t).q).position,
        task=task.name,
        trajectory=f"{trajectory.kind.value}+ssc32",
        settle_s=settle_s,
        gripper_cmd=gripper,
    )
    twin = Playback(report=summarize(log), log=log)
    if video is not None:
        targets = np.array([p.position for p in tool_poses(trajectory.waypoints)])
        render_log(model, log, video, render or RenderSettings(), targets, None)
    if progress is not None:
        progress(1.0)
    return TwinRun(
        stream, motion, ideal, twin, TwinComparison(ideal.report, twin.report, deviation)
    )


class ArmSsc32:
    """The arm's real backend (:class:`~lynxsim.sim.adapter.RealBackend`): an SSC-32U.

    Its calibration is :func:`lynxsim.real.arm.load_arm_calibration`'s, its twin
    :func:`run_twin`.
    """

    @property
    def controller(self) -> str:
        """The SSC-32U servo controller: ``"ssc32"``."""
        return "ssc32"

    def calibration(self, path: str | os.PathLike[str] | None) -> Calibration:
        """Read an arm calibration file (None: the shipped one)."""
        return load_arm_calibration(path)

    def twin(
        self,
        task: Task,
        motion: Motion,
        calibration: Calibration,
        options: StreamOptions | None = None,
        *,
        video: str | os.PathLike[str] | None = None,
        render: RenderSettings | None = None,
        progress: ProgressFn | None = None,
    ) -> TwinRun:
        """Play an arm task's trajectory ideally and through the board (:func:`run_twin`)."""
        return run_twin(
            task,
            instance(motion, Trajectory, "motion"),
            calibration,
            options,
            video=video,
            render=render,
            progress=progress,
        )


BACKEND: RealBackend = ArmSsc32()
"""The real backend the arm's record names."""
