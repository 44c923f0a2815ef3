"""Fuzz campaign of the trajectory layer's public functions (and the 3-RRR platform paths).

Each call picks one public function, one of its arguments and an odd value for
it (a special number: 5e-324, 1e-300, 1e300, 10**400, NaN, inf, -0.0, ...; a
wrong type: str, None, dict, complex, bool, object arrays, ragged lists; a
wrong shape; or a valid argument with one element replaced by such a value),
fills the other arguments with valid ones, and runs it with NumPy's
RuntimeWarnings and DeprecationWarnings raised as errors. The contract:

* the call returns a valid result (a trajectory or path whose durations lie in
  [MIN_SEGMENT_S, MAX_SEGMENT_S] and whose samples are finite; finite arrays), or
* it raises a :class:`~lynxsim.errors.LynxsimError`.

Anything else (an untyped exception, a warning, a non-finite result) is a
finding: the script prints the counts and a reproducer line per finding, and
exits 1::

    python tools/fuzz_traj.py --calls 4000 --seed 0

``tests/fuzz/test_fuzz_traj.py`` drives the same targets and oracle with hypothesis.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from lynxsim.arm.motion import (
    ArmPose,
    JointPose,
    cartesian_line,
    cubic,
    free_motion,
    generate,
    lspb,
    quintic,
    resolve_waypoints,
    ruckig_trajectory,
)
from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import LynxsimError
from lynxsim.rrr.path import PlatformLimits, PlatformPath, platform_path
from lynxsim.traj import (
    JointLimits,
    PolynomialSegment,
    Trajectory,
    TrajectorySample,
    check_trajectory,
    cubic_coefficients,
    quintic_coefficients,
)
from lynxsim.traj.lspb import lspb_segment

Q = np.radians(
    [
        [0.0, 60.0, -60.0, 0.0, 0.0],
        [40.0, 90.0, -30.0, 20.0, 90.0],
        [-20.0, 45.0, -90.0, -30.0, 180.0],
    ]
)
"""Valid joint waypoints [rad]."""


def arm_limits(velocity: Any, acceleration: Any, jerk: Any) -> JointLimits:
    """Limits of the arm's five joints, a scalar field for every joint."""
    return JointLimits.for_joints(5, velocity, acceleration, jerk)


POSES = (ArmPose((0.25, 0.0, 0.2), 0.0), ArmPose((0.2, 0.1, 0.25), -0.3, 0.5, "B"))
"""Valid task poses (tool point [m], pitch, roll [rad])."""

PLATFORM = np.array([[0.2511, 0.145, 0.0], [0.3, 0.2, 0.3], [0.2, 0.15, -0.2]])
"""Valid 3-RRR platform poses (x, y [m], alpha [rad])."""

SPECIALS: tuple[Any, ...] = (
    0,
    1,
    -1,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    1e-4,
    1e-3,
    0.5,
    1.0,
    2.0,
    3600.0,
    3600.5,
    1e60,
    1e300,
    -1e300,
    6.5e306,
    1.7976931348623157e308,
    math.nan,
    math.inf,
    -math.inf,
    10**400,
    -(10**400),
    2**63,
    True,
    False,
    None,
    "1.0",
    "abc",
    b"1",
    1j,
    1 + 0j,
    {},
    {"a": 1},
    [],
    (),
    set(),
    object(),
    np.float32(1.5),
    np.float16(1e4),
    np.longdouble("1e400"),
    np.int64(3),
    np.uint8(7),
    np.bool_(True),
    np.array(1.0),
    np.array([1.0]),
    np.array([True, False]),
    np.array([1.0], dtype=object),
    np.array(["1"]),
    np.array([1 + 1j]),
    np.zeros((0,)),
    np.zeros((2, 0)),
    np.ones((3, 3, 3)),
    [[1.0], [2.0, 3.0]],
    [1.0, "a"],
    [1.0, None],
    [1.0, 10**400],
    np.datetime64("2020-01-01"),
)
"""Odd values: special magnitudes, wrong types and wrong shapes."""

Outcome = Literal["ok", "typed", "untyped", "non_finite"]
FINDINGS = ("untyped", "non_finite")
"""Outcomes that break the contract."""


def odd_value(rng: np.random.Generator, valid: Any = None) -> Any:
    """An odd value: a special one, a random magnitude, a random array, or ``valid`` spoilt.

    Spoilt: one element replaced by a special value, or the whole scaled by 1e-6 to 1e6.
    """
    mode = int(rng.integers(7 if valid is not None else 4))
    if mode == 0:
        return SPECIALS[int(rng.integers(len(SPECIALS)))]
    if mode == 1:  # any magnitude, either sign
        return float(rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-320, 308))
    if mode == 2:  # a random array of odd shape
        shape = tuple(int(n) for n in rng.integers(0, 5, int(rng.integers(0, 4))))
        return rng.choice([1e-300, 1e-3, 1.0, 1e3, 1e300]) * rng.standard_normal(shape)
    if mode == 3:  # a nested list of specials
        n = int(rng.integers(0, 4))
        return [[odd_value(rng) for _ in range(int(rng.integers(0, 4)))] for _ in range(n)]
    if mode == 4:
        return spoil(valid, int(rng.integers(1 << 30)), SPECIALS[int(rng.integers(len(SPECIALS)))])
    # Plausible but extreme: the valid value scaled by 1e-6 .. 1e6 (deep paths of the math).
    return np.asarray(valid, dtype=float) * 10.0 ** rng.uniform(-6.0, 6.0)


def spoil(valid: Any, index: int, value: Any) -> Any:
    """``valid`` (a number or array) with one element, chosen by ``index``, set to ``value``."""
    if isinstance(valid, float | int):
        return value
    arr = np.asarray(valid, dtype=float)
    items: Any = arr.tolist()
    if arr.size == 0:
        return value
    flat = index % arr.size
    pos = np.unravel_index(flat, arr.shape)
    target = items
    for i in pos[:-1]:
        target = target[i]
    if pos:
        target[pos[-1]] = value
        return items
    return value


@dataclass(frozen=True)
class Call:
    """One call of a public function: what the campaign runs and prints."""

    name: str
    func: Callable[..., Any]
    args: tuple[Any, ...] = ()
    kwargs: dict[str, Any] = field(default_factory=dict)

    def run(self) -> Any:
        """Call the function."""
        return self.func(*self.args, **self.kwargs)

    def reproducer(self) -> str:
        """A Python line that repeats the call (arrays as their repr)."""
        parts = [_repr(a) for a in self.args] + [f"{k}={_repr(v)}" for k, v in self.kwargs.items()]
        return f"{self.name}({', '.join(parts)})"


def _repr(value: Any) -> str:
    if isinstance(value, np.ndarray):
        return f"np.{np.array_repr(value, precision=17)}".replace("\n", " ")
    try:
        text = repr(value)
    except ValueError:
        return f"<{type(value).__name__} too long to print>"
    return text if len(text) < 400 else text[:400] + "..."


_TRAJ: dict[str, Trajectory] = {}
_PATH: dict[str, PlatformPath] = {}


def _trajectory(kind: str) -> Trajectory:
    if kind not in _TRAJ:
        _TRAJ[kind] = generate(kind, Q if kind != "line" else list(POSES))
    return _TRAJ[kind]


def _path() -> PlatformPath:
    if "p" not in _PATH:
        _PATH["p"] = platform_path(PLATFORM)
    return _PATH["p"]


GENERATORS: dict[str, Callable[..., Trajectory]] = {
    "free_motion": free_motion,
    "cubic": cubic,
    "quintic": quintic,
    "lspb": lspb,
    "cartesian_line": cartesian_line,
    "ruckig_trajectory": ruckig_trajectory,
}
KINDS = ("free", "cubic", "quintic", "lspb", "line", "ruckig")


def _valid_waypoints(rng: np.random.Generator) -> Any:
    return list(POSES) if rng.random() < 0.3 else Q[: int(rng.integers(2, 4))]


def _durations(rng: np.random.Generator) -> Any:
    return [None, 1.5, 2.5][int(rng.integers(3))]


def make_call(target: str, rng: np.random.Generator) -> Call:
    """A call of ``target`` with one argument odd (drawn with ``rng``), the others valid."""
    odd = lambda valid=None: odd_value(rng, valid)  # noqa: E731
    if target in GENERATORS or target == "generate":
        wp = _valid_waypoints(rng)
        kwargs: dict[str, Any] = {"durations": _durations(rng)}
        slot = ["waypoints", "durations", "limits", "stretch", "geometry", "kind", "pass"][
            int(rng.integers(7 if target == "generate" else 5))
        ]
        if slot == "waypoints":
            wp = odd(Q)
        elif slot == "durations":
            kwargs["durations"] = odd(1.5)
        elif slot == "limits":
            kwargs["limits"] = Call("arm_limits", arm_limits, (odd(3.0), odd(10.0), odd(100.0)))
        elif slot == "stretch":
            kwargs["stretch"] = odd() if rng.random() < 0.5 else True
        elif slot == "geometry":
            kwargs["geometry"] = odd()
        elif slot == "pass":
            kwargs["pass_through"] = odd() if rng.random() < 0.5 else True
        if target == "generate":
            kind = odd() if slot == "kind" else KINDS[int(rng.integers(len(KINDS)))]
            return Call("generate", generate, (kind, wp), kwargs)
        return Call(target, GENERATORS[target], (wp,), kwargs)
    if target in ("sample", "times_at_rate", "times_per_segment"):
        kind = KINDS[int(rng.integers(len(KINDS)))]
        traj = _trajectory(kind)
        valid = {"sample": np.linspace(0.0, traj.duration, 4), "times_at_rate": 500.0}
        value = odd(valid.get(target, 10))
        return Call(f"generate({kind!r}, ...).{target}", getattr(traj, target), (value,))
    if target == "JointLimits":
        return Call("arm_limits", arm_limits, (odd(3.0), odd([1.0, 2.0, 3.0, 4.0, 5.0]), odd(9.0)))
    if target == "ArmPose":
        args = [odd([0.25, 0.0, 0.2]), odd(0.1), odd(0.2), odd() if rng.random() < 0.2 else "P"]
        keep = int(rng.integers(4))  # most of them valid
        valid = [(0.25, 0.0, 0.2), 0.1, 0.2, "P"]
        return Call(
            target, ArmPose, tuple(a if i == keep else valid[i] for i, a in enumerate(args))
        )
    if target == "JointPose":
        return Call(target, JointPose, (odd(Q[0]),))
    if target == "resolve_waypoints":
        return Call(target, resolve_waypoints, (odd(Q),))
    if target in ("cubic_coefficients", "quintic_coefficients"):
        n = 6 if target == "cubic_coefficients" else 8
        valid = [0.0, 1.0, *([0.5] * (n - 2))]
        i = int(rng.integers(n))
        valid[i] = odd(valid[i])
        func = cubic_coefficients if n == 6 else quintic_coefficients
        return Call(target, func, tuple(valid))
    if target == "PolynomialSegment":
        breaks, coefficients = np.array([0.0, 0.5, 1.0]), np.ones((2, 3, 5))
        if rng.random() < 0.5:
            return Call(target, PolynomialSegment, (odd(breaks), coefficients))
        return Call(target, PolynomialSegment, (breaks, odd(coefficients)))
    if target == "lspb_segment":
        valid = [Q[0], Q[1], 1.0, 4.0]
        i = int(rng.integers(4))
        valid[i] = odd(valid[i])
        return Call(target, lspb_segment, tuple(valid))
    if target == "check_trajectory":
        return Call(target, check_trajectory, (odd(),))
    if target == "platform_path":
        args: dict[str, Any] = {"durations": [None, 2.0][int(rng.integers(2))]}
        slot = int(rng.integers(7))
        wp: Any = PLATFORM
        if slot == 0:
            wp = odd(PLATFORM)
        elif slot == 1:
            args["durations"] = odd(2.0)
        elif slot == 2:
            args["limits"] = Call(
                "PlatformLimits", PlatformLimits, (odd(0.15), odd(1.0), odd(1.0), odd(6.0))
            )
        elif slot == 3:
            args["names"] = odd()
        elif slot == 4:
            args["through"] = odd() if rng.random() < 0.5 else True
        elif slot == 5:
            args["stretch"] = odd() if rng.random() < 0.5 else True
        else:
            args["through"] = True
            args["limits"] = Call(
                "PlatformLimits", PlatformLimits, (odd(0.15), odd(1.0), odd(1.0), odd(6.0))
            )
        return Call(target, platform_path, (wp,), args)
    if target == "path.sample":
        return Call("platform_path(PLATFORM).sample", _path().sample, (odd(np.linspace(0, 1, 4)),))
    raise ValueError(f"unknown target {target!r}")


TARGETS = (
    "generate",
    *GENERATORS,
    "sample",
    "times_at_rate",
    "times_per_segment",
    "JointLimits",
    "ArmPose",
    "JointPose",
    "resolve_waypoints",
    "cubic_coefficients",
    "quintic_coefficients",
    "PolynomialSegment",
    "lspb_segment",
    "check_trajectory",
    "platform_path",
    "path.sample",
)
"""Every public function fuzzed."""


def _resolve(value: Any) -> Any:
    """Build nested :class:`Call` arguments (limits objects) inside the fuzzed call."""
    return value.run() if isinstance(value, Call) else value


def _finite(values: Any) -> bool:
    return all(np.isfinite(np.asarray(v, dtype=float)).all() for v in values)


def result_problem(result: Any) -> str:
    """Why a returned value breaks the contract, or "" if it is valid."""
    if isinstance(result, Trajectory):
        d = result.segment_durations
        if not ((d >= MIN_SEGMENT_S * (1 - 1e-12)) & (d <= MAX_SEGMENT_S)).all():
            return f"segment durations {d.tolist()} outside [{MIN_SEGMENT_S}, {MAX_SEGMENT_S}] s"
        if not _finite(result.sample(np.linspace(0.0, result.duration, 33))):
            return "non-finite samples"
        return ""
    if isinstance(result, PlatformPath):
        d = result.durations
        if not (np.isfinite(d).all() and (d >= MIN_SEGMENT_S * (1 - 1e-12)).all()):
            return f"durations {d.tolist()}"
        if not result.through and (d > MAX_SEGMENT_S).any():
            return f"durations {d.tolist()} beyond {MAX_SEGMENT_S} s"
        if not _finite(result.sample(np.linspace(0.0, result.duration, 33))):
            return "non-finite samples"
        return ""
    if isinstance(result, TrajectorySample | tuple) and not isinstance(result, ArmPose):
        try:
            return "" if _finite(result) else "non-finite result"
        except (TypeError, ValueError):
            return ""
    if isinstance(result, np.ndarray) and not np.isfinite(result).all():
        return "non-finite array"
    return ""


def classify(call: Call) -> tuple[Outcome, str]:
    """Run a call under the contract: the outcome and a detail (error class or problem)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        warnings.simplefilter("error", DeprecationWarning)
        try:
            resolved = Call(
                call.name,
                call.func,
                tuple(_resolve(a) for a in call.args),
                {k: _resolve(v) for k, v in call.kwargs.items()},
            )
            result = resolved.run()
            problem = result_problem(result)
        except LynxsimError as exc:
            return "typed", type(exc).__name__
        except Exception as exc:  # the finding the campaign hunts
            return "untyped", f"{type(exc).__name__}: {str(exc)[:200]}"
    if problem:
        return "non_finite", problem
    return "ok", ""


def campaign(calls: int, seed: int) -> tuple[Counter[str], Counter[str], list[str]]:
    """Run ``calls`` fuzzed calls; (outcome counts, typed errors by class, findings)."""
    rng = np.random.default_rng(seed)
    outcomes: Counter[str] = Counter()
    typed: Counter[str] = Counter()
    findings: list[str] = []
    for i in range(calls):
        target = TARGETS[i % len(TARGETS)]
        call = make_call(target, rng)
        outcome, detail = classify(call)
        outcomes[outcome] += 1
        if outcome == "typed":
            typed[detail] += 1
        elif outcome in FINDINGS:
            findings.append(f"call {i} [{outcome}] {detail}\n    {call.reproducer()}")
    return outcomes, typed, findings


def main(argv: list[str] | None = None) -> int:
    """Run the campaign and print its counts; 1 if anything broke the contract."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=4000, help="calls to make (default 4000)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the generator (default 0)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    outcomes, typed, findings = campaign(args.calls, args.seed)
    elapsed = time.perf_counter() - start
    print(f"calls: {args.calls} (seed {args.seed}, {elapsed:.1f} s, {len(TARGETS)} targets)")
    print(f"results ok: {outcomes['ok']}")
    print(f"typed errors: {outcomes['typed']}")
    for name, count in sorted(typed.items(), key=lambda kv: (-kv[1], kv[0])):
        print(f"    {name}: {count}")
    print(f"untyped exceptions: {outcomes['untyped']}")
    print(f"non-finite or out-of-range results: {outcomes['non_finite']}")
    for line in findings:
        print(line)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
