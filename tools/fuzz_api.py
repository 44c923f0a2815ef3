"""Fuzz campaign of lynxsim's public library API: odd Python types, huge and odd numbers.

Calls every public function of :mod:`lynxsim.arm`, :mod:`lynxsim.rrr` (but its
``path`` and ``task`` modules), :mod:`lynxsim.scene` and :mod:`lynxsim.angles`,
and the env constructors, ``reset`` and ``step``, with arguments drawn by a plain
:class:`numpy.random.Generator`: about half of them valid, the others odd (None,
strings, dicts, ragged lists, complex numbers, booleans and bool or object arrays,
``10**400``, NaN, infinity, 1e300, denormals, NumPy scalars, wrong shapes, huge
counts, tiny resolutions). The contract:

* a call returns a valid result (finite, or NaN exactly where the function
  documents it: a status array, an unreachable pose, a NaN input), or
* it raises a :class:`~lynxsim.errors.LynxsimError`.

Anything else (an untyped exception, a RuntimeWarning, a non-finite result) is a
finding: the script prints the counts and one reproducer line per finding, and
exits 1::

    python tools/fuzz_api.py --calls 4000 --seed 0

``tests/fuzz/test_fuzz_api.py`` drives the same targets and oracle with hypothesis.
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
from typing import Any

import numpy as np

from lynxsim import angles, arm, rrr, scene
from lynxsim.errors import LynxsimError

Check = Callable[[Any, tuple[Any, ...], dict[str, Any]], None]
"""Raises AssertionError when a returned result breaks the contract."""

# ------------------------------------------------------------------ the oracle


def _arrays(result: Any) -> list[np.ndarray]:
    """Every float array (or float) inside a result, walked recursively."""
    if isinstance(result, float | np.floating):
        return [np.asarray(result, dtype=float)]
    if isinstance(result, np.ndarray):
        return [result] if result.dtype.kind == "f" else []
    if isinstance(result, tuple | list):
        return [a for item in result for a in _arrays(item)]
    if hasattr(result, "__dataclass_fields__"):
        return [a for name in result.__dataclass_fields__ for a in _arrays(getattr(result, name))]
    return []


def _inputs_finite(args: tuple[Any, ...], kwargs: dict[str, Any]) -> bool:
    """Whether every numeric input is finite (a non-finite one may give NaN)."""
    for value in (*args, *kwargs.values()):
        try:
            arr = np.asarray(value)
        except (TypeError, ValueError):
            continue
        if arr.dtype.kind in "fc" and not np.isfinite(arr).all():
            return False
    return True


def finite(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Every float in the result is finite."""
    for a in _arrays(result):
        assert np.isfinite(a).all(), f"non-finite result {a!r}"


def nan_in_nan_out(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Never infinity; NaN only where an input is NaN or infinite."""
    for a in _arrays(result):
        assert not np.isinf(a).any(), f"infinite result {a!r}"
        if _inputs_finite(args, kwargs):
            assert not np.isnan(a).any(), f"NaN result from finite inputs: {a!r}"


def no_inf(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Never infinity (NaN marks documented outcomes: unreachable, not converged)."""
    for a in _arrays(result):
        assert not np.isinf(a).any(), f"infinite result {a!r}"


def arm_ik_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Solved targets have finite joints inside the ranges; the others NaN."""
    assert set(np.unique(result.status)) <= {int(s) for s in arm.IKStatus}
    q_ok = result.q[result.ok]
    assert np.isfinite(q_ok).all(), "a solved target has non-finite joints"
    assert np.isnan(result.q[~result.ok]).all(), "an unsolved target has joints"


def ik_nearest_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """``(status, q)``: q is 5 finite floats exactly when the status is OK."""
    status, q = result
    assert isinstance(status, arm.IKStatus)
    if status is arm.IKStatus.OK:
        assert isinstance(q, tuple)
        assert len(q) == 5
        assert all(type(v) is float and math.isfinite(v) for v in q), q
    else:
        assert q is None


def rrr_ik_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Reachable poses have finite angles in [-pi, pi]; the others NaN."""
    theta_ok = result.theta[result.ok]
    assert np.isfinite(theta_ok).all()
    assert (np.abs(theta_ok) <= math.pi + 1e-12).all()
    assert np.isnan(result.theta[~result.ok]).all()


def fk_all_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """The first ``num_solutions`` poses are finite, the padding NaN."""
    n = result.num_solutions
    filled = np.arange(rrr.MAX_ASSEMBLY_MODES) < n[..., None]
    assert np.isfinite(result.pose[filled]).all()
    assert np.isnan(result.pose[~filled]).all()


def fk_near_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Converged poses finite, the others NaN."""
    assert np.isfinite(result.pose[result.converged]).all()
    assert np.isnan(result.pose[~result.converged]).all()


def range_in_mode_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Two floats, both finite (lower <= upper) or both NaN."""
    lo, hi = result
    assert (math.isnan(lo) and math.isnan(hi)) or (math.isfinite(lo) and lo <= hi <= lo + 7.0)


def workspace_map_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Finite measures where reachable, NaN elsewhere."""
    ok = result.reachable
    assert np.isfinite(result.serial[ok]).all()
    assert np.isnan(result.serial[~ok]).all()
    assert np.isfinite(result.parallel[ok]).all()


def workspace_maps_result(result: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Each map as :func:`workspace_map_result`."""
    for wmap in result:
        workspace_map_result(wmap, args, kwargs)


# -------------------------------------------------------------- the arguments

_ODD_COMMON: tuple[Any, ...] = (
    None,
    "abc",
    "0.1",
    b"\x00",
    {},
    {"x": 1.0},
    [1.0, [2.0, 3.0]],
    1 + 2j,
    True,
    np.bool_(True),
    10**400,
    -(10**400),
    math.nan,
    math.inf,
    -math.inf,
    1e300,
    -1e300,
    5e-324,
    np.float32(0.1),
    np.int64(3),
    np.array([True, False, True]),
    np.array([1.0, "a", None], dtype=object),
    np.array([10**400, 1, 2], dtype=object),
    np.zeros(0),
    np.zeros((2, 0, 3)),
    np.array(0.5),
    np.array([0.5]),
    np.complex128(1.0),
    object(),
    [],
    (),
    [None, None, None],
)
"""Odd values tried for every argument."""


def _vec(rng: np.random.Generator, lo: Any, hi: Any, n: int) -> Any:
    """A valid vector, as a list, tuple, float64 array, float32 array or small batch."""
    v = rng.uniform(lo, hi, n)
    form = rng.integers(5)
    if form == 0:
        return v.tolist()
    if form == 1:
        return tuple(v.tolist())
    if form == 2:
        return v.astype(np.float32)
    if form == 3:
        return rng.uniform(lo, hi, (int(rng.integers(1, 4)), n))
    return v


def _mutate(rng: np.random.Generator, value: Any) -> Any:
    """A near-valid value made odd: one entry NaN/inf/huge/str, a wrong shape or dtype."""
    arr = np.array(value, dtype=float)
    choice = int(rng.integers(9))
    if arr.size == 0 or choice == 0:
        return np.append(arr.ravel(), 0.0)  # one too many
    flat = arr.ravel().copy()
    i = int(rng.integers(flat.size))
    if choice == 1:
        flat[i] = rng.choice([math.nan, math.inf, -math.inf])
        return flat.reshape(arr.shape)
    if choice == 2:
        flat[i] = rng.choice([1e300, -1e300, 1e20, 5e-324, 1e16])
        return flat.reshape(arr.shape)
    if choice == 3:
        out = flat.tolist()
        out[i] = "x"
        return out
    if choice == 4:
        out = flat.tolist()
        out[i] = 10**400
        return out
    if choice == 5:
        return arr.astype(complex)
    if choice == 6:
        return arr.astype(bool)
    if choice == 7:
        return arr.ravel()[:-1]  # one too few
    return arr.reshape(arr.shape + (1,))  # an extra axis


Gen = Callable[[np.random.Generator], Any]


@dataclass(frozen=True)
class Arg:
    """How to draw one argument: a valid value, and odd values beyond the common ones."""

    valid: Gen
    odd: tuple[Any, ...] = ()
    mutate: bool = True


@dataclass(frozen=True)
class Target:
    """One public function under test."""

    name: str
    fn: Callable[..., Any]
    args: tuple[Arg, ...]
    check: Check = finite
    kwargs: dict[str, Arg] = field(default_factory=dict)


_Q_LO, _Q_HI = arm.LYNX_ARM.lower, arm.LYNX_ARM.upper
Q5 = Arg(lambda r: _vec(r, _Q_LO, _Q_HI, 5))
Q5_ONE = Arg(lambda r: r.uniform(_Q_LO, _Q_HI).tolist())
POS3 = Arg(lambda r: _vec(r, [-0.3, -0.3, -0.1], [0.4, 0.4, 0.4], 3))
POS3_ONE = Arg(lambda r: r.uniform([-0.3, -0.3, -0.1], [0.4, 0.4, 0.4]).tolist())
ANGLE = Arg(lambda r: float(r.uniform(-math.pi, math.pi)), odd=(np.array([[0.1]]), np.zeros(2)))
ANGLE_ONE = Arg(
    lambda r: [float(r.uniform(-1.5, 1.5)), np.array([r.uniform(-1.5, 1.5)])][int(r.integers(2))],
    odd=(np.array([[0.1]]), np.zeros(2)),
)
COORD = Arg(lambda r: float(r.uniform(-0.3, 0.4)), odd=(11.0, -1e6))
ANGLES_ANY = Arg(lambda r: _vec(r, -10.0, 10.0, int(r.integers(1, 6))))
RNG = Arg(
    lambda r: np.random.default_rng(int(r.integers(1000))),
    odd=(0, np.random.RandomState(0)),
    mutate=False,
)
COUNT = Arg(
    lambda r: int(r.integers(1, 200)),
    odd=(0, -5, 999_999_999_999, 10**18, 2.5, np.float64(3.0), 10**400),
    mutate=False,
)
KIND = Arg(
    lambda r: ["position", "position_pitch"][int(r.integers(2))],
    odd=("x", ["position"]),
    mutate=False,
)
GEOM_ARM = Arg(lambda r: arm.LYNX_ARM, odd=(rrr.RRR_ROBOT, "arm"), mutate=False)
GEOM_RRR = Arg(lambda r: rrr.RRR_ROBOT, odd=(arm.LYNX_ARM, "rrr"), mutate=False)

_XY_LO, _XY_HI = [0.1, 0.0], [0.4, 0.3]
POSE = Arg(lambda r: _vec(r, [*_XY_LO, -1.0], [*_XY_HI, 1.0], 3), odd=([11.0, 0.0, 0.0],))
POSE_ONE = Arg(lambda r: r.uniform([*_XY_LO, -1.0], [*_XY_HI, 1.0]).tolist())
THETA = Arg(lambda r: _vec(r, -math.pi, math.pi, 3))
THETA_PATH = Arg(lambda r: r.uniform(-0.2, 0.2, (int(r.integers(1, 4)), 3)) + [-0.5, 2.0, 4.5])
XY = Arg(lambda r: _vec(r, _XY_LO, _XY_HI, 2))
GRID = Arg(lambda r: np.linspace(0.0, 0.5, int(r.integers(1, 30))), odd=(np.zeros((2, 2)),))
MODE = Arg(
    lambda r: int(r.integers(8)),
    odd=(8, -1, 2.0, np.array([0, 9]), np.arange(3), 10**400, np.int8(3)),
    mutate=False,
)
SIGNS = Arg(lambda r: r.choice([-1, 1], 3).tolist(), odd=([1, 0, 1], [1.0, -1.0, 1.0]))
EXTENT = Arg(
    lambda r: (0.0, float(r.uniform(0.05, 0.5)), 0.0, float(r.uniform(0.05, 0.4))),
    odd=((0.5, 0.0, 0.0, 0.4), (0.0, 1e9, 0.0, 1.0)),
)
RESOLUTION = Arg(
    lambda r: float(r.uniform(0.01, 0.05)), odd=(1e-300, 0.0, -0.01, 1e-9, 5e-324, 1e-5)
)
ALPHAS = Arg(lambda r: r.uniform(-1.0, 1.0, int(r.integers(1, 3))).tolist(), odd=([], [[0.1]]))
STEP = Arg(lambda r: float(r.uniform(0.01, 0.2)), odd=(0.0, 1e-300, 5e-324, -0.1, 10.0))
SMALL_INT = Arg(lambda r: int(r.integers(1, 30)), odd=(0, -1, 10**9, 2.5), mutate=False)
BOOL = Arg(lambda r: bool(r.integers(2)), odd=("yes",), mutate=False)
MARGIN = Arg(lambda r: float(r.uniform(0.0, 0.05)), odd=(-1.0, 1e300))

TARGETS: tuple[Target, ...] = (
    Target("lynxsim.angles.wrap_angle", angles.wrap_angle, (ANGLES_ANY,), nan_in_nan_out),
    Target("lynxsim.arm.fk", arm.fk, (Q5,), kwargs={"geometry": GEOM_ARM}),
    Target("lynxsim.arm.frame_transforms", arm.frame_transforms, (Q5,)),
    Target("lynxsim.arm.frame_origins", arm.frame_origins, (Q5,)),
    Target("lynxsim.arm.tool_pose", arm.tool_pose, (Q5,), kwargs={"geometry": GEOM_ARM}),
    Target("lynxsim.arm.jacobian", arm.jacobian, (Q5,)),
    Target("lynxsim.arm.geometric_jacobian", arm.geometric_jacobian, (Q5,)),
    Target("lynxsim.arm.manipulability", arm.manipulability, (Q5, KIND)),
    Target("lynxsim.arm.tool_pose_of", arm.tool_pose_of, (Q5_ONE,), kwargs={"geometry": GEOM_ARM}),
    Target(
        "lynxsim.arm.ik",
        arm.ik,
        (POS3, ANGLE_ONE),
        arm_ik_result,
        kwargs={"roll": ANGLE_ONE, "q_ref": Q5, "geometry": GEOM_ARM},
    ),
    Target(
        "lynxsim.arm.ik_one",
        arm.ik_one,
        (POS3_ONE, ANGLE_ONE),
        kwargs={"roll": ANGLE_ONE, "q_ref": Q5_ONE},
    ),
    Target(
        "lynxsim.arm.ik_nearest",
        arm.ik_nearest,
        (COORD, COORD, COORD, ANGLE_ONE, ANGLE_ONE, Q5_ONE),
        ik_nearest_result,
    ),
    Target(
        "lynxsim.arm.sample_workspace",
        arm.sample_workspace,
        (COUNT, RNG),
        kwargs={"geometry": GEOM_ARM},
    ),
    Target("lynxsim.rrr.ik", rrr.ik, (POSE,), rrr_ik_result, kwargs={"geometry": GEOM_RRR}),
    Target("lynxsim.rrr.ik_one", rrr.ik_one, (POSE_ONE,)),
    Target("lynxsim.rrr.leg_points", rrr.leg_points, (POSE, MODE), no_inf),
    Target("lynxsim.rrr.platform_joints", rrr.platform_joints, (POSE,), nan_in_nan_out),
    Target("lynxsim.rrr.rotation", rrr.rotation, (ANGLES_ANY,), nan_in_nan_out),
    Target("lynxsim.rrr.elbow_points", rrr.elbow_points, (THETA,), nan_in_nan_out),
    Target("lynxsim.rrr.loop_residual", rrr.loop_residual, (POSE, THETA), nan_in_nan_out),
    Target("lynxsim.rrr.fk_all", rrr.fk_all, (THETA,), fk_all_result),
    Target(
        "lynxsim.rrr.fk_near",
        rrr.fk_near,
        (THETA, POSE),
        fk_near_result,
        kwargs={"max_iter": SMALL_INT},
    ),
    Target(
        "lynxsim.rrr.fk_path",
        rrr.fk_path,
        (THETA_PATH, POSE_ONE),
        fk_near_result,
        kwargs={"max_halvings": SMALL_INT},
    ),
    Target(
        "lynxsim.rrr.constraint_jacobians", rrr.constraint_jacobians, (POSE, THETA), nan_in_nan_out
    ),
    Target("lynxsim.rrr.forward_jacobian", rrr.forward_jacobian, (POSE, THETA), no_inf),
    Target("lynxsim.rrr.inverse_jacobian", rrr.inverse_jacobian, (POSE, THETA), no_inf),
    Target("lynxsim.rrr.singularity_measures", rrr.singularity_measures, (POSE, THETA), no_inf),
    Target("lynxsim.rrr.mode_signs", rrr.mode_signs, (MODE,)),
    Target("lynxsim.rrr.mode_index", rrr.mode_index, (SIGNS,)),
    Target("lynxsim.rrr.mode_label", rrr.mode_label, (MODE,)),
    Target(
        "lynxsim.rrr.orientation_range",
        rrr.orientation_range,
        (XY,),
        no_inf,
        kwargs={"alpha_ref": ANGLE},
    ),
    Target("lynxsim.rrr.orientation_intervals", rrr.orientation_intervals, (COORD, COORD)),
    Target(
        "lynxsim.rrr.orientation_range_in_mode",
        rrr.orientation_range_in_mode,
        (COORD, COORD, MODE),
        range_in_mode_result,
        kwargs={"alpha_ref": ANGLE, "step": STEP},
    ),
    Target("lynxsim.rrr.leg_annuli", rrr.leg_annuli, (ANGLE,), kwargs={"geometry": GEOM_RRR}),
    Target("lynxsim.rrr.grid_extent", rrr.grid_extent, (ALPHAS,), kwargs={"margin": MARGIN}),
    Target(
        "lynxsim.rrr.workspace_map",
        rrr.workspace_map,
        (GRID, GRID, ANGLE),
        workspace_map_result,
        kwargs={"with_theta": BOOL},
    ),
    Target(
        "lynxsim.rrr.workspace.workspace_maps",
        rrr.workspace.workspace_maps,
        (ALPHAS, EXTENT, RESOLUTION),
        workspace_maps_result,
    ),
    Target(
        "lynxsim.rrr.RRRGeometry.symmetric",
        lambda base_radius, platform_radius, proximal, distal: rrr.RRRGeometry.symmetric(
            base_centre=(0.25, 0.15),
            base_radius=base_radius,
            platform_radius=platform_radius,
            proximal=proximal,
            distal=distal,
        ),
        (Arg(lambda r: 0.29), Arg(lambda r: 0.13), Arg(lambda r: 0.17), Arg(lambda r: 0.13)),
    ),
    Target(
        "lynxsim.arm.ServoSpec",
        lambda torque, speed, armature: arm.ServoSpec("base", "HS-0", torque, speed, armature),
        (Arg(lambda r: 6.0), Arg(lambda r: 0.18), Arg(lambda r: 0.002)),
    ),
    Target(
        "lynxsim.scene.Cylinder",
        lambda position, radius, height: scene.Cylinder("c", position, radius, height),
        (Arg(lambda r: (0.2, 0.2, 0.0)), Arg(lambda r: 0.04), Arg(lambda r: 0.3)),
    ),
    Target(
        "lynxsim.scene.Box",
        lambda position, size, yaw: scene.Box("b", position, size, yaw),
        (Arg(lambda r: (0.2, 0.2, 0.0)), Arg(lambda r: (0.1, 0.1, 0.1)), ANGLE),
    ),
    Target(
        "lynxsim.scene.Sphere",
        lambda position, radius: scene.Sphere("s", position, radius),
        (Arg(lambda r: (0.2, 0.2, 0.1)), Arg(lambda r: 0.05)),
    ),
    Target(
        "lynxsim.scene.Cube",
        lambda position, size, yaw, mass: scene.Cube(position, size, yaw, mass),
        (Arg(lambda r: (0.0, 0.3, 0.0)), Arg(lambda r: 0.025), ANGLE, Arg(lambda r: 0.01)),
    ),
    Target(
        "lynxsim.scene.Table",
        lambda top_z, center, size: scene.Table(top_z, center, size),
        (Arg(lambda r: -0.0125), Arg(lambda r: (0.1, 0.0)), Arg(lambda r: (0.7, 1.0))),
    ),
    Target(
        "lynxsim.scene.Scene",
        lambda obstacles, cube: scene.Scene(obstacles, cube=cube),
        (
            Arg(lambda r: (scene.REPORT_CYLINDER,), odd=([scene.REPORT_CYLINDER],), mutate=False),
            Arg(lambda r: scene.REPORT_CUBE, odd=(scene.TABLE,), mutate=False),
        ),
    ),
)
"""Every public function (and value constructor) under test."""


def draw_value(rng: np.random.Generator, spec: Arg) -> Any:
    """A valid value (about half the time) or an odd one."""
    u = rng.uniform()
    if u < 0.5:
        return spec.valid(rng)
    if u < 0.75 and spec.mutate:
        return _mutate(rng, spec.valid(rng))
    pool = spec.odd + _ODD_COMMON if rng.uniform() < 0.5 or not spec.odd else spec.odd
    return pool[int(rng.integers(len(pool)))]


def draw_call(rng: np.random.Generator, target: Target) -> tuple[tuple[Any, ...], dict[str, Any]]:
    """Positional and keyword arguments of one call."""
    args = tuple(draw_value(rng, spec) for spec in target.args)
    kwargs = {k: draw_value(rng, spec) for k, spec in target.kwargs.items() if rng.uniform() < 0.4}
    return args, kwargs


# ------------------------------------------------------------------ one call


def _show(value: Any) -> str:
    """A Python expression that rebuilds ``value`` (numpy as ``np``)."""
    if isinstance(value, np.ndarray):
        if value.size > 12:
            return f"np.full({value.shape}, {_show(value.flat[0])}, dtype=np.{value.dtype})"
        return f"np.array({_show(value.tolist())}, dtype=np.{value.dtype})"
    if isinstance(value, np.generic):
        return f"np.{type(value).__name__}({_show(value.item())})"
    if isinstance(value, float) and not math.isfinite(value):
        return f"float('{value}')"
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > 10**20:
        return f"{'-' if value < 0 else ''}10**{len(str(abs(value))) - 1}"
    if isinstance(value, list):
        return "[" + ", ".join(_show(v) for v in value) + "]"
    if isinstance(value, tuple):
        return "(" + ", ".join(_show(v) for v in value) + ("," if len(value) == 1 else "") + ")"
    if isinstance(value, np.random.Generator):
        return "np.random.default_rng(0)"
    if type(value) is object:
        return "object()"
    return repr(value)


def reproducer(name: str, args: tuple[Any, ...], kwargs: dict[str, Any]) -> str:
    """One line of Python that repeats a call."""
    parts = [_show(a) for a in args] + [f"{k}={_show(v)}" for k, v in kwargs.items()]
    return f"{name}({', '.join(parts)})"


@dataclass(frozen=True)
class Outcome:
    """What one call did: ``"ok"``, ``"typed"`` (with the class) or ``"untyped"``."""

    kind: str
    detail: str = ""


def run_call(
    fn: Callable[..., Any], check: Check, args: tuple[Any, ...], kw: dict[str, Any]
) -> Outcome:
    """Call ``fn``, turning RuntimeWarnings into errors, and judge the outcome."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        try:
            result = fn(*args, **kw)
        except LynxsimError as exc:
            return Outcome("typed", type(exc).__name__)
        except Exception as exc:
            return Outcome("untyped", f"{type(exc).__name__}: {str(exc)[:160]}")
        try:
            check(result, args, kw)
        except AssertionError as exc:
            return Outcome("untyped", f"invalid result: {str(exc)[:160]}")
        except Exception as exc:
            return Outcome("untyped", f"result check failed: {type(exc).__name__}: {exc}")
    return Outcome("ok")


# ---------------------------------------------------------------------- envs

_ENV_ARGS: dict[str, tuple[Any, ...]] = {
    "control_dt": (1e9, 0.0, -0.04, 0.001, 0.041, math.nan, math.inf, "0.04", 10**400, None, 2.0),
    "distance_threshold": (0.0, -1.0, math.nan, "a", 1e300, None, True),
    "collision_penalty": (-1.0, math.nan, math.inf, "a", 10**400, 1e300),
    "position_step": (0.0, -0.1, math.inf, 1e300, "a", None),
    "pitch_step": (0.0, math.nan, 100.0, [0.1]),
    "roll_step": (0.0, -0.1, math.nan, 100.0, "a", None),
    "joint_step": (0.0, -0.05, 1e9, complex(1, 1)),
    "width": (0, -1, 10**9, 64.5, "640", None, True),
    "height": (0, 10**400, 2.0, np.float64(480.0)),
    "camera": ("nope", None, 3, ["front"]),
    "render_mode": ("bad", 3, ["rgb_array"], np.array(["rgb_array"])),
    "render_quality": ("ultra", None, 1),
    "control": ("torque", None, 1.0, ["tool"]),
    "reward_type": ("medium", {}, None),
    "collision_check": ("always", 0),
    "terminate_on_collision": ("yes", 2, None),
    "obstacles": (None, "cylinder", [1.0], 3),
    "goal_in_air_prob": (-0.1, 1.5, math.nan, "half", None),
}
"""Odd values of the env constructors' arguments."""

_ENV_VALID: dict[str, tuple[Any, ...]] = {
    "control_dt": (0.02, 0.04, 0.002, 1.0),
    "distance_threshold": (0.01, 0.05),
    "width": (64, 128),
    "height": (48, 96),
    "camera": ("front", "top"),
    "control": ("tool", "joint", "tool_roll"),
    "collision_check": ("control_step", "physics_step"),
}

_ODD_ACTIONS: tuple[Any, ...] = (
    None,
    "abc",
    {},
    [0.1, [0.2]],
    np.zeros(3),
    np.zeros(7),
    np.zeros((1, 5)),
    np.array([True] * 5),
    np.array([1j] * 5),
    np.array([0.0, math.nan, 0.0, 0.0, 0.0]),
    np.array([math.inf] * 5),
    [1e308] * 5,
    [10**400] * 5,
    np.array([0.0] * 5, dtype=object),
)

_ODD_SEEDS: tuple[Any, ...] = (-1, "1", 1.5, True, np.int64(3), 10**30, None, [1])


def env_calls(rng: np.random.Generator, n_make: int, n_step: int) -> list[tuple[str, Outcome]]:
    """Constructor calls with one odd or valid argument, then steps and resets with odd inputs."""
    import lynxsim.envs as envs

    classes = (envs.PickAndPlaceEnv, envs.ReachEnv)
    out: list[tuple[str, Outcome]] = []
    for _ in range(n_make):
        cls = classes[int(rng.integers(2))]
        names = [k for k in _ENV_ARGS if k != "goal_in_air_prob" or cls is envs.PickAndPlaceEnv]
        key = names[int(rng.integers(len(names)))]
        pool = _ENV_ARGS[key] if rng.uniform() < 0.8 or key not in _ENV_VALID else _ENV_VALID[key]
        kwargs = {key: pool[int(rng.integers(len(pool)))]}

        def make(cls: Any = cls, **kw: Any) -> Any:
            env = cls(**kw)
            env.close()
            return None

        line = reproducer(f"lynxsim.envs.{cls.__name__}", (), kwargs)
        out.append((line, run_call(make, finite, (), kwargs)))
    for cls in classes:
        env = cls()
        env.reset(seed=0)
        n = env.action_space.shape[0]

        def step(action: Any, env: Any = env) -> Any:
            obs, reward, *_ = env.step(action)
            return obs["observation"], reward

        def reset(seed: Any, env: Any = env) -> Any:
            obs, _ = env.reset(seed=seed)
            return obs["observation"]

        for _ in range(n_step // 2):
            u = rng.uniform()
            if u < 0.4:
                action = rng.uniform(-2.0, 2.0, n).astype(rng.choice([np.float32, np.float64]))
            elif u < 0.85:
                action = _ODD_ACTIONS[int(rng.integers(len(_ODD_ACTIONS)))]
                if isinstance(action, list | np.ndarray) and len(action) == 5 and n == 4:
                    action = action[:4]
            else:
                seed = _ODD_SEEDS[int(rng.integers(len(_ODD_SEEDS)))]
                line = reproducer(f"lynxsim.envs.{cls.__name__}().reset", (), {"seed": seed})
                out.append((line, run_call(reset, finite, (seed,), {})))
                continue
            line = reproducer(f"lynxsim.envs.{cls.__name__}().step", (action,), {})
            out.append((line, run_call(step, finite, (action,), {})))
        env.close()
    return out


# ---------------------------------------------------------------------- main


def campaign(calls: int, seed: int, env_make: int, env_step: int) -> tuple[Counter[str], list[str]]:
    """Run the campaign; return the counts and the reproducer lines of the findings."""
    rng = np.random.default_rng(seed)
    counts: Counter[str] = Counter()
    findings: list[str] = []

    def record(line: str, outcome: Outcome) -> None:
        counts["calls"] += 1
        if outcome.kind == "ok":
            counts["ok"] += 1
        elif outcome.kind == "typed":
            counts[f"typed {outcome.detail}"] += 1
        else:
            counts["untyped"] += 1
            findings.append(f"{line}  # {outcome.detail}")

    for k in range(calls):
        target = (
            TARGETS[k % len(TARGETS)]
            if k < len(TARGETS)
            else TARGETS[int(rng.integers(len(TARGETS)))]
        )
        args, kwargs = draw_call(rng, target)
        record(
            reproducer(target.name, args, kwargs), run_call(target.fn, target.check, args, kwargs)
        )
    for line, outcome in env_calls(rng, env_make, env_step):
        record(line, outcome)
    return counts, findings


def main(argv: list[str] | None = None) -> int:
    """Run the campaign and print its counts; exit status 1 on any finding."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=4000, help="library calls (default 4000)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the generator (default 0)")
    parser.add_argument("--env-make", type=int, default=200, help="env constructor calls")
    parser.add_argument("--env-step", type=int, default=200, help="env step/reset calls")
    opts = parser.parse_args(argv)
    start = time.perf_counter()
    counts, findings = campaign(opts.calls, opts.seed, opts.env_make, opts.env_step)
    elapsed = time.perf_counter() - start
    print(f"calls: {counts['calls']} ({len(TARGETS)} library functions + env make/step/reset)")
    print(f"ok: {counts['ok']}")
    typed = sorted((k for k in counts if k.startswith("typed ")), key=lambda k: -counts[k])
    print(f"typed errors: {sum(counts[k] for k in typed)}")
    for k in typed:
        print(f"  {k.removeprefix('typed '):32s} {counts[k]}")
    print(f"untyped: {counts['untyped']}")
    for line in findings:
        print(f"  {line}")
    print(f"time: {elapsed:.1f} s")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
