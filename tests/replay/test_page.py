"""The page's text: names escaped whatever they hold, data that parses back, the verdict table."""

from __future__ import annotations

import base64
import dataclasses
import html
import json
import re
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.errors import InvalidInputError, OutputPathError, ReplayFileError
from lynxsim.web.page import page_payload, replay_page, write_replay_page
from lynxsim.web.verdicts import canonical_json, check_report, read_report, verdict_rows

_SETTINGS = settings(
    max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
_DATA = re.compile(r'<script id="replay-data" type="application/json">(.*?)</script>', re.S)


@_SETTINGS
@given(st.text(), st.lists(st.text(max_size=30), min_size=1, max_size=3))
def test_any_names_stay_text_and_parse_back_equal(planned_run, title, names):
    data = planned_run.data
    geoms = dataclasses.replace(data.geoms, names=(*names, *data.geoms.names[len(names) :]))
    report = json.loads(data.report_json)
    report["task"] = title
    page = replay_page(
        dataclasses.replace(data, title=title, geoms=geoms, report_json=canonical_json(report))
    )
    (blob,) = _DATA.findall(page)  # the data ends where it should: no name closed its element
    assert "<" not in blob
    assert json.loads(blob)["geoms"]["names"][: len(names)] == names
    assert f"<h1>{html.escape(title)}</h1>" in page
    assert page.count("<script") == 3  # the data, the renderer, the page's script


def test_the_payload_carries_the_replay_exactly(planned_run):
    data = planned_run.data
    payload = page_payload(data)
    pos_q = np.frombuffer(base64.b64decode(payload["poses"]["pos_q"]), "<i2")
    np.testing.assert_array_equal(pos_q, data.poses.pos_q.ravel())
    time_s = np.frombuffer(base64.b64decode(payload["time_s"]), "<f8")
    np.testing.assert_array_equal(time_s, data.time_s)
    assert payload["cameras"][0]["name"] == data.default_camera


def test_the_page_loads_nothing_and_states_its_error(planned_run):
    page = replay_page(planned_run.data)
    assert "default-src 'none'" in page
    assert not re.search(r"(src|href)=\"(https?:)?//", page)
    assert f"within {planned_run.data.pose_error_m * 1e3:.2f} mm of the simulation" in page


def test_a_replay_whose_report_is_not_one_makes_no_page(planned_run):
    with pytest.raises(InvalidInputError, match="report_json is not a run report"):
        replay_page(dataclasses.replace(planned_run.data, report_json='{"task": 1}'))


def test_the_verdict_table_says_what_the_report_says(colliding_run, rrr_run):
    rows = {
        r.label.strip(): r
        for r in verdict_rows(check_report(json.loads(colliding_run.data.report_json)))
    }
    assert rows["obstacles"].status == "bad"
    assert rows["obstacles"].value.startswith("COLLISION with cylinder first at ")
    assert rows["cylinder"].status == "bad"
    assert rows["simulation"].value == "healthy"
    rrr = {r.label: r for r in verdict_rows(check_report(json.loads(rrr_run.data.report_json)))}
    assert rrr["obstacles"].value == "none in the scene"
    assert rrr["loop closure max"].value.endswith(" mm")
    assert rrr["working mode"].value == "7"


@pytest.mark.parametrize(
    ("edit", "field", "problem"),
    [
        (lambda r: r.pop("healthy"), "healthy", "missing"),
        (lambda r: r.update(task=3), "task", "must be str"),
        (lambda r: r.update(obstacles=[{"name": "x"}]), "obstacles[0].collided", "missing"),
        (lambda r: r.update(obstacle={"collided": "yes"}), "obstacle.collided", "must be bool"),
        (lambda r: r.update(warnings={"x": 1.5}), "warnings", "must be counts"),
        (lambda r: r.update(max_torque_ratio=[True]), "max_torque_ratio", "must be numbers"),
    ],
)
def test_a_bad_report_file_names_its_field(planned_run, tmp_path, edit, field, problem):
    report = json.loads(planned_run.data.report_json)
    edit(report)
    path = tmp_path / "r.json"
    path.write_text(json.dumps(report))
    with pytest.raises(ReplayFileError) as info:
        read_report(path)
    assert str(info.value) == f"{path}: {field}: {problem}"


@_SETTINGS
@given(
    st.recursive(
        st.none() | st.booleans() | st.floats() | st.text(),
        lambda c: st.lists(c) | st.dictionaries(st.text(), c),
    )
)
def test_any_json_is_a_report_or_refused_with_a_field(tmp_path, value):
    path = tmp_path / "any.json"
    path.write_text(json.dumps(value))
    try:
        outcome: object = verdict_rows(read_report(path))
    except ReplayFileError as exc:
        outcome = exc
    if isinstance(outcome, ReplayFileError):
        assert outcome.path == str(path)
    else:
        assert outcome  # a report: it has its table


def test_the_web_side_never_imports_mujoco():
    code = (
        "import sys, lynxsim.web.page, lynxsim.web.index, lynxsim.web.replay_file, "
        "lynxsim.cli.view; print('mujoco' in sys.modules)"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout == "False\n"


def test_a_page_is_written_whole_or_not_at_all(planned_run, tmp_path):
    folder = tmp_path / "page.html"
    folder.mkdir()
    with pytest.raises(OutputPathError, match="it is a folder"):
        write_replay_page(planned_run.data, folder)
    bad = dataclasses.replace(planned_run.data)
    object.__setattr__(bad, "report_json", "[]")  # fails while making the page
    with pytest.raises(InvalidInputError):
        write_replay_page(bad, tmp_path / "x.html")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["page.html"]
