"""A replay as one self-contained HTML page: data, renderer, styles and report inside one file.

The page (``lynxsim/web/assets/replay.html``) carries its data as JSON in a
``<script type="application/json">`` element (arrays as base64 of
little-endian typed arrays: the poses as int16, everything else float64 or
int32), its own WebGL renderer of MuJoCo's primitives (``gl.js``) and the
page's script (``replay.js``). It loads nothing: its Content-Security-Policy
refuses every request, so it works offline and without a server. Names from
files are escaped (text in HTML, ``<`` as a Unicode escape in the JSON), never markup.
"""

from __future__ import annotations

import base64
import html
import json
import os
import re
from importlib import resources
from pathlib import Path

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, ReplayFileError
from lynxsim.fileio import atomic_path
from lynxsim.web.replay_data import ReplayData
from lynxsim.web.replay_file import read_replay_file
from lynxsim.web.verdicts import check_report, verdict_rows

__all__ = ["page_from_file", "page_payload", "replay_page", "write_replay_page"]

_MARKER = re.compile(r"@@(TITLE|NOTE|CSS|VERDICTS|DATA|GL|JS)@@")


def _asset(name: str) -> str:
    text = resources.files("lynxsim.web").joinpath("assets", name).read_text(encoding="utf-8")
    closing = {".css": "</style", ".js": "</script"}.get(Path(name).suffix)
    if closing is not None and closing in text.lower():
        raise InvalidInputError(f"asset {name} holds {closing!r}: it would end its element")
    return text


def _b64(array: npt.ArrayLike, dtype: str) -> str:
    return base64.b64encode(np.ascontiguousarray(array, dtype=dtype).tobytes()).decode("ascii")


def page_payload(data: ReplayData) -> dict[str, object]:
    """What the page's script reads (JSON-ready; see ``replay.js``)."""
    g = data.geoms
    return {
        "time_s": _b64(data.time_s, "<f8"),
        "body_names": list(data.body_names),
        "poses": {
            "pos_q": _b64(data.poses.pos_q, "<i2"),
            "quat_q": _b64(data.poses.quat_q, "<i2"),
            "origin": [float(v) for v in data.poses.origin],
            "step_m": float(data.poses.step_m),
        },
        "pose_error_m": float(data.pose_error_m),
        "geoms": {
            "kind": [int(v) for v in g.kind],
            "size": np.asarray(g.size, dtype=float).tolist(),
            "rgba": np.asarray(g.rgba, dtype=float).tolist(),
            "body": [int(v) for v in g.body],
            "pos": np.asarray(g.pos, dtype=float).tolist(),
            "quat": np.asarray(g.quat, dtype=float).tolist(),
            "names": list(g.names),
        },
        "cameras": [
            {
                "name": c.name,
                "pos": np.asarray(c.pos, dtype=float).tolist(),
                "xmat": np.asarray(c.xmat, dtype=float).ravel().tolist(),
                "fovy": float(c.fovy),
                "orthographic": bool(c.orthographic),
            }
            for c in data.cameras
        ],
        "default_camera": data.default_camera,
        "tool": _b64(data.tool, "<f8"),
        "tool_ref": _b64(data.tool_ref, "<f8"),
        "targets": _b64(data.targets, "<f8"),
        "contacts": {
            "geom": _b64(data.contacts.geom, "<i4"),
            "kind": _b64(data.contacts.kind, "<i4"),
            "start_s": _b64(data.contacts.start_s, "<f8"),
            "end_s": _b64(data.contacts.end_s, "<f8"),
        },
        "clearance": {
            "names": list(data.clearance.names),
            "values_m": _b64(data.clearance.values_m, "<f8"),
        },
        "center": [float(v) for v in data.center],
        "extent": float(data.extent),
        "znear": float(data.znear),
        "zfar": float(data.zfar),
    }


def _script_json(value: object) -> str:
    """JSON that cannot end its ``<script>`` element or start a comment in it."""
    text = json.dumps(value, ensure_ascii=True, allow_nan=False, separators=(",", ":"))
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _verdict_table(data: ReplayData) -> str:
    try:
        report = check_report(json.loads(data.report_json))
    except (ValueError, RecursionError) as exc:
        raise InvalidInputError(f"report_json is not a run report: {exc.args}") from None
    rows = "\n".join(
        f'<tr class="{r.status}"><th>{html.escape(r.label)}</th>'
        f"<td>{html.escape(r.value)}</td></tr>"
        for r in verdict_rows(report)
    )
    return f'<table class="verdicts">\n{rows}\n</table>'


def replay_page(data: ReplayData) -> str:
    """The replay page of ``data``, as HTML text.

    Raises:
        InvalidInputError: ``data.report_json`` is not a run report.
    """
    span = float(data.time_s[-1] - data.time_s[0])
    rate = (data.frames - 1) / span if span > 0 else 0.0
    note = (
        f"Replay of a lynxsim run: {data.frames} frames ({rate:.0f} per simulated second) over "
        f"{span:.2f} s; between frames the poses are interpolated, and every drawn point lies "
        f"within {data.pose_error_m * 1e3:.2f} mm of the simulation at each physics step. "
        "Self-contained: it loads nothing."
    )
    parts = {
        "TITLE": html.escape(data.title),
        "NOTE": html.escape(note),
        "CSS": _asset("replay.css"),
        "VERDICTS": _verdict_table(data),
        "DATA": _script_json(page_payload(data)),
        "GL": _asset("gl.js"),
        "JS": _asset("replay.js"),
    }
    return _MARKER.sub(lambda m: parts[m.group(1)], _asset("replay.html"))


def write_replay_page(data: ReplayData, dest: str | os.PathLike[str]) -> Path:
    """Write the replay page of ``data`` to ``dest``, atomically; returns the path.

    Raises:
        OutputPathError: ``dest`` is not a regular file or its folder cannot be made.
        InvalidInputError: ``data.report_json`` is not a run report.
    """
    text = replay_page(data)
    with atomic_path(dest) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(dest)


def page_from_file(
    replay: str | os.PathLike[str], dest: str | os.PathLike[str], report_json: str | None = None
) -> Path:
    """Write the page of a saved replay (:func:`~lynxsim.web.replay_file.read_replay_file`).

    Args:
        replay: The replay data file.
        dest: The page.
        report_json: The run report the replay must belong to, as canonical JSON
            (:func:`~lynxsim.web.verdicts.canonical_json`), or None.

    Raises:
        ReplayFileError: The replay file is not one lynxsim wrote, or it was
            written with another report than ``report_json``.
        OutputPathError: ``dest`` is not a regular file or its folder cannot be made.
    """
    data = read_replay_file(replay)
    if report_json is not None and data.report_json != report_json:
        raise ReplayFileError(
            os.fspath(replay), "meta.report_json", "written with another run report"
        )
    return write_replay_page(data, dest)
