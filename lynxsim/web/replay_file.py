"""A replay's data on disk: ``RUN.replay.npz`` beside the run's JSON report, checked on reading.

A zip of ``.npy`` arrays (no pickles; every entry stamped 1980-01-01 so that
the same replay gives the same bytes) and ``meta.npy``, a JSON text of the
names and numbers. :func:`write_replay_file` writes to a temporary name, reads
it back and renames it only when it checks; :func:`read_replay_file` refuses
any file that is not exactly what it writes, naming file and entry. Pure NumPy.
"""

from __future__ import annotations

import io
import json
import math
import os
import tokenize
import zipfile
import zlib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.errors import ReplayFileError
from lynxsim.fileio import atomic_path
from lynxsim.web.replay_data import (
    Clearances,
    ContactSpans,
    QuantisedPoses,
    ReplayCamera,
    ReplayData,
    ReplayFieldError,
    ReplayGeoms,
)

__all__ = ["FORMAT", "MAX_FILE_BYTES", "REPLAY_SUFFIX", "read_replay_file", "write_replay_file"]

FORMAT = ("lynxsim-replay", 1)
"""Name and version of the format this module writes and reads."""
REPLAY_SUFFIX = ".replay.npz"
"""What a run's replay data file is named: its report's stem and this."""
MAX_FILE_BYTES = 256 * 2**20
"""Largest replay file read, packed or unpacked [bytes] (a 6 s run takes under 1 MB)."""
_ZIP_TIME = (1980, 1, 1, 0, 0, 0)

_DTYPES = {
    "time_s": "<f8",
    "pos_q": "<i2",
    "quat_q": "<i2",
    "origin": "<f8",
    "geom_kind": "<i4",
    "geom_size": "<f8",
    "geom_rgba": "<f8",
    "geom_body": "<i4",
    "geom_pos": "<f8",
    "geom_quat": "<f8",
    "camera_pos": "<f8",
    "camera_xmat": "<f8",
    "tool": "<f8",
    "tool_ref": "<f8",
    "targets": "<f8",
    "contact_geom": "<i4",
    "contact_kind": "<i4",
    "contact_start_s": "<f8",
    "contact_end_s": "<f8",
    "clearance_m": "<f8",
    "center": "<f8",
}
"""Every array entry and its exact dtype."""
_META = {
    "format": str,
    "version": int,
    "title": str,
    "task": str,
    "trajectory": str,
    "body_names": list,
    "geom_names": list,
    "camera_names": list,
    "camera_fovy": list,
    "camera_orthographic": list,
    "default_camera": str,
    "obstacle_names": list,
    "report_json": str,
    "pose_error_m": float,
    "step_m": float,
    "extent": float,
    "znear": float,
    "zfar": float,
}
"""Every field of ``meta.npy`` and its JSON kind."""


def _arrays(data: ReplayData) -> dict[str, npt.NDArray[Any]]:
    g, c = data.geoms, data.cameras
    arrays: dict[str, npt.ArrayLike] = {
        "time_s": data.time_s,
        "pos_q": data.poses.pos_q,
        "quat_q": data.poses.quat_q,
        "origin": data.poses.origin,
        "geom_kind": g.kind,
        "geom_size": g.size,
        "geom_rgba": g.rgba,
        "geom_body": g.body,
        "geom_pos": g.pos,
        "geom_quat": g.quat,
        "camera_pos": np.array([x.pos for x in c], dtype=float).reshape(-1, 3),
        "camera_xmat": np.array([x.xmat for x in c], dtype=float).reshape(-1, 3, 3),
        "tool": data.tool,
        "tool_ref": data.tool_ref,
        "targets": data.targets,
        "contact_geom": data.contacts.geom,
        "contact_kind": data.contacts.kind,
        "contact_start_s": data.contacts.start_s,
        "contact_end_s": data.contacts.end_s,
        "clearance_m": data.clearance.values_m,
        "center": data.center,
    }
    return {k: np.ascontiguousarray(arrays[k], dtype=v) for k, v in _DTYPES.items()}


def _meta(data: ReplayData) -> dict[str, object]:
    return {
        "format": FORMAT[0],
        "version": FORMAT[1],
        "title": data.title,
        "task": data.task,
        "trajectory": data.trajectory,
        "body_names": list(data.body_names),
        "geom_names": list(data.geoms.names),
        "camera_names": [c.name for c in data.cameras],
        "camera_fovy": [float(c.fovy) for c in data.cameras],
        "camera_orthographic": [bool(c.orthographic) for c in data.cameras],
        "default_camera": data.default_camera,
        "obstacle_names": list(data.clearance.names),
        "report_json": data.report_json,
        "pose_error_m": float(data.pose_error_m),
        "step_m": float(data.poses.step_m),
        "extent": float(data.extent),
        "znear": float(data.znear),
        "zfar": float(data.zfar),
    }


def _entry(z: zipfile.ZipFile, name: str, array: npt.NDArray[Any]) -> None:
    info = zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_TIME)
    info.compress_type = zipfile.ZIP_DEFLATED
    with z.open(info, "w") as f:
        np.lib.format.write_array(f, array, allow_pickle=False)


def write_replay_file(data: ReplayData, dest: str | os.PathLike[str]) -> Path:
    """Write a replay's data, atomically, and check it reads back equal.

    Args:
        data: The replay.
        dest: The file (by convention the report's stem + :data:`REPLAY_SUFFIX`).

    Returns:
        ``dest`` as a path.

    Raises:
        OutputPathError: ``dest`` is not a regular file or its folder cannot be made.
    """
    meta = json.dumps(_meta(data), ensure_ascii=False)
    with atomic_path(dest) as tmp:
        with zipfile.ZipFile(tmp, "w") as z:
            _entry(z, "meta", np.array(meta))
            for name, array in _arrays(data).items():
                _entry(z, name, array)
        try:
            back = read_replay_file(tmp)
        except ReplayFileError as exc:
            raise ReplayFileError(
                os.fspath(dest), exc.field, "written, it does not read back"
            ) from None
        if _meta(back) != _meta(data) or any(
            not np.array_equal(a, b)
            for a, b in zip(_arrays(back).values(), _arrays(data).values(), strict=True)
        ):
            raise ReplayFileError(os.fspath(dest), None, "did not read back as written")
    return Path(dest)


def _npy(blob: bytes) -> npt.NDArray[Any]:
    """The array of one ``.npy`` file's bytes, its header checked against its length first.

    Raises:
        ValueError: Not a ``.npy`` file of plain numbers or text, or not as long
            as its header says.
    """
    f = io.BytesIO(blob)
    try:
        version = np.lib.format.read_magic(f)
        if version == (1, 0):
            shape, fortran, dtype = np.lib.format.read_array_header_1_0(f)
        elif version in ((2, 0), (3, 0)):
            shape, fortran, dtype = np.lib.format.read_array_header_2_0(f)
        else:
            raise ValueError(f"unknown .npy version {version}")
    except (SyntaxError, tokenize.TokenError, TypeError, OverflowError, MemoryError) as exc:
        raise ValueError(f"bad header ({type(exc).__name__})") from None
    if dtype.hasobject or dtype.kind not in "biufU":
        raise ValueError(f"holds {dtype}, not numbers or text")
    data = blob[f.tell() :]
    if math.prod(shape) * dtype.itemsize != len(data):
        raise ValueError(f"its header says {shape} of {dtype}, but {len(data)} bytes follow")
    return np.frombuffer(data, dtype=dtype).reshape(shape, order="F" if fortran else "C")


def _read_entries(path: Path) -> dict[str, npt.NDArray[Any]]:
    name = os.fspath(path)
    if path.stat().st_size > MAX_FILE_BYTES:
        raise ReplayFileError(name, None, f"larger than {MAX_FILE_BYTES} bytes")
    with zipfile.ZipFile(path) as z:
        infos = z.infolist()
        if sum(i.file_size for i in infos) > MAX_FILE_BYTES:
            raise ReplayFileError(name, None, f"unpacks to over {MAX_FILE_BYTES} bytes")
        want = {f"{k}.npy" for k in ("meta", *_DTYPES)}
        have = [i.filename for i in infos]
        if sorted(have) != sorted(want):
            missing, extra = sorted(want - set(have)), sorted(set(have) - want)
            what = f"missing {missing}" if missing else f"unexpected {extra or 'repeated entries'}"
            raise ReplayFileError(name, None, f"not a lynxsim replay: {what}")
        out = {}
        for info in infos:
            field = info.filename.removesuffix(".npy")
            try:
                with z.open(info) as f:
                    array = _npy(f.read())
            except (ValueError, OSError, EOFError, zipfile.BadZipFile, zlib.error) as exc:
                raise ReplayFileError(name, field, f"not a NumPy array ({exc})") from None
            expected = "<U" if field == "meta" else _DTYPES[field]
            if not array.dtype.str.startswith(expected) or (
                field != "meta" and array.dtype.str != expected
            ):
                raise ReplayFileError(
                    name, field, f"must have dtype {expected}, got {array.dtype.str}"
                )
            out[field] = array
    return out


def _read_meta(name: str, array: npt.NDArray[Any]) -> Mapping[str, Any]:
    if array.shape != ():
        raise ReplayFileError(name, "meta", "must be one text")
    try:
        meta = json.loads(str(array))
    except (json.JSONDecodeError, RecursionError) as exc:
        raise ReplayFileError(name, "meta", f"not JSON ({exc})") from None
    if not isinstance(meta, dict):
        raise ReplayFileError(name, "meta", "must be a JSON object")
    for key, kind in _META.items():
        value = meta.get(key)
        ok = isinstance(value, kind) and not isinstance(value, bool)
        if kind is float:
            ok = isinstance(value, int | float) and not isinstance(value, bool)
        if not ok:
            raise ReplayFileError(name, f"meta.{key}", f"must be a {kind.__name__}")
    if (meta["format"], meta["version"]) != FORMAT:
        raise ReplayFileError(
            name, "meta.format", f"{meta['format']!r} version {meta['version']}, not {FORMAT}"
        )
    for key in ("body_names", "geom_names", "camera_names", "obstacle_names"):
        if not all(isinstance(v, str) for v in meta[key]):
            raise ReplayFileError(name, f"meta.{key}", "must be a list of strings")
    cams = len(meta["camera_names"])
    for key, number in (("camera_fovy", True), ("camera_orthographic", False)):
        values = meta[key]
        if len(values) != cams or not all(
            isinstance(v, bool) != (number and isinstance(v, int | float)) for v in values
        ):
            raise ReplayFileError(name, f"meta.{key}", f"must hold one value per camera ({cams})")
    return meta


def read_replay_file(path: str | os.PathLike[str]) -> ReplayData:
    """Read and check a replay's data file.

    Raises:
        ReplayFileError: Not readable, not a zip of the entries this module
            writes, an entry of another dtype, shape or meaning (names the
            file and the entry).
    """
    name = os.fspath(path)
    try:
        a = _read_entries(Path(path))
    except ReplayFileError:
        raise
    except (OSError, zipfile.BadZipFile, zipfile.LargeZipFile, EOFError, ValueError) as exc:
        raise ReplayFileError(name, None, f"not a readable replay file ({exc})") from None
    meta = _read_meta(name, a["meta"])
    try:
        if len(a["camera_pos"]) != len(meta["camera_names"]) or len(a["camera_xmat"]) != len(
            meta["camera_names"]
        ):
            raise ReplayFieldError("camera_pos", "must hold one pose per camera")
        cameras = tuple(
            ReplayCamera(n, a["camera_pos"][i], a["camera_xmat"][i], float(f), o)
            for i, (n, f, o) in enumerate(
                zip(
                    meta["camera_names"],
                    meta["camera_fovy"],
                    meta["camera_orthographic"],
                    strict=True,
                )
            )
        )
        return ReplayData(
            title=meta["title"],
            task=meta["task"],
            trajectory=meta["trajectory"],
            time_s=a["time_s"],
            body_names=tuple(meta["body_names"]),
            poses=QuantisedPoses(a["pos_q"], a["origin"], float(meta["step_m"]), a["quat_q"]),
            pose_error_m=float(meta["pose_error_m"]),
            geoms=ReplayGeoms(
                kind=a["geom_kind"],
                size=a["geom_size"],
                rgba=a["geom_rgba"],
                body=a["geom_body"],
                pos=a["geom_pos"],
                quat=a["geom_quat"],
                names=tuple(meta["geom_names"]),
            ),
            cameras=cameras,
            default_camera=meta["default_camera"],
            tool=a["tool"],
            tool_ref=a["tool_ref"],
            targets=a["targets"],
            contacts=ContactSpans(
                a["contact_geom"], a["contact_kind"], a["contact_start_s"], a["contact_end_s"]
            ),
            clearance=Clearances(tuple(meta["obstacle_names"]), a["clearance_m"]),
            center=a["center"],
            extent=float(meta["extent"]),
            znear=float(meta["znear"]),
            zfar=float(meta["zfar"]),
            report_json=meta["report_json"],
        )
    except ReplayFieldError as exc:
        raise ReplayFileError(name, exc.field, exc.problem) from None
