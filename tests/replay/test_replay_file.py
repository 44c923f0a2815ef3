"""The replay data file.

Round trip, same bytes, atomic writes, and every bad file refused with its file and entry named.
"""

from __future__ import annotations

import dataclasses
import io
import json
import zipfile

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.errors import OutputPathError, ReplayFileError
from lynxsim.web.replay_data import ReplayData, ReplayFieldError
from lynxsim.web.replay_file import read_replay_file, write_replay_file

_SETTINGS = settings(
    max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)


def _equal(a: ReplayData, b: ReplayData) -> None:
    for f in dataclasses.fields(ReplayData):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if dataclasses.is_dataclass(x) and not isinstance(x, type):
            for g in dataclasses.fields(x):
                np.testing.assert_array_equal(
                    getattr(x, g.name), getattr(y, g.name), f"{f.name}.{g.name}"
                )
        elif f.name == "cameras":
            assert [c.name for c in x] == [c.name for c in y]
            for c, d in zip(x, y):
                np.testing.assert_array_equal(c.xmat, d.xmat)
                np.testing.assert_array_equal(c.pos, d.pos)
                assert (c.fovy, c.orthographic) == (d.fovy, d.orthographic)
        else:
            np.testing.assert_array_equal(x, y, f.name)


def test_a_replay_reads_back_equal_and_the_same_replay_gives_the_same_bytes(planned_run, tmp_path):
    data = planned_run.data
    a, b = (
        write_replay_file(data, tmp_path / "a.replay.npz"),
        write_replay_file(data, tmp_path / "b.replay.npz"),
    )
    _equal(read_replay_file(a), data)
    assert a.read_bytes() == b.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.replay.npz", "b.replay.npz"]


def test_a_failed_write_leaves_nothing_and_replaces_no_folder(planned_run, tmp_path):
    folder = tmp_path / "x.replay.npz"
    folder.mkdir()
    with pytest.raises(OutputPathError, match="it is a folder"):
        write_replay_file(planned_run.data, folder)
    bad = dataclasses.replace(planned_run.data)
    object.__setattr__(bad, "report_json", None)  # breaks while writing, after the temp file
    with pytest.raises(
        ReplayFileError, match=r"y\.replay\.npz: meta\.report_json: written, it does"
    ):
        write_replay_file(bad, tmp_path / "y.replay.npz")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.replay.npz"]


def _entries(path) -> dict[str, bytes]:
    with zipfile.ZipFile(path) as z:
        return {i.filename: z.read(i) for i in z.infolist()}


def _zip(path, entries: dict[str, bytes]) -> None:
    with zipfile.ZipFile(path, "w") as z:
        for name, blob in entries.items():
            z.writestr(name, blob)


def _npy(array) -> bytes:
    buf = io.BytesIO()
    np.lib.format.write_array(buf, np.asarray(array), allow_pickle=False)
    return buf.getvalue()


class _Entries(dict):
    """A good file's entries (a short repr: hypothesis prints its arguments on failure)."""

    def __repr__(self) -> str:
        return f"<entries of a good replay file: {sorted(self)}>"


@pytest.fixture(scope="module")
def good(planned_run, tmp_path_factory):
    path = tmp_path_factory.mktemp("good") / "run.replay.npz"
    write_replay_file(planned_run.data, path)
    return _Entries(_entries(path))


def _meta(entries) -> dict:
    return json.loads(str(np.lib.format.read_array(io.BytesIO(entries["meta.npy"]))))


def _geoms(entries) -> int:
    return len(_meta(entries)["geom_names"])


def _quat_shape(entries) -> tuple[int, ...]:
    return np.lib.format.read_array(io.BytesIO(entries["quat_q.npy"])).shape


@pytest.mark.parametrize(
    ("change", "field", "message"),
    [
        (lambda e: e.pop("tool.npy"), None, r"not a lynxsim replay: missing \['tool.npy'\]"),
        (lambda e: e.update({"extra.npy": _npy([1])}), None, r"unexpected \['extra.npy'\]"),
        (lambda e: e.update({"pos_q.npy": b"\x93NUMPY garbage"}), "pos_q", "not a NumPy array"),
        (
            lambda e: e.update({"time_s.npy": _npy(np.zeros(3, np.float32))}),
            "time_s",
            "must have dtype <f8",
        ),
        (lambda e: e.update({"time_s.npy": _npy(np.zeros(3))}), "time_s", "increasing"),
        (
            lambda e: e.update({"tool.npy": _npy(np.full((2, 3), np.nan))}),
            "tool",
            "must have shape",
        ),
        (
            lambda e: e.update({"geom_kind.npy": _npy(np.full(_geoms(e), 1, np.int32))}),
            "geoms.kind",
            "must hold [0-9]+ of",
        ),
        (
            lambda e: e.update({"geom_body.npy": _npy(np.full(_geoms(e), 99, np.int32))}),
            "geoms.body",
            "entries must lie in",
        ),
        (
            lambda e: e.update({"quat_q.npy": _npy(np.zeros(_quat_shape(e), np.int16))}),
            "poses.quat_q",
            "a quaternion is zero",
        ),
        (lambda e: e.update({"meta.npy": _npy("[1, 2]")}), "meta", "must be a JSON object"),
        (lambda e: e.update({"meta.npy": _npy("{")}), "meta", "not JSON"),
        (
            lambda e: e.update({"meta.npy": _npy(json.dumps({**_meta(e), "version": 9}))}),
            "meta.format",
            "version 9",
        ),
        (
            lambda e: e.update({"meta.npy": _npy(json.dumps({**_meta(e), "title": 3}))}),
            "meta.title",
            "must be a str",
        ),
        (
            lambda e: e.update(
                {"meta.npy": _npy(json.dumps({**_meta(e), "default_camera": "nope"}))}
            ),
            "default_camera",
            "must name one of the cameras",
        ),
        (
            lambda e: e.update({"meta.npy": _npy(json.dumps({**_meta(e), "camera_fovy": [45.0]}))}),
            "meta.camera_fovy",
            "one value per camera",
        ),
    ],
    ids=[
        "missing",
        "extra",
        "not-npy",
        "dtype",
        "times",
        "shape",
        "kind",
        "body",
        "zero-quat",
        "meta-list",
        "meta-json",
        "version",
        "title",
        "camera",
        "fovy",
    ],
)
def test_a_bad_entry_is_refused_naming_file_and_entry(good, tmp_path, change, field, message):
    entries = dict(good)
    change(entries)
    path = tmp_path / "bad.replay.npz"
    _zip(path, entries)
    with pytest.raises(ReplayFileError, match=message) as info:
        read_replay_file(path)
    assert info.value.field == field
    assert info.value.path == str(path)
    assert str(info.value).startswith(f"{path}: {field + ': ' if field else ''}")


def test_files_that_are_no_zip_or_too_large_are_refused(tmp_path, monkeypatch):
    path = tmp_path / "x.replay.npz"
    with pytest.raises(ReplayFileError, match="not a readable replay file"):
        read_replay_file(path)  # missing
    path.write_bytes(b"not a zip")
    with pytest.raises(ReplayFileError, match="not a readable replay file"):
        read_replay_file(path)
    monkeypatch.setattr("lynxsim.web.replay_file.MAX_FILE_BYTES", 4)
    with pytest.raises(ReplayFileError, match="larger than 4 bytes"):
        read_replay_file(path)


@_SETTINGS
@given(st.data())
def test_any_corruption_of_a_good_file_is_refused_or_reads_as_a_valid_replay(good, tmp_path, data):
    entries = dict(good)
    name = data.draw(st.sampled_from(sorted(entries)))
    blob = bytearray(entries[name])
    for _ in range(data.draw(st.integers(1, 8))):
        i = data.draw(st.integers(0, len(blob) - 1))
        blob[i] = data.draw(st.integers(0, 255))
    entries[name] = bytes(blob)
    path = tmp_path / "fuzz.replay.npz"
    _zip(path, entries)
    try:
        replay: ReplayData | ReplayFileError = read_replay_file(path)  # passed every check
    except ReplayFileError as exc:
        replay = exc
    if isinstance(replay, ReplayFileError):
        assert str(replay).startswith(str(path))
    else:
        assert replay.frames >= 1


@_SETTINGS
@given(st.binary(max_size=2000))
def test_random_bytes_are_refused(tmp_path, blob):
    path = tmp_path / "random.replay.npz"
    path.write_bytes(blob)
    with pytest.raises(ReplayFileError):
        read_replay_file(path)


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("time_s", np.array([0.0, 0.0]), "increasing"),
        ("pose_error_m", -1.0, "must be >= 0"),
        ("tool", np.zeros((2, 2)), "must have shape"),
        ("targets", np.array([[np.inf, 0, 0]]), "must be finite"),
        ("extent", 0.0, "must be > 0"),
        ("title", b"bytes", "must be a string"),
        ("body_names", ["list"], "must be a tuple of strings"),
    ],
)
def test_replay_data_checks_its_fields(planned_run, field, value, message):
    with pytest.raises(ReplayFieldError, match=message) as info:
        dataclasses.replace(planned_run.data, **{field: value})
    assert info.value.field.startswith(field.split(".")[0])
