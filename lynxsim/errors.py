"""Exceptions raised by lynxsim.

Every error a caller can provoke derives from :class:`LynxsimError`. Errors that
stem from a bad value also derive from :class:`ValueError`, so that generic code
catching ``ValueError`` keeps working.
"""

from __future__ import annotations

__all__ = [
    "InvalidInputError",
    "InvalidTypeError",
    "JointRangeError",
    "LynxsimError",
    "NonFiniteInputError",
    "OutOfReachError",
    "UnreachablePlatformPoseError",
    "UnreachablePoseError",
]


class LynxsimError(Exception):
    """Base class of every error lynxsim raises on purpose."""


class InvalidInputError(LynxsimError, ValueError):
    """An argument has the wrong shape, type or value."""


class InvalidTypeError(InvalidInputError, TypeError):
    """An argument has the wrong type (a string, None, a complex or boolean array...).

    Both a ``ValueError`` (as every :class:`InvalidInputError`) and a ``TypeError``.
    """


class NonFiniteInputError(InvalidInputError):
    """An input holds NaN or infinity."""


class UnreachablePoseError(LynxsimError, ValueError):
    """A target pose has no inverse-kinematics solution.

    Attributes:
        reason: Short machine-readable reason (``"out_of_reach"``,
            ``"joint_range"`` or ``"not_finite"``).
    """

    reason = "unreachable"


class OutOfReachError(UnreachablePoseError):
    """The wrist point lies outside the annulus the two arm links can reach."""

    reason = "out_of_reach"


class JointRangeError(UnreachablePoseError):
    """Every geometric solution puts at least one joint outside its range.

    Attributes:
        joint: 1-based number of the offending joint.
    """

    reason = "joint_range"

    def __init__(self, message: str, joint: int) -> None:
        super().__init__(message)
        self.joint = joint


class UnreachablePlatformPoseError(UnreachablePoseError):
    """A 3-RRR platform pose that at least one leg cannot reach.

    A leg reaches its platform joint only when the base-to-platform-joint
    distance lies in ``[|s_a - L|, s_a + L]``.

    Attributes:
        legs: 1-based numbers of the legs that cannot reach, ascending.
    """

    reason = "out_of_reach"

    def __init__(self, message: str, legs: tuple[int, ...]) -> None:
        super().__init__(message)
        self.legs = legs


class TrajectoryError(LynxsimError):
    """A trajectory cannot be generated as asked."""


class LimitViolationError(TrajectoryError, ValueError):
    """A trajectory breaks a joint range or a velocity, acceleration or jerk limit.

    Attributes:
        joint: 1-based number of the offending joint.
        quantity: ``"position"``, ``"velocity"``, ``"acceleration"`` or ``"jerk"``.
        time: When the worst violation happens [s] from the trajectory's start.
        segment: 0-based index of the segment it happens in.
        value: The offending value [rad, rad/s, rad/s^2 or rad/s^3].
        limit: The bound it breaks, in the same unit.
    """

    def __init__(
        self,
        message: str,
        *,
        joint: int,
        quantity: str,
        time: float,
        segment: int,
        value: float,
        limit: float,
    ) -> None:
        super().__init__(message)
        self.joint = joint
        self.quantity = quantity
        self.time = time
        self.segment = segment
        self.value = value
        self.limit = limit


class SegmentDurationError(TrajectoryError, ValueError):
    """A given segment duration is shorter than the limits allow (Ruckig).

    Attributes:
        segment: 0-based index of the segment.
        joint: 1-based number of the joint that needs the most time.
        given: The duration asked for [s].
        required: The shortest duration within the limits [s].
    """

    def __init__(
        self, message: str, *, segment: int, joint: int, given: float, required: float
    ) -> None:
        super().__init__(message)
        self.segment = segment
        self.joint = joint
        self.given = given
        self.required = required


class TaskFileError(LynxsimError, ValueError):
    """A task file is not valid TOML or breaks the task schema.

    Attributes:
        path: The file.
        field: Dotted path of the offending field (``"poses[2].pitch_deg"``), or
            ``None`` when the problem is the file as a whole.
    """

    def __init__(self, path: str, field: str | None, problem: str) -> None:
        shown = path if path.isprintable() else repr(path)  # one line, whatever the name
        where = f"{shown}: {field}" if field else shown
        super().__init__(f"{where}: {problem}")
        self.path = path
        self.field = field


class PathError(TrajectoryError, ValueError):
    """A Cartesian path cannot be followed continuously by the joints.

    It passes a singular configuration (the base axis, the stretched arm), where
    joint rates are unbounded, or the IK solution jumps (the arm would have to
    change configuration, e.g. from leaning forward to leaning back).

    Attributes:
        segment: 0-based index of the segment.
        joint: 1-based number of the joint concerned.
        fraction: Where along the segment's line, in [0, 1].
    """

    def __init__(self, message: str, *, segment: int, joint: int, fraction: float) -> None:
        super().__init__(message)
        self.segment = segment
        self.joint = joint
        self.fraction = fraction


__all__ += [
    "LimitViolationError",
    "PathError",
    "SegmentDurationError",
    "TaskFileError",
    "TrajectoryError",
]


class OutputPathError(LynxsimError, ValueError):
    """An output destination lynxsim will not write (a folder, FIFO, device or link)."""


class VideoError(LynxsimError, OSError):
    """The video encoder failed, or the file it wrote does not decode to the frames given."""


class ReplayFileError(LynxsimError, ValueError):
    """A replay's data file or run report that is not what lynxsim wrote, or not one run's pair.

    Attributes:
        path: The file.
        field: The offending entry or field (``"poses.quat_q"``), or None when
            the problem is the file as a whole.
    """

    def __init__(self, path: str, field: str | None, problem: str) -> None:
        shown = path if path.isprintable() else repr(path)
        where = f"{shown}: {field}" if field else shown
        super().__init__(f"{where}: {problem}")
        self.path = path
        self.field = field


__all__ += ["OutputPathError", "ReplayFileError", "VideoError"]


def short(value: object) -> str:
    """``repr(value)`` cut to 80 characters, for messages (huge values stay readable)."""
    try:
        text = repr(value)
    except ValueError:  # an integer of more than 4300 digits
        return f"a {type(value).__name__} too long to print"
    return text if len(text) <= 80 else text[:77] + "..."


__all__ += ["short"]


class DataFileError(LynxsimError, ValueError):
    """A data file (calibration, serial log, measured angles) breaks its schema.

    Attributes:
        path: The file.
        field: Where in it (``"joints.base.channel"``, ``"line 7"``), or ``None``
            when the problem is the file as a whole.
    """

    def __init__(self, path: str, field: str | None, problem: str) -> None:
        shown = path if path.isprintable() else repr(path)
        where = f"{shown}: {field}" if field else shown
        super().__init__(f"{where}: {problem}")
        self.path = path
        self.field = field


class CalibrationFileError(DataFileError):
    """A servo calibration file (TOML) is malformed or breaks its schema."""


class SerialLinkError(LynxsimError, OSError):
    """The serial port cannot be opened, vanished, or the board does not answer."""


class BoardTimeoutError(SerialLinkError):
    """The servo controller did not answer a query in time."""


class ProtocolError(LynxsimError, ValueError):
    """A servo-controller line or answer that the protocol does not define."""


class CommandLimitError(LynxsimError, ValueError):
    """A command stream would leave a joint's calibrated pulse range or exceed its speed.

    Attributes:
        joint: Name of the joint.
        quantity: ``"pulse"`` or ``"speed"``.
        time_s: When, from the start of the motion [s].
        value: The offending value [us or us/s].
        limit: The bound it breaks, in the same unit.
    """

    def __init__(
        self, message: str, *, joint: str, quantity: str, time_s: float, value: float, limit: float
    ) -> None:
        super().__init__(message)
        self.joint = joint
        self.quantity = quantity
        self.time_s = time_s
        self.value = value
        self.limit = limit


class CollisionRefusedError(LynxsimError):
    """A motion whose simulation collides, refused before anything is sent to hardware."""


__all__ += [
    "BoardTimeoutError",
    "CalibrationFileError",
    "CollisionRefusedError",
    "CommandLimitError",
    "DataFileError",
    "ProtocolError",
    "SerialLinkError",
]


class CapabilityError(InvalidInputError):
    """A robot asked for something it cannot do (a checker, a plan, a real backend, ...).

    The message names the robot and the capability; generic code raises it from a
    robot record's fields, never from its name.
    """


__all__ += ["CapabilityError"]


class InfeasibleSceneError(InvalidInputError):
    """An env's options can never produce an episode (refused at construction).

    E.g. fixed obstacles that leave the arm no point of a task region it reaches
    top-down, or a success radius no goal can lie outside of. The message names
    the options and the region.
    """


__all__ += ["InfeasibleSceneError"]
