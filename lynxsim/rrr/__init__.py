"""Kinematics of the planar 3-RRR parallel robot: pure numpy, SI units, no MuJoCo.

Poses are ``(x, y, alpha)`` arrays of shape (..., 3) [m, m, rad]; actuated
angles ``theta`` have shape (..., 3) [rad]; working modes are numbered 0..7
(:mod:`lynxsim.rrr.modes`).
"""

from lynxsim.rrr.fk import (
    CLOSURE_TOL,
    MAX_ASSEMBLY_MODES,
    FKResult,
    FKSolutions,
    elbow_points,
    fk_all,
    fk_near,
    fk_path,
    loop_residual,
)
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, platform_joints, rotation
from lynxsim.rrr.ik import LegStatus, PoseStatus, RRRIKResult, ik, ik_one, leg_points
from lynxsim.rrr.jacobian import (
    PlatformJacobians,
    SingularityMeasures,
    constraint_jacobians,
    forward_jacobian,
    inverse_jacobian,
    singularity_measures,
)
from lynxsim.rrr.modes import MODE_SIGNS, N_MODES, mode_index, mode_label, mode_signs
from lynxsim.rrr.orientation import (
    OrientationRange,
    orientation_intervals,
    orientation_range,
    orientation_range_in_mode,
)
from lynxsim.rrr.workspace import (
    LegAnnuli,
    WorkspaceMap,
    grid_extent,
    leg_annuli,
    parallel_singularity_loci,
    workspace_map,
)

__all__ = [
    "CLOSURE_TOL",
    "MAX_ASSEMBLY_MODES",
    "MODE_SIGNS",
    "N_MODES",
    "RRR_ROBOT",
    "FKResult",
    "FKSolutions",
    "LegAnnuli",
    "LegStatus",
    "OrientationRange",
    "PlatformJacobians",
    "PoseStatus",
    "RRRGeometry",
    "RRRIKResult",
    "SingularityMeasures",
    "WorkspaceMap",
    "constraint_jacobians",
    "elbow_points",
    "fk_all",
    "fk_near",
    "fk_path",
    "forward_jacobian",
    "grid_extent",
    "ik",
    "ik_one",
    "inverse_jacobian",
    "leg_annuli",
    "leg_points",
    "loop_residual",
    "mode_index",
    "mode_label",
    "mode_signs",
    "orientation_intervals",
    "orientation_range",
    "orientation_range_in_mode",
    "parallel_singularity_loci",
    "platform_joints",
    "rotation",
    "singularity_measures",
    "workspace_map",
]
