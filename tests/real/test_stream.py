"""Trajectories as command streams: timing, targets, refusals, and the controller's deviation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import free_motion, quintic
from lynxsim.errors import CommandLimitError, InvalidInputError
from lynxsim.real.arm import arm_tool_points, load_arm_calibration
from lynxsim.real.board import FRAME_S
from lynxsim.real.deviation import board_motion, stream_deviation
from lynxsim.real.protocol import GroupMove, parse_line
from lynxsim.real.stream import StreamOptions, command_stream
from lynxsim.robots.arm import build_trajectory
from lynxsim.tasks import load_task

CAL = load_arm_calibration()
START = np.array([0.2, 1.2, -1.4, -0.6, 0.3])
END = np.array([-0.4, 0.9, -1.0, -0.2, 0.5])
QUANTUM_RAD = 0.5 / (2000 / math.pi)
"""Half a microsecond of pulse, in joint radians (the rounding of a target)."""


def _moves(stream):
    return [ln for ln in stream.lines if ln.kind == "move"]


def test_streamed_lines_every_period_with_t_the_period_end_at_the_final_pose():
    traj = quintic([START, END], durations=1.3)
    stream = command_stream(traj, CAL, StreamOptions(period_ms=100))
    moves = _moves(stream)
    assert len(moves) == 13
    assert [round(m.at_s - stream.motion_start_s, 6) for m in moves] == [
        round(0.1 * k, 6) for k in range(13)
    ]
    commands = [parse_line(m.text) for m in moves]
    assert all(isinstance(c, GroupMove) and c.time_ms == 100 for c in commands)
    expected = np.round(CAL.pulses_us(END)).astype(int)
    assert stream.final_us == tuple(expected)
    assert [s.pulse_us for s in commands[-1].targets] == list(expected)  # type: ignore[union-attr]
    assert [s.channel for s in commands[-1].targets] == list(CAL.channels)  # type: ignore[union-attr]
    approach = parse_line(stream.lines[0].text)
    assert isinstance(approach, GroupMove)
    assert approach.time_ms == 2000


def test_waypoint_moves_take_each_segments_time():
    traj = quintic([START, END, START], durations=[1.0, 1.5])
    stream = command_stream(traj, CAL, StreamOptions(mode="waypoints"))
    times = [parse_line(m.text).time_ms for m in _moves(stream)]  # type: ignore[union-attr]
    assert times == [1000, 1500]


def test_gripper_closes_before_and_opens_after_the_motion():
    traj = quintic([START, END], durations=1.0)
    stream = command_stream(traj, CAL, grip=True)
    grips = [ln for ln in stream.lines if ln.kind == "gripper"]
    assert [g.text for g in grips] == ["#4P1900", "#4P1000"]
    assert grips[0].at_s < stream.motion_start_s < stream.motion_start_s + 1.0 < grips[1].at_s


def test_a_pulse_outside_the_calibrated_range_is_refused():
    narrow = dataclasses.replace(
        CAL, joints=(dataclasses.replace(CAL.joints[0], max_us=1550), *CAL.joints[1:])
    )
    traj = quintic([START, END], durations=1.0)  # base 0.2 rad = 1627 us at the start
    with pytest.raises(CommandLimitError, match=r"joint base: pulse 1627 us at 0\.000 s") as info:
        command_stream(traj, narrow)
    assert (info.value.quantity, info.value.limit) == ("pulse", 1550.0)


def test_a_move_over_the_speed_limit_is_refused():
    slow = dataclasses.replace(
        CAL, joints=(dataclasses.replace(CAL.joints[0], max_speed_rad_s=0.2), *CAL.joints[1:])
    )
    traj = quintic([START, END], durations=1.0)
    with pytest.raises(CommandLimitError, match="over its speed limit") as info:
        command_stream(traj, slow)
    assert info.value.joint == "base"
    assert info.value.quantity == "speed"
    assert info.value.value > info.value.limit


def test_a_stream_the_serial_line_cannot_carry_is_refused():
    traj = quintic([START, END], durations=1.0)
    with pytest.raises(InvalidInputError, match=r"at 9600 baud a line of \d+ bytes takes"):
        command_stream(traj, CAL, StreamOptions(period_ms=40))
    fast = dataclasses.replace(CAL, baud=115200)
    assert command_stream(traj, fast, StreamOptions(period_ms=20)).lines


@pytest.mark.parametrize(
    "kwargs", [{"period_ms": 30}, {"period_ms": 0}, {"mode": "burst"}, {"hold_s": 1.0}]
)
def test_bad_options_are_refused(kwargs):
    with pytest.raises(InvalidInputError):
        StreamOptions(**kwargs)


def test_linear_joint_motion_through_waypoint_moves_deviates_by_timing_only():
    # Free motion is linear in joint space, as the board's interpolation: the only
    # deviation left is the rounding and where the 20 ms frames fall.
    traj = free_motion([START, END, START], durations=[1.0, 1.0])
    stream = command_stream(traj, CAL, StreamOptions(mode="waypoints"))
    dev = stream_deviation(traj, stream, CAL)
    speed = np.abs(END - START) / 1.0
    assert (np.array(dev.joint_max_rad) <= speed * FRAME_S + QUANTUM_RAD + 1e-9).all()


def test_streamed_deviation_is_below_a_chord_and_a_frame_of_motion():
    traj = quintic([START, END], durations=1.0)
    stream = command_stream(traj, CAL, StreamOptions(period_ms=100))
    dev = stream_deviation(traj, stream, CAL, arm_tool_points)
    t = np.linspace(0, 1, 2001)
    s = traj.sample(t)
    chord = np.abs(s.qdd).max(axis=0) * 0.1**2 / 8
    frame = np.abs(s.qd).max(axis=0) * FRAME_S
    assert (np.array(dev.joint_max_rad) <= chord + frame + QUANTUM_RAD).all()
    assert dev.tool_max_m is not None
    assert 0 < dev.tool_max_m < 0.05


def test_board_motion_reaches_every_shipped_tasks_final_pulses():
    for name in ("obstacle_avoidance", "pick_and_place", "three_obstacles"):
        traj = build_trajectory(load_task(f"tasks/{name}.toml"), None)
        stream = command_stream(traj, CAL)
        motion = board_motion(stream, CAL)
        assert tuple(motion.pulses_us[-1]) == stream.final_us
        assert abs(motion.end_s - traj.duration) <= FRAME_S + 1e-9
        assert (motion.q_rad >= np.asarray(LYNX_ARM.q_min) - QUANTUM_RAD).all()
