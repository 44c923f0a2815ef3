"""Sensors that let MuJoCo record a run natively: what a playback reads from ``sensordata``.

A playback records, per step, the tool site, the actuator forces, the pose of
every carried geom (robot and payload: the clearance bounds need them; none
in a scene without obstacles) and
whether any contact that may count (:mod:`lynxsim.sim.collision`) exists.
:func:`add_recording_sensors` compiles those as MuJoCo sensors into a scene, so
that ``mujoco.rollout`` or ``mujoco.batch`` record them with no Python per
step; :class:`RecordingLayout` finds them again in a compiled model and cuts a
recorded ``sensordata`` into the records. The values are MuJoCo's own (copies
of ``site_xpos``, ``geom_xpos``, the columns of ``geom_xmat``,
``actuator_force``), bit for bit what a Python loop reads from ``MjData``.

The contacts that may count pass a conservative **gate**: a state is flagged
when the robot touches anything but the payload, or the payload touches an
obstacle; only flagged states are posed again for their contact lists (a grip
and a cube resting on the table are never flagged). Two contact sensors per
robot subtree (its contacts with anything, and with the payload: the robot
touches something else when the first count is larger) and one per
payload–obstacle pair keep the gate's cost independent of how many geoms
touch (per-body sensors cost 1.6 µs a step on the arm, these 0.5 µs;
per-pair sensors for every carried geom and obstacle were measured dearer
than posing the touching states once a scene has three obstacles). The
subtrees are those of the robot's topmost bodies; a scene in which such a
subtree also holds a colliding geom that is not the robot's gets no sensors
(its contacts would pass for the robot's) and records in Python.

Position-stage values written by a step describe the state the step started
from (MuJoCo's forward pass comes before integration); forces describe the
step itself. :meth:`RecordingLayout.split` pairs them accordingly.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.binding import RobotBinding

__all__ = ["PREFIX", "RecordingLayout", "SensorRecords", "add_recording_sensors"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]

PREFIX = "lynxsim/"
"""Name prefix of the recording sensors (no other sensor of a scene may use it)."""

_TOOL = PREFIX + "tool"
_AXES = ("x", "y", "z")
_FOUND = 1  # the contact sensor's data bit for "found"


def _robot_roots(model: mujoco.MjModel, binding: RobotBinding) -> list[int] | None:
    """Bodies whose subtrees hold the robot: its bodies with no robot body above them.

    None if a subtree also holds a geom that can collide and is not the
    robot's (its contacts would pass for the robot's).
    """
    groups = binding.groups
    parent = np.asarray(model.body_parentid)
    body_of = np.asarray(model.geom_bodyid)
    robot = set(body_of[groups.robot].tolist())

    def above(b: int) -> set[int]:
        out = set()
        while b:
            b = int(parent[b])
            out.add(b)
        return out

    roots = {b for b in robot if not above(b) & robot}
    collides = (np.asarray(model.geom_contype) | np.asarray(model.geom_conaffinity)) != 0
    for g in np.flatnonzero(collides & ~groups.robot).tolist():
        body = int(body_of[g])
        if (above(body) | {body}) & roots:  # in a robot subtree
            return None
    return sorted(roots)


def _names(
    model: mujoco.MjModel, binding: RobotBinding, roots: list[int]
) -> tuple[list[str], list[str], list[str]]:
    """Carried geoms, robot subtree roots and payload bodies by name ("" where unnamed).

    The carried geoms' poses serve the clearance bounds only: a scene without
    obstacles records none.
    """
    groups = binding.groups
    body_of = np.asarray(model.geom_bodyid)
    posed = np.flatnonzero(groups.carried).tolist() if len(groups.obstacle_geoms) else []
    carried = [model.geom(g).name for g in posed]
    payload = sorted(set(body_of[groups.payload].tolist()))
    return (
        carried,
        [model.body(b).name for b in roots],
        [model.body(b).name for b in payload],
    )


def add_recording_sensors(
    spec: mujoco.MjSpec, model: mujoco.MjModel, binding: RobotBinding
) -> mujoco.MjModel:
    """Compile ``spec`` with the recording sensors of its model and binding.

    Args:
        spec: The scene's spec, ``model`` its compilation (the sensors are added to it).
        model: The compiled scene, to resolve what the binding names.
        binding: What a playback drives and watches in it.

    Returns:
        The model with the sensors; ``model`` itself if an element they need
        has no name, or a robot subtree holds a colliding geom that is not the
        robot's (a playback then records in Python, the same records).
    """
    roots = _robot_roots(model, binding)
    if roots is None:
        return model
    carried, robot, payload = _names(model, binding, roots)
    obstacles = [model.geom(int(g)).name for g in binding.groups.obstacle_geoms]
    actuators = [model.actuator(a).name for a in range(model.nu)]
    tool = model.site(binding.tool_site_id).name
    needed = [*carried, *robot, *payload, *obstacles, *actuators, tool]
    if not all(needed) or any(
        model.sensor(s).name.startswith(PREFIX) for s in range(model.nsensor)
    ):
        return model
    obj, sensor = mujoco.mjtObj, mujoco.mjtSensor

    def add(
        name: str, kind: mujoco.mjtSensor, objtype: mujoco.mjtObj, objname: str
    ) -> mujoco.MjsSensor:
        s = spec.add_sensor()
        s.name, s.type, s.objtype, s.objname = PREFIX + name, kind, objtype, objname
        return s

    add("tool", sensor.mjSENS_FRAMEPOS, obj.mjOBJ_SITE, tool)
    for g in carried:
        add(f"pos/{g}", sensor.mjSENS_FRAMEPOS, obj.mjOBJ_GEOM, g)
        for axis, kind in zip(
            _AXES,
            (sensor.mjSENS_FRAMEXAXIS, sensor.mjSENS_FRAMEYAXIS, sensor.mjSENS_FRAMEZAXIS),
            strict=True,
        ):
            add(f"{axis}axis/{g}", kind, obj.mjOBJ_GEOM, g)
    for a in actuators:
        add(f"force/{a}", sensor.mjSENS_ACTUATORFRC, obj.mjOBJ_ACTUATOR, a)

    def contact(
        name: str,
        objtype: mujoco.mjtObj,
        body: str,
        reftype: mujoco.mjtObj | None = None,
        ref: str = "",
    ) -> None:
        """A gate sensor: how many contacts involve ``body`` (and ``ref``, if given)."""
        s = add(name, sensor.mjSENS_CONTACT, objtype, body)
        if reftype is not None:
            s.reftype, s.refname = reftype, ref
        s.intprm[0] = _FOUND  # data="found"
        s.intprm[2] = 1  # num: one slot (found counts every match)

    for b in robot:  # mjOBJ_XBODY: the body's subtree
        contact(f"touch/{b}", obj.mjOBJ_XBODY, b)
        for p in payload:
            contact(f"touch/{b}/{p}", obj.mjOBJ_XBODY, b, obj.mjOBJ_BODY, p)
    for p in payload:
        for o in obstacles:
            contact(f"touch/{p}/{o}", obj.mjOBJ_BODY, p, obj.mjOBJ_GEOM, o)
    out: mujoco.MjModel = spec.compile()
    return out


@dataclass(frozen=True)
class SensorRecords:
    """What the recording sensors say about S recorded states (r carried geoms, nu actuators).

    Attributes:
        tool: The tracked site of each state, (S, 3) [m].
        geom_xpos: Centres of the carried geoms, (S, r, 3) [m].
        geom_xmat: Their orientations, MuJoCo's ``geom_xmat`` rows, (S, r, 9).
        force: Actuator forces of each step, (S, nu) [N·m or N].
        gate: Whether a contact that may count exists in each state, (S,).
    """

    tool: FloatArray
    geom_xpos: FloatArray
    geom_xmat: FloatArray
    force: FloatArray
    gate: BoolArray


@dataclass(frozen=True)
class RecordingLayout:
    """Where the recording sensors of a model sit in ``sensordata``.

    Attributes:
        tool: Columns of the tool site, (3,).
        geom_pos: Columns of each carried geom's centre, (r, 3).
        geom_mat: Columns of each carried geom's ``geom_xmat`` row, (r, 9).
        force: Column of each actuator's force, (nu,).
        touch_any: Found-count column of each robot subtree against anything, (b,).
        touch_payload: Found-count columns of each robot subtree against each payload body, (b, p).
        touch_obstacle: Found-count columns of each payload body against each obstacle, (p * m,).
    """

    tool: IntArray
    geom_pos: IntArray
    geom_mat: IntArray
    force: IntArray
    touch_any: IntArray
    touch_payload: IntArray
    touch_obstacle: IntArray

    @classmethod
    def of(cls, model: mujoco.MjModel, binding: RobotBinding) -> RecordingLayout | None:
        """The layout of a model's recording sensors, or None if it has none."""
        adr = {
            model.sensor(s).name: int(model.sensor_adr[s])
            for s in range(model.nsensor)
            if model.sensor(s).name.startswith(PREFIX)
        }
        if _TOOL not in adr:
            return None
        roots = _robot_roots(model, binding)
        if roots is None:
            return None
        carried, robot, payload = _names(model, binding, roots)
        obstacles = [model.geom(int(g)).name for g in binding.groups.obstacle_geoms]
        pos = np.array([adr[f"{PREFIX}pos/{g}"] for g in carried], dtype=np.intp).reshape(-1, 1)
        axes = np.array(
            [[adr[f"{PREFIX}{a}axis/{g}"] for a in _AXES] for g in carried], dtype=np.intp
        ).reshape(-1, 1, 3)
        # geom_xmat[3 i + j] = R[i, j] = component i of axis j
        mat = (axes + np.arange(3)[None, :, None]).reshape(-1, 9)
        return cls(
            tool=adr[_TOOL] + np.arange(3),
            geom_pos=pos + np.arange(3),
            geom_mat=mat,
            force=np.array(
                [adr[f"{PREFIX}force/{model.actuator(a).name}"] for a in range(model.nu)],
                dtype=np.intp,
            ),
            touch_any=np.array([adr[f"{PREFIX}touch/{b}"] for b in robot], dtype=np.intp),
            touch_payload=np.array(
                [[adr[f"{PREFIX}touch/{b}/{p}"] for p in payload] for b in robot], dtype=np.intp
            ).reshape(len(robot), len(payload)),
            touch_obstacle=np.array(
                [adr[f"{PREFIX}touch/{p}/{o}"] for p in payload for o in obstacles],
                dtype=np.intp,
            ),
        )

    def split(self, stepped: FloatArray, final: FloatArray) -> SensorRecords:
        """Records of S states from the ``sensordata`` written by their S steps.

        Args:
            stepped: ``sensordata`` after each of the S steps, (S, nsensordata):
                positions and contacts of the state each step started from,
                forces of the step.
            final: ``sensordata`` of a forward pass at the last state, (nsensordata,).
        """
        at = np.concatenate([stepped[1:], final[None]])  # row k: the state step k reached
        touching = at[:, self.touch_any] > at[:, self.touch_payload].sum(axis=2)
        gate = touching.any(axis=1) | (at[:, self.touch_obstacle] > 0.0).any(axis=1)
        return SensorRecords(
            tool=at[:, self.tool],
            geom_xpos=at[:, self.geom_pos],
            geom_xmat=at[:, self.geom_mat],
            force=stepped[:, self.force],
            gate=gate,
        )
