"""Off-screen rendering of a scene with overlays (tool path, targets, contacts).

Overlays are geoms added to MuJoCo's scene, drawn by the same GL pass as the
model. On a CPU renderer each added geom costs a draw call, so a recorded path
is traced through the few points a tolerance far below a pixel needs
(:class:`PathTrace`), not through every physics step.

Import :mod:`lynxsim.sim` (which picks the GL backend) before this module
creates a context; ``with SceneRenderer(...) as r:`` frees it.
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import TracebackType

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_FPS, MIN_FPS, check_range
from lynxsim.errors import InvalidInputError
from lynxsim.sim.quality import Quality

__all__ = [
    "TRACE_TOLERANCE_M",
    "Overlay",
    "PathTrace",
    "Quality",
    "RenderSettings",
    "SceneRenderer",
    "camera_names",
    "set_scene_flags",
    "simplify_polyline",
    "tessellation",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

_PATH_RGBA = np.array([0.1, 0.45, 1.0, 1.0], dtype=np.float32)
_TARGET_RGBA = np.array([1.0, 0.6, 0.0, 0.8], dtype=np.float32)
_CONTACT_RGBA = np.array([0.95, 0.05, 0.05, 1.0], dtype=np.float32)
_PATH_WIDTH_PX = 3.0
_TARGET_RADIUS_M = 0.008
_MAX_PATH_SEGMENTS = 600
_LINE = int(mujoco.mjtGeom.mjGEOM_LINE)
_SPHERE = int(mujoco.mjtGeom.mjGEOM_SPHERE)
_GEOM = int(mujoco.mjtObj.mjOBJ_GEOM)
_PLANE = int(mujoco.mjtGeom.mjGEOM_PLANE)
_NO_GEOM = int(mujoco.mjtGeom.mjGEOM_NONE)
_ZERO3 = np.zeros(3)
_ZERO9 = np.zeros(9)
_EYE9 = np.eye(3).ravel()
_TARGET_SIZE = np.array([_TARGET_RADIUS_M, 0.0, 0.0])

TRACE_TOLERANCE_M = 0.5e-3
"""Largest distance of a recorded path point from its drawn trace [m]: a third of
a pixel at 640x480 from the models' cameras (about 1.7 mm per pixel)."""


@dataclass(frozen=True)
class RenderSettings:
    """How frames are made.

    Attributes:
        width: Frame width [px].
        height: Frame height [px].
        camera: Name of a camera in the model.
        quality: Preset.
        fps: Video frame rate [1/s]; frames sample simulated time at this rate.
        sites: Whether the model's sites of the groups MuJoCo shows by default
            (0-2) are drawn (False: none is, e.g. the scene's goal mark).
    """

    width: int = 640
    height: int = 480
    camera: str = "front"
    quality: Quality = Quality.DEFAULT
    fps: float = 30.0
    sites: bool = True

    def __post_init__(self) -> None:
        for side in (self.width, self.height):
            if isinstance(side, bool) or not isinstance(side, int) or side <= 0:
                raise InvalidInputError(
                    f"frame size must be positive integers, got {self.width!r}x{self.height!r}"
                )
        check_range(self.fps, "fps", MIN_FPS, MAX_FPS, "frames/s")
        if not isinstance(self.sites, bool):
            raise InvalidInputError(f"sites must be True or False, got {self.sites!r}")


@dataclass
class Overlay:
    """Markers drawn into the scene on top of the model.

    Attributes:
        path: Points of the tool path so far, shape (N, 3) [m].
        targets: Task target points, shape (M, 3) [m].
        contact_bodies: Body ids whose visual geoms are drawn red.
    """

    path: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    targets: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    contact_bodies: frozenset[int] = frozenset()


def simplify_polyline(points: npt.ArrayLike, tolerance_m: float) -> IntArray:
    """Indices of the points a polyline needs to stay within a tolerance (Ramer-Douglas-Peucker).

    Every dropped point lies within ``tolerance_m`` of the segment joining the
    kept points on either side of it.

    Args:
        points: The polyline, shape (N, 3) [m].
        tolerance_m: Largest distance of a dropped point from the result [m], >= 0.

    Returns:
        Increasing indices into ``points``, the first and last included (empty if N = 0).

    Raises:
        InvalidInputError: ``tolerance_m`` negative or not finite.
    """
    if not math.isfinite(tolerance_m) or tolerance_m < 0.0:
        raise InvalidInputError(f"tolerance_m must be finite and >= 0, got {tolerance_m!r}")
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    keep = np.zeros(len(p), dtype=bool)
    keep[[0, -1] if len(p) else []] = True
    spans = [(0, len(p) - 1)]
    while spans:
        i, j = spans.pop()
        if j - i < 2:
            continue
        chord = p[j] - p[i]
        rel = p[i + 1 : j] - p[i]
        length2 = float(chord @ chord)
        t = np.clip(rel @ chord / length2, 0.0, 1.0) if length2 > 0.0 else np.zeros(len(rel))
        dist = np.linalg.norm(rel - t[:, None] * chord, axis=1)
        worst = int(np.argmax(dist))
        if dist[worst] > tolerance_m:
            m = i + 1 + worst
            keep[m] = True
            spans += [(i, m), (m, j)]
    return np.flatnonzero(keep)


@dataclass(frozen=True)
class PathTrace:
    """A recorded path drawn as it grows, through the points a tolerance needs.

    Simplified once (:func:`simplify_polyline`); each frame draws the kept points
    up to its step and then the step's own point, so the trace ends at the tool.

    Attributes:
        points: The whole path, shape (S, 3) [m], one point per recorded step.
        kept: Indices of the points drawn, increasing, (K,).
    """

    points: FloatArray
    kept: IntArray

    @classmethod
    def of(cls, points: npt.ArrayLike, tolerance_m: float = TRACE_TOLERANCE_M) -> PathTrace:
        """The trace of ``points`` (S, 3) [m] within ``tolerance_m`` [m]."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        return cls(p, simplify_polyline(p, tolerance_m))

    def until(self, step: int) -> FloatArray:
        """The polyline drawn at recorded step ``step`` (0 <= step < S), shape (n, 3) [m]."""
        n = int(np.searchsorted(self.kept, step, side="right"))
        idx = self.kept[:n] if self.kept[n - 1] == step else np.append(self.kept[:n], step)
        return self.points[idx]


_LEAN_SHAPES = (8, 4, 1)
"""Slices, stacks and quads of the built-in shapes with ``Quality.LEAN`` (model: 28, 16, 4)."""


@contextlib.contextmanager
def tessellation(model: mujoco.MjModel, quality: Quality) -> Iterator[None]:
    """While a GL context is made: the shapes and multisampling ``quality`` draws with.

    MuJoCo builds its shapes and its off-screen buffer once, when the context is
    made, from ``model.vis.quality``: the built-in shapes coarse for LEAN, no
    multisampling but for DEFAULT. The model's values are put back afterwards,
    so that a later renderer of the same model gets its own.
    """
    q = model.vis.quality
    kept = (int(q.numslices), int(q.numstacks), int(q.numquads), int(q.offsamples))
    if quality is Quality.LEAN:
        q.numslices, q.numstacks, q.numquads = _LEAN_SHAPES
    if quality is not Quality.DEFAULT:
        q.offsamples = 0
    try:
        yield
    finally:
        q.numslices, q.numstacks, q.numquads, q.offsamples = kept


def set_scene_flags(flags: npt.NDArray[np.uint8], quality: Quality) -> None:
    """Set an ``mjvScene``'s render flags for a preset (``flags``: its ``flags`` array).

    Shadows with MEDIUM and DEFAULT; never reflections (they double the cost of a
    frame on a CPU renderer for little gain); LEAN also drops skybox, fog and haze.
    """
    flags[int(mujoco.mjtRndFlag.mjRND_SHADOW)] = quality in (Quality.MEDIUM, Quality.DEFAULT)
    flags[int(mujoco.mjtRndFlag.mjRND_REFLECTION)] = False
    if quality is Quality.LEAN:
        for flag in ("mjRND_SKYBOX", "mjRND_FOG", "mjRND_HAZE"):
            flags[int(getattr(mujoco.mjtRndFlag, flag))] = False


def _drop_infinite_planes(scene: mujoco.MjvScene) -> None:
    """Leave a scene's infinite planes (the floor) undrawn: LEAN draws no floor.

    On Mesa's llvmpipe the floor is most of a small frame's cost (84x84: 2.7 of
    3.0 ms, whatever its grid, material or size); without it the background is
    black, the table and everything on it as before. ``mjr_render`` skips a geom
    of type ``mjGEOM_NONE``.
    """
    for g in scene.geoms[: scene.ngeom]:
        if g.type == _PLANE and g.size[0] == 0.0 and g.size[1] == 0.0:
            g.type = _NO_GEOM


def camera_names(model: mujoco.MjModel) -> tuple[str, ...]:
    """The names of a model's cameras, in id order."""
    return tuple(model.camera(i).name for i in range(model.ncam))


class SceneRenderer:
    """A MuJoCo renderer bound to one model, camera and quality preset.

    Args:
        model: The model (left as it is given: the preset's multisampling and
            shapes apply to this renderer's context only, :func:`tessellation`).
        settings: Size, camera, quality.

    Raises:
        InvalidInputError: Unknown camera, or a frame larger than the model's
            off-screen buffer (``<visual><global offwidth offheight>``).
    """

    def __init__(self, model: mujoco.MjModel, settings: RenderSettings) -> None:
        buf_w, buf_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
        if settings.width > buf_w or settings.height > buf_h:
            raise InvalidInputError(
                f"frame {settings.width}x{settings.height} exceeds the model's off-screen buffer "
                f"{buf_w}x{buf_h}; raise <visual><global offwidth/offheight> in the model"
            )
        self._camera = mujoco.mj_name2id(model, int(mujoco.mjtObj.mjOBJ_CAMERA), settings.camera)
        if self._camera < 0:
            names = list(camera_names(model))
            raise InvalidInputError(f"no camera named {settings.camera!r}; available: {names}")
        self._model = model
        self._settings = settings
        with tessellation(model, settings.quality):
            self._renderer = mujoco.Renderer(model, settings.height, settings.width)
        self._option = mujoco.MjvOption()
        if not settings.sites:
            self._option.sitegroup[:] = 0
        set_scene_flags(self._renderer.scene.flags, settings.quality)

    @property
    def settings(self) -> RenderSettings:
        """The settings this renderer was made with."""
        return self._settings

    def __enter__(self) -> SceneRenderer:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def close(self) -> None:
        """Free the GL context."""
        self._renderer.close()

    def render(
        self,
        data: mujoco.MjData,
        overlay: Overlay | None = None,
        *,
        out: npt.NDArray[np.uint8] | None = None,
    ) -> npt.NDArray[np.uint8]:
        """One RGB frame of shape (height, width, 3), uint8.

        A frame depends on ``data``, the camera and ``overlay`` only: MuJoCo's scene
        keeps state from its previous update (the first frame of a new renderer
        differed from later ones of the same state in up to 7 % of its pixels, by
        1-2 levels), so the scene is updated twice (~4 us).

        Args:
            data: The state to draw (its kinematics and camera/light poses computed).
            overlay: Markers added to the scene, or None.
            out: A C-contiguous (height, width, 3) uint8 array to draw into and
                return (saves allocating a frame per call), or None.
        """
        for _ in range(2):
            self._renderer.update_scene(data, camera=self._camera, scene_option=self._option)
        if self._settings.quality is Quality.LEAN:
            _drop_infinite_planes(self._renderer.scene)
        if overlay is not None:
            self._draw(overlay)
        frame: npt.NDArray[np.uint8] = self._renderer.render(out=out)
        return frame

    def _draw(self, overlay: Overlay) -> None:
        scene = self._renderer.scene
        geoms = scene.geoms
        if overlay.contact_bodies:
            body_of = self._model.geom_bodyid
            for g in geoms[: scene.ngeom]:
                if g.objtype == _GEOM and int(body_of[g.objid]) in overlay.contact_bodies:
                    g.rgba[:] = _CONTACT_RGBA
        for point in np.asarray(overlay.targets, dtype=float).reshape(-1, 3):
            if scene.ngeom >= scene.maxgeom:
                return
            geom = geoms[scene.ngeom]
            mujoco.mjv_initGeom(geom, _SPHERE, _TARGET_SIZE, point, _EYE9, _TARGET_RGBA)
            scene.ngeom += 1
        path = np.asarray(overlay.path, dtype=float).reshape(-1, 3)
        if len(path) > _MAX_PATH_SEGMENTS + 1:
            path = path[np.linspace(0, len(path) - 1, _MAX_PATH_SEGMENTS + 1).astype(int)]
        for a, b in itertools.pairwise(path):
            if scene.ngeom >= scene.maxgeom:
                return
            geom = geoms[scene.ngeom]
            mujoco.mjv_initGeom(geom, _LINE, _ZERO3, _ZERO3, _ZERO9, _PATH_RGBA)
            mujoco.mjv_connector(geom, _LINE, _PATH_WIDTH_PX, a, b)
            scene.ngeom += 1
