"""The digital twin: every shipped arm task keeps its verdicts through the board; the dead band."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.real.arm import load_arm_calibration
from lynxsim.real.board import FRAME_S
from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.sim.arm.ssc32 import dead_band, run_twin, servo_targets
from lynxsim.tasks import find_tasks
from tests.helpers import assert_close

CAL = load_arm_calibration()
ARM_TASKS = find_tasks("tasks", "arm")


def test_the_dead_band_holds_changes_inside_it_and_follows_with_half_its_width():
    pulses = np.array([[1500.0], [1503.0], [1497.0], [1500.0], [1520.0], [1540.0], [1536.0]])
    acted = dead_band(pulses, [8.0])
    assert acted[:4, 0].tolist() == [1500.0] * 4  # +-3 us: inside the 8 us band
    assert acted[4:, 0].tolist() == [1516.0, 1536.0, 1536.0]  # 4 us behind, then held
    assert_close(dead_band(pulses, [0.0]), pulses, atol=0.0)


def test_servo_targets_hold_each_20_ms_frame():
    traj = motion(ARM, ARM_TASKS[0])
    from lynxsim.real.deviation import board_motion
    from lynxsim.real.stream import command_stream

    board = board_motion(command_stream(traj, CAL), CAL)
    t = np.arange(0.0, 1.0, 0.002)
    q = servo_targets(board, CAL, t)
    frames = np.floor(t / FRAME_S + 1e-9)
    for k in np.unique(frames):
        rows = q[frames == k]
        assert (rows == rows[0]).all()


@pytest.mark.parametrize("task", ARM_TASKS, ids=[t.name for t in ARM_TASKS])
def test_the_twin_keeps_the_verdicts_of_ideal_playback_and_reports_the_extra_error(task):
    run = run_twin(task, motion(ARM, task), CAL)
    c = run.comparison
    assert c.same_verdicts, c.lines()
    assert c.ideal.collided == c.twin.collided
    assert math.isfinite(c.extra_tool_max_error_m)
    assert c.twin.trajectory.endswith("+ssc32")
    assert c.twin.healthy
    lines = "\n".join(c.lines())
    assert f"extra {c.extra_tool_max_error_m * 1e3:+.2f} mm" in lines
    if not c.ideal.collided:  # a clear motion: the twin's error is the board's and the servos'
        assert 0.0 < c.extra_tool_max_error_m < 0.05
    t, q = run.simulated_joints()
    assert t[0] == pytest.approx(run.motion.latency_s, abs=0.01)
    assert q.shape == (len(t), 5)


def test_obstacle_avoidance_through_waypoint_moves_collides_in_the_twin():
    """The board's straight pulse lines cut the corner the trajectory goes around."""
    from lynxsim.real.stream import StreamOptions

    task = next(t for t in ARM_TASKS if t.name == "obstacle_avoidance")
    run = run_twin(task, motion(ARM, task), CAL, StreamOptions(mode="waypoints"))
    assert not run.comparison.ideal.collided
    assert run.comparison.twin.collided
