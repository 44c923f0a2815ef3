"""A run report as JSON: read back and checked, written canonically, shown as a verdict table.

A replay page shows the run report (``RunReport.to_dict()``, or the JSON file
``lynxsim play`` writes) as rows of label, value and status. Reading a report
file checks every field the table shows and names file and field when one is
wrong. Pure Python.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Literal, NamedTuple, TypeAlias

from lynxsim.errors import ReplayFileError

__all__ = [
    "JsonValue",
    "ReportDict",
    "VerdictRow",
    "canonical_json",
    "check_report",
    "read_report",
    "verdict_rows",
]

JsonValue: TypeAlias = "bool | int | float | str | list[JsonValue] | dict[str, JsonValue] | None"
"""A value JSON can hold."""
ReportDict: TypeAlias = dict[str, JsonValue]
"""A run report as ``RunReport.to_dict()`` gives it (tuples as lists)."""

Status = Literal["ok", "bad", "info"]


class VerdictRow(NamedTuple):
    """One row of the verdict table: what, its value (readable units), and whether it is good."""

    label: str
    value: str
    status: Status


def canonical_json(report: Mapping[str, object]) -> str:
    """The report as one canonical JSON text (sorted keys, no spaces; lists for tuples)."""
    return json.dumps(report, sort_keys=True, separators=(",", ":"))


def _is_number(v: JsonValue) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def _number(v: JsonValue) -> float:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else math.nan


def _checker(kind: str) -> Callable[[JsonValue], bool]:
    checks: dict[str, Callable[[JsonValue], bool]] = {
        "str": lambda v: isinstance(v, str),
        "str?": lambda v: v is None or isinstance(v, str),
        "bool": lambda v: isinstance(v, bool),
        "number": _is_number,
        "number?": lambda v: v is None or _is_number(v),
        "numbers": lambda v: isinstance(v, list) and all(_is_number(x) for x in v),
        "object?": lambda v: v is None or isinstance(v, dict),
        "counts": lambda v: (
            isinstance(v, dict)
            and all(isinstance(x, int) and not isinstance(x, bool) for x in v.values())
        ),
    }
    return checks[kind]


_REPORT = {
    "task": "str",
    "trajectory": "str",
    "duration_s": "number",
    "settle_s": "number",
    "physics_dt_s": "number",
    "tool_max_error_m": "number",
    "tool_rms_error_m": "number",
    "tool_final_error_m": "number",
    "max_torque_ratio": "numbers",
    "healthy": "bool",
    "warnings": "counts",
    "diverged_at_s": "number?",
    "metrics": "object?",
    "obstacle": "object?",
}
_VERDICT = {
    "collided": "bool",
    "first_time_s": "number?",
    "first_obstacle": "str?",
    "max_penetration_m": "number",
    "steps_in_contact": "number",
}
_OBSTACLE = {
    "name": "str",
    "collided": "bool",
    "first_contact_s": "number?",
    "min_clearance_m": "number",
    "min_clearance_time_s": "number",
}
_PAIR = {"geom1": "str", "geom2": "str", "first_time_s": "number", "max_penetration_m": "number"}


def _check_object(value: JsonValue, schema: Mapping[str, str], where: str) -> dict[str, JsonValue]:
    """``value`` if it is an object whose fields ``schema`` names have their kinds.

    Raises:
        ValueError: ``(field, problem)`` of the first field that is wrong.
    """
    if not isinstance(value, dict):
        raise ValueError(where or "report", "must be a JSON object")
    for key, kind in schema.items():
        field = f"{where}.{key}" if where else key
        if key not in value:
            raise ValueError(field, "missing")
        if not _checker(kind)(value[key]):
            raise ValueError(field, f"must be {kind.replace('?', ' or null')}")
    return value


def check_report(report: JsonValue) -> ReportDict:
    """``report`` if it holds every field the verdict table shows, of the right kind.

    Raises:
        ValueError: With arguments ``(field, problem)``.
    """
    out = _check_object(report, _REPORT, "")
    if out["obstacle"] is not None:
        _check_object(out["obstacle"], _VERDICT, "obstacle")
    for key, schema in (
        ("obstacles", _OBSTACLE),
        ("self_collisions", _PAIR),
        ("floor_contacts", _PAIR),
    ):
        items = out.get(key)
        if not isinstance(items, list):
            raise ValueError(key, "must be a list")
        for i, item in enumerate(items):
            _check_object(item, schema, f"{key}[{i}]")
    return out


def read_report(path: str | os.PathLike[str]) -> ReportDict:
    """A run report JSON file, checked (see :func:`check_report`).

    Raises:
        ReplayFileError: Not readable, not JSON, or a field missing or wrong
            (names the file and the field).
    """
    name = os.fspath(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise ReplayFileError(name, None, "not UTF-8 text") from None
    except OSError as exc:
        raise ReplayFileError(name, None, f"cannot read it ({exc.strerror})") from None
    try:
        value: JsonValue = json.loads(text)
    except (json.JSONDecodeError, RecursionError) as exc:
        raise ReplayFileError(name, None, f"not JSON ({exc})") from None
    try:
        return check_report(value)
    except ValueError as exc:
        field, problem = exc.args
        raise ReplayFileError(name, field or None, problem) from None


def _mm(v: JsonValue) -> str:
    return f"{_number(v) * 1e3:.1f} mm"


def _s(v: JsonValue) -> str:
    return f"{_number(v):.3f} s"


def _pairs(items: JsonValue) -> str:
    rows = items if isinstance(items, list) else []
    return ", ".join(
        f"{p['geom1']}/{p['geom2']} at {_s(p['first_time_s'])}" for p in rows if isinstance(p, dict)
    )


def _metric(key: str, v: JsonValue) -> VerdictRow:
    """A robot metric by its unit suffix: m as mm, rad as degrees, rad/s as deg/s."""
    units = (("_rad_s", 180 / math.pi, "{:.2f} deg/s"), ("_rad", 180 / math.pi, "{:.3f} deg"))
    for suffix, scale, form in (*units, ("_m", 1e3, "{:.2f} mm")):
        if key.endswith(suffix) and _is_number(v):
            label = key.removesuffix(suffix).replace("_", " ")
            return VerdictRow(label, form.format(scale * _number(v)), "info")
    value = f"{v:g}" if _is_number(v) else str(v)
    return VerdictRow(key.replace("_", " "), value, "info")


def verdict_rows(report: ReportDict) -> list[VerdictRow]:
    """The verdict table of a checked report (:func:`check_report`), in mm, degrees and s."""
    r = report
    rows = [
        VerdictRow("task", f"{r['task']} ({r['trajectory']})", "info"),
        VerdictRow(
            "duration",
            f"{_number(r['duration_s']):.2f} s + {_number(r['settle_s']):.2f} s settling, "
            f"physics step {_number(r['physics_dt_s']) * 1e3:.1f} ms",
            "info",
        ),
        VerdictRow(
            "tool tracking",
            f"max {_mm(r['tool_max_error_m'])}, RMS {_mm(r['tool_rms_error_m'])}, "
            f"final {_mm(r['tool_final_error_m'])}",
            "info",
        ),
    ]
    verdict = r["obstacle"]
    if not isinstance(verdict, dict):
        rows.append(VerdictRow("obstacles", "none in the scene", "info"))
    elif verdict["collided"]:
        rows.append(
            VerdictRow(
                "obstacles",
                f"COLLISION with {verdict['first_obstacle']} first at "
                f"{_s(verdict['first_time_s'])}, deepest {_mm(verdict['max_penetration_m'])}, "
                f"{verdict['steps_in_contact']} steps in contact",
                "bad",
            )
        )
    else:
        rows.append(VerdictRow("obstacles", "clear", "ok"))
    for o in r["obstacles"] if isinstance(r["obstacles"], list) else []:
        if not isinstance(o, dict):
            continue
        hit = f"hit at {_s(o['first_contact_s'])}" if o["collided"] else "clear"
        rows.append(
            VerdictRow(
                f"  {o['name']}",
                f"{hit}, minimum clearance {_mm(o['min_clearance_m'])} at "
                f"{_s(o['min_clearance_time_s'])}",
                "bad" if o["collided"] else "ok",
            )
        )
    for label, key in (("self-collisions", "self_collisions"), ("table/floor", "floor_contacts")):
        pairs = _pairs(r[key])
        rows.append(VerdictRow(label, pairs or "none", "bad" if pairs else "ok"))
    torque = r["max_torque_ratio"] if isinstance(r["max_torque_ratio"], list) else []
    peak = max((_number(v) for v in torque), default=0.0)
    rows.append(
        VerdictRow(
            "peak torque / stall",
            " ".join(f"{_number(v):.2f}" for v in torque),
            "bad" if peak >= 1.0 else "ok",
        )
    )
    metrics = r["metrics"]
    if isinstance(metrics, dict):
        rows.extend(_metric(key, v) for key, v in metrics.items())
    health = "healthy" if r["healthy"] else "NOT healthy"
    if r["diverged_at_s"] is not None:
        health += f": diverged at {_s(r['diverged_at_s'])}"
    if r["warnings"]:
        health += f", MuJoCo warnings {r['warnings']}"
    rows.append(VerdictRow("simulation", health, "ok" if r["healthy"] else "bad"))
    return rows
