"""Calibration files: the shipped one, both forms of a joint's map, hostile files."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.arm import AL5D_SERVOS, LYNX_ARM
from lynxsim.errors import CalibrationFileError
from lynxsim.real.arm import DEFAULT_CALIBRATION, load_arm_calibration
from lynxsim.real.calibration import load_calibration
from tests.helpers import assert_close

US_TOL = 1e-6
"""Pulse round trips agree to this [us]."""

_GOOD = """
[board]
baud = 115200
[joints.base]
channel = 0
points = [[-45.0, 1000], [45.0, 2000]]
min_us = 600
max_us = 2400
dead_band_us = 4
[joints.shoulder]
channel = 1
reference_deg = 90.0
reference_us = 1500
us_per_deg = 10.0
direction = -1
min_us = 500
max_us = 2500
max_speed_deg_s = 90.0
dead_band_us = 8
[joints.elbow]
channel = 2
points = [[0.0, 2400], [-90.0, 1400]]
min_us = 500
max_us = 2500
dead_band_us = 8
[joints.wrist_pitch]
channel = 3
reference_deg = 0.0
reference_us = 1500
us_per_deg = 11.0
direction = 1
min_us = 500
max_us = 2500
dead_band_us = 8
[joints.wrist_roll]
channel = 5
reference_deg = 0.0
reference_us = 1500
us_per_deg = 11.0
direction = 1
min_us = 500
max_us = 2500
dead_band_us = 8
[gripper]
channel = 4
open_us = 1100
closed_us = 1800
"""


def _write(tmp_path, text):
    path = tmp_path / "cal.toml"
    path.write_text(text)
    return path


def test_the_shipped_calibration_loads_and_maps_the_joint_ranges_into_500_2500_us():
    cal = load_arm_calibration()
    assert cal.names == LYNX_ARM.joint_names
    assert DEFAULT_CALIBRATION.is_file()
    assert cal.baud == 9600
    for joint, servo in zip(cal.joints, AL5D_SERVOS):
        assert joint.max_speed_rad_s == servo.velocity_limit  # one definition: servos.py
        assert joint.us_per_rad == pytest.approx(2000 / math.pi, rel=1e-6)
    lo = cal.pulses_us(LYNX_ARM.q_min)
    hi = cal.pulses_us(np.minimum(LYNX_ARM.q_max, math.pi / 2))  # the roll servo turns 180 deg
    assert (np.minimum(lo, hi) >= 500 - US_TOL).all()
    assert (np.maximum(lo, hi) <= 2500 + US_TOL).all()


def test_two_points_give_slope_and_direction_and_the_map_inverts(tmp_path):
    cal = load_calibration(_write(tmp_path, _GOOD), LYNX_ARM.joint_names, [1.0] * 5)
    base, shoulder, elbow = cal.joints[:3]
    assert base.pulse_us(0.0) == pytest.approx(1500.0)
    assert base.direction == 1
    assert elbow.direction == 1  # 2400 us at 0 deg, 1400 us at -90 deg
    assert elbow.pulse_us(math.radians(-45.0)) == pytest.approx(1900.0)
    assert shoulder.max_speed_rad_s == pytest.approx(math.radians(90.0))
    assert shoulder.pulse_us(math.radians(80.0)) == pytest.approx(1600.0)  # direction -1
    q = np.random.default_rng(0).uniform(-1.0, 1.0, (50, 5))
    assert_close(cal.angles_rad(cal.pulses_us(q)), q, atol=1e-12)
    assert cal.gripper is not None
    assert cal.gripper.closed_us == 1800
    assert cal.baud == 115200


@pytest.mark.parametrize(
    ("old", "new", "field", "problem"),
    [
        ("channel = 0", "channel = 32", "joints.base.channel", "0..31"),
        ("channel = 1", "channel = 0", "joints.shoulder.channel", "already joints.base's"),
        ("baud = 115200", "baud = 9601", "board.baud", "one of 2400"),
        ("min_us = 600", "min_us = 400", "joints.base.min_us", "500..2500"),
        ("max_us = 2400", "max_us = 550", "joints.base.max_us", "must exceed min_us"),
        (
            "[[-45.0, 1000], [45.0, 2000]]",
            "[[1.0, 1000], [2.0, 2000]]",
            "joints.base.points",
            "5 deg",
        ),
        ("[[-45.0, 1000], [45.0, 2000]]", "[[0.0, 1500]]", "joints.base.points", "two"),
        ("us_per_deg = 10.0", "us_per_deg = nan", "joints.shoulder.us_per_deg", "finite"),
        ("direction = -1", "direction = 0", "joints.shoulder.direction", "1 or -1"),
        ("direction = -1", 'direction = "up"', "joints.shoulder.direction", "integer"),
        ("dead_band_us = 4", "dead_band_us = true", "joints.base.dead_band_us", "number"),
        (
            "max_speed_deg_s = 90.0",
            "max_speed_deg_s = 0.0",
            "joints.shoulder.max_speed_deg_s",
            "1..10000",
        ),
        ("[joints.wrist_roll]", "[joints.wrist_twist]", "joints.wrist_twist", "unknown key"),
        ("dead_band_us = 4", "dead_band_us = 4\ncolour = 1", "joints.base.colour", "unknown key"),
        ("closed_us = 1800", "", "gripper.closed_us", "missing"),
        ("channel = 4", "channel = 3", "gripper.channel", "already joints.wrist_pitch's"),
    ],
)
def test_bad_fields_name_file_and_field(tmp_path, old, new, field, problem):
    assert old in _GOOD
    path = _write(tmp_path, _GOOD.replace(old, new, 1))
    with pytest.raises(CalibrationFileError, match=problem) as info:
        load_calibration(path, LYNX_ARM.joint_names, [1.0] * 5)
    assert info.value.path == str(path)
    assert info.value.field == field
    assert str(path) in str(info.value)


def test_not_toml_not_utf8_and_folders_are_one_line_errors(tmp_path):
    for raw, problem in ((b"[joints", "not valid TOML"), (b"\xff\xfe", "not UTF-8")):
        path = tmp_path / "bad.toml"
        path.write_bytes(raw)
        with pytest.raises(CalibrationFileError, match=problem):
            load_calibration(path, LYNX_ARM.joint_names, [1.0] * 5)
    with pytest.raises(CalibrationFileError, match="not a regular file"):
        load_calibration(tmp_path, LYNX_ARM.joint_names, [1.0] * 5)


values = st.one_of(
    st.integers(-(10**30), 10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    st.text(max_size=8),
    st.lists(st.integers(-3000, 3000), max_size=3),
    st.lists(st.lists(st.floats(-400, 3000), max_size=3), max_size=3),
)


@st.composite
def hostile_files(draw):
    text = _GOOD
    lines = [ln for ln in text.splitlines() if "=" in ln]
    for _ in range(draw(st.integers(1, 3))):
        line = draw(st.sampled_from(lines))
        key = line.split("=")[0].strip()
        value = draw(values)
        toml = (
            repr(value).replace("True", "true").replace("False", "false").replace("'", '"')
            if not isinstance(value, float) or math.isfinite(value)
            else {True: "nan"}.get(math.isnan(value), "inf" if value > 0 else "-inf")
        )
        text = text.replace(line, f"{key} = {toml}", 1)
    if draw(st.booleans()):
        cut = draw(st.integers(0, len(text)))
        text = text[:cut]
    return text


@settings(max_examples=150, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(hostile_files())
def test_hostile_files_load_or_fail_with_the_file_named(tmp_path, text):
    path = _write(tmp_path, text)
    message = None
    try:
        cal = load_calibration(path, LYNX_ARM.joint_names, [1.0] * 5)
    except CalibrationFileError as exc:
        message = str(exc)
    if message is not None:
        assert str(path) in message
        assert "\n" not in message
    else:
        for j in cal.joints:
            assert 500 <= j.min_us < j.max_us <= 2500
            assert 0 <= j.channel <= 31
            assert math.isfinite(j.us_per_rad)
            assert j.us_per_rad > 0
        assert len(set(cal.channels)) == 5
