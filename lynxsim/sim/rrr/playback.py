"""Playing a 3-RRR platform path through the actuated joints, watching the closed loops.

The path is sampled at the end of every physics step, solved by the inverse
kinematics in one working mode (:func:`lynxsim.rrr.path.actuated_path`) and
played with :func:`lynxsim.sim.playback.play`, the arm's playback: the run
report's tool point is the platform-centre needle, its self-collisions are
the link interference, and :attr:`RunReport.extra` carries the 3-RRR figures
of :data:`RRR_EXTRA_KEYS` (SI units, names with units).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.rrr.path import PlatformPath, actuated_path
from lynxsim.sim.arm.playback import physics_grid
from lynxsim.sim.playback import Playback, StepHook, play
from lynxsim.sim.rrr.model import (
    RRRIds,
    assembly_qpos,
    load_rrr_scene,
    rrr_binding,
)

__all__ = [
    "CLEARANCE_CAP_M",
    "CLEARANCE_STRIDE",
    "RRR_EXTRA_KEYS",
    "LoopMonitor",
    "link_pairs",
    "play_rrr",
    "start_model",
]

FloatArray = npt.NDArray[np.float64]

CLEARANCE_CAP_M = 0.1
"""Link clearances are measured up to this distance [m] (larger reads as the cap)."""
CLEARANCE_STRIDE = 5
"""Physics steps between two link-clearance measurements (10 ms at 2 ms steps)."""

RRR_EXTRA_KEYS = (
    "working_mode",
    "loop_closure_max_m",
    "loop_closure_final_m",
    "platform_position_max_error_m",
    "platform_position_rms_error_m",
    "platform_position_final_error_m",
    "platform_orientation_max_error_rad",
    "platform_orientation_rms_error_rad",
    "platform_orientation_final_error_rad",
    "link_min_clearance_m",
    "path_min_abs_parallel",
    "path_min_serial",
    "base_speed_max_rad_s",
)
"""What a 3-RRR run report adds in ``extra``:

* ``working_mode``: the mode (0..7) the IK used;
* ``loop_closure_*``: largest distance between a leg tip and its platform joint,
  over the whole run and at its end [m];
* ``platform_position_*_error_m`` / ``platform_orientation_*_error_rad``: simulated
  platform pose against the commanded one, max and RMS over the trajectory and
  after settling [m], [rad];
* ``link_min_clearance_m``: smallest distance between links that may touch
  (sampled every :data:`CLEARANCE_STRIDE` steps, capped at :data:`CLEARANCE_CAP_M`;
  negative: overlap, also listed as self-collisions);
* ``path_min_abs_parallel`` / ``path_min_serial``: distance of the commanded path
  from parallel and leg singularities [-];
* ``base_speed_max_rad_s``: fastest commanded actuated joint [rad/s].
"""


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

    Called by :func:`~lynxsim.sim.playback.play` as its ``extra_metrics`` after
    every recorded physics step; the step index is the number of calls so far.

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

    def __call__(self, data: mujoco.MjData) -> dict[str, float]:
        """Record this step; returns the per-step maxima for the run report."""
        # Plain floats: this runs every physics step, numpy calls on scalars would dominate.
        step = len(self.loop)
        x_ref, y_ref, a_ref = self._ref[min(step, len(self._ref) - 1)].tolist()
        a = self._ids.platform_qpos
        x, y, _, w, qx, qy, qz = data.qpos[a : a + 7].tolist()
        alpha = math.atan2(2.0 * (w * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
        sites = data.site_xpos.tolist()
        loop = max(math.dist(sites[t], sites[j]) for t, j in self._loop_sites)
        turn = (alpha - a_ref + math.pi) % (2.0 * math.pi) - math.pi
        self.loop.append(loop)
        self.position_error.append(math.hypot(x - x_ref, y - y_ref))
        self.orientation_error.append(abs(turn))
        if self._pairs and step % CLEARANCE_STRIDE == 0:
            self.clearance.append(
                min(
                    mujoco.mj_geomDistance(self._model, data, g1, g2, CLEARANCE_CAP_M, self._fromto)
                    for g1, g2 in self._pairs
                )
            )
        return {"loop_closure_max_m": loop}

    def summary(self, trajectory_steps: int) -> dict[str, float]:
        """The monitored part of :data:`RRR_EXTRA_KEYS` for a run of ``trajectory_steps``."""
        loop = np.asarray(self.loop)
        pos = np.asarray(self.position_error)
        ori = np.asarray(self.orientation_error)
        n = min(trajectory_steps, len(loop))
        traj_pos, traj_ori = pos[:n], ori[:n]
        return {
            "loop_closure_max_m": float(loop.max(initial=0.0)),
            "loop_closure_final_m": float(loop[-1]) if len(loop) else np.nan,
            "platform_position_max_error_m": float(traj_pos.max(initial=0.0)),
            "platform_position_rms_error_m": float(np.sqrt(np.mean(traj_pos**2))) if n else 0.0,
            "platform_position_final_error_m": float(pos[-1]) if len(pos) else np.nan,
            "platform_orientation_max_error_rad": float(traj_ori.max(initial=0.0)),
            "platform_orientation_rms_error_rad": float(np.sqrt(np.mean(traj_ori**2)))
            if n
            else 0.0,
            "platform_orientation_final_error_rad": float(ori[-1]) if len(ori) else np.nan,
            "link_min_clearance_m": float(min(self.clearance, default=CLEARANCE_CAP_M)),
        }


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
    monitor: Callable[[LoopMonitor], None] | None = None,
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
        monitor: Receives the :class:`LoopMonitor` after the run (per-step logs).

    Returns:
        The :class:`~lynxsim.sim.playback.Playback`; its report's ``extra`` holds
        :data:`RRR_EXTRA_KEYS`.

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
    playback = play(
        model,
        data,
        rrr_binding(model, ids),
        theta[1:],
        tool_ref,
        task=task,
        trajectory=path.label,
        settle_s=settle_s,
        presettle_s=presettle_s,
        on_step=on_step,
        extra_metrics=watcher,
    )
    extra = dict(playback.report.extra)
    extra.update(watcher.summary(playback.log.trajectory_steps))
    extra.update(
        {
            "working_mode": float(mode),
            "path_min_abs_parallel": act.min_abs_parallel,
            "path_min_serial": act.min_serial,
            "base_speed_max_rad_s": float(np.abs(np.diff(theta, axis=0)).max(initial=0.0) / dt),
        }
    )
    if monitor is not None:
        monitor(watcher)
    report = dataclasses.replace(playback.report, extra={k: extra[k] for k in RRR_EXTRA_KEYS})
    return Playback(report=report, log=playback.log)
