"""The robot interface's values and lookups: validated, typed, refused by capability."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lynxsim.arm.motion import ARM_BOUNDS, ARM_KINEMATICS, ARM_LIMITS
from lynxsim.errors import CapabilityError, InvalidInputError
from lynxsim.plan import PlanRequest
from lynxsim.registry import RobotInfo, info, names
from lynxsim.robots import (
    Robot,
    every,
    get,
    motion,
    plan,
    real_backend,
    register,
    simulation,
    unregister,
)
from lynxsim.rrr.modes import MODE_OPTION
from lynxsim.run_options import NO_OBSTACLE, RunOption, RunValues
from lynxsim.scene import REPORT_SCENE
from lynxsim.sim.adapter import RealBackend, SimAdapter
from lynxsim.tasks import load_task
from lynxsim.traj import Kinematics, ToolReadout, TrajectoryKind
from tests.robots.conftest import ROOT

ARM_TASK = ROOT / "tasks" / "pick_and_place.toml"
RRR_TASK = ROOT / "tasks" / "rrr_closed_curve.toml"


def _record(name: str = "scara", **changes: object) -> Robot:
    """A record of a made-up robot, borrowing the arm's parts."""
    arm = get("arm")
    row = RobotInfo(name, "made-up robot", "tool", True, f"nowhere.{name}:ROBOT", joints=5)
    fields: dict[str, object] = {"info": row, "real": None, **changes}
    return dataclasses.replace(arm, **fields)  # type: ignore[arg-type]


def test_the_built_in_records_say_what_each_robot_can_do():
    arm, rrr = get("arm"), get("rrr")
    assert arm.kinds == tuple(TrajectoryKind)
    assert TrajectoryKind.PLANNED in arm.kinds
    assert rrr.kinds == (TrajectoryKind.QUINTIC,)
    assert (arm.kinematics, rrr.kinematics) == (ARM_KINEMATICS, None)
    assert arm.planning is not None
    assert rrr.planning is None
    assert (arm.run_options, rrr.run_options) == ((NO_OBSTACLE,), (MODE_OPTION,))
    assert (arm.cameras[0], rrr.cameras[0]) == ("front", "top")
    assert isinstance(real_backend(arm, "x", "t"), RealBackend)
    assert [r.name for r in every()] == list(names()) == ["arm", "rrr"]


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"kinds": ()}, "kinds must be a non-empty tuple"),
        ({"kinds": (TrajectoryKind.QUINTIC, TrajectoryKind.QUINTIC)}, "kinds must be distinct"),
        ({"kinds": (TrajectoryKind.QUINTIC,)}, "'planned' is among its kinds exactly when"),
        ({"planning": None}, "'planned' is among its kinds exactly when"),
        ({"kinematics": None}, "a robot that plans needs kinematics"),
        ({"sim": "no entry"}, "sim must be 'module:attribute'"),
        ({"real": "x"}, "real must be 'module:attribute'"),
        ({"cameras": ()}, "cameras must be a non-empty tuple of distinct names"),
        ({"cameras": ("top", "top")}, "cameras must be a non-empty tuple of distinct names"),
        ({"run_options": (NO_OBSTACLE, NO_OBSTACLE)}, "run options must have distinct names"),
        ({"motion": "build"}, "motion must be callable"),
    ],
)
def test_a_malformed_record_is_refused(changes, message):
    with pytest.raises(InvalidInputError, match=message):
        _record(**changes)


def test_register_is_idempotent_and_refuses_clashes():
    arm = get("arm")
    assert register(arm) is arm
    with pytest.raises(InvalidInputError, match="robot 'arm' is registered already"):
        register(dataclasses.replace(arm, cameras=("top", "front")))
    clash = dataclasses.replace(NO_OBSTACLE, help="another meaning")
    with pytest.raises(InvalidInputError, match="run option 'no_obstacle' differs from that of"):
        register(_record(run_options=(clash,)))
    assert "scara" not in names()  # nothing of a refused record stays
    with pytest.raises(InvalidInputError, match="robot must be of type Robot"):
        register(arm.info)  # type: ignore[arg-type]


def test_a_registered_robot_is_known_by_name_until_unregistered():
    scara = register(_record())
    try:
        assert get("scara") is scara
        assert info("scara") == scara.info
        with pytest.raises(InvalidInputError, match=r"cannot import 'nowhere\.scara'"):
            simulation(dataclasses.replace(scara, sim="nowhere.scara:ADAPTER"))
    finally:
        unregister("scara")
    with pytest.raises(InvalidInputError, match="unknown robot 'scara'; expected one of: arm, rrr"):
        get("scara")


def test_commands_refuse_by_capability_naming_the_robot():
    rrr, arm = get("rrr"), get("arm")
    task = load_task(RRR_TASK)
    with pytest.raises(CapabilityError, match="which does not plan; robots that plan: arm"):
        plan(rrr, task)
    with pytest.raises(CapabilityError, match="x applies only to arm tasks; t is a task of robot"):
        real_backend(rrr, "x", "t")
    with pytest.raises(InvalidInputError, match="is for robot 'rrr', not the Lynxmotion 5-DOF"):
        motion(arm, task)
    adapter = simulation(rrr)
    assert isinstance(adapter, SimAdapter)
    for call in (
        lambda: adapter.checker(task.scene),
        lambda: adapter.scene_model(task.scene),
        lambda: adapter.record(task, motion(rrr, task), task.scene),
        lambda: adapter.model(REPORT_SCENE),
    ):
        with pytest.raises(CapabilityError, match=r"planar 3-RRR parallel robot \(robot 'rrr'\)"):
            call()


def test_a_robots_own_message_refuses_a_type_it_does_not_build():
    task = load_task(RRR_TASK)
    with pytest.raises(InvalidInputError, match="'planned' is not planned for the 3-RRR robot"):
        motion(get("rrr"), task, "planned")
    with pytest.raises(InvalidInputError, match="unknown trajectory type 'spline'"):
        motion(get("rrr"), task, "spline")


def test_run_values_fill_defaults_and_check_what_is_given():
    options = (NO_OBSTACLE, MODE_OPTION)
    values = RunValues.of(options, {"mode": 3, "no_obstacle": None})
    assert values.integer("mode") == 3
    assert values.flag("no_obstacle") is False
    assert "mode" in values
    assert "speed" not in values
    with pytest.raises(InvalidInputError, match="unknown run option 'speed'"):
        RunValues.of(options, {"speed": 1})
    with pytest.raises(InvalidInputError, match="--mode must be one of 0, 1"):
        RunValues.of(options, {"mode": 8})
    with pytest.raises(InvalidInputError, match="--no-obstacle is a flag"):
        RunValues.of(options, {"no_obstacle": 1})
    with pytest.raises(InvalidInputError, match="is a flag, not an integer"):
        values.integer("no_obstacle")
    with pytest.raises(InvalidInputError, match="no run option 'speed'"):
        values.flag("speed")


@given(st.one_of(st.none(), st.booleans(), st.integers(-10, 10), st.floats(), st.text()))
def test_run_option_values_are_accepted_or_refused_with_a_typed_error(value):
    for option in (NO_OBSTACLE, MODE_OPTION):
        try:
            values = RunValues.of((option,), {option.name: value})
        except InvalidInputError:
            continue
        got = values.flag(option.name) if option.type is bool else values.integer(option.name)
        assert got == (option.default if value is None else value)


@pytest.mark.parametrize(
    ("fields", "message"),
    [
        ({"name": "No"}, "a run option's name must be lower-case"),
        ({"help": " "}, "help must be a non-empty string"),
        ({"type": float, "default": 0.5}, "type must be bool or int"),
        ({"type": bool, "default": 1}, "a flag's default is a bool"),
        ({"type": int, "default": 3, "choices": ()}, "choices must be a non-empty tuple"),
        ({"type": int, "default": 9, "choices": (1, 2)}, "must be one of 1, 2, got 9"),
    ],
)
def test_a_malformed_run_option_is_refused(fields, message):
    base = {"name": "speed", "help": "how fast", "type": int, "default": 1}
    with pytest.raises(InvalidInputError, match=message):
        RunOption(**{**base, **fields})  # type: ignore[arg-type]


def test_plan_requests_kinematics_and_readouts_check_their_shapes():
    q = np.zeros(5)
    good = {
        "start": q,
        "goal_sets": (q[None],),
        "grasped": (False,),
        "labels": ("a -> b",),
        "pose_names": ("a", "b"),
        "bounds": ARM_BOUNDS,
        "limits": ARM_LIMITS,
        "lipschitz": 1.0,
    }
    request = PlanRequest(**good)  # type: ignore[arg-type]
    assert request.n_joints == 5
    assert not request.start.flags.writeable
    for change, message in (
        ({"start": np.zeros(4)}, "start must be 5 finite joint angles"),
        ({"goal_sets": (np.zeros((0, 5)),)}, "goal set 1 must be K >= 1"),
        ({"goal_sets": ()}, "at least one segment"),
        ({"grasped": (1,)}, "grasped must be 1 bools"),
        ({"pose_names": ("a",)}, "pose_names must be 2 strings"),
        ({"lipschitz": float("inf")}, "lipschitz must be positive and finite"),
    ):
        with pytest.raises(InvalidInputError, match=message):
            PlanRequest(**{**good, **change})  # type: ignore[arg-type]
    with pytest.raises(InvalidInputError, match="tool points must have shape"):
        ToolReadout(np.zeros(3))
    with pytest.raises(InvalidInputError, match="tool angle 'pitch' must have shape"):
        ToolReadout(np.zeros((2, 3)), (("pitch", np.zeros(3)),))
    with pytest.raises(InvalidInputError, match="tool must be callable"):
        Kinematics(ARM_BOUNDS, ARM_LIMITS, "fk")  # type: ignore[arg-type]
    readout = ARM_KINEMATICS.tool(np.zeros((2, 5)))
    assert readout.position.shape == (2, 3)
    assert [n for n, _ in readout.angles] == ["pitch"]
