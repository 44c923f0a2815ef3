"""A recorded run as a replay: MuJoCo model + :class:`~lynxsim.sim.stepping.log.PlaybackLog` in.

:func:`export_replay` poses every recorded state (``mj_kinematics`` of the
log's ``qpos``: a closed loop or a free body needs nothing else), keeps the
moving bodies' poses at the replay's frames as 16-bit integers
(:mod:`lynxsim.web.poses`), and measures, over every recorded physics step,
how far any point of a drawn geom then lies from the simulation's pose when
the page interpolates between frames: the error stated on the page
(:attr:`~lynxsim.web.replay_data.ReplayData.pose_error_m`). Contacts become
spans of time during which the touching geoms are painted; clearances keep,
per frame, the minimum of the steps it stands for.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_FPS, MIN_FPS
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import number_in_range
from lynxsim.sim.collision import classify_contacts
from lynxsim.sim.recording import frame_steps
from lynxsim.sim.replay.scene import SceneParts, scene_parts
from lynxsim.sim.report import RunReport
from lynxsim.sim.stepping.log import PlaybackLog
from lynxsim.sim.summary import Playback
from lynxsim.web.poses import point_error_bound, quantise_positions, quantise_quaternions
from lynxsim.web.replay_data import (
    Clearances,
    ContactSpans,
    QuantisedPoses,
    ReplayCamera,
    ReplayData,
)
from lynxsim.web.replay_file import write_replay_file
from lynxsim.web.verdicts import canonical_json

__all__ = ["FREE_CAMERA", "REPLAY_FPS", "export_replay", "free_camera", "save_replay"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

REPLAY_FPS = 100.0
"""Frames per simulated second a replay keeps (a 6 s run: 651 frames, about 0.2 mm off;
see :attr:`~lynxsim.web.replay_data.ReplayData.pose_error_m`)."""
FREE_CAMERA = "free"
"""Name of the camera every replay adds: MuJoCo's default free camera of the model."""


def free_camera(model: mujoco.MjModel) -> ReplayCamera:
    """MuJoCo's default free camera: at ``1.5 extent`` from ``stat.center``, the model's angles."""
    az, el = np.radians([model.vis.global_.azimuth, model.vis.global_.elevation])
    forward = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    return ReplayCamera(
        name=FREE_CAMERA,
        pos=np.asarray(model.stat.center) - 1.5 * float(model.stat.extent) * forward,
        xmat=np.column_stack([right, up, -forward]),
        fovy=float(model.vis.global_.fovy),
        orthographic=False,
    )


def _true_poses(
    model: mujoco.MjModel, qpos: FloatArray, bodies: IntArray
) -> tuple[FloatArray, FloatArray]:
    """World poses of ``bodies`` in each state: positions (S, B, 3) [m], quaternions (S, B, 4)."""
    data = mujoco.MjData(model)
    pos = np.empty((len(qpos), len(bodies), 3))
    quat = np.empty((len(qpos), len(bodies), 4))
    for k in range(len(qpos)):
        data.qpos[:] = qpos[k]
        mujoco.mj_kinematics(model, data)
        pos[k] = data.xpos[bodies]
        quat[k] = data.xquat[bodies]
    return pos, quat


def _frames(time_s: FloatArray, fps: float) -> IntArray:
    """Recorded steps shown as frames: one per ``1 / fps`` and the last step."""
    steps = frame_steps(time_s, fps)
    if steps[-1] != len(time_s) - 1:
        steps = np.append(steps, len(time_s) - 1)
    out: IntArray = np.unique(steps)
    return out


def _runs(steps: IntArray) -> Iterator[tuple[int, int]]:
    """(first, last) of each run of consecutive values of sorted unique ``steps``."""
    if len(steps) == 0:
        return
    breaks = np.flatnonzero(np.diff(steps) > 1)
    starts = np.concatenate([[0], breaks + 1])
    ends = np.concatenate([breaks, [len(steps) - 1]])
    for a, b in zip(starts.tolist(), ends.tolist(), strict=True):
        yield int(steps[a]), int(steps[b])


def _contact_spans(model: mujoco.MjModel, log: PlaybackLog, parts: SceneParts) -> ContactSpans:
    """Spans of time during which each drawn geom touches something that counts.

    A contact paints the touching geom where it is drawn, else the drawn geoms
    of its body (a robot's collision geoms are hidden; its visual ones are painted).
    """
    c = classify_contacts(log.meta.groups, log.contact_geoms, log.contact_dist)
    kinds = np.select([c.obstacle, c.self_hit, c.support], [0, 1, 2], default=-1)
    drawn_body = np.full(len(parts.geoms.names), -1)
    moving = parts.geoms.body >= 0
    drawn_body[moving] = parts.bodies[parts.geoms.body[moving]]
    painted: dict[int, IntArray] = {}
    for g in np.unique(log.contact_geoms).tolist():
        own = np.flatnonzero(parts.model_geom == g)
        body = int(model.geom_bodyid[g])
        painted[g] = own if len(own) else np.flatnonzero(drawn_body == body)
    steps: dict[tuple[int, int], list[int]] = {}
    for row in np.flatnonzero(kinds >= 0).tolist():
        for g in log.contact_geoms[row].tolist():
            for prim in painted[g].tolist():
                steps.setdefault((prim, int(kinds[row])), []).append(int(log.contact_step[row]))
    spans = [
        (prim, kind, float(log.time_s[a]), float(log.time_s[b]))
        for (prim, kind), s in sorted(steps.items())
        for a, b in _runs(np.unique(s))
    ]
    table = np.array(spans, dtype=float).reshape(-1, 4)
    return ContactSpans(
        geom=table[:, 0].astype(np.intp),
        kind=table[:, 1].astype(np.intp),
        start_s=table[:, 2],
        end_s=table[:, 3],
    )


def export_replay(
    model: mujoco.MjModel,
    log: PlaybackLog,
    report: RunReport,
    *,
    targets: npt.ArrayLike = (),
    camera: str | None = None,
    fps: float = REPLAY_FPS,
    title: str | None = None,
) -> ReplayData:
    """The replay of a recorded run.

    Args:
        model: The model the log was recorded with.
        log: The run's log (at least one recorded step).
        report: Its report (shown as the verdict table).
        targets: Points to mark, (M, 3) [m].
        camera: The camera the page starts from (default the model's first
            fixed camera, else MuJoCo's free camera, :data:`FREE_CAMERA`).
        fps: Frames kept per simulated second [1/s].
        title: Heading of the page (default "TASK: TRAJECTORY").

    Returns:
        The :class:`~lynxsim.web.replay_data.ReplayData`.

    Raises:
        InvalidInputError: The log is empty or not of this model, ``fps`` out of
            range, unknown camera, targets not (M, 3) finite.
    """
    fps = number_in_range(fps, "fps", MIN_FPS, MAX_FPS, "frames/s")
    if log.steps == 0:
        raise InvalidInputError("the log holds no recorded step: there is nothing to replay")
    if log.qpos.shape[1] != model.nq or len(log.meta.geom_names) != model.ngeom:
        raise InvalidInputError("the log was recorded with another model")
    parts = scene_parts(model)
    cameras = (*parts.cameras, free_camera(model))
    names = [c.name for c in cameras]
    if FREE_CAMERA in names[:-1]:
        cameras, names = cameras[:-1], names[:-1]
    start = camera if camera is not None else names[0]
    if start not in names:
        raise InvalidInputError(f"no camera named {start!r}; available: {', '.join(names)}")
    marks = np.asarray(targets, dtype=float).reshape(-1, 3)
    frames = _frames(log.time_s, fps)
    pos_true, quat_true = _true_poses(model, log.qpos, parts.bodies)
    pos_q, origin, step = quantise_positions(pos_true[frames])
    poses = QuantisedPoses(pos_q, origin, step, quantise_quaternions(quat_true[frames]))
    clearance = log.clearance_m
    bins = np.concatenate([[0], frames[:-1] + 1])
    values = np.minimum.reduceat(clearance, bins, axis=0) if clearance.shape[1] else clearance
    data = ReplayData(
        title=title if title is not None else f"{log.meta.task}: {log.meta.trajectory}",
        task=log.meta.task,
        trajectory=log.meta.trajectory,
        time_s=log.time_s[frames],
        body_names=parts.body_names,
        poses=poses,
        pose_error_m=0.0,
        geoms=parts.geoms,
        cameras=tuple(cameras),
        default_camera=start,
        tool=log.tool[frames],
        tool_ref=log.tool_ref[frames],
        targets=marks,
        contacts=_contact_spans(model, log, parts),
        clearance=Clearances(log.meta.groups.obstacle_names, values[: len(frames)]),
        center=np.array(model.stat.center, dtype=float),
        extent=float(model.stat.extent),
        znear=float(model.vis.map.znear),
        zfar=float(model.vis.map.zfar),
        report_json=canonical_json(report.to_dict()),
    )
    return _with_error(data, log.time_s, pos_true, quat_true, parts.reach_m)


def _with_error(
    data: ReplayData,
    time_s: FloatArray,
    pos_true: FloatArray,
    quat_true: FloatArray,
    reach_m: FloatArray,
) -> ReplayData:
    """``data`` with its pose error measured at every recorded step."""
    if pos_true.shape[1] == 0:
        return data
    pos, quat = data.body_poses(time_s)
    error = point_error_bound(pos_true, quat_true, pos, quat, reach_m)
    return replace(data, pose_error_m=float(error.max()))


def save_replay(
    model: mujoco.MjModel,
    playback: Playback,
    dest: str | os.PathLike[str],
    *,
    targets: npt.ArrayLike = (),
    camera: str | None = None,
) -> Path:
    """Export a run's replay and write it (:func:`~lynxsim.web.replay_file.write_replay_file`).

    Args:
        model: The model the run was recorded with.
        playback: The run's report and log.
        dest: The replay data file (``RUN.replay.npz`` beside ``RUN.json``).
        targets: Points to mark, (M, 3) [m].
        camera: The camera the page starts from.

    Returns:
        ``dest`` as a path.
    """
    data = export_replay(model, playback.log, playback.report, targets=targets, camera=camera)
    return write_replay_file(data, dest)
