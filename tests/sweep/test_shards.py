"""Saved shards are verified before use: damaged, foreign or altered ones are computed again."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.sweep.runner import run_sweep
from lynxsim.sweep.shard_files import ShardFileError, read_shard, write_shard
from lynxsim.sweep.table import COLUMNS
from tests.sweep.conftest import grid_spec
from tests.sweep.test_runner import LINE


def _small():
    return grid_spec(60.0, LINE, x_mm=(-60.0, 180.0), y_mm=(-120.0, 240.0), rows_per_shard=10)


def _same(a, b) -> None:
    for name in COLUMNS:
        assert np.array_equal(a[name], b[name], equal_nan=a[name].dtype.kind == "f"), name


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    """A small sweep run once: its table and its 8 shard files (bytes, by index)."""
    out = tmp_path_factory.mktemp("clean")
    outcome = run_sweep(_small(), out)
    files = sorted(out.glob("*.shards/*/shard_*.npz"))
    assert len(files) == 8
    return _Clean(outcome.table, [f.read_bytes() for f in files])


class _Clean(tuple):
    """(table, shard bytes), shown briefly in hypothesis' reports."""

    def __new__(cls, table, shards):
        return super().__new__(cls, (table, shards))

    def __repr__(self) -> str:
        return "<clean sweep>"


def _truncated(shards: list[bytes], path: Path) -> None:
    path.write_bytes(shards[2][: len(shards[2]) // 2])


def _flipped(shards: list[bytes], path: Path) -> None:
    data = bytearray(shards[2])
    data[len(data) // 3] ^= 0xFF
    path.write_bytes(bytes(data))


def _swapped(shards: list[bytes], path: Path) -> None:
    path.write_bytes(shards[5])  # another shard of the same sweep, same row count


def _edited(shards: list[bytes], path: Path) -> None:
    """A valid NPZ with one verdict changed, everything else (its marks too) kept."""
    with np.load(io.BytesIO(shards[2])) as data:
        arrays = {name: data[name] for name in data.files}
    verdict = arrays["verdict"].copy()
    verdict[0] = "clear" if verdict[0] != "clear" else "collided"
    arrays["verdict"] = verdict
    np.savez_compressed(path, **arrays)


def _foreign(shards: list[bytes], path: Path) -> None:
    """Shard 2 of the clean sweep's rows, saved as another sweep's."""
    with np.load(io.BytesIO(shards[2])) as data:
        arrays = {name: data[name] for name in data.files if not name.startswith("_")}
    write_shard(path, arrays, sweep="0" * 64, index=2)


@pytest.mark.parametrize(
    "damage",
    [_truncated, _flipped, _swapped, _edited, _foreign],
    ids=["truncated", "flipped", "swapped", "edited", "foreign"],
)
def test_a_damaged_shard_is_computed_again_with_one_line(clean, tmp_path, damage):
    table, shards = clean
    spec = _small()
    run_sweep(spec, tmp_path)
    files = sorted(tmp_path.glob("*.shards/*/shard_*.npz"))
    damage(shards, files[2])
    lines: list[str] = []
    again = run_sweep(spec, tmp_path, notice=lines.append)
    assert (again.computed, again.reused) == (1, 7)
    _same(again.table, table)
    assert len(lines) == 1
    assert "shard 2" in lines[0]
    assert "computed again" in lines[0]
    assert files[2].read_bytes() == shards[2]  # saved again, whole


def test_a_missing_shard_is_computed_again_without_a_word(clean, tmp_path):
    table, _ = clean
    spec = _small()
    run_sweep(spec, tmp_path)
    sorted(tmp_path.glob("*.shards/*/shard_*.npz"))[5].unlink()
    lines: list[str] = []
    again = run_sweep(spec, tmp_path, notice=lines.append)
    assert (again.computed, again.reused, lines) == (1, 7, [])
    _same(again.table, table)


def test_a_shard_file_names_its_sweep_and_index(clean, tmp_path):
    _, shards = clean
    path = tmp_path / "s.npz"
    path.write_bytes(shards[2])
    spec = _small()
    rows = read_shard(path, sweep=spec.digest, index=2, rows=10)
    assert len(rows["task"]) == 10
    with pytest.raises(ShardFileError, match="another shard"):
        read_shard(path, sweep=spec.digest, index=1, rows=10)
    with pytest.raises(ShardFileError, match="another sweep"):
        read_shard(path, sweep="f" * 64, index=2, rows=10)
    with pytest.raises(ShardFileError, match="rows"):
        read_shard(path, sweep=spec.digest, index=2, rows=9)


_FUZZ = settings(
    max_examples=300,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


def _damage(shards: list[bytes], choice: int, a: int, b: int, value: int) -> bytes:
    """One of several kinds of damage to shard 2's bytes, placed by ``a``, ``b``, ``value``."""
    data = bytearray(shards[2])
    n = len(data)
    if choice == 0:  # truncated
        return bytes(data[: a % n])
    if choice == 1:  # bytes flipped
        for k in range(1 + b % 4):
            data[(a + 7919 * k) % n] ^= 1 + value % 255
        return bytes(data)
    if choice == 2:  # another shard's file
        return shards[(2 + 1 + a % 7) % 8]
    if choice == 3:  # bytes overwritten by a run of one value
        start, stop = a % n, min(n, a % n + 1 + b % 64)
        data[start:stop] = bytes([value % 256]) * (stop - start)
        return bytes(data)
    # a value of one column edited, the file written again with its marks kept
    with np.load(io.BytesIO(shards[2])) as npz:
        arrays = {name: npz[name] for name in npz.files}
    name = list(COLUMNS)[a % len(COLUMNS)]
    column = arrays[name].copy()
    i = b % len(column)
    if column.dtype.kind == "U":
        column = column.astype(object)
        column[i] = column[i] + "x"
    elif column.dtype.kind == "b":
        column[i] = not column[i]
    elif column.dtype.kind == "f":
        column[i] = np.nextafter(column[i], np.inf) if np.isfinite(column[i]) else 1.0
    else:
        column[i] = column[i] + 1 + value % 5
    arrays[name] = column
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        for key, array in arrays.items():
            member = io.BytesIO()
            np.save(member, np.asarray(array).astype(str) if array.dtype == object else array)
            archive.writestr(f"{key}.npy", member.getvalue())
    return buffer.getvalue()


@_FUZZ
@given(
    choice=st.integers(0, 4),
    a=st.integers(0, 2**31),
    b=st.integers(0, 2**31),
    value=st.integers(0, 2**31),
)
def test_any_damaged_shard_reads_whole_or_raises_a_shard_file_error(
    clean, tmp_path, choice, a, b, value
):
    table, shards = clean
    spec = _small()
    path = tmp_path / "shard.npz"
    path.write_bytes(_damage(shards, choice, a, b, value))
    try:
        rows = read_shard(path, sweep=spec.digest, index=2, rows=10)
    except ShardFileError as exc:
        message = str(exc)
    else:
        _same(rows, {name: table[name][20:30] for name in COLUMNS})
        return
    assert message
    assert "\n" not in message
