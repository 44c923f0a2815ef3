"""The joint-space generators of :mod:`lynxsim.traj` for the arm: poses in, its joints held.

Each takes the arm's waypoints (poses solved by its IK, or joint vectors,
:mod:`lynxsim.arm.motion.waypoints`) and calls the generic generator with the
arm's joint ranges (:func:`~lynxsim.arm.motion.space.joint_bounds`) and, unless
given others, its servo limits (:data:`~lynxsim.arm.motion.space.ARM_LIMITS`)::

    traj = quintic(poses, durations=1.0)

Their arguments: ``waypoints`` (poses or joints, shape (N, 5) [rad]),
``durations`` (segment durations [s], see :mod:`lynxsim.traj.timing`),
``limits``, ``stretch`` (lengthen given durations too short for the limits) and
``geometry`` (the arm description: its joint ranges and names); each returns
the checked :class:`~lynxsim.traj.Trajectory` and raises what its generic
generator raises, and UnreachablePoseError for a pose the IK cannot solve.
"""

from __future__ import annotations

from typing import Protocol

from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.motion.space import ARM_LIMITS, joint_bounds
from lynxsim.arm.motion.waypoints import ArmWaypointsLike, resolve_waypoints
from lynxsim.traj import lspb as joint_lspb
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.polynomial import cubic as joint_cubic
from lynxsim.traj.polynomial import free_motion as joint_free_motion
from lynxsim.traj.polynomial import quintic as joint_quintic
from lynxsim.traj.ruckig_profile import ruckig_trajectory as joint_ruckig
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory
from lynxsim.traj.waypoints import Waypoints, WaypointsLike

__all__ = [
    "ArmGenerator",
    "arm_joints",
    "cubic",
    "free_motion",
    "lspb",
    "quintic",
    "ruckig_trajectory",
]


def arm_joints(
    waypoints: ArmWaypointsLike, geometry: ArmGeometry = LYNX_ARM
) -> tuple[Waypoints, JointBounds]:
    """The arm's waypoints as joints (IK solved, ranges checked), and its joint bounds."""
    bounds = joint_bounds(geometry)
    return resolve_waypoints(waypoints, geometry).joints, bounds


class _JointGenerator(Protocol):
    __name__: str

    def __call__(
        self,
        waypoints: WaypointsLike,
        durations: Durations = None,
        *,
        bounds: JointBounds,
        limits: JointLimits,
        stretch: bool = False,
    ) -> Trajectory: ...


class ArmGenerator(Protocol):
    """A generator of the arm's trajectories (see the module docs for its arguments)."""

    __name__: str

    def __call__(
        self,
        waypoints: ArmWaypointsLike,
        durations: Durations = None,
        *,
        limits: JointLimits = ARM_LIMITS,
        stretch: bool = False,
        geometry: ArmGeometry = LYNX_ARM,
    ) -> Trajectory:
        """The trajectory through ``waypoints``."""
        ...


def _for_the_arm(generate: _JointGenerator) -> ArmGenerator:
    """``generate`` with the arm's waypoints, joint ranges and default limits."""

    def generator(
        waypoints: ArmWaypointsLike,
        durations: Durations = None,
        *,
        limits: JointLimits = ARM_LIMITS,
        stretch: bool = False,
        geometry: ArmGeometry = LYNX_ARM,
    ) -> Trajectory:
        joints, bounds = arm_joints(waypoints, geometry)
        return generate(joints, durations, bounds=bounds, limits=limits, stretch=stretch)

    generator.__name__ = generator.__qualname__ = generate.__name__
    generator.__doc__ = (
        f"The arm's :func:`lynxsim.traj.{generate.__name__}` (arguments: the module docs)."
    )
    return generator


free_motion = _for_the_arm(joint_free_motion)
cubic = _for_the_arm(joint_cubic)
quintic = _for_the_arm(joint_quintic)
lspb = _for_the_arm(joint_lspb)


def ruckig_trajectory(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    pass_through: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's :func:`lynxsim.traj.ruckig_trajectory` (arguments: the module docs).

    ``pass_through`` passes intermediate waypoints without stopping.
    """
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_ruckig(
        joints,
        durations,
        bounds=bounds,
        limits=limits,
        stretch=stretch,
        pass_through=pass_through,
    )
