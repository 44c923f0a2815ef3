"""Property tests of the trajectory layer's contract under odd inputs (hypothesis).

Every public function of :mod:`lynxsim.traj` (and :func:`lynxsim.rrr.path.platform_path`)
either returns a valid result (durations in [MIN_SEGMENT_S, MAX_SEGMENT_S], finite
samples) or raises a :class:`~lynxsim.errors.LynxsimError`. The targets and the
oracle are those of the campaign script ``tools/fuzz_traj.py``.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import array_shapes, arrays

from lynxsim.arm.motion import ArmPose, JointPose, generate, resolve_waypoints
from lynxsim.rrr.path import PlatformLimits, platform_path
from lynxsim.traj import PolynomialSegment, cubic_coefficients, quintic_coefficients

TOOL = Path(__file__).resolve().parents[2] / "tools" / "fuzz_traj.py"


def _load_tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("fuzz_traj", TOOL)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


fuzz = _load_tool()

FEW = settings(max_examples=150)
"""Examples per property: the whole file runs in a few seconds."""

numbers = st.one_of(
    st.sampled_from(fuzz.SPECIALS),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**400), max_value=10**400),
)
odd = st.one_of(
    numbers,
    st.lists(numbers, max_size=6),
    st.lists(st.lists(st.floats(), max_size=6), max_size=4),
    arrays(np.float64, array_shapes(min_dims=0, max_dims=3, max_side=5)),
    arrays(st.sampled_from([np.int64, np.float32, np.bool_, np.complex128]), st.integers(0, 6)),
)
"""Odd values: special magnitudes (5e-324, 1e-300, 1e300, 10**400, NaN, inf, -0.0),
wrong types, wrong shapes and dtypes."""


def spoilt(valid: Any) -> st.SearchStrategy[Any]:
    """``valid`` with one element replaced by an odd number, or scaled by 1e-6 .. 1e6."""
    return st.one_of(
        st.builds(fuzz.spoil, st.just(valid), st.integers(0, 1 << 20), numbers),
        st.builds(lambda e: np.asarray(valid, dtype=float) * 10.0**e, st.floats(-6.0, 6.0)),
    )


def assert_contract(call: Any) -> None:
    """A valid result or a LynxsimError; anything else fails with a reproducer."""
    outcome, detail = fuzz.classify(call)
    assert outcome not in fuzz.FINDINGS, f"{outcome}: {detail}\n{call.reproducer()}"


KINDS = st.sampled_from(fuzz.KINDS)
SLOTS = ("waypoints", "durations", "limits", "stretch", "pass_through", "geometry", "kind")


@FEW
@given(
    kind=KINDS,
    slot=st.sampled_from(SLOTS),
    value=st.one_of(odd, spoilt(fuzz.Q), spoilt(1.5)),
    durations=st.sampled_from([None, 1.5, 2.5]),
)
def test_generators_return_a_valid_trajectory_or_raise_a_typed_error(kind, slot, value, durations):
    args: list[Any] = [kind, fuzz.Q]
    kwargs: dict[str, Any] = {"durations": durations}
    if slot == "kind":
        args[0] = value
    elif slot == "waypoints":
        args[1] = value
    elif slot == "limits":
        kwargs["limits"] = fuzz.Call("arm_limits", fuzz.arm_limits, (value, 10.0, 100.0))
    else:
        kwargs[slot] = value
    assert_contract(fuzz.Call("generate", generate, tuple(args), kwargs))


@FEW
@given(
    kind=KINDS,
    method=st.sampled_from(["sample", "times_at_rate", "times_per_segment"]),
    value=st.one_of(odd, spoilt(np.linspace(0.0, 1.0, 4)), spoilt(500.0)),
)
def test_sampling_returns_finite_states_or_raises_a_typed_error(kind, method, value):
    traj = fuzz._trajectory(kind)
    assert_contract(fuzz.Call(f"{kind}.{method}", getattr(traj, method), (value,)))


@FEW
@given(
    which=st.sampled_from(["JointLimits", "ArmPose", "JointPose", "resolve_waypoints"]),
    value=st.one_of(odd, spoilt([0.25, 0.0, 0.2]), spoilt(fuzz.Q)),
    position=st.integers(0, 3),
)
def test_value_types_validate_their_fields(which, value, position):
    if which == "JointLimits":
        fields: list[Any] = [3.0, 10.0, 100.0]
        fields[position % 3] = value
        call = fuzz.Call("arm_limits", fuzz.arm_limits, tuple(fields))
    elif which == "ArmPose":
        fields = [(0.25, 0.0, 0.2), 0.1, 0.2, "P"]
        fields[position] = value
        call = fuzz.Call(which, ArmPose, tuple(fields))
    elif which == "JointPose":
        call = fuzz.Call(which, JointPose, (value,))
    else:
        call = fuzz.Call(which, resolve_waypoints, (value,))
    assert_contract(call)


@FEW
@given(value=st.one_of(odd, spoilt(1.0)), position=st.integers(0, 7), quintic=st.booleans())
def test_coefficients_and_segments_validate_their_inputs(value, position, quintic):
    n = 8 if quintic else 6
    args: list[Any] = [0.0, 1.0, *([0.5] * (n - 2))]
    args[position % n] = value
    func = quintic_coefficients if quintic else cubic_coefficients
    assert_contract(fuzz.Call(func.__name__, func, tuple(args)))
    breaks, coefficients = np.array([0.0, 0.5, 1.0]), np.ones((2, 3, 5))
    segment = (value, coefficients) if position % 2 else (breaks, value)
    assert_contract(fuzz.Call("PolynomialSegment", PolynomialSegment, segment))


@FEW
@given(
    slot=st.sampled_from(["waypoints", "durations", "limits", "names", "through", "stretch"]),
    value=st.one_of(odd, spoilt(fuzz.PLATFORM), spoilt(2.0)),
    through=st.booleans(),
    durations=st.sampled_from([None, 2.0]),
)
def test_platform_paths_are_valid_or_raise_a_typed_error(slot, value, through, durations):
    args: tuple[Any, ...] = (fuzz.PLATFORM,)
    kwargs: dict[str, Any] = {"durations": durations, "through": through}
    if slot == "waypoints":
        args = (value,)
    elif slot == "limits":
        kwargs["limits"] = fuzz.Call("PlatformLimits", PlatformLimits, (value, 1.0, value, 6.0))
    else:
        kwargs[slot] = value
    assert_contract(fuzz.Call("platform_path", platform_path, args, kwargs))


def test_the_campaign_finds_nothing_in_a_short_run():
    outcomes, typed, findings = fuzz.campaign(calls=2 * len(fuzz.TARGETS), seed=0)
    assert not findings, "\n".join(findings)
    assert outcomes["ok"] > 0
    assert sum(typed.values()) > 0
