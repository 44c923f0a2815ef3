"""Errors of the motion planner, all :class:`~lynxsim.errors.LynxsimError`.

A planning failure is an outcome the caller must handle (a blocked start, goals
in collision, no path in the time allowed, a potential field stuck in a local
minimum, a timed motion that cannot be kept clear); each names the segment when
the caller gave it a label, and carries the numbers it reports.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, LynxsimError

__all__ = [
    "GoalsInCollisionError",
    "LocalMinimumError",
    "NoPathError",
    "PlanningError",
    "StartInCollisionError",
    "TimingClearanceError",
    "UnknownPlannerError",
    "clearance_text",
]

FloatArray = npt.NDArray[np.float64]


def where(label: str) -> str:
    """``"segment 'label': "`` for messages, or ``""`` without a label."""
    return f"segment {label!r}: " if label else ""


class PlanningError(LynxsimError):
    """No collision-free motion was found as asked.

    Attributes:
        label: The segment's label as the caller gave it ("" if none).
    """

    def __init__(self, message: str, *, label: str = "") -> None:
        super().__init__(where(label) + message)
        self.label = label


def clearance_text(clearance_m: float) -> str:
    """A clearance for a message: metres, or "none (in collision)" where it is -inf.

    Shared by the planning modules' messages.
    """
    return f"{clearance_m:.4g} m" if np.isfinite(clearance_m) else "none (in collision)"


class StartInCollisionError(PlanningError):
    """The start configuration has less clearance than the margin.

    Attributes:
        q: The start, shape (n,) [rad].
        clearance_m: Its clearance [m] (<= 0 or -inf: in collision).
        margin_m: The margin asked for [m].
    """

    def __init__(self, q: FloatArray, clearance_m: float, margin_m: float, label: str = "") -> None:
        super().__init__(
            f"the start {np.array2string(q, precision=4)} rad has clearance "
            f"{clearance_text(clearance_m)}, less than the margin {margin_m:.4g} m",
            label=label,
        )
        self.q = q
        self.clearance_m = clearance_m
        self.margin_m = margin_m


class GoalsInCollisionError(PlanningError):
    """Every goal candidate has less clearance than the margin.

    Attributes:
        clearances_m: Clearance of each candidate, shape (K,) [m].
        margin_m: The margin asked for [m].
    """

    def __init__(self, clearances_m: FloatArray, margin_m: float, label: str = "") -> None:
        k = len(clearances_m)
        super().__init__(
            f"all {k} goal candidate{'s' if k != 1 else ''} have clearance below the margin "
            f"{margin_m:.4g} m (largest {clearance_text(float(np.max(clearances_m)))})",
            label=label,
        )
        self.clearances_m = clearances_m
        self.margin_m = margin_m


class NoPathError(PlanningError):
    """The planner found no path within its time limit.

    Attributes:
        planner: The planner's name.
        time_limit_s: The time it had [s].
    """

    def __init__(self, planner: str, time_limit_s: float, label: str = "") -> None:
        super().__init__(
            f"{planner} found no collision-free path within {time_limit_s:.4g} s "
            "(the goals may be unreachable, or need more time)",
            label=label,
        )
        self.planner = planner
        self.time_limit_s = time_limit_s


class LocalMinimumError(PlanningError):
    """The potential-field planner stopped moving before reaching a goal.

    Attributes:
        q: Where it stopped, shape (n,) [rad].
        distance_rad: Joint-space distance from there to the nearest goal [rad].
        steps: Steps taken.
    """

    def __init__(self, q: FloatArray, distance_rad: float, steps: int, label: str = "") -> None:
        super().__init__(
            f"potential field stuck in a local minimum at {np.array2string(q, precision=4)} "
            f"rad, {distance_rad:.4g} rad from the nearest goal, after {steps} steps",
            label=label,
        )
        self.q = q
        self.distance_rad = distance_rad
        self.steps = steps


class TimingClearanceError(PlanningError):
    """The timed motion cuts too close to an obstacle even after every repair.

    Attributes:
        time_s: When the smallest clearance occurs, from the segment's start [s].
        clearance_m: That clearance [m].
        required_m: The clearance a timed sample must keep [m].
        repairs: Repair rounds tried.
    """

    def __init__(
        self, time_s: float, clearance_m: float, required_m: float, repairs: int, label: str = ""
    ) -> None:
        super().__init__(
            f"the timed motion has clearance {clearance_text(clearance_m)} at {time_s:.4g} s, "
            f"less than {required_m:.4g} m, after {repairs} repair rounds "
            "(stops and midpoints added)",
            label=label,
        )
        self.time_s = time_s
        self.clearance_m = clearance_m
        self.required_m = required_m
        self.repairs = repairs


class UnknownPlannerError(InvalidInputError):
    """A planner name that is not one of the selectable OMPL planners.

    Attributes:
        name: The name given.
        valid: The selectable names.
    """

    def __init__(self, name: object, valid: Sequence[str], why: str = "") -> None:
        reason = f" ({why})" if why else ""
        super().__init__(f"unknown planner {name!r}{reason}; valid planners: {', '.join(valid)}")
        self.name = name
        self.valid = tuple(valid)
