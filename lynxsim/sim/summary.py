"""A run's log in, its :class:`~lynxsim.sim.report.RunReport` out: the same function for any run.

Pure NumPy over a :class:`~lynxsim.sim.stepping.log.PlaybackLog` (no MuJoCo state),
so a single playback, a batch of them or a saved log are summarised alike.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from lynxsim.sim.collision import ContactTracker
from lynxsim.sim.report import ObstacleClearance, RobotMetrics, RunReport
from lynxsim.sim.stepping.log import PlaybackLog

__all__ = ["Playback", "summarize"]


class Playback(NamedTuple):
    """A run's report and the log it was computed from."""

    report: RunReport
    log: PlaybackLog


def summarize(log: PlaybackLog, metrics: RobotMetrics | None = None) -> RunReport:
    """Tracking, collisions, clearance and health of a run.

    Args:
        log: The run's log.
        metrics: The robot's own figures (from its adapter), kept as they are.

    Returns:
        The :class:`RunReport`.
    """
    meta = log.meta
    tracker = ContactTracker(meta.geom_names, meta.groups)
    steps = log.contact_step
    tracker.update_many(log.time_s[steps], steps, log.contact_geoms, log.contact_dist)

    n_traj = log.trajectory_steps
    joint_err = np.abs(log.q[:n_traj] - log.q_cmd[:n_traj])
    tool_err = np.linalg.norm(log.tool[:n_traj] - log.tool_ref[:n_traj], axis=1)
    final_err = float(np.linalg.norm(log.tool[-1] - log.tool_target)) if log.steps else np.inf
    names = meta.groups.obstacle_names
    obstacles: list[ObstacleClearance] = []
    if names and log.steps:
        i_min, lowest = log.clearance.first_step, log.clearance.minimum
        for j, name in enumerate(names):
            first = tracker.first_contact_s(j)
            obstacles.append(
                ObstacleClearance(
                    name=name,
                    collided=first is not None,
                    first_contact_s=first,
                    min_clearance_m=float(lowest[j]),
                    min_clearance_time_s=float(log.time_s[i_min[j]]),
                )
            )
    closest = min(obstacles, key=lambda o: o.min_clearance_m, default=None)
    return RunReport(
        task=meta.task,
        trajectory=meta.trajectory,
        duration_s=log.duration_s,
        settle_s=log.settle_s,
        physics_dt_s=meta.physics_dt_s,
        joint_max_error_rad=tuple(float(v) for v in joint_err.max(axis=0, initial=0.0)),
        joint_rms_error_rad=tuple(
            float(v) for v in np.sqrt(np.mean(joint_err**2, axis=0)) if n_traj
        ),
        tool_max_error_m=float(tool_err.max(initial=0.0)),
        tool_rms_error_m=float(np.sqrt(np.mean(tool_err**2))) if n_traj else 0.0,
        tool_final_error_m=final_err,
        max_torque_ratio=tuple(
            float(v) for v in (np.abs(log.force).max(axis=0, initial=0.0) / meta.force_limit)
        ),
        obstacle=tracker.verdict() if names else None,
        obstacles=tuple(obstacles),
        min_clearance_m=None if closest is None else closest.min_clearance_m,
        min_clearance_time_s=None if closest is None else closest.min_clearance_time_s,
        self_collisions=tracker.self_collisions(),
        floor_contacts=tracker.support_contacts(),
        healthy=log.diverged_at_s is None and not log.warnings,
        warnings=dict(log.warnings),
        diverged_at_s=log.diverged_at_s,
        metrics=metrics,
    )
