"""Safe output paths and atomic writes (:mod:`lynxsim.fileio`, :mod:`lynxsim.sim.video`)."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.errors import OutputPathError, VideoError
from lynxsim.fileio import (
    MAX_STEM,
    atomic_path,
    check_destination,
    output_path,
    safe_stem,
    unique_stems,
)
from lynxsim.sim.video import decoded_frames, mp4_writer

STEM = re.compile(r"[A-Za-z0-9+][A-Za-z0-9._+-]*")


@settings(max_examples=500)
@given(st.text(max_size=300))
def test_any_name_gives_a_plain_stem_inside_the_folder(name):
    stem = safe_stem(name)
    assert STEM.fullmatch(stem), stem
    assert ".." not in stem
    assert len(stem) <= MAX_STEM
    dest = output_path("/work/out", name, "quintic", suffix=".mp4")
    assert dest.parent == Path("/work/out")
    assert os.path.normpath(dest) == str(dest)


def test_stems_keep_ordinary_names():
    assert safe_stem("pick_and_place") == "pick_and_place"
    assert safe_stem("Pick & place, v2") == "Pick_place_v2"
    assert safe_stem("über-Greifer") == "uber-Greifer"


@pytest.mark.parametrize(
    ("make", "kind"),
    [
        (lambda p: p.mkdir(), "a folder"),
        (lambda p: os.mkfifo(p), "not a regular file"),
        (lambda p: p.symlink_to(p.parent / "elsewhere"), "a symbolic link"),
    ],
    ids=["folder", "fifo", "symlink"],
)
def test_only_regular_files_are_replaced(tmp_path, make, kind):
    dest = tmp_path / "out.json"
    make(dest)
    with (
        pytest.raises(
            OutputPathError, match=f"will not replace {re.escape(str(dest))}: it is {kind}"
        ),
        atomic_path(dest) as tmp,
    ):
        tmp.write_text("{}")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.json"]


def test_a_file_in_the_way_of_the_folder_is_refused(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(OutputPathError, match="is not a folder"):
        check_destination(tmp_path / "f" / "out.png")


def test_video_without_frames_is_not_written(tmp_path):
    dest = tmp_path / "empty.mp4"
    with pytest.raises(VideoError, match="no frames were written"), mp4_writer(dest, 30.0):
        pass
    assert list(tmp_path.iterdir()) == []


def test_written_video_decodes_to_its_frames(tmp_path):
    dest = tmp_path / "clip.mp4"
    frames = np.random.default_rng(0).integers(0, 255, size=(7, 64, 96, 3), dtype=np.uint8)
    with mp4_writer(dest, 25.0) as sink:
        for frame in frames:
            sink.append_data(frame)
    assert decoded_frames(dest) == 7


def test_a_truncated_video_does_not_decode(tmp_path):
    dest = tmp_path / "clip.mp4"
    with mp4_writer(dest, 25.0) as sink:
        for _ in range(5):
            sink.append_data(np.zeros((64, 96, 3), dtype=np.uint8))
    data = dest.read_bytes()
    dest.write_bytes(data[: len(data) // 2])
    with pytest.raises(VideoError, match="does not decode"):
        decoded_frames(dest)


def test_repeated_stems_are_made_distinct_in_order():
    assert unique_stems(["a", "b", "a", "a", "a_2"]) == ["a", "b", "a_2", "a_3", "a_2_2"]
    assert unique_stems([]) == []
