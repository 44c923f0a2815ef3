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
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, tool_pose
from lynxsim.arm.motion import tool_poses
from lynxsim.real.arm import arm_tool_points
from lynxsim.real.calibration import Calibration
from lynxsim.real.deviation import BoardMotion, StreamDeviation, board_motion, stream_deviation
from lynxsim.real.stream import CommandStream, StreamOptions, command_stream
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.recording import ProgressFn, render_log
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.sim.summary import Playback, summarize
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory

__all__ = ["TwinComparison", "TwinRun", "dead_band", "run_twin", "servo_targets"]

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


@dataclass(frozen=True)
class TwinComparison:
    """The digital twin's run against the ideal playback of the same trajectory.

    Attributes:
        ideal: Report of the ideal playback (targets updated every physics step).
        twin: Report of the run through the board and the servos' dead bands.
        deviation: The board's interpolation against the trajectory.
    """

    ideal: RunReport
    twin: RunReport
    deviation: StreamDeviation

    @property
    def extra_tool_max_error_m(self) -> float:
        """Twin's largest tool tracking error minus the ideal's [m]."""
        return self.twin.tool_max_error_m - self.ideal.tool_max_error_m

    @property
    def extra_tool_rms_error_m(self) -> float:
        """Twin's RMS tool tracking error minus the ideal's [m]."""
        return self.twin.tool_rms_error_m - self.ideal.tool_rms_error_m

    @property
    def same_verdicts(self) -> bool:
        """Whether both runs collide alike: the same verdict and the same obstacles hit."""
        hit = [{o.name for o in r.obstacles if o.collided} for r in (self.ideal, self.twin)]
        return self.ideal.collided == self.twin.collided and hit[0] == hit[1]

    def lines(self) -> list[str]:
        """The comparison as readable lines (mm)."""
        verdict = {True: "collides", False: "clear"}
        return [
            "ssc32 twin vs ideal playback: tool error max "
            f"{self.twin.tool_max_error_m * 1e3:.2f} mm "
            f"(ideal {self.ideal.tool_max_error_m * 1e3:.2f} mm, extra "
            f"{self.extra_tool_max_error_m * 1e3:+.2f} mm), RMS "
            f"{self.twin.tool_rms_error_m * 1e3:.2f} mm (extra "
            f"{self.extra_tool_rms_error_m * 1e3:+.2f} mm)",
            f"verdicts: ideal {verdict[self.ideal.collided]}, twin {verdict[self.twin.collided]}"
            + ("" if self.same_verdicts else "  (THEY DIFFER)"),
        ]


@dataclass(frozen=True)
class TwinRun:
    """A trajectory's stream, board motion, ideal and twin playbacks.

    Attributes:
        stream: The command stream.
        motion: What the board sends.
        ideal: The ideal playback.
        twin: The twin's playback.
        comparison: The two compared.
    """

    stream: CommandStream
    motion: BoardMotion
    ideal: Playback
    twin: Playback
    comparison: TwinComparison

    def simulated_joints(self) -> tuple[FloatArray, FloatArray]:
        """The twin's simulated joints on the stream's clock: times (S,) [s], joints (S, n) [rad].

        The stream's clock starts when its first line is sent; the motion starts
        :attr:`BoardMotion.latency_s` later.
        """
        log = self.twin.log
        return log.time_s + self.motion.latency_s, log.q


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
