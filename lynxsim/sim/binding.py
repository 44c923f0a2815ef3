"""Which parts of a MuJoCo model the playback drives, watches and judges.

A :class:`RobotBinding` holds ids resolved once from names, so that the
per-step loop only indexes arrays. Robot-specific constructors (the arm's, the
3-RRR's) live beside their scenes.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.sim.collision import CollisionGroups

__all__ = ["RobotBinding", "body_subtree", "geoms_of_bodies", "name_to_id"]

IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]


def name_to_id(model: mujoco.MjModel, obj: mujoco.mjtObj, name: str) -> int:
    """Id of a named element, or raise listing what exists.

    Raises:
        InvalidInputError: If the model has no element of that kind and name.
    """
    i = int(mujoco.mj_name2id(model, int(obj), name))
    if i < 0:
        raise InvalidInputError(f"model has no {obj.name.removeprefix('mjOBJ_').lower()} {name!r}")
    return i


def body_subtree(model: mujoco.MjModel, root: int) -> list[int]:
    """Ids of ``root`` and every body below it."""
    parents = np.asarray(model.body_parentid)
    out = [root]
    for b in range(root + 1, model.nbody):
        if int(parents[b]) in out:
            out.append(b)
    return out


def geoms_of_bodies(
    model: mujoco.MjModel, bodies: Iterable[int], collide: bool = True
) -> BoolArray:
    """Mask over geoms: those on ``bodies`` (only colliding ones if ``collide``)."""
    body_set = np.zeros(model.nbody, dtype=bool)
    body_set[list(bodies)] = True
    mask: BoolArray = body_set[np.asarray(model.geom_bodyid)]
    if collide:
        mask &= (np.asarray(model.geom_contype) != 0) | (np.asarray(model.geom_conaffinity) != 0)
    return mask


@dataclass(frozen=True)
class RobotBinding:
    """Ids of the driven joints, the tracked site and the collision groups.

    Attributes:
        actuator_ids: Position actuators of the commanded joints, shape (n,).
        qpos_adr: qpos addresses of those joints, shape (n,).
        tool_site_id: The site whose position is tracked (tool point, platform centre).
        groups: Which geoms are robot, payload, obstacles and support
            (:mod:`lynxsim.sim.collision`).
        gripper_actuator_id: The gripper's actuator, or None.
    """

    actuator_ids: IntArray
    qpos_adr: IntArray
    tool_site_id: int
    groups: CollisionGroups
    gripper_actuator_id: int | None = None

    @staticmethod
    def for_joints(model: mujoco.MjModel, joint_names: Iterable[str]) -> tuple[IntArray, IntArray]:
        """Actuator ids and qpos addresses for joints whose actuators share their names."""
        names = list(joint_names)
        act = [name_to_id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, n) for n in names]
        jnt = [name_to_id(model, mujoco.mjtObj.mjOBJ_JOINT, n) for n in names]
        return (
            np.asarray(act, dtype=np.intp),
            np.asarray(model.jnt_qposadr, dtype=np.intp)[jnt],
        )
