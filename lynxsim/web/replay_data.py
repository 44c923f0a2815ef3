"""What a replay holds: a scene of primitives, body poses per frame, overlays, the run's report.

Everything a replay page draws, in SI units, checked on construction (shapes,
finiteness, indices in range), so that a file read back (:mod:`lynxsim.web.replay_file`)
or a hostile caller cannot make a page that misdraws. Pure NumPy: made from a
MuJoCo model and a run's log by :func:`lynxsim.sim.replay.export_replay`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.web.poses import dequantise_positions, dequantise_quaternions, interpolate_poses

__all__ = [
    "CONTACT_KINDS",
    "GEOM_KINDS",
    "MAX_ABS",
    "Clearances",
    "ContactSpans",
    "QuantisedPoses",
    "ReplayCamera",
    "ReplayData",
    "ReplayFieldError",
    "ReplayGeoms",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

GEOM_KINDS: dict[int, str] = {
    0: "plane",
    2: "sphere",
    3: "capsule",
    4: "ellipsoid",
    5: "cylinder",
    6: "box",
}
"""The primitive kinds a replay draws, by MuJoCo's ``mjtGeom`` value."""

MAX_ABS = 1e6
"""Largest magnitude of any number of a replay (metres, seconds, degrees alike)."""

CONTACT_KINDS = ("obstacle", "self", "support")
"""What a contact span is, by its ``kind`` value: an obstacle hit (robot or
payload against an obstacle), a self hit, a touch of the table or floor."""


class ReplayFieldError(InvalidInputError):
    """One field of a replay is wrong.

    Attributes:
        field: Dotted name of the field (``"geoms.size"``).
        problem: What is wrong with it.
    """

    def __init__(self, field: str, problem: str) -> None:
        super().__init__(f"{field}: {problem}")
        self.field = field
        self.problem = problem


def _array(value: npt.ArrayLike, name: str, shape: tuple[int | None, ...]) -> FloatArray:
    """``value`` as finite float64 of ``shape`` (None: any length)."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ReplayFieldError(name, f"not an array of numbers ({exc})") from None
    if a.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, a.shape)):
        want = "(" + ", ".join("N" if s is None else str(s) for s in shape) + ")"
        raise ReplayFieldError(name, f"must have shape {want}, got {a.shape}")
    if not np.isfinite(a).all():
        raise ReplayFieldError(name, "must be finite")
    if (np.abs(a) > MAX_ABS).any():
        raise ReplayFieldError(name, f"must lie within ±{MAX_ABS:g}")
    return a


def _indices(value: npt.ArrayLike, name: str, low: int, high: int) -> IntArray:
    """``value`` as a 1-D integer array with every entry in ``[low, high)``."""
    a = np.asarray(value)
    if a.ndim != 1 or (a.size and a.dtype.kind not in "iu"):
        raise ReplayFieldError(name, f"must be a 1-D integer array, got {a.dtype} {a.shape}")
    out = a.astype(np.intp)
    if out.size and (out.min() < low or out.max() >= high):
        raise ReplayFieldError(name, f"entries must lie in [{low}, {high - 1}]")
    return out


def _names(value: tuple[str, ...], name: str, count: int) -> tuple[str, ...]:
    if not isinstance(value, tuple) or not all(isinstance(v, str) for v in value):
        raise ReplayFieldError(name, "must be a tuple of strings")
    if len(value) != count:
        raise ReplayFieldError(name, f"must hold {count} names, got {len(value)}")
    return value


@dataclass(frozen=True)
class ReplayGeoms:
    """The drawn primitives (G of them): the model's visible geoms and sites.

    Attributes:
        kind: MuJoCo geom type of each (a key of :data:`GEOM_KINDS`), (G,).
        size: MuJoCo's size parameters, (G, 3) [m] (plane: half sizes, 0 = infinite).
        rgba: Colour as MuJoCo draws it (texture averaged), (G, 4) in [0, 1].
        body: Index of the moving body each is fixed to, or -1: fixed to the world, (G,).
        pos: Position in its body's frame (the world's where ``body`` is -1), (G, 3) [m].
        quat: Orientation there, unit quaternions (w, x, y, z), (G, 4).
        names: Name of each ("" where unnamed).
    """

    kind: IntArray
    size: FloatArray
    rgba: FloatArray
    body: IntArray
    pos: FloatArray
    quat: FloatArray
    names: tuple[str, ...]

    def check(self, bodies: int) -> None:
        """Raise :class:`ReplayFieldError` unless every field is consistent (``bodies``: B)."""
        n = len(self.names)
        _names(self.names, "geoms.names", n)
        kind = _indices(self.kind, "geoms.kind", 0, max(GEOM_KINDS) + 1)
        if len(kind) != n or not set(kind.tolist()) <= set(GEOM_KINDS):
            raise ReplayFieldError("geoms.kind", f"must hold {n} of {sorted(GEOM_KINDS)}")
        if len(_indices(self.body, "geoms.body", -1, bodies)) != n:
            raise ReplayFieldError("geoms.body", f"must hold {n} entries")
        if (_array(self.size, "geoms.size", (n, 3)) < 0.0).any():
            raise ReplayFieldError("geoms.size", "must be >= 0")
        rgba = _array(self.rgba, "geoms.rgba", (n, 4))
        if ((rgba < 0.0) | (rgba > 1.0)).any():
            raise ReplayFieldError("geoms.rgba", "must lie in [0, 1]")
        _array(self.pos, "geoms.pos", (n, 3))
        if not np.allclose(np.linalg.norm(_array(self.quat, "geoms.quat", (n, 4)), axis=1), 1.0):
            raise ReplayFieldError("geoms.quat", "must be unit quaternions")


@dataclass(frozen=True)
class ReplayCamera:
    """A camera of the model, fixed to the world.

    Attributes:
        name: Its name.
        pos: Position, (3,) [m].
        xmat: Orientation: its columns are the camera's x (right), y (up) and
            z (backwards) axes in the world, (3, 3).
        fovy: Vertical field of view [deg]; for an orthographic camera the
            height it sees [m].
        orthographic: Whether it projects orthographically.
    """

    name: str
    pos: FloatArray
    xmat: FloatArray
    fovy: float
    orthographic: bool

    def check(self, index: int) -> None:
        """Raise :class:`ReplayFieldError` unless the camera is a valid one."""
        field = f"cameras[{index}]"
        if not isinstance(self.name, str) or not self.name:
            raise ReplayFieldError(f"{field}.name", "must be a non-empty string")
        _array(self.pos, f"{field}.pos", (3,))
        m = _array(self.xmat, f"{field}.xmat", (3, 3))
        if not np.allclose(m.T @ m, np.eye(3), atol=1e-6):
            raise ReplayFieldError(f"{field}.xmat", "must be a rotation")
        fovy = _array(self.fovy, f"{field}.fovy", ())
        if not (0.0 < float(fovy) < (180.0 if not self.orthographic else MAX_ABS)):
            raise ReplayFieldError(f"{field}.fovy", f"out of range: {float(fovy)!r}")
        if not isinstance(self.orthographic, bool):
            raise ReplayFieldError(f"{field}.orthographic", "must be True or False")


@dataclass(frozen=True)
class QuantisedPoses:
    """Poses of B moving bodies at F frames, 16-bit (see :mod:`lynxsim.web.poses`).

    Attributes:
        pos_q: Positions on the grid, (F, B, 3) int16.
        origin: The grid's centre, (3,) [m].
        step_m: The grid's step [m].
        quat_q: Quaternions (w, x, y, z) times 32767, (F, B, 4) int16.
    """

    pos_q: npt.NDArray[np.int16]
    origin: FloatArray
    step_m: float
    quat_q: npt.NDArray[np.int16]

    def positions(self) -> FloatArray:
        """Positions at the frames, (F, B, 3) [m]."""
        return dequantise_positions(self.pos_q, self.origin, self.step_m)

    def quaternions(self) -> FloatArray:
        """Unit quaternions at the frames, (F, B, 4)."""
        return dequantise_quaternions(self.quat_q)

    def check(self, frames: int, bodies: int) -> None:
        """Raise :class:`ReplayFieldError` unless the poses are F x B and valid."""
        for name, a, width in (("pos_q", self.pos_q, 3), ("quat_q", self.quat_q, 4)):
            a = np.asarray(a)
            if a.dtype != np.int16 or a.shape != (frames, bodies, width):
                raise ReplayFieldError(
                    f"poses.{name}",
                    f"must be int16 of shape ({frames}, {bodies}, {width}), got {a.dtype} "
                    f"{a.shape}",
                )
        if bodies and (np.abs(np.asarray(self.quat_q, dtype=float)).sum(axis=-1) == 0).any():
            raise ReplayFieldError("poses.quat_q", "a quaternion is zero")
        _array(self.origin, "poses.origin", (3,))
        step = float(_array(self.step_m, "poses.step_m", ()))
        if not 0.0 < step < 1.0:
            raise ReplayFieldError("poses.step_m", f"must lie in (0, 1) m, got {step!r}")


@dataclass(frozen=True)
class ContactSpans:
    """When each drawn geom is painted as touching (E spans).

    Attributes:
        geom: The drawn geom (index into :class:`ReplayGeoms`), (E,).
        kind: What touched (index into :data:`CONTACT_KINDS`), (E,).
        start_s: First recorded step in contact, (E,) [s].
        end_s: Last recorded step in contact, (E,) [s] (>= ``start_s``).
    """

    geom: IntArray
    kind: IntArray
    start_s: FloatArray
    end_s: FloatArray

    def check(self, geoms: int) -> None:
        """Raise :class:`ReplayFieldError` unless every span is valid."""
        n = len(np.asarray(self.geom).reshape(-1))
        _indices(self.geom, "contacts.geom", 0, geoms)
        if len(_indices(self.kind, "contacts.kind", 0, len(CONTACT_KINDS))) != n:
            raise ReplayFieldError("contacts.kind", f"must hold {n} entries")
        start = _array(self.start_s, "contacts.start_s", (n,))
        if (_array(self.end_s, "contacts.end_s", (n,)) < start).any():
            raise ReplayFieldError("contacts.end_s", "a span ends before it starts")


@dataclass(frozen=True)
class Clearances:
    """The clearance curve of each obstacle (m of them) at the frames.

    Attributes:
        names: Obstacle names, (m,).
        values_m: Per frame, the smallest signed distance over the physics steps
            that frame stands for (so the run's minimum is kept), (F, m) [m].
    """

    names: tuple[str, ...]
    values_m: FloatArray

    def check(self, frames: int) -> None:
        """Raise :class:`ReplayFieldError` unless there is one curve per name, F values each."""
        _names(self.names, "clearance.names", len(self.names))
        _array(self.values_m, "clearance.values_m", (frames, len(self.names)))


@dataclass(frozen=True)
class ReplayData:
    """Everything a replay page shows of one run (F frames, B moving bodies).

    Attributes:
        title: Heading of the page.
        task: Task name.
        trajectory: Trajectory type name.
        time_s: Simulated time of each frame, (F,) [s], increasing.
        body_names: Name of each moving body, (B,).
        poses: Their poses at the frames.
        pose_error_m: Largest distance of any point of a drawn geom from where
            the simulation had it, at every recorded physics step, for the poses
            as the page interpolates them [m].
        geoms: The drawn primitives.
        cameras: The model's cameras fixed to the world.
        default_camera: The camera the page starts from (one of ``cameras``).
        tool: The simulated tool point (or platform needle) at the frames, (F, 3) [m].
        tool_ref: The commanded one, (F, 3) [m].
        targets: Task targets marked, (M, 3) [m].
        contacts: When drawn geoms touch.
        clearance: The clearance curve of each obstacle.
        center: Centre of the model's extent (MuJoCo's ``stat.center``), (3,) [m].
        extent: The model's extent [m] (``stat.extent``).
        znear: Near clip plane, as a fraction of ``extent`` (``vis.map.znear``).
        zfar: Far clip plane, as a fraction of ``extent`` (``vis.map.zfar``).
        report_json: The run report, as canonical JSON text
            (:func:`lynxsim.web.verdicts.canonical_json`).
    """

    title: str
    task: str
    trajectory: str
    time_s: FloatArray
    body_names: tuple[str, ...]
    poses: QuantisedPoses
    pose_error_m: float
    geoms: ReplayGeoms
    cameras: tuple[ReplayCamera, ...]
    default_camera: str
    tool: FloatArray
    tool_ref: FloatArray
    targets: FloatArray
    contacts: ContactSpans
    clearance: Clearances
    center: FloatArray
    extent: float
    znear: float
    zfar: float
    report_json: str

    def __post_init__(self) -> None:
        for name in ("title", "task", "trajectory", "default_camera", "report_json"):
            if not isinstance(getattr(self, name), str):
                raise ReplayFieldError(name, "must be a string")
        t = _array(self.time_s, "time_s", (None,))
        if len(t) == 0 or (np.diff(t) <= 0.0).any():
            raise ReplayFieldError("time_s", "must hold at least one time, increasing")
        frames, bodies = len(t), len(self.body_names)
        _names(self.body_names, "body_names", bodies)
        self.poses.check(frames, bodies)
        error = float(_array(self.pose_error_m, "pose_error_m", ()))
        if error < 0.0:
            raise ReplayFieldError("pose_error_m", "must be >= 0")
        self.geoms.check(bodies)
        if not isinstance(self.cameras, tuple):
            raise ReplayFieldError("cameras", "must be a tuple")
        for i, camera in enumerate(self.cameras):
            camera.check(i)
        names = [c.name for c in self.cameras]
        if len(set(names)) != len(names):
            raise ReplayFieldError("cameras", "two cameras share a name")
        if self.default_camera not in names:
            raise ReplayFieldError("default_camera", f"must name one of the cameras {names}")
        _array(self.tool, "tool", (frames, 3))
        _array(self.tool_ref, "tool_ref", (frames, 3))
        _array(self.targets, "targets", (None, 3))
        self.contacts.check(len(self.geoms.names))
        self.clearance.check(frames)
        _array(self.center, "center", (3,))
        for name in ("extent", "znear", "zfar"):
            if float(_array(getattr(self, name), name, ())) <= 0.0:
                raise ReplayFieldError(name, "must be > 0")
        if not self.znear < self.zfar:
            raise ReplayFieldError("zfar", "must be beyond znear")

    @property
    def frames(self) -> int:
        """Number of frames F."""
        return len(self.time_s)

    def body_poses(self, t_s: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
        """The moving bodies' poses as the page draws them at times ``t_s`` (T,) [s].

        Returns:
            Positions (T, B, 3) [m] and unit quaternions (T, B, 4).
        """
        return interpolate_poses(self.time_s, self.poses.positions(), self.poses.quaternions(), t_s)
