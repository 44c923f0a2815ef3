"""Readers of the pose schemas (:data:`lynxsim.registry.PoseSchema`) of task files."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from lynxsim.poses import ArmPose, JointPose, PlanarPose
from lynxsim.registry import PoseSchema
from lynxsim.tasks.reader import FieldReader, show
from lynxsim.tasks.task import TaskPose

__all__ = ["POSE_READERS"]

_MM = 1e-3

_TOOL_POSE_KEYS = ("name", "position_mm", "pitch_deg", "roll_deg", "q_deg")
_PLATFORM_POSE_KEYS = ("name", "x_mm", "y_mm", "alpha_deg")
_JOINT_POSE_KEYS = ("name", "q_deg")


def _joint_pose(
    r: FieldReader, raw: Mapping[str, Any], field: str, name: str, joints: int | None
) -> JointPose:
    raw_q = r.required(raw, "q_deg", f"{field}.q_deg")
    if joints is None:
        raise r.fail(f"{field}.q_deg", "this robot takes no joint poses")
    if not isinstance(raw_q, list) or len(raw_q) != joints:
        raise r.fail(f"{field}.q_deg", f"must be a list of {joints} numbers, got {show(raw_q)}")
    q = tuple(r.angle_deg(v, f"{field}.q_deg[{i}]") for i, v in enumerate(raw_q))
    return JointPose(q, name)


def _tool_pose(
    r: FieldReader, raw: Mapping[str, Any], field: str, name: str, joints: int | None
) -> ArmPose | JointPose:
    if "q_deg" in raw:
        extra = sorted(set(raw) & {"position_mm", "pitch_deg", "roll_deg"})
        if extra:
            raise r.fail(
                f"{field}.{extra[0]}", "a pose gives either q_deg or a tool pose, not both"
            )
        return _joint_pose(r, raw, field, name, joints)
    position = r.position_mm(
        r.required(raw, "position_mm", f"{field}.position_mm"), f"{field}.position_mm"
    )
    pitch = r.angle_deg(r.required(raw, "pitch_deg", f"{field}.pitch_deg"), f"{field}.pitch_deg")
    roll = None
    if "roll_deg" in raw:
        roll = r.angle_deg(raw["roll_deg"], f"{field}.roll_deg")
    x, y, z = (v * _MM for v in position)
    return ArmPose((x, y, z), pitch, roll, name)


def _platform_pose(
    r: FieldReader, raw: Mapping[str, Any], field: str, name: str, joints: int | None
) -> PlanarPose:
    x, y = (
        r.coordinate_mm(r.required(raw, key, f"{field}.{key}"), f"{field}.{key}")
        for key in ("x_mm", "y_mm")
    )
    alpha = r.angle_deg(r.required(raw, "alpha_deg", f"{field}.alpha_deg"), f"{field}.alpha_deg")
    return PlanarPose(x * _MM, y * _MM, alpha, name)


_PoseReader = Callable[[FieldReader, Mapping[str, Any], str, str, int | None], TaskPose]
POSE_READERS: dict[PoseSchema, tuple[tuple[str, ...], _PoseReader]] = {
    "tool": (_TOOL_POSE_KEYS, _tool_pose),
    "platform": (_PLATFORM_POSE_KEYS, _platform_pose),
    "joints": (_JOINT_POSE_KEYS, _joint_pose),
}
"""Each pose schema of :mod:`lynxsim.registry`: its keys and its reader, called as
``reader(fields, raw pose, field name, pose name, the robot's joint count)``."""
