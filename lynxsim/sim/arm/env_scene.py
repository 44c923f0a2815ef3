"""The MuJoCo side of an arm env: its scene compiled, ids resolved, reset, stepped, contacts.

:class:`EnvScene` owns the env's :class:`mujoco.MjModel` / :class:`mujoco.MjData`
pair, built from a :class:`~lynxsim.scene.Scene` (:func:`load_arm_spec`), with
spare obstacle geoms for obstacles drawn at every reset
(:mod:`lynxsim.sim.arm.slots`). The envs (:mod:`lynxsim.envs`) reach MuJoCo
through it; its step path resolves nothing by name: ids are resolved once, and
physics runs as ``mj_step(model, data, nstep=...)``.
"""

from __future__ import annotations

from collections.abc import Sequence

import mujoco

from lynxsim.angles import quat_yaw
from lynxsim.scene import Cube, Obstacle, Scene
from lynxsim.sim.arm.model import SceneIds, load_arm_spec, table_top_z
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.arm.slots import ObstacleSlots, add_obstacle_slots
from lynxsim.sim.collision import CollisionChecker

__all__ = ["GOAL_MARK_SITE", "EnvScene"]

GOAL_MARK_SITE = "place_target"
"""The scene's green disc on the table; an env moves it below its goal (visual only)."""


def _as_index(ids: tuple[int, ...]) -> slice | list[int]:
    """A slice when the ids are consecutive (faster to index with), else the list."""
    if list(ids) == list(range(ids[0], ids[0] + len(ids))):
        return slice(ids[0], ids[0] + len(ids))
    return list(ids)


class EnvScene:
    """An arm scene compiled for an env, and the ids its step loop needs.

    Args:
        obstacles: The fixed obstacles.
        cube: The cube, or None (a scene without one).
        spare: Obstacle slots for obstacles drawn later (all parked away), or
            None for none.

    Attributes:
        model: The compiled model.
        data: Its data.
        ids: The scene's ids.
        slots: The spare obstacle geoms, or None.
        table_top_z: Height of the table's top [m].
        arm_qpos: ``qpos`` addresses of the five arm joints.
        arm_dofs: Their ``qvel`` addresses.
        arm_actuators: The five hinge actuators (a slice where consecutive).
        gripper_actuator: The opening actuator.
        finger_qpos: ``qpos`` addresses of the two finger slides.
        finger_dofs: Their ``qvel`` addresses.
        goal_mark: Site id of :data:`GOAL_MARK_SITE`.
    """

    def __init__(self, obstacles: Sequence[Obstacle], cube: Cube | None, spare: int | None) -> None:
        spec = load_arm_spec(Scene(tuple(obstacles), cube=cube))
        if spare is not None:
            add_obstacle_slots(spec, spare)
        self.table_top_z = table_top_z(spec)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        self.slots = None if spare is None else ObstacleSlots.from_model(self.model)
        if self.slots is not None:
            self.slots.place(())
        m = self.model
        ids = SceneIds.from_model(m)
        self.ids = ids
        self.arm_qpos = list(ids.arm_qpos)
        self.arm_dofs = list(ids.arm_dofs)
        self.arm_actuators = _as_index(ids.arm_actuators)
        self.gripper_actuator = ids.gripper_actuator
        self.finger_qpos = [int(m.jnt_qposadr[j]) for j in ids.finger_joints]
        self.finger_dofs = [int(m.jnt_dofadr[j]) for j in ids.finger_joints]
        groups = ids.collision_groups(m)
        self._obstacle_pairs = groups.obstacle_pairs()
        self._has_obstacle = bool(len(groups.obstacle_geoms))
        self.goal_mark = m.site(GOAL_MARK_SITE).id

    @property
    def timestep(self) -> float:
        """Physics step [s]."""
        return float(self.model.opt.timestep)

    def rest(self, q: Sequence[float], finger_m: float, opening_m: float) -> None:
        """Reset the data: the arm at rest at ``q`` (5 values [rad]), targets there.

        Each finger at ``finger_m`` [m], the gripper commanded to ``opening_m``
        [m]; velocities, time, contacts and warnings cleared. The caller sets the
        rest of the state (the cube), then calls :meth:`forward`.
        """
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)  # qvel, act, warm start, time, contacts, warnings
        for adr, v in zip(self.arm_qpos, q):
            d.qpos[adr] = v
        for adr in self.finger_qpos:
            d.qpos[adr] = finger_m
        d.ctrl[self.arm_actuators] = q
        d.ctrl[self.gripper_actuator] = opening_m

    def forward(self) -> None:
        """Positions, contacts and sensors of the state now (``mj_forward``)."""
        mujoco.mj_forward(self.model, self.data)

    def simulate(self, steps: int, *, every_step: bool) -> bool:
        """Run ``steps`` physics steps; whether the arm or cube touched an obstacle.

        Args:
            steps: Physics steps.
            every_step: Test the contacts after every step (else only after the
                last: one native call for all steps).
        """
        m, d = self.model, self.data
        if not every_step:
            mujoco.mj_step(m, d, nstep=steps)
            return self.touching_obstacle()
        hit = False
        for _ in range(steps):
            mujoco.mj_step(m, d)
            hit = self.touching_obstacle() or hit
        return hit

    def touching_obstacle(self) -> bool:
        """Whether the arm or the cube touches an obstacle in the current contacts.

        The pairs are those :func:`lynxsim.sim.collision.classify_contacts` calls
        obstacle hits (:meth:`~lynxsim.sim.collision.CollisionGroups.obstacle_pairs`),
        looked up in a set: this runs every physics step.
        """
        if not self._has_obstacle or self.data.ncon == 0:
            return False
        contact = self.data.contact
        pairs = self._obstacle_pairs
        for k, (g1, g2) in enumerate(contact.geom.tolist()):
            if (g1, g2) in pairs and contact.dist[k] <= 0.0:
                return True
        return False

    def checker(self, base_qpos: Sequence[float] | None = None) -> CollisionChecker:
        """The arm's batch collision checker of this scene (its obstacle slots as they stand).

        Args:
            base_qpos: The rest of the state (fingers, cube), (nq,); default ``qpos0``.
        """
        return arm_checker(self.model, base_qpos)

    def cube_pose(self) -> tuple[float, float, float, float] | None:
        """The cube's centre (x, y, z) [m] and yaw [rad] now, or None without a cube."""
        adr = self.ids.cube_qpos
        if adr is None:
            return None
        x, y, z = self.data.qpos[adr : adr + 3].tolist()
        w, qx, qy, qz = self.data.qpos[adr + 3 : adr + 7].tolist()
        return x, y, z, quat_yaw(w, qx, qy, qz)
