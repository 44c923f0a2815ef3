"""A dataset is complete or absent: never replaced, never left half-written, Minari optional."""

from __future__ import annotations

import subprocess
import sys

import pytest

from lynxsim.datasets import MissingExtraError, write_dataset
from lynxsim.errors import OutputPathError
from tests.datasets.conftest import FORMATS, record


class _Stop(Exception):
    pass


def _tree(root):
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("interrupt", [KeyboardInterrupt, _Stop], ids=["ctrl-c", "error"])
def test_an_interrupted_write_leaves_no_dataset(tmp_path, fmt, interrupt):
    def stop_at_the_second(episode):
        if episode.seed == 1:
            raise interrupt

    with pytest.raises(interrupt):
        write_dataset(tmp_path, 3, seed=0, format=fmt, on_episode=stop_at_the_second)
    assert _tree(tmp_path) == []  # no hidden .tmp, and no folder made for it, left


@pytest.mark.parametrize("fmt", FORMATS)
def test_an_existing_dataset_is_never_replaced(tmp_path, fmt):
    summary = record(tmp_path, fmt, episodes=1)
    before = {p: p.read_bytes() for p in summary.path.rglob("*") if p.is_file()}
    with pytest.raises(OutputPathError, match=r"will not replace .*expert-v0: it exists"):
        record(tmp_path, fmt, episodes=1, seed=99)
    assert {p: p.read_bytes() for p in summary.path.rglob("*") if p.is_file()} == before


def test_an_empty_folder_under_the_dataset_name_is_not_replaced(tmp_path):
    (tmp_path / "lynxsim" / "pick-and-place-v1" / "expert-v0").mkdir(parents=True)
    with pytest.raises(OutputPathError, match="it exists"):
        write_dataset(tmp_path, 1)


def test_a_file_in_the_datasets_path_is_refused_before_any_work(tmp_path):
    (tmp_path / "lynxsim").write_text("not a folder")
    with pytest.raises(OutputPathError, match=r"lynxsim is not a folder"):
        write_dataset(tmp_path, 1)


def test_minari_missing_is_a_clear_error_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "minari", None)  # what an install without the extra gives
    with pytest.raises(MissingExtraError, match=r"pip install 'lynxsim\[datasets\]'"):
        write_dataset(tmp_path, 1, format="minari")
    assert _tree(tmp_path) == []
    assert write_dataset(tmp_path, 1, format="npz").episodes == 1  # NPZ needs no extra


def test_importing_the_package_loads_neither_mujoco_nor_the_extras():
    code = (
        "import sys, lynxsim.datasets, lynxsim.datasets.layout, lynxsim.datasets.episode, "
        "lynxsim.datasets.npz, lynxsim.datasets.minari_writer, lynxsim.datasets.lerobot_writer, "
        "lynxsim.datasets.lerobot_check, lynxsim.cli.dataset; "
        "print(sorted({'mujoco', 'minari', 'h5py', 'pyarrow'} & set(sys.modules)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout == "[]\n"
