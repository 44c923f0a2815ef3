"""The 3-RRR robot's MuJoCo scene: loading it, naming its parts, assembling it at a pose.

The MJCF files in ``lynxsim/models/rrr/`` are the model (see their README). The
mechanism moves in a horizontal plane. Per leg, ``qpos`` holds the actuated
angle ``theta_i`` (direction of the proximal link from +x, as in
:mod:`lynxsim.rrr`) and the elbow angle (distal link relative to the proximal
one); the platform is a free body (``qpos``: position, quaternion) that three
``connect`` equalities close onto the legs at the platform joints ``P_i``.

MuJoCo measures hinge angles from ``qpos0``, and a playback resets to it, so
a run that starts away from the ``home`` keyframe uses a model written at its
start assembly: :func:`load_rrr_spec` rewrites the body frames and joint
``ref`` values with MjSpec (hinge ``qpos`` stay absolute angles).

Actuated angles are kept in a per-leg range of one turn centred on the
direction from ``B_i`` towards the base centre ``C_b`` (the actuators'
``ctrlrange``; :func:`lynxsim.rrr.path.wrap_to_window`).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.angles import quat_yaw
from lynxsim.errors import InvalidInputError
from lynxsim.resources import model_path
from lynxsim.rrr import RRR_ROBOT, ik_one, leg_points
from lynxsim.rrr.geometry import as_pose_array
from lynxsim.rrr.ik import wrap_angle
from lynxsim.rrr.modes import HOME_MODE
from lynxsim.rrr.path import wrap_to_window
from lynxsim.sim.binding import RobotBinding, name_to_id
from lynxsim.sim.collision import CollisionGroups

__all__ = [
    "HOME_POSE",
    "LEG_BASE_JOINTS",
    "LEG_ELBOW_JOINTS",
    "LEG_TIP_SITES",
    "LOOP_EQUALITIES",
    "PLATFORM_BODY",
    "PLATFORM_JOINT",
    "PLATFORM_JOINT_SITES",
    "PLATFORM_SITE",
    "RRR_ACTUATORS",
    "RRR_COLLISION_GROUP",
    "RRR_HOME_KEY",
    "RRR_SCENE_XML",
    "RRR_XML",
    "RRRIds",
    "assembly_qpos",
    "load_rrr_model",
    "load_rrr_scene",
    "load_rrr_spec",
    "loop_closure_errors",
    "platform_pose",
    "rrr_binding",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

RRR_XML = "rrr/rrr.xml"
"""The robot alone, relative to the models folder."""
RRR_SCENE_XML = "rrr/scene.xml"
"""The robot on its base plate, with lights and the cameras ``top`` and ``front``."""

LEG_BASE_JOINTS = ("leg1_base", "leg2_base", "leg3_base")
"""Actuated hinges at ``B_i``; qpos is ``theta_i`` [rad] (see :mod:`lynxsim.rrr.path`)."""
RRR_ACTUATORS = LEG_BASE_JOINTS
"""Position actuators of the actuated hinges, named after their joints; ctrl in [rad]."""
LEG_ELBOW_JOINTS = ("leg1_elbow", "leg2_elbow", "leg3_elbow")
"""Passive hinges at the elbows ``E_i``; qpos is the distal link's angle from the proximal."""
PLATFORM_JOINT = "platform"
"""The platform's free joint; :func:`platform_pose` reads ``(x, y, alpha)`` from it."""
PLATFORM_BODY = "platform"
LEG_TIP_SITES = ("leg1_tip", "leg2_tip", "leg3_tip")
"""Sites at the distal end of each leg."""
PLATFORM_JOINT_SITES = ("platform_joint1", "platform_joint2", "platform_joint3")
"""Sites at the platform joints ``P_i`` on the platform."""
LOOP_EQUALITIES = ("leg1_loop", "leg2_loop", "leg3_loop")
"""The ``connect`` equalities joining each leg tip site to its platform joint site."""
PLATFORM_SITE = "platform_centre"
"""Tracked site: the needle tip above the platform centre."""
RRR_HOME_KEY = "home"
RRR_COLLISION_GROUP = 3
"""Geom group of the link capsules that detect link interference."""

HOME_POSE: tuple[float, float, float] = (*RRR_ROBOT.base_centre, 0.0)
"""Platform pose of the ``home`` keyframe: centre at ``C_b``, alpha 0 [m, m, rad]."""


def _assembly(
    pose: npt.ArrayLike, mode: int, theta: npt.ArrayLike | None
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Actuated angles (in range), elbow angles and the pose of an assembly, each (3,)."""
    p = as_pose_array(pose)
    if p.shape != (3,):
        raise InvalidInputError(f"pose must have shape (3,), got {p.shape}")
    if not (isinstance(mode, int | np.integer) and 0 <= int(mode) <= 7):
        raise InvalidInputError(f"working mode must be an integer in 0..7, got {mode!r}")
    ik_theta = ik_one(p)[int(mode)]
    th = wrap_to_window(ik_theta) if theta is None else np.asarray(theta, dtype=float)
    if th.shape != (3,) or not np.allclose(wrap_angle(th - ik_theta), 0.0, atol=1e-9):
        raise InvalidInputError(
            f"theta {np.asarray(theta).tolist()} are not the actuated angles of pose "
            f"{p.tolist()} in working mode {mode} (up to whole turns)"
        )
    pts = leg_points(p, int(mode))
    distal = pts[:, 2] - pts[:, 1]
    elbow = wrap_angle(np.arctan2(distal[:, 1], distal[:, 0]) - ik_theta)
    return th, elbow, p


def _quat_z(alpha: float) -> FloatArray:
    return np.array([np.cos(alpha / 2.0), 0.0, 0.0, np.sin(alpha / 2.0)])


def load_rrr_spec(
    pose: npt.ArrayLike | None = None,
    mode: int = HOME_MODE,
    *,
    theta: npt.ArrayLike | None = None,
) -> mujoco.MjSpec:
    """Parse the 3-RRR scene, optionally rewritten at another assembly, without compiling it.

    Args:
        pose: Platform pose (x, y, alpha) of the assembly [m, m, rad]; None
            keeps the file's (``home``).
        mode: Working mode 0..7 of the assembly.
        theta: Its actuated angles [rad], (3,), if they must differ from the
            IK's by whole turns (default: in the actuators' ranges).

    Returns:
        The spec; compiled, its ``qpos0`` is that assembly and every loop is closed.

    Raises:
        UnreachablePlatformPoseError: The pose is out of reach (``legs`` names which).
        InvalidInputError: Bad pose, mode or theta.
    """
    spec = mujoco.MjSpec.from_file(str(model_path(RRR_SCENE_XML)))
    if pose is None:
        return spec
    th, elbow, p = _assembly(pose, mode, theta)
    for i in range(3):
        for body, joint, angle in (
            (f"leg{i + 1}_proximal", LEG_BASE_JOINTS[i], th[i]),
            (f"leg{i + 1}_distal", LEG_ELBOW_JOINTS[i], elbow[i]),
        ):
            spec.body(body).alt.euler = [0.0, 0.0, float(angle)]
            spec.joint(joint).ref = float(angle)
    platform = spec.body(PLATFORM_BODY)
    platform.pos = [float(p[0]), float(p[1]), float(platform.pos[2])]
    platform.quat = _quat_z(float(p[2]))
    return spec


def load_rrr_scene(
    pose: npt.ArrayLike | None = None,
    mode: int = HOME_MODE,
    *,
    theta: npt.ArrayLike | None = None,
) -> mujoco.MjModel:
    """Compile the 3-RRR scene (2 ms timestep, implicitfast), optionally at another assembly.

    Arguments as :func:`load_rrr_spec`; ``qpos0`` of the model is the assembly.
    """
    return load_rrr_spec(pose, mode, theta=theta).compile()


def load_rrr_model() -> mujoco.MjModel:
    """Compile the robot alone (no base plate, lights or cameras)."""
    return mujoco.MjModel.from_xml_path(str(model_path(RRR_XML)))


@dataclass(frozen=True)
class RRRIds:
    """Ids and addresses of the 3-RRR model elements lynxsim refers to.

    Attributes:
        base_qpos: qpos addresses of the actuated joints, (3,).
        elbow_qpos: qpos addresses of the elbow joints, (3,).
        platform_qpos: qpos address of the platform's free joint (7 values follow).
        platform_dof: Its first dof address (6 values follow: linear, angular).
        platform_body: The platform body.
        proximal_bodies: The proximal link bodies, whose origins are ``B_i``, (3,).
        actuators: Actuator ids, (3,).
        tip_sites: Leg tip sites, (3,).
        joint_sites: Platform joint sites, (3,).
        centre_site: The tracked needle-tip site.
        loops: The three loop-closing equalities.
        link_geoms: Collision capsules of the links and the platform.
        home_key: The ``home`` keyframe.
    """

    base_qpos: IntArray
    elbow_qpos: IntArray
    platform_qpos: int
    platform_dof: int
    platform_body: int
    proximal_bodies: IntArray
    actuators: IntArray
    tip_sites: IntArray
    joint_sites: IntArray
    centre_site: int
    loops: IntArray
    link_geoms: IntArray
    home_key: int

    @classmethod
    def from_model(cls, model: mujoco.MjModel) -> RRRIds:
        """Resolve the names of this module in a compiled model.

        Raises:
            InvalidInputError: If an element is missing (names it).
        """
        obj = mujoco.mjtObj

        def ids(kind: mujoco.mjtObj, names: tuple[str, ...]) -> IntArray:
            return np.array([name_to_id(model, kind, n) for n in names], dtype=np.intp)

        qposadr = np.asarray(model.jnt_qposadr, dtype=np.intp)
        platform_joint = name_to_id(model, obj.mjOBJ_JOINT, PLATFORM_JOINT)
        if int(model.jnt_type[platform_joint]) != int(mujoco.mjtJoint.mjJNT_FREE):
            raise InvalidInputError(f"joint {PLATFORM_JOINT!r} must be a free joint")
        root = name_to_id(model, obj.mjOBJ_BODY, PLATFORM_BODY)
        proximal = ids(obj.mjOBJ_BODY, tuple(f"leg{i}_proximal" for i in (1, 2, 3)))
        distal = ids(obj.mjOBJ_BODY, tuple(f"leg{i}_distal" for i in (1, 2, 3)))
        robot_bodies = {root} | {int(b) for b in (*proximal, *distal)}
        links = [
            g
            for g in range(model.ngeom)
            if int(model.geom_group[g]) == RRR_COLLISION_GROUP
            and int(model.geom_bodyid[g]) in robot_bodies
        ]
        return cls(
            base_qpos=qposadr[ids(obj.mjOBJ_JOINT, LEG_BASE_JOINTS)],
            elbow_qpos=qposadr[ids(obj.mjOBJ_JOINT, LEG_ELBOW_JOINTS)],
            platform_qpos=int(qposadr[platform_joint]),
            platform_dof=int(model.jnt_dofadr[platform_joint]),
            platform_body=root,
            proximal_bodies=proximal,
            actuators=ids(obj.mjOBJ_ACTUATOR, RRR_ACTUATORS),
            tip_sites=ids(obj.mjOBJ_SITE, LEG_TIP_SITES),
            joint_sites=ids(obj.mjOBJ_SITE, PLATFORM_JOINT_SITES),
            centre_site=name_to_id(model, obj.mjOBJ_SITE, PLATFORM_SITE),
            loops=ids(obj.mjOBJ_EQUALITY, LOOP_EQUALITIES),
            link_geoms=np.asarray(links, dtype=np.intp),
            home_key=name_to_id(model, obj.mjOBJ_KEY, RRR_HOME_KEY),
        )


def rrr_binding(model: mujoco.MjModel, ids: RRRIds | None = None) -> RobotBinding:
    """What the playback drives and watches in a 3-RRR model.

    Robot geoms are the link capsules, so the contact tracker's self-collisions
    are the link interference; the scene has no obstacle and no support geoms
    that the links could touch.
    """
    ids = RRRIds.from_model(model) if ids is None else ids
    robot = np.zeros(model.ngeom, dtype=bool)
    robot[ids.link_geoms] = True
    none = np.zeros(model.ngeom, dtype=bool)
    groups = CollisionGroups(
        robot=robot,
        payload=none,
        support=none.copy(),
        obstacle_geoms=np.zeros(0, dtype=np.intp),
        obstacle_names=(),
    )
    return RobotBinding(
        actuator_ids=ids.actuators,
        qpos_adr=ids.base_qpos,
        tool_site_id=ids.centre_site,
        groups=groups,
    )


def assembly_qpos(
    model: mujoco.MjModel,
    pose: npt.ArrayLike,
    mode: int,
    *,
    ids: RRRIds | None = None,
    theta: npt.ArrayLike | None = None,
) -> FloatArray:
    """The configuration that puts the platform at ``pose`` in working mode ``mode``.

    Args:
        model: A 3-RRR model.
        pose: Platform pose (x, y, alpha), shape (3,) [m, m, rad].
        mode: Working mode 0..7 (:mod:`lynxsim.rrr.modes`).
        ids: Resolved ids (resolved here if None).
        theta: Actuated angles to use, (3,) [rad]; they must equal the IK's up
            to whole turns (default: the IK's, in the actuators' ranges).

    Returns:
        qpos, shape (nq,), with every loop closed; the platform at the height
        of the model's ``qpos0``.

    Raises:
        UnreachablePlatformPoseError: A leg cannot reach (``legs`` names which).
        InvalidInputError: Bad pose shape, mode or theta.
    """
    ids = RRRIds.from_model(model) if ids is None else ids
    th, elbow, p = _assembly(pose, mode, theta)
    qpos = np.array(model.qpos0, dtype=float)
    qpos[ids.base_qpos] = th
    qpos[ids.elbow_qpos] = elbow
    a = ids.platform_qpos
    qpos[a : a + 2] = p[:2]
    qpos[a + 3 : a + 7] = _quat_z(float(p[2]))
    return qpos


def platform_pose(data: mujoco.MjData, ids: RRRIds) -> FloatArray:
    """Simulated platform pose ``(x, y, alpha)`` [m, m, rad] from its free joint, (3,).

    ``alpha`` is the yaw of the platform's orientation, in [-pi, pi].
    """
    a = ids.platform_qpos
    x, y = data.qpos[a], data.qpos[a + 1]
    w, qx, qy, qz = data.qpos[a + 3 : a + 7].tolist()
    return np.array([x, y, quat_yaw(w, qx, qy, qz)], dtype=float)


def loop_closure_errors(data: mujoco.MjData, ids: RRRIds) -> FloatArray:
    """Distance between each leg tip and its platform joint, (3,) [m] (after kinematics)."""
    gap = data.site_xpos[ids.tip_sites] - data.site_xpos[ids.joint_sites]
    out: FloatArray = np.sqrt((gap * gap).sum(axis=1))
    return out
