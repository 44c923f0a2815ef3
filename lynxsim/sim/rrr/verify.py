"""Verifying the 3-RRR kinematics by simulation: settling at commanded poses, pulling the platform.

* :func:`check_pose` assembles the mechanism a few millimetres from a target
  pose, drives the actuated joints along the IK's angles to the target's, lets
  it settle and compares the simulated platform pose with the target. Links
  that overlap at the target (link interference, see ``lynxsim/models/rrr/README.md``)
  are reported, and the settling then runs with contacts off, so that the
  kinematic verdict stays separate from the interference verdict.
* :func:`pull_toward` switches the actuators off and pulls the free platform
  towards a pose with a task-space spring: it reaches a reachable pose, and
  stops on the workspace boundary (a leg stretched or folded) short of an
  unreachable one; no inverse kinematics involved.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.rrr import RRR_ROBOT, ik_one, mode_index, singularity_measures
from lynxsim.rrr.geometry import as_pose_array
from lynxsim.rrr.ik import wrap_angle
from lynxsim.rrr.modes import HOME_MODE
from lynxsim.rrr.path import actuated_path, platform_path
from lynxsim.sim.collision import ContactTracker
from lynxsim.sim.report import ContactPair
from lynxsim.sim.rrr.model import (
    HOME_POSE,
    RRRIds,
    assembly_qpos,
    loop_closure_errors,
    platform_pose,
    rrr_binding,
)

__all__ = [
    "APPROACH_OFFSET",
    "ORIENTATION_TOL_RAD",
    "POSITION_TOL_M",
    "PoseCheck",
    "PullCheck",
    "check_pose",
    "interference_at",
    "pull_toward",
    "settled_mode",
]

FloatArray = npt.NDArray[np.float64]

POSITION_TOL_M = 0.5e-3
"""A settled platform within this distance of its target reached it [m]."""
ORIENTATION_TOL_RAD = math.radians(0.1)
"""... and within this angle [rad]."""
APPROACH_OFFSET = (0.004, math.radians(0.5))
"""Start of :func:`check_pose`'s approach: this far from the target, towards the
base centre [m], and turned this much towards alpha = 0 [rad]."""

_PULL_STIFFNESS_N_M = 1000.0
"""Task-space spring of :func:`pull_toward` on the platform centre [N/m]."""
_PULL_DAMPING_N_S_M = 60.0
"""... its damping [N s/m]; rotation uses both times the platform radius squared."""


def settled_mode(data: mujoco.MjData, ids: RRRIds) -> int:
    """Working mode (0..7) of the simulated mechanism, from the sign of each elbow's bend."""
    bend = np.sin(data.qpos[ids.elbow_qpos])
    return int(mode_index(np.where(bend < 0.0, -1, 1)))


@contextlib.contextmanager
def _disabled(model: mujoco.MjModel, flags: int) -> Iterator[None]:
    saved = int(model.opt.disableflags)
    model.opt.disableflags = saved | flags
    try:
        yield
    finally:
        model.opt.disableflags = saved


def interference_at(
    model: mujoco.MjModel, data: mujoco.MjData, qpos: npt.ArrayLike, ids: RRRIds | None = None
) -> tuple[ContactPair, ...]:
    """Link pairs that overlap in a configuration (collision detection only, no step).

    Args:
        model: A 3-RRR model.
        data: Scratch data (its state is overwritten).
        qpos: The configuration, (nq,).
        ids: Resolved ids.

    Returns:
        The overlapping pairs, deepest overlap as ``max_penetration_m`` [m].
    """
    ids = RRRIds.from_model(model) if ids is None else ids
    data.qpos[:] = qpos
    data.time = 0.0
    mujoco.mj_kinematics(model, data)
    mujoco.mj_collision(model, data)
    names = tuple(model.geom(g).name for g in range(model.ngeom))
    tracker = ContactTracker(names, rrr_binding(model, ids).groups)
    n = int(data.ncon)
    tracker.update(0.0, np.array(data.contact.geom[:n], dtype=np.intp), data.contact.dist[:n])
    return tracker.self_collisions()


@dataclass(frozen=True)
class PoseCheck:
    """A commanded pose settled in simulation.

    Attributes:
        pose: The target (x, y, alpha) [m, m, rad].
        mode: The working mode commanded.
        settled_pose: Simulated platform pose after settling [m, m, rad].
        position_error_m: Distance of the settled platform centre from the target [m].
        orientation_error_rad: |settled alpha - target alpha| [rad].
        loop_closure_max_m: Largest leg-tip to platform-joint distance over the run [m].
        loop_closure_final_m: The same after settling [m].
        settled_mode: Working mode of the settled mechanism (elbow signs).
        parallel_measure: Signed parallel-singularity measure of the target in
            ``mode`` [-] (0 at a parallel singularity, see :mod:`lynxsim.rrr.jacobian`).
        interference: Link pairs overlapping at the target (or the approach's
            start); empty when the links are clear.
        contacts: Whether contacts were on while settling (off when ``interference``).
        healthy: No MuJoCo warning and a finite state.
    """

    pose: tuple[float, float, float]
    mode: int
    settled_pose: tuple[float, float, float]
    position_error_m: float
    orientation_error_rad: float
    loop_closure_max_m: float
    loop_closure_final_m: float
    settled_mode: int
    parallel_measure: float
    interference: tuple[ContactPair, ...]
    contacts: bool
    healthy: bool

    @property
    def reached(self) -> bool:
        """Settled within :data:`POSITION_TOL_M` and :data:`ORIENTATION_TOL_RAD`, mode kept."""
        return (
            self.healthy
            and self.settled_mode == self.mode
            and self.position_error_m <= POSITION_TOL_M
            and self.orientation_error_rad <= ORIENTATION_TOL_RAD
        )


def _approach_start(target: FloatArray) -> FloatArray:
    towards = np.asarray(RRR_ROBOT.base_centre) - target[:2]
    dist = float(np.linalg.norm(towards))
    step, turn = APPROACH_OFFSET
    xy = target[:2] + (towards / dist * min(step, dist) if dist > 0.0 else 0.0)
    return np.array([xy[0], xy[1], target[2] - math.copysign(min(turn, abs(target[2])), target[2])])


def _warnings(data: mujoco.MjData) -> int:
    return int(sum(int(w.number) for w in data.warning))


def check_pose(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    pose: npt.ArrayLike,
    mode: int,
    *,
    ids: RRRIds | None = None,
    start: npt.ArrayLike | None = None,
    approach_s: float = 0.2,
    settle_s: float = 0.5,
) -> PoseCheck:
    """Command the IK's actuated angles of a pose and compare where the platform settles.

    The mechanism is assembled at ``start`` (default: :data:`APPROACH_OFFSET`
    from the target), the actuated joints follow the IK along the straight
    task-space line to the target for ``approach_s`` (quintic timing), then
    hold the target's angles for ``settle_s``. Where the approach would cross
    a singularity or leave the workspace, the run starts at the target itself.

    Args:
        model: A 3-RRR model (any assembly; the state is set here).
        data: Its data (overwritten).
        pose: Target (x, y, alpha), (3,) [m, m, rad].
        mode: Working mode 0..7.
        ids: Resolved ids.
        start: Start pose of the approach, (3,) [m, m, rad].
        approach_s: Approach duration [s].
        settle_s: Hold time [s].

    Returns:
        The :class:`PoseCheck`.

    Raises:
        UnreachablePlatformPoseError: The target is out of reach; the message
            names the legs that cannot reach and why.
        InvalidInputError: Bad pose or mode.
    """
    ids = RRRIds.from_model(model) if ids is None else ids
    target = as_pose_array(pose)
    if target.shape != (3,):
        raise InvalidInputError(f"pose must have shape (3,), got {target.shape}")
    theta_target = ik_one(target)[int(mode)]  # raises for an unreachable or non-finite pose
    parallel = float(singularity_measures(target, theta_target).parallel)
    dt = float(model.opt.timestep)
    p0 = _approach_start(target) if start is None else as_pose_array(start)
    n_app = max(1, round(approach_s / dt))
    try:
        path = platform_path(np.stack([p0, target]), approach_s)
        theta = actuated_path(path.sample(np.arange(n_app + 1) * dt).pose, mode).theta
    except LynxsimError:
        p0 = target
        theta = np.repeat(actuated_path(target[None], mode).theta, 2, axis=0)
    q_start = assembly_qpos(model, p0, mode, ids=ids, theta=theta[0])
    q_target = assembly_qpos(model, target, mode, ids=ids)
    interference = interference_at(model, data, q_target, ids) or interference_at(
        model, data, q_start, ids
    )
    flags = int(mujoco.mjtDisableBit.mjDSBL_CONTACT) if interference else 0
    with _disabled(model, flags):
        mujoco.mj_resetData(model, data)
        data.qpos[:] = q_start
        data.ctrl[ids.actuators] = theta[0]
        mujoco.mj_forward(model, data)
        loop_max = 0.0
        finite = True
        for k in range(len(theta) - 1 + round(settle_s / dt)):
            data.ctrl[ids.actuators] = theta[min(k + 1, len(theta) - 1)]
            mujoco.mj_step(model, data)
            if not np.isfinite(data.qpos).all():
                finite = False
                break
            loop_max = max(loop_max, float(loop_closure_errors(data, ids).max()))
        mujoco.mj_kinematics(model, data)
    final = platform_pose(data, ids)
    return PoseCheck(
        pose=(float(target[0]), float(target[1]), float(target[2])),
        mode=int(mode),
        settled_pose=(float(final[0]), float(final[1]), float(final[2])),
        position_error_m=float(np.hypot(*(final[:2] - target[:2]))),
        orientation_error_rad=float(abs(wrap_angle(final[2] - target[2]))),
        loop_closure_max_m=loop_max,
        loop_closure_final_m=float(loop_closure_errors(data, ids).max()),
        settled_mode=settled_mode(data, ids),
        parallel_measure=parallel,
        interference=interference,
        contacts=not interference,
        healthy=finite and _warnings(data) == 0,
    )


@dataclass(frozen=True)
class PullCheck:
    """Where the free mechanism ends when its platform is pulled towards a pose.

    Attributes:
        target: The pose pulled towards (x, y, alpha) [m, m, rad].
        final_pose: Where the platform came to rest [m, m, rad].
        position_gap_m: Distance of the final platform centre from the target [m].
        orientation_gap_rad: |final alpha - target alpha| [rad].
        leg_span_m: Final ``|P_i - B_i|`` of each leg [m]; ``s_a + L`` means stretched.
        loop_closure_max_m: Largest leg-tip to platform-joint distance over the pull [m].
        speed_final: Platform-centre speed at the end [m/s] (small: at rest).
    """

    target: tuple[float, float, float]
    final_pose: tuple[float, float, float]
    position_gap_m: float
    orientation_gap_rad: float
    leg_span_m: tuple[float, float, float]
    loop_closure_max_m: float
    speed_final: float

    @property
    def reached(self) -> bool:
        """The platform got within :data:`POSITION_TOL_M` and :data:`ORIENTATION_TOL_RAD`."""
        return (
            self.position_gap_m <= POSITION_TOL_M
            and self.orientation_gap_rad <= ORIENTATION_TOL_RAD
        )


def pull_toward(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    target: npt.ArrayLike,
    *,
    ids: RRRIds | None = None,
    start: npt.ArrayLike = HOME_POSE,
    start_mode: int = HOME_MODE,
    duration_s: float = 2.0,
) -> PullCheck:
    """Pull the platform of the unactuated mechanism towards a pose and see where it stops.

    Actuators and contacts are off (only the loops constrain the motion); a
    damped spring in ``(x, y, alpha)`` acts on the platform. A reachable target
    is reached; an unreachable one leaves the platform on the workspace boundary.

    Args:
        model: A 3-RRR model.
        data: Its data (overwritten).
        target: Pose to pull towards, (3,) [m, m, rad].
        ids: Resolved ids.
        start: Assembly pose to start from [m, m, rad].
        start_mode: Its working mode.
        duration_s: Simulated time [s].

    Returns:
        The :class:`PullCheck`.
    """
    ids = RRRIds.from_model(model) if ids is None else ids
    goal = as_pose_array(target)
    r2 = RRR_ROBOT.platform_radius**2
    k_lin, d_lin = _PULL_STIFFNESS_N_M, _PULL_DAMPING_N_S_M
    k_rot, d_rot = k_lin * r2, d_lin * r2
    flags = int(mujoco.mjtDisableBit.mjDSBL_ACTUATION) | int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    with _disabled(model, flags):
        mujoco.mj_resetData(model, data)
        data.qpos[:] = assembly_qpos(model, as_pose_array(start), start_mode, ids=ids)
        mujoco.mj_forward(model, data)
        base = np.array(data.xpos[ids.proximal_bodies])
        loop_max = 0.0
        dof = ids.platform_dof
        for _ in range(round(duration_s / float(model.opt.timestep))):
            pose = platform_pose(data, ids)
            v = data.qvel[dof : dof + 3]
            w = data.qvel[dof + 5]
            force = k_lin * (goal[:2] - pose[:2]) - d_lin * v[:2]
            torque = k_rot * wrap_angle(goal[2] - pose[2]) - d_rot * w
            data.xfrc_applied[ids.platform_body] = [force[0], force[1], 0.0, 0.0, 0.0, torque]
            mujoco.mj_step(model, data)
            loop_max = max(loop_max, float(loop_closure_errors(data, ids).max()))
        data.xfrc_applied[ids.platform_body] = 0.0
        mujoco.mj_kinematics(model, data)
    final = platform_pose(data, ids)
    spans = np.linalg.norm(data.site_xpos[ids.joint_sites][:, :2] - base[:, :2], axis=1)
    return PullCheck(
        target=(float(goal[0]), float(goal[1]), float(goal[2])),
        final_pose=(float(final[0]), float(final[1]), float(final[2])),
        position_gap_m=float(np.hypot(*(final[:2] - goal[:2]))),
        orientation_gap_rad=float(abs(wrap_angle(final[2] - goal[2]))),
        leg_span_m=(float(spans[0]), float(spans[1]), float(spans[2])),
        loop_closure_max_m=loop_max,
        speed_final=float(np.linalg.norm(data.qvel[ids.platform_dof : ids.platform_dof + 2])),
    )
