"""Playing a 3-RRR platform path through the actuated joints, watching the closed loops.

The path is sampled at the end of every physics step, solved by the inverse
kinematics in one working mode (:func:`lynxsim.rrr.path.actuated_path`) and
stepped by :func:`lynxsim.sim.stepping.rollout.rollout` and summarised by
:func:`lynxsim.sim.summary.summarize`, as every run: the run report's tool
point is the platform-centre needle, its self-collisions are the link
interference, and its ``metrics`` are the 3-RRR figures (:class:`RRRMetrics`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.angles import quat_yaw
from lynxsim.errors import InvalidInputError
from lynxsim.rrr.path import ActuatedPath, PlatformPath, actuated_path
from lynxsim.sim.report import RobotMetrics
from lynxsim.sim.rrr.model import (
    RRRIds,
    assembly_qpos,
    load_rrr_scene,
    rrr_binding,
)
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.log import PlaybackLog, StepHook
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.sim.summary import Playback, summarize

__all__ = [
    "CLEARANCE_CAP_M",
    "CLEARANCE_STRIDE",
    "LoopMonitor",
    "RRRMetrics",
    "link_pairs",
    "play_rrr",
    "start_model",
]

FloatArray = npt.NDArray[np.float64]

CLEARANCE_CAP_M = 0.1
"""Link clearances are measured up to this distance [m] (larger reads as the cap)."""
CLEARANCE_STRIDE = 5
"""Physics steps between two link-clearance measurements (10 ms at 2 ms steps)."""


@dataclass(frozen=True)
class RRRMetrics(RobotMetrics):
    """What a 3-RRR run report adds (SI units).

    Attributes:
        working_mode: The mode (0..7) the IK used.
        loop_closure_max_m: Largest distance between a leg tip and its platform
            joint over the whole run [m].
        loop_closure_final_m: The same at the end of the run [m].
        platform_position_max_error_m: Simulated platform centre against the
            commanded one, max over the trajectory [m].
        platform_position_rms_error_m: RMS of the same [m].
        platform_position_final_error_m: The same after settling [m].
        platform_orientation_max_error_rad: Simulated platform orientation
            against the commanded one, max over the trajectory [rad].
        platform_orientation_rms_error_rad: RMS of the same [rad].
        platform_orientation_final_error_rad: The same after settling [rad].
        link_min_clearance_m: Smallest distance between links that may touch
            (sampled every :data:`CLEARANCE_STRIDE` steps, capped at
            :data:`CLEARANCE_CAP_M`; negative: overlap, also listed as self-collisions) [m].
        path_min_abs_parallel: Distance of the commanded path from parallel singularities [-].
        path_min_serial: Distance of the commanded path from leg singularities [-].
        base_speed_max_rad_s: Fastest commanded actuated joint [rad/s].
    """

    working_mode: int
    loop_closure_max_m: float
    loop_closure_final_m: float
    platform_position_max_error_m: float
    platform_position_rms_error_m: float
    platform_position_final_error_m: float
    platform_orientation_max_error_rad: float
    platform_orientation_rms_error_rad: float
    platform_orientation_final_error_rad: float
    link_min_clearance_m: float
    path_min_abs_parallel: float
    path_min_serial: float
    base_speed_max_rad_s: float

    def lines(self) -> list[str]:
        """The figures as readable lines (mm, degrees)."""
        deg = math.degrees
        return [
            f"working mode: {self.working_mode}",
            f"loop closure: max {self.loop_closure_max_m * 1e3:.4g} mm, "
            f"final {self.loop_closure_final_m * 1e3:.4g} mm",
            f"platform position error: max {self.platform_position_max_error_m * 1e3:.4g} mm, "
            f"RMS {self.platform_position_rms_error_m * 1e3:.4g} mm, "
            f"final {self.platform_position_final_error_m * 1e3:.4g} mm",
            "platform orientation error: "
            f"max {deg(self.platform_orientation_max_error_rad):.4g} deg, "
            f"RMS {deg(self.platform_orientation_rms_error_rad):.4g} deg, "
            f"final {deg(self.platform_orientation_final_error_rad):.4g} deg",
            f"link clearance: min {self.link_min_clearance_m * 1e3:.4g} mm",
            f"path singularity distance: parallel {self.path_min_abs_parallel:.4g}, "
            f"serial {self.path_min_serial:.4g}",
            f"base speed: max {deg(self.base_speed_max_rad_s):.4g} deg/s",
        ]


def link_pairs(model: mujoco.MjModel, ids: RRRIds) -> list[tuple[int, int]]:
    """Pairs of link capsules that the model lets collide.

    Leaves out pairs on one body, parent and child bodies (MuJoCo's filter)
    and the body pairs of ``<contact><exclude>``.
    """
    parent = np.asarray(model.body_parentid)
    excluded = {(int(s) >> 16, int(s) & 0xFFFF) for s in np.asarray(model.exclude_signature)}
    out = []
    geoms = [int(g) for g in ids.link_geoms]
    for i, g1 in enumerate(geoms):
        for g2 in geoms[i + 1 :]:
            b1, b2 = sorted((int(model.geom_bodyid[g1]), int(model.geom_bodyid[g2])))
            if b1 == b2 or parent[b2] == b1 or parent[b1] == b2 or (b1, b2) in excluded:
                continue
            compatible = (model.geom_contype[g1] & model.geom_conaffinity[g2]) or (
                model.geom_contype[g2] & model.geom_conaffinity[g1]
            )
            if compatible:
                out.append((g1, g2))
    return out


class LoopMonitor:
    """Per-step bookkeeping of a 3-RRR run: loop closure, pose error, link clearance.

    A step hook of :func:`~lynxsim.sim.stepping.rollout.rollout`, called after every
    recorded physics step.

    Args:
        model: The model.
        ids: Its resolved ids.
        pose_ref: Commanded platform pose at the end of each step, (T, 3)
            [m, m, rad]; held at the last one while settling.
    """

    def __init__(self, model: mujoco.MjModel, ids: RRRIds, pose_ref: FloatArray) -> None:
        self._model = model
        self._ids = ids
        self._ref = pose_ref
        self._pairs = link_pairs(model, ids)
        self._loop_sites = list(zip(ids.tip_sites.tolist(), ids.joint_sites.tolist(), strict=True))
        self._fromto = np.zeros(6)
        self.loop: list[float] = []
        self.position_error: list[float] = []
        self.orientation_error: list[float] = []
        self.clearance: list[float] = []

    def __call__(self, step: int, data: mujoco.MjData) -> None:
        """Record this step."""
        # Plain floats: this runs every physics step, numpy calls on scalars would dominate.
        x_ref, y_ref, a_ref = self._ref[min(step, len(self._ref) - 1)].tolist()
        a = self._ids.platform_qpos
        x, y, _, w, qx, qy, qz = data.qpos[a : a + 7].tolist()
        alpha = quat_yaw(w, qx, qy, qz)
        sites = data.site_xpos.tolist()
        turn = (alpha - a_ref + math.pi) % (2.0 * math.pi) - math.pi
        self.loop.append(max(math.dist(sites[t], sites[j]) for t, j in self._loop_sites))
        self.position_error.append(math.hypot(x - x_ref, y - y_ref))
        self.orientation_error.append(abs(turn))
        clearance = math.nan
        if self._pairs and step % CLEARANCE_STRIDE == 0:
            clearance = min(
                mujoco.mj_geomDistance(self._model, data, g1, g2, CLEARANCE_CAP_M, self._fromto)
                for g1, g2 in self._pairs
            )
        self.clearance.append(clearance)

    def channels(self) -> dict[str, FloatArray]:
        """The per-step records for the run's log: each (S,) (clearance NaN between samples)."""
        return {
            "loop_closure_m": np.asarray(self.loop),
            "platform_position_error_m": np.asarray(self.position_error),
            "platform_orientation_error_rad": np.asarray(self.orientation_error),
            "link_clearance_m": np.asarray(self.clearance),
        }


def _rrr_metrics(log: PlaybackLog, mode: int, act: ActuatedPath, dt: float) -> RRRMetrics:
    """The 3-RRR figures of a run from its log's channels and the commanded path."""
    ch = log.channels
    loop = ch["loop_closure_m"]
    pos = ch["platform_position_error_m"]
    ori = ch["platform_orientation_error_rad"]
    clearance = ch["link_clearance_m"]
    n = min(log.trajectory_steps, len(loop))
    traj_pos, traj_ori = pos[:n], ori[:n]
    sampled = clearance[np.isfinite(clearance)]
    return RRRMetrics(
        working_mode=mode,
        loop_closure_max_m=float(loop.max(initial=0.0)),
        loop_closure_final_m=float(loop[-1]) if len(loop) else math.nan,
        platform_position_max_error_m=float(traj_pos.max(initial=0.0)),
        platform_position_rms_error_m=float(np.sqrt(np.mean(traj_pos**2))) if n else 0.0,
        platform_position_final_error_m=float(pos[-1]) if len(pos) else math.nan,
        platform_orientation_max_error_rad=float(traj_ori.max(initial=0.0)),
        platform_orientation_rms_error_rad=float(np.sqrt(np.mean(traj_ori**2))) if n else 0.0,
        platform_orientation_final_error_rad=float(ori[-1]) if len(ori) else math.nan,
        link_min_clearance_m=float(sampled.min(initial=CLEARANCE_CAP_M)),
        path_min_abs_parallel=act.min_abs_parallel,
        path_min_serial=act.min_serial,
        base_speed_max_rad_s=float(np.abs(np.diff(act.theta, axis=0)).max(initial=0.0) / dt),
    )


def start_model(path: PlatformPath, mode: int) -> tuple[mujoco.MjModel, FloatArray]:
    """The scene written at a path's first pose, and the path's actuated angles.

    Args:
        path: The timed platform path.
        mode: Working mode 0..7.

    Returns:
        The compiled scene whose ``qpos0`` is the start assembly, and the
        actuated angles on the physics grid including ``t = 0``, (T + 1, 3) [rad].
    """
    dt = float(load_rrr_scene().opt.timestep)
    times = np.concatenate([[0.0], physics_grid(path.duration, dt)])
    theta = actuated_path(path.sample(times).pose, mode, times=times, geometry=path.geometry).theta
    return load_rrr_scene(path.waypoints[0], mode, theta=theta[0]), theta


def play_rrr(
    path: PlatformPath,
    mode: int,
    *,
    task: str,
    model: mujoco.MjModel | None = None,
    data: mujoco.MjData | None = None,
    settle_s: float = 0.5,
    presettle_s: float = 0.2,
    on_step: StepHook | None = None,
) -> Playback:
    """Play a platform path through the actuated joints, IK in one working mode every step.

    The playback resets the mechanism to the model's ``qpos0``, so the model
    must be written at the path's first pose in ``mode``
    (:func:`lynxsim.sim.rrr.model.load_rrr_scene` with that pose, or
    :func:`start_model`); by default it is built here.

    Args:
        path: The timed platform path.
        mode: Working mode 0..7 of the inverse kinematics.
        task: Task name for the report.
        model: The scene assembled at the path's start (built if None).
        data: Data to use (a new one if None).
        settle_s: Hold time after the path [s].
        presettle_s: Unrecorded hold at the start [s].
        on_step: Called after every physics step (rendering, progress).

    Returns:
        The :class:`~lynxsim.sim.summary.Playback`; its report's ``metrics`` are
        :class:`RRRMetrics`, its log's ``channels`` the per-step loop closure,
        platform errors and link clearance.

    Raises:
        UnreachablePlatformPoseError: The path leaves the workspace.
        PlatformPathError: It crosses a parallel singularity of ``mode`` or
            needs an actuated angle out of range.
        InvalidInputError: ``model`` is not assembled at the path's start in ``mode``.
    """
    if model is None:
        model, _ = start_model(path, mode)
    ids = RRRIds.from_model(model)
    data = mujoco.MjData(model) if data is None else data
    dt = float(model.opt.timestep)
    times = np.concatenate([[0.0], physics_grid(path.duration, dt)])
    sample = path.sample(times)
    act = actuated_path(sample.pose, mode, times=times, geometry=path.geometry)
    theta = act.theta
    start = assembly_qpos(model, sample.pose[0], mode, ids=ids, theta=theta[0])
    if not np.allclose(start, model.qpos0, atol=1e-9):
        raise InvalidInputError(
            f"the model is not assembled at the path's first pose in working mode {mode}; "
            "build it with load_rrr_scene(pose, mode) or start_model(path, mode)"
        )
    data.qpos[:] = start
    mujoco.mj_kinematics(model, data)
    centre_z = float(data.site_xpos[ids.centre_site][2])
    pose_ref = sample.pose[1:]
    tool_ref = np.column_stack([pose_ref[:, :2], np.full(len(pose_ref), centre_z)])
    watcher = LoopMonitor(model, ids, pose_ref)

    def hooks(step: int, d: mujoco.MjData) -> None:
        watcher(step, d)
        if on_step is not None:
            on_step(step, d)

    log = rollout(
        model,
        data,
        rrr_binding(model, ids),
        theta[1:],
        tool_ref,
        task=task,
        trajectory=path.label,
        settle_s=settle_s,
        presettle_s=presettle_s,
        on_step=hooks,
    )
    log = dataclasses.replace(log, channels=watcher.channels())
    return Playback(report=summarize(log, _rrr_metrics(log, mode, act, dt)), log=log)
