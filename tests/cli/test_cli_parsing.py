"""Parsing the command line: help, usage errors, numbers, output flags, robot-specific flags.

Help exits 0 for every command; a wrong argument count is one line and exit 2; any float
literal is a value (``-9e1`` is not an option); NaN and infinities are one-line errors;
``--out`` names a file and ``--out-dir`` a folder; ``play`` refuses the other robot's flags.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from lynxsim.cli import build_parser, main, play
from lynxsim.cli.flags import DEFAULT_QUALITY
from lynxsim.robots import get
from lynxsim.sim.quality import Quality
from lynxsim.tasks import load_task

TASKS = Path(__file__).resolve().parents[2] / "tasks"
ARM_TASK = str(TASKS / "pick_and_place.toml")
RRR_TASK = str(TASKS / "rrr_figure20_tour.toml")

COMMANDS = [
    (),
    ("fk",),
    ("ik",),
    ("workspace",),
    ("traj",),
    ("plan",),
    ("play",),
    ("view",),
    ("rrr",),
    ("rrr", "ik"),
    ("rrr", "fk"),
    ("rrr", "workspace"),
    ("rrr", "poses"),
    ("demo",),
    ("env",),
    ("dataset",),
    ("sweep",),
    ("real",),
    ("real", "play"),
    ("real", "emulate"),
    ("real", "compare"),
]
"""Every (sub-)command, ``()`` for ``lynxsim`` itself."""

IK_PITCH_MINUS_90 = "q1..q5 [deg]: 90.00  15.89  -18.47  -87.42  0.00"
"""What ``lynxsim ik 0 300 0 -90`` prints."""


def _command_id(command: tuple[str, ...]) -> str:
    return " ".join(command) or "lynxsim"


def _parsers(parser: argparse.ArgumentParser) -> dict[tuple[str, ...], argparse.ArgumentParser]:
    """Every parser under ``parser`` (itself included) by its command path."""
    found = {(): parser}
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                found.update({(name, *path): p for path, p in _parsers(sub).items()})
    return found


def _one_line_usage_error(result, message: str) -> None:
    assert result.code == 2, result
    assert result.err.count("\n") == 1, result.err
    assert result.err.startswith("lynxsim")
    assert "error: " in result.err
    assert message in result.err
    assert result.out == ""


def test_the_help_tests_cover_every_command():
    assert set(_parsers(build_parser())) == set(COMMANDS)


@pytest.mark.parametrize("flag", ["--help", "-h"])
@pytest.mark.parametrize("command", COMMANDS, ids=_command_id)
def test_help_prints_usage_and_exits_zero(capsys, command, flag):
    with pytest.raises(SystemExit) as info:
        main([*command, flag])
    assert info.value.code == 0
    captured = capsys.readouterr()
    assert captured.out.startswith(f"usage: {' '.join(('lynxsim', *command))} ")
    assert captured.err == ""


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        ([], "required: {fk,ik,workspace,traj,plan,play,view,rrr,demo,env,dataset,sweep,real}"),
        (["fk"], "required: Q1, Q2, Q3, Q4, Q5"),
        (["fk", "1", "2"], "required: Q3, Q4, Q5"),
        (["fk", "1", "2", "3", "4", "5", "6"], "unrecognized arguments: 6"),
        (["ik", "1", "2", "3"], "required: PITCH"),
        (["ik", "1", "2", "3", "4", "5", "6"], "unrecognized arguments: 6"),
        (["workspace", "extra"], "unrecognized arguments: extra"),
        (["traj", "a.toml", "b.toml"], "unrecognized arguments: b.toml"),
        (["play"], "required: task"),
        (["play", "a.toml", "b.toml"], "unrecognized arguments: b.toml"),
        (["view"], "required: REPORT.json"),
        (["view", "a.json", "b.json"], "unrecognized arguments: b.json"),
        (["rrr"], "required: {ik,fk,workspace,poses}"),
        (["rrr", "ik", "1", "2"], "required: ALPHA"),
        (["rrr", "ik", "1", "2", "3", "4"], "unrecognized arguments: 4"),
        (["rrr", "fk", "1", "2"], "required: THETA3"),
        (["rrr", "fk", "1", "2", "3", "4"], "unrecognized arguments: 4"),
        (["rrr", "workspace", "extra"], "unrecognized arguments: extra"),
        (["rrr", "poses", "extra"], "unrecognized arguments: extra"),
        (["demo", "extra"], "unrecognized arguments: extra"),
        (["env", "extra"], "unrecognized arguments: extra"),
    ],
    ids=_command_id,
)
def test_wrong_argument_count_is_one_line_and_exit_2(cli, argv, message):
    _one_line_usage_error(cli(*argv), message)


@pytest.mark.parametrize("pitch", ["-90", "-90.0", "-9e1", "-9E+1", "-900e-1", "-.9e2", "-90."])
def test_any_negative_float_literal_is_a_pitch(cli, pitch):
    result = cli("ik", "0", "300", "0", pitch)
    assert result.code == 0, result.err
    assert result.out.splitlines()[0] == IK_PITCH_MINUS_90


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (
            ["fk", "-1e1", "-2.5E+1", "-.5", "-0", "-5."],
            {"q1": -10.0, "q2": -25.0, "q3": -0.5, "q4": 0.0, "q5": -5.0},
        ),
        (
            ["ik", "-1e1", "-2e1", "-3e1", "-4e1", "-5e1"],
            {"x": -10.0, "y": -20.0, "z": -30.0, "pitch": -40.0, "roll": -50.0},
        ),
        (["rrr", "ik", "-1e1", "-2e1", "-3e1"], {"x": -10.0, "y": -20.0, "alpha": -30.0}),
        (
            ["rrr", "fk", "-1e1", "-2E1", "-.3e2"],
            {"theta1": -10.0, "theta2": -20.0, "theta3": -30.0},
        ),
        (["rrr", "workspace", "--alpha-deg", "-2e1", "-.5"], {"alpha_deg": [-20.0, -0.5]}),
    ],
    ids=["fk", "ik", "rrr-ik", "rrr-fk", "rrr-workspace"],
)
def test_negative_float_literals_are_values_not_options(argv, expected):
    args = build_parser().parse_args(argv)
    assert {name: getattr(args, name) for name in expected} == expected


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["traj", ARM_TASK, "--segment-duration-s", "-1e1"], "must be between 0.001 and 3600 s"),
        (["traj", ARM_TASK, "--rate-hz", "-5E2"], "must be between 1 and 10000 Hz, got -5E2"),
        (["play", ARM_TASK, "--fps", "-3e1"], "must be between 1 and 240 frames/s"),
        (["rrr", "workspace", "--resolution-mm", "-2e0"], "must be between 0.1 and 100 mm"),
        (["workspace", "--samples", "-1e3"], "must be an integer, got '-1e3'"),
        (["rrr", "poses", "--mode", "-1e0"], "working mode must be an integer 0..7"),
    ],
    ids=["segment-duration", "rate", "fps", "resolution", "samples", "mode"],
)
def test_negative_option_values_reach_the_value_check(cli, argv, message):
    _one_line_usage_error(cli(*argv), message)


NON_FINITE = ["nan", "-nan", "inf", "-inf", "Infinity", "-1e999"]
"""Float literals of NaN and infinities (``-1e999`` overflows to ``-inf``)."""


def _every_slot(argv: list[str]) -> list[list[str]]:
    """``argv`` once per ``{}`` in it, that one kept as the slot and the others set to 0."""
    slots = [i for i, a in enumerate(argv) if a == "{}"]
    return [[a if i == s else ("0" if a == "{}" else a) for i, a in enumerate(argv)] for s in slots]


FLOAT_SLOTS = [
    *_every_slot(["fk", "{}", "{}", "{}", "{}", "{}"]),
    *_every_slot(["ik", "{}", "{}", "{}", "{}", "{}"]),
    *_every_slot(["rrr", "ik", "{}", "{}", "{}"]),
    *_every_slot(["rrr", "fk", "{}", "{}", "{}"]),
    ["rrr", "workspace", "--alpha-deg", "0", "{}"],
    ["rrr", "workspace", "--resolution-mm", "{}"],
    ["traj", ARM_TASK, "--rate-hz", "{}"],
    ["traj", ARM_TASK, "--segment-duration-s", "{}"],
    ["play", ARM_TASK, "--fps", "{}"],
]
"""Every float argument of every command, ``{}`` where the value goes."""

INT_SLOTS = [
    ["workspace", "--samples", "{}"],
    ["workspace", "--seed", "{}"],
    ["play", ARM_TASK, "--mode", "{}"],
    ["rrr", "workspace", "--mode", "{}"],
    ["rrr", "poses", "--mode", "{}"],
    ["env", "--episodes", "{}"],
    ["env", "--seed", "{}"],
    ["env", "--video-episodes", "{}"],
]
"""Every integer argument of every command."""


def _slot_id(argv: list[str]) -> str:
    return " ".join(Path(a).name for a in argv)


@pytest.mark.parametrize("value", NON_FINITE)
@pytest.mark.parametrize("argv", FLOAT_SLOTS, ids=_slot_id)
def test_non_finite_floats_are_one_line_errors(cli, argv, value):
    result = cli(*[value if a == "{}" else a for a in argv])
    _one_line_usage_error(result, f"must be a finite number, got {value!r}")


@pytest.mark.parametrize("value", NON_FINITE)
@pytest.mark.parametrize("argv", INT_SLOTS, ids=_slot_id)
def test_non_finite_integers_are_one_line_errors(cli, argv, value):
    result = cli(*[value if a == "{}" else a for a in argv])
    _one_line_usage_error(result, f"argument {argv[-2]}: ")
    assert repr(value) in result.err


def test_out_names_a_file_and_out_dir_a_folder():
    writes_a_file, writes_a_folder = set(), set()
    for command, parser in _parsers(build_parser()).items():
        for action in parser._actions:
            if "--out" in action.option_strings:
                assert action.metavar == "FILE", command
                writes_a_file.add(command)
            if "--out-dir" in action.option_strings:
                assert action.metavar == "DIR", command
                writes_a_folder.add(command)
    assert writes_a_file == {
        ("workspace",),
        ("play",),
        ("view",),
        ("rrr", "workspace"),
        ("rrr", "poses"),
    }
    assert writes_a_folder == {("traj",), ("plan",), ("demo",), ("dataset",), ("sweep",)}


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["play", ARM_TASK, "--mode", "3", "--no-video"],
            "--mode applies only to tasks of the planar 3-RRR parallel robot (robot 'rrr'); "
            f"{ARM_TASK} is a task of the Lynxmotion 5-DOF arm (robot 'arm')",
        ),
        (
            ["play", RRR_TASK, "--no-obstacle", "--no-video"],
            "--no-obstacle applies only to tasks of the Lynxmotion 5-DOF arm (robot 'arm'); "
            f"{RRR_TASK} is a task of the planar 3-RRR parallel robot (robot 'rrr')",
        ),
        (
            ["play", ARM_TASK, "--camera", "side", "--no-video"],
            "--camera 'side': the Lynxmotion 5-DOF arm model has no such camera; "
            "available: front, top",
        ),
        (
            ["play", RRR_TASK, "--camera", "wrist"],
            "--camera 'wrist': the planar 3-RRR parallel robot model has no such camera; "
            "available: top, front",
        ),
    ],
    ids=["mode-on-arm", "no-obstacle-on-rrr", "camera-arm", "camera-rrr"],
)
def test_flags_of_the_other_robot_are_refused(cli, argv, message):
    result = cli(*argv)
    assert result.code == 1
    assert result.err == f"lynxsim: error: {message}\n"
    assert result.out == ""


@pytest.mark.parametrize(
    "argv",
    [
        ["play", RRR_TASK, "--mode", "3", "--camera", "front"],
        ["play", ARM_TASK, "--no-obstacle", "--camera", "top"],
        ["play", ARM_TASK],
    ],
    ids=["rrr", "arm", "no-flags"],
)
def test_flags_of_the_tasks_robot_pass_the_check(argv):
    args = build_parser().parse_args(argv)
    play._check_flags(args, get(load_task(args.task).robot))


def test_demo_and_play_share_one_quality_flag():
    parser = build_parser()
    defaults = {parser.parse_args(["demo"]).quality, parser.parse_args(["play", "t.toml"]).quality}
    assert defaults == {DEFAULT_QUALITY.value}
    parsers = _parsers(parser)
    for command in ("demo", "play"):
        (action,) = [a for a in parsers[(command,)]._actions if a.dest == "quality"]
        assert list(action.choices or ()) == [q.value for q in Quality]
