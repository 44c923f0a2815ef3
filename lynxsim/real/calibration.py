"""Servo calibration files: joint angle <-> SSC-32U pulse width, per joint, validated.

A calibration file (TOML, one per arm) maps each joint to its controller channel
and its servo's pulse width. A joint's map is linear::

    pulse_us = reference_us + direction * us_per_rad * (q - reference_rad)

written either as a reference point and a slope (``reference_deg``,
``reference_us``, ``us_per_deg``, ``direction``) or as two measured points
(``points = [[deg, us], [deg, us]]``: the slope and direction follow). Every
joint also gives its pulse range (``min_us``, ``max_us``), optionally its speed
limit (``max_speed_deg_s``; default: the velocity limit the trajectories are
generated with) and its servo's dead band (``dead_band_us``). An optional
``[gripper]`` gives the gripper's channel and its open and closed pulses. Every
error names the file and the field.

Pure Python and numpy: no MuJoCo, no pyserial.
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.errors import CalibrationFileError, InvalidInputError

__all__ = [
    "BAUD_RATES",
    "MAX_CHANNEL",
    "MAX_PULSE_US",
    "MIN_PULSE_US",
    "Calibration",
    "GripperCalibration",
    "JointCalibration",
    "load_calibration",
    "parse_calibration",
]

FloatArray = npt.NDArray[np.float64]

MIN_PULSE_US = 500
"""Smallest pulse width of the SSC-32U's normal range [us] (its manual)."""
MAX_PULSE_US = 2500
"""Largest pulse width of the SSC-32U's normal range [us] (its manual)."""
MAX_CHANNEL = 31
"""Highest channel number of the SSC-32U (channels 0 to 31)."""
BAUD_RATES = (2400, 9600, 38400, 115200)
"""The SSC-32U's baud rates [bit/s]; 9600 is its default."""

_US_PER_DEG = (1.0, 100.0)
"""Accepted slopes [us/deg] (hobby servos: about 11 us/deg, 2000 us per 180 deg)."""
_MAX_REFERENCE_DEG = 360.0
_MIN_POINT_SPAN_DEG = 5.0
"""Two measured points must lie at least this far apart [deg] (a protractor's
error of 0.5 deg then moves the slope by at most 10 %)."""
_MAX_SPEED_DEG_S = (1.0, 10000.0)
_MAX_DEAD_BAND_US = 100.0
_FILE_BYTES = 1 << 20
"""Largest calibration file read [bytes]."""

_JOINT_KEYS = (
    "channel",
    "reference_deg",
    "reference_us",
    "us_per_deg",
    "direction",
    "points",
    "min_us",
    "max_us",
    "max_speed_deg_s",
    "dead_band_us",
)


@dataclass(frozen=True)
class JointCalibration:
    """One joint's servo: its channel and its angle-to-pulse map.

    Attributes:
        name: The joint's name.
        channel: SSC-32U channel, 0..31.
        reference_rad: Joint angle of the reference point [rad].
        reference_us: Pulse width at the reference angle [us].
        us_per_rad: Pulse change per joint radian, positive [us/rad].
        direction: +1 if a wider pulse turns the joint positive, else -1.
        min_us: Smallest pulse the arm may be sent on this channel [us].
        max_us: Largest pulse [us].
        max_speed_rad_s: Fastest joint speed a command may ask for [rad/s].
        dead_band_us: The servo's dead band width [us]: pulse changes inside it
            do not move the horn.
    """

    name: str
    channel: int
    reference_rad: float
    reference_us: float
    us_per_rad: float
    direction: int
    min_us: int
    max_us: int
    max_speed_rad_s: float
    dead_band_us: float

    def __post_init__(self) -> None:
        if not (0 <= self.channel <= MAX_CHANNEL):
            raise InvalidInputError(f"joint {self.name}: channel {self.channel} not in 0..31")
        if self.direction not in (1, -1):
            raise InvalidInputError(f"joint {self.name}: direction must be 1 or -1")
        if not (MIN_PULSE_US <= self.min_us < self.max_us <= MAX_PULSE_US):
            raise InvalidInputError(
                f"joint {self.name}: pulse range {self.min_us}..{self.max_us} us must lie "
                f"within {MIN_PULSE_US}..{MAX_PULSE_US} us, min below max"
            )
        for field in ("reference_rad", "reference_us", "us_per_rad", "max_speed_rad_s"):
            if not math.isfinite(getattr(self, field)):
                raise InvalidInputError(f"joint {self.name}: {field} must be finite")
        if self.us_per_rad <= 0 or self.max_speed_rad_s <= 0 or not self.dead_band_us >= 0:
            raise InvalidInputError(
                f"joint {self.name}: slope and speed must be positive, dead band not negative"
            )

    @property
    def max_speed_us_s(self) -> float:
        """The speed limit as a pulse rate [us/s]."""
        return self.max_speed_rad_s * self.us_per_rad

    def pulse_us(self, q: npt.ArrayLike) -> FloatArray:
        """Pulse widths of joint angles [rad] -> [us], any shape, not rounded."""
        out: FloatArray = self.reference_us + self.direction * self.us_per_rad * (
            np.asarray(q, dtype=float) - self.reference_rad
        )
        return out

    def angle_rad(self, pulse_us: npt.ArrayLike) -> FloatArray:
        """Joint angles of pulse widths [us] -> [rad], any shape."""
        out: FloatArray = self.reference_rad + (
            np.asarray(pulse_us, dtype=float) - self.reference_us
        ) / (self.direction * self.us_per_rad)
        return out

    def to_dict(self) -> dict[str, Any]:
        """The map in the file's units (degrees, us), as a calibration file writes it."""
        return {
            "channel": self.channel,
            "reference_deg": math.degrees(self.reference_rad),
            "reference_us": self.reference_us,
            "us_per_deg": self.us_per_rad * math.pi / 180.0,
            "direction": self.direction,
            "min_us": self.min_us,
            "max_us": self.max_us,
            "max_speed_deg_s": math.degrees(self.max_speed_rad_s),
            "dead_band_us": self.dead_band_us,
        }


@dataclass(frozen=True)
class GripperCalibration:
    """The gripper's servo: channel and the pulses that open and close it [us]."""

    channel: int
    open_us: int
    closed_us: int


@dataclass(frozen=True)
class Calibration:
    """One arm's calibration: a joint map per joint in joint order, the gripper, the baud rate.

    Attributes:
        joints: Per joint, in the robot's joint order.
        gripper: The gripper's servo, or None.
        baud: Serial baud rate of the board [bit/s].
        source: The file it was read from ("" if built in code).
    """

    joints: tuple[JointCalibration, ...]
    gripper: GripperCalibration | None = None
    baud: int = 9600
    source: str = ""

    def __post_init__(self) -> None:
        channels = [j.channel for j in self.joints]
        if self.gripper is not None:
            channels.append(self.gripper.channel)
        if len(set(channels)) != len(channels):
            raise InvalidInputError(f"two servos share a channel: {channels}")
        if self.baud not in BAUD_RATES:
            raise InvalidInputError(f"baud {self.baud} is not one of {BAUD_RATES}")

    @property
    def channels(self) -> tuple[int, ...]:
        """The joints' channels, in joint order."""
        return tuple(j.channel for j in self.joints)

    @property
    def names(self) -> tuple[str, ...]:
        """The joints' names, in joint order."""
        return tuple(j.name for j in self.joints)

    def pulses_us(self, q: npt.ArrayLike) -> FloatArray:
        """Pulse widths of joint vectors, (..., n) [rad] -> (..., n) [us], not rounded."""
        arr = np.asarray(q, dtype=float)
        return np.stack([j.pulse_us(arr[..., i]) for i, j in enumerate(self.joints)], axis=-1)

    def angles_rad(self, pulses_us: npt.ArrayLike) -> FloatArray:
        """Joint vectors of pulse widths, (..., n) [us] -> (..., n) [rad]."""
        arr = np.asarray(pulses_us, dtype=float)
        return np.stack([j.angle_rad(arr[..., i]) for i, j in enumerate(self.joints)], axis=-1)

    def to_dict(self) -> dict[str, Any]:
        """The calibration as a calibration file's tables (degrees, us)."""
        out: dict[str, Any] = {
            "board": {"baud": self.baud},
            "joints": {j.name: j.to_dict() for j in self.joints},
        }
        if self.gripper is not None:
            g = self.gripper
            out["gripper"] = {"channel": g.channel, "open_us": g.open_us, "closed_us": g.closed_us}
        return out


class _Reader:
    """Validating accessors that name the file and the field on failure."""

    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, field: str | None, problem: str) -> CalibrationFileError:
        return CalibrationFileError(self.path, field, problem)

    def table(self, value: object, field: str, keys: Sequence[str] | None) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.fail(field, f"must be a table, got {_show(value)}")
        if keys is not None:
            unknown = sorted(str(k) for k in value if k not in keys)
            if unknown:
                raise self.fail(
                    f"{field}.{_show_key(unknown[0])}",
                    f"unknown key; expected one of: {', '.join(keys)}",
                )
        return value

    def number(self, value: object, field: str, low: float, high: float, unit: str) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(field, f"must be a number, got {_show(value)}")
        try:
            number = float(value)
        except OverflowError:
            raise self.fail(field, "must be finite, got an integer beyond 1e308") from None
        if not math.isfinite(number):
            raise self.fail(field, f"must be finite, got {_show(value)}")
        if not low <= number <= high:
            raise self.fail(field, f"must lie within {low:g}..{high:g} {unit}, got {_show(value)}")
        return number

    def integer(self, value: object, field: str, low: int, high: int, unit: str) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(field, f"must be an integer, got {_show(value)}")
        if not low <= value <= high:
            raise self.fail(field, f"must lie within {low}..{high}{unit}, got {_show(value)}")
        return value


def _show(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _show_key(key: str) -> str:
    return key if key.isprintable() and len(key) <= 60 else _show(key)


def _pulse(r: _Reader, value: object, field: str) -> int:
    return r.integer(value, field, MIN_PULSE_US, MAX_PULSE_US, " us")


def _joint_map(r: _Reader, raw: Mapping[str, Any], field: str) -> tuple[float, float, float, int]:
    """(reference_rad, reference_us, us_per_rad, direction) from either form."""
    slope_keys = [k for k in ("reference_deg", "reference_us", "us_per_deg") if k in raw]
    if "points" in raw:
        if slope_keys:
            raise r.fail(f"{field}.{slope_keys[0]}", "give either points or a reference and slope")
        points = raw["points"]
        if not (isinstance(points, list) and len(points) == 2):
            raise r.fail(f"{field}.points", f"must be two [deg, us] pairs, got {_show(points)}")
        pairs = []
        for i, p in enumerate(points):
            where = f"{field}.points[{i}]"
            if not (isinstance(p, list) and len(p) == 2):
                raise r.fail(where, f"must be a pair [deg, us], got {_show(p)}")
            deg = r.number(p[0], f"{where}[0]", -_MAX_REFERENCE_DEG, _MAX_REFERENCE_DEG, "deg")
            pairs.append((deg, float(_pulse(r, p[1], f"{where}[1]"))))
        (a_deg, a_us), (b_deg, b_us) = pairs
        if abs(b_deg - a_deg) < _MIN_POINT_SPAN_DEG:
            raise r.fail(
                f"{field}.points",
                f"the two angles must lie at least {_MIN_POINT_SPAN_DEG:g} deg apart",
            )
        slope = (b_us - a_us) / (b_deg - a_deg)
        if not _US_PER_DEG[0] <= abs(slope) <= _US_PER_DEG[1]:
            raise r.fail(
                f"{field}.points",
                f"slope {abs(slope):.3g} us/deg must lie within "
                f"{_US_PER_DEG[0]:g}..{_US_PER_DEG[1]:g} us/deg",
            )
        implied = 1 if slope > 0 else -1
        if "direction" in raw:
            given = r.integer(raw["direction"], f"{field}.direction", -1, 1, "")
            if given != implied:
                raise r.fail(
                    f"{field}.direction", f"{given} contradicts the points (they give {implied})"
                )
        return math.radians(a_deg), a_us, math.degrees(abs(slope)), implied
    for key in ("reference_deg", "reference_us", "us_per_deg", "direction"):
        if key not in raw:
            raise r.fail(f"{field}.{key}", "missing (or give points = [[deg, us], [deg, us]])")
    ref = r.number(
        raw["reference_deg"],
        f"{field}.reference_deg",
        -_MAX_REFERENCE_DEG,
        _MAX_REFERENCE_DEG,
        "deg",
    )
    ref_us = r.number(
        raw["reference_us"], f"{field}.reference_us", MIN_PULSE_US, MAX_PULSE_US, "us"
    )
    slope = r.number(raw["us_per_deg"], f"{field}.us_per_deg", *_US_PER_DEG, "us/deg")
    direction = r.integer(raw["direction"], f"{field}.direction", -1, 1, "")
    if direction == 0:
        raise r.fail(f"{field}.direction", "must be 1 or -1, got 0")
    return math.radians(ref), ref_us, math.degrees(slope), direction


def _joint(r: _Reader, name: str, raw: object, default_speed_rad_s: float) -> JointCalibration:
    field = f"joints.{name}"
    table = r.table(raw, field, _JOINT_KEYS)
    for key in ("channel", "min_us", "max_us", "dead_band_us"):
        if key not in table:
            raise r.fail(f"{field}.{key}", "missing")
    channel = r.integer(table["channel"], f"{field}.channel", 0, MAX_CHANNEL, "")
    ref_rad, ref_us, us_per_rad, direction = _joint_map(r, table, field)
    min_us = _pulse(r, table["min_us"], f"{field}.min_us")
    max_us = _pulse(r, table["max_us"], f"{field}.max_us")
    if min_us >= max_us:
        raise r.fail(f"{field}.max_us", f"must exceed min_us ({min_us}), got {max_us}")
    speed = (
        math.radians(
            r.number(
                table["max_speed_deg_s"], f"{field}.max_speed_deg_s", *_MAX_SPEED_DEG_S, "deg/s"
            )
        )
        if "max_speed_deg_s" in table
        else default_speed_rad_s
    )
    dead_band = r.number(
        table["dead_band_us"], f"{field}.dead_band_us", 0.0, _MAX_DEAD_BAND_US, "us"
    )
    return JointCalibration(
        name, channel, ref_rad, ref_us, us_per_rad, direction, min_us, max_us, speed, dead_band
    )


def _gripper(r: _Reader, raw: object) -> GripperCalibration:
    table = r.table(raw, "gripper", ("channel", "open_us", "closed_us"))
    for key in ("channel", "open_us", "closed_us"):
        if key not in table:
            raise r.fail(f"gripper.{key}", "missing")
    return GripperCalibration(
        r.integer(table["channel"], "gripper.channel", 0, MAX_CHANNEL, ""),
        _pulse(r, table["open_us"], "gripper.open_us"),
        _pulse(r, table["closed_us"], "gripper.closed_us"),
    )


def parse_calibration(
    data: Mapping[str, Any],
    path: str,
    joint_names: Sequence[str],
    default_speeds_rad_s: Sequence[float],
) -> Calibration:
    """Validate a calibration's tables (as TOML reads them); see :func:`load_calibration`."""
    r = _Reader(path)
    top = r.table(data, "", ("board", "joints", "gripper"))
    baud = 9600
    if "board" in top:
        board = r.table(top["board"], "board", ("baud",))
        if "baud" in board:
            value = board["baud"]
            if isinstance(value, bool) or value not in BAUD_RATES:
                rates = ", ".join(str(b) for b in BAUD_RATES)
                raise r.fail("board.baud", f"must be one of {rates}, got {_show(value)}")
            baud = int(value)
    if "joints" not in top:
        raise r.fail("joints", f"missing (a table per joint: {', '.join(joint_names)})")
    joints_raw = r.table(top["joints"], "joints", tuple(joint_names))
    joints = []
    for name, speed in zip(joint_names, default_speeds_rad_s, strict=True):
        if name not in joints_raw:
            raise r.fail(f"joints.{name}", "missing")
        joints.append(_joint(r, name, joints_raw[name], speed))
    gripper = _gripper(r, top["gripper"]) if "gripper" in top else None
    seen: dict[int, str] = {}
    for field, channel in [(f"joints.{j.name}", j.channel) for j in joints] + (
        [("gripper", gripper.channel)] if gripper is not None else []
    ):
        if channel in seen:
            raise r.fail(f"{field}.channel", f"channel {channel} is already {seen[channel]}'s")
        seen[channel] = field
    return Calibration(tuple(joints), gripper, baud, path)


def load_calibration(
    path: str | os.PathLike[str],
    joint_names: Sequence[str],
    default_speeds_rad_s: Sequence[float],
) -> Calibration:
    """Read and validate a calibration file.

    Args:
        path: The TOML file.
        joint_names: The robot's joints, in order: the file must give each, no other.
        default_speeds_rad_s: Per joint, the speed limit when the file gives none [rad/s].

    Returns:
        The :class:`Calibration`, in SI units.

    Raises:
        CalibrationFileError: Not a regular file, not UTF-8 TOML, or a field breaks the
            schema (the message names the file and the field).
        OSError: The file cannot be read.
    """
    p = Path(path)
    if p.exists() and not p.is_file():
        raise CalibrationFileError(str(p), None, "not a regular file")
    with p.open("rb") as f:
        raw = f.read(_FILE_BYTES + 1)
    if len(raw) > _FILE_BYTES:
        raise CalibrationFileError(str(p), None, f"larger than {_FILE_BYTES} bytes")
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise CalibrationFileError(str(p), None, f"not UTF-8 text ({exc.reason})") from None
    except (tomllib.TOMLDecodeError, ValueError, RecursionError) as exc:
        raise CalibrationFileError(str(p), None, f"not valid TOML: {exc}") from None
    return parse_calibration(data, str(p), joint_names, default_speeds_rad_s)
