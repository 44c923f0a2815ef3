"""Domain randomisation written into an arm scene's model, and the model's values read back.

:class:`ModelRandomizer` draws what a :class:`Draws` asks (cube size, mass and
friction, servo gains, joint damping, camera poses) into a compiled model,
always from its nominal values, and reports the values now in force as a
:class:`Domain`. The envs' :class:`lynxsim.envs.Randomization` is such a
:class:`Draws`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Protocol

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.scene import Cube
from lynxsim.sim.arm.slots import primitive_bounds

__all__ = ["Domain", "Draws", "ModelRandomizer"]

FloatArray = npt.NDArray[np.float64]


class Draws(Protocol):
    """What to draw: ranges ``(lo, hi)`` (None: nominal) and relative tolerances (0: none).

    See :class:`lynxsim.envs.Randomization` for the meaning and units of each.
    """

    @property
    def cube_size_m(self) -> tuple[float, float] | None:
        """Cube edge range [m]."""

    @property
    def cube_mass_kg(self) -> tuple[float, float] | None:
        """Cube mass range [kg]."""

    @property
    def cube_friction(self) -> tuple[float, float] | None:
        """Cube sliding friction range [-]."""

    @property
    def servo_gain_tolerance(self) -> float:
        """Relative tolerance of the arm servos' gains [-]."""

    @property
    def joint_damping_tolerance(self) -> float:
        """Relative tolerance of the arm joints' damping [-]."""

    @property
    def camera_shift_m(self) -> float:
        """Largest camera shift per axis [m]."""

    @property
    def camera_tilt_rad(self) -> float:
        """Largest camera tilt [rad]."""

    @property
    def touches_cube(self) -> bool:
        """Whether the cube is randomised."""


@dataclass(frozen=True)
class Domain:
    """The physical parameters of an episode (drawn, or nominal where not randomised).

    Attributes:
        cube_size_m: Cube edge [m], None without a cube.
        cube_mass_kg: Cube mass [kg], None without a cube.
        cube_friction: Cube sliding friction coefficient [-], None without a cube.
        servo_kp: Proportional gains of the five arm servos, q1..q5 [N·m/rad].
        joint_damping: Damping of the five arm joints [N·m·s/rad].
        camera_pos: Each camera's position, shape (ncam, 3) [m], world frame.
        camera_quat: Each camera's orientation (w, x, y, z), shape (ncam, 4).
    """

    cube_size_m: float | None
    cube_mass_kg: float | None
    cube_friction: float | None
    servo_kp: tuple[float, ...]
    joint_damping: tuple[float, ...]
    camera_pos: tuple[tuple[float, ...], ...]
    camera_quat: tuple[tuple[float, ...], ...]


class ModelRandomizer:
    """Writes an episode's draws into a model and puts its nominal values back.

    Args:
        model: The env's model (edited in place).
        data: Its data (``mj_setConst`` uses it as scratch: apply before ``mj_resetData``).
        actuators: The arm's position actuators (index into ``actuator_*``).
        dofs: The arm's dofs (index into ``dof_*``).
        cube_geom: The cube's geom, or None.
        cube: The nominal cube (its size, mass and friction are the model's).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        actuators: slice | list[int],
        dofs: list[int],
        cube_geom: int | None,
        cube: Cube,
    ) -> None:
        self._model, self._data = model, data
        self._act, self._dofs, self._geom = actuators, dofs, cube_geom
        self._cube = cube
        self._nominal = self._read()
        adr, num = int(model.body_bvhadr[0]), int(model.body_bvhnum[0])
        self._world_bvh = slice(max(adr, 0), max(adr, 0) + (num if adr >= 0 else 0))
        self._world_aabb = model.bvh_aabb[self._world_bvh].copy()
        self._randomized = False
        self.domain = self._current()
        """The model's physical parameters now (a :class:`Domain`)."""

    def _read(self) -> list[FloatArray]:
        """Copies of the fields randomisation writes (the cube's: none without one)."""
        m, g = self._model, self._geom
        fields = [
            m.actuator_gainprm[self._act, 0].copy(),
            m.actuator_biasprm[self._act, 1].copy(),
            m.dof_damping[self._dofs].copy(),
            m.cam_pos.copy(),
            m.cam_quat.copy(),
        ]
        if g is not None:
            b = int(m.geom_bodyid[g])
            fields += [
                m.geom_size[g].copy(),
                m.geom_aabb[g].copy(),
                m.geom_rbound[g : g + 1].copy(),
                m.geom_friction[g].copy(),
                m.body_mass[b : b + 1].copy(),
                m.body_inertia[b].copy(),
            ]
        return fields

    def _write(self, fields: list[FloatArray]) -> None:
        """Write what :meth:`_read` read."""
        m, g = self._model, self._geom
        m.actuator_gainprm[self._act, 0] = fields[0]
        m.actuator_biasprm[self._act, 1] = fields[1]
        m.dof_damping[self._dofs] = fields[2]
        m.cam_pos[:] = fields[3]
        m.cam_quat[:] = fields[4]
        if g is not None:
            b = int(m.geom_bodyid[g])
            m.geom_size[g] = fields[5]
            m.geom_aabb[g] = fields[6]
            m.geom_rbound[g] = fields[7][0]
            m.geom_friction[g] = fields[8]
            m.body_mass[b] = fields[9][0]
            m.body_inertia[b] = fields[10]

    def apply(self, r: Draws | None, rng: np.random.Generator) -> Cube:
        """Draw from ``rng`` what ``r`` asks, starting from the nominal model; return the cube.

        ``r`` None restores the nominal model (touching nothing when nothing was
        randomised, so the random stream is untouched). Runs ``mj_setConst``, so
        the constants that depend on masses (``body_subtreemass``,
        ``*_invweight0``, ``dof_M0``, ``actuator_acc0``) and the cube's bounding
        volumes follow the cube; the world body's, which it refits too, are put
        back as compiled.
        """
        if r is None and not self._randomized:
            return self._cube
        m, g = self._model, self._geom
        self._write(self._nominal)
        cube = self._cube
        if r is not None:
            if r.touches_cube and g is not None:
                size, mass, friction = (
                    default if span is None else float(rng.uniform(*span))
                    for span, default in (
                        (r.cube_size_m, cube.size),
                        (r.cube_mass_kg, cube.mass),
                        (r.cube_friction, cube.friction),
                    )
                )
                cube = replace(cube, size=size, mass=mass, friction=friction)
                b = int(m.geom_bodyid[g])
                half = 0.5 * size
                extents, radius = primitive_bounds(int(m.geom_type[g]), (half, half, half))
                m.geom_size[g] = half
                m.geom_aabb[g, 3:] = extents
                m.geom_rbound[g] = radius
                m.geom_friction[g, 0] = friction
                m.body_mass[b] = mass
                m.body_inertia[b] = mass * size * size / 6.0  # a solid cube
            self._draw_servos_and_cameras(r, rng)
        mujoco.mj_setConst(m, self._data)
        # mj_setConst also refits the bounding-volume hierarchies to the geoms as they
        # stand: the world's to the obstacle slots of the last episode (parked, or
        # where it put them). Its compiled boxes cover every place a slot may take;
        # keep them, or the next episode would depend on the last one (and miss
        # contacts). The cube's follows its new size.
        m.bvh_aabb[self._world_bvh] = self._world_aabb
        self._randomized = r is not None
        self.domain = self._current()
        return cube

    def _draw_servos_and_cameras(self, r: Draws, rng: np.random.Generator) -> None:
        m, n = self._model, len(self._dofs)
        if r.servo_gain_tolerance:
            t = r.servo_gain_tolerance
            kp = self._nominal[0] * rng.uniform(1.0 - t, 1.0 + t, n)
            m.actuator_gainprm[self._act, 0] = kp
            m.actuator_biasprm[self._act, 1] = -kp
        if r.joint_damping_tolerance:
            t = r.joint_damping_tolerance
            m.dof_damping[self._dofs] = self._nominal[2] * rng.uniform(1.0 - t, 1.0 + t, n)
        if r.camera_shift_m:
            shift = r.camera_shift_m
            m.cam_pos[:] = self._nominal[3] + rng.uniform(-shift, shift, (m.ncam, 3))
        if r.camera_tilt_rad:
            axes = rng.standard_normal((m.ncam, 3))
            angles = rng.uniform(0.0, r.camera_tilt_rad, m.ncam)
            turn, quat = np.zeros(4), np.zeros(4)
            for i in range(m.ncam):
                mujoco.mju_axisAngle2Quat(turn, axes[i] / np.linalg.norm(axes[i]), angles[i])
                mujoco.mju_mulQuat(quat, self._nominal[4][i], turn)
                m.cam_quat[i] = quat / np.linalg.norm(quat)

    def _current(self) -> Domain:
        """The model's physical parameters now."""
        m, g = self._model, self._geom
        return Domain(
            cube_size_m=None if g is None else 2.0 * float(m.geom_size[g, 0]),
            cube_mass_kg=None if g is None else float(m.body_mass[m.geom_bodyid[g]]),
            cube_friction=None if g is None else float(m.geom_friction[g, 0]),
            servo_kp=tuple(m.actuator_gainprm[self._act, 0].tolist()),
            joint_damping=tuple(m.dof_damping[self._dofs].tolist()),
            camera_pos=tuple(map(tuple, m.cam_pos.tolist())),
            camera_quat=tuple(map(tuple, m.cam_quat.tolist())),
        )
