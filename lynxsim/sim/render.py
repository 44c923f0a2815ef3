"""Off-screen rendering of a scene with overlays (tool path, targets, contacts).

Import :mod:`lynxsim.sim` (which picks the GL backend) before this module
creates a context; ``with SceneRenderer(...) as r:`` frees it.
"""

from __future__ import annotations

import enum
import itertools
from dataclasses import dataclass, field
from types import TracebackType

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_FPS, MIN_FPS, check_range
from lynxsim.errors import InvalidInputError

__all__ = ["Overlay", "Quality", "RenderSettings", "SceneRenderer"]

FloatArray = npt.NDArray[np.float64]

_PATH_RGBA = np.array([0.1, 0.45, 1.0, 1.0], dtype=np.float32)
_TARGET_RGBA = np.array([1.0, 0.6, 0.0, 0.8], dtype=np.float32)
_CONTACT_RGBA = np.array([0.95, 0.05, 0.05, 1.0], dtype=np.float32)
_PATH_WIDTH_PX = 3.0
_TARGET_RADIUS_M = 0.008
_MAX_PATH_SEGMENTS = 600


class Quality(enum.Enum):
    """Rendering presets.

    FAST: no shadows, no multisampling (tests; ~20 ms a 640x480 frame on a CPU).
    DEFAULT: shadows and the model's multisampling (~70 ms on a CPU).
    """

    FAST = "fast"
    DEFAULT = "default"


@dataclass(frozen=True)
class RenderSettings:
    """How frames are made.

    Attributes:
        width: Frame width [px].
        height: Frame height [px].
        camera: Name of a camera in the model.
        quality: Preset.
        fps: Video frame rate [1/s]; frames sample simulated time at this rate.
    """

    width: int = 640
    height: int = 480
    camera: str = "front"
    quality: Quality = Quality.DEFAULT
    fps: float = 30.0

    def __post_init__(self) -> None:
        for side in (self.width, self.height):
            if isinstance(side, bool) or not isinstance(side, int) or side <= 0:
                raise InvalidInputError(
                    f"frame size must be positive integers, got {self.width!r}x{self.height!r}"
                )
        check_range(self.fps, "fps", MIN_FPS, MAX_FPS, "frames/s")


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


class SceneRenderer:
    """A MuJoCo renderer bound to one model, camera and quality preset.

    Args:
        model: The model; with ``Quality.FAST`` its off-screen multisampling is
            set to 0 (before the context is created).
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
            names = [model.camera(i).name for i in range(model.ncam)]
            raise InvalidInputError(f"no camera named {settings.camera!r}; available: {names}")
        if settings.quality is Quality.FAST:
            model.vis.quality.offsamples = 0
        self._model = model
        self._settings = settings
        self._renderer = mujoco.Renderer(model, settings.height, settings.width)
        self._option = mujoco.MjvOption()
        # Reflections double the cost of a frame on a CPU renderer for little gain.
        flags = self._renderer.scene.flags
        flags[int(mujoco.mjtRndFlag.mjRND_SHADOW)] = settings.quality is Quality.DEFAULT
        flags[int(mujoco.mjtRndFlag.mjRND_REFLECTION)] = False

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

    def render(self, data: mujoco.MjData, overlay: Overlay | None = None) -> npt.NDArray[np.uint8]:
        """One RGB frame of shape (height, width, 3), uint8."""
        self._renderer.update_scene(data, camera=self._camera, scene_option=self._option)
        if overlay is not None:
            self._draw(overlay)
        frame: npt.NDArray[np.uint8] = self._renderer.render()
        return frame

    def _draw(self, overlay: Overlay) -> None:
        scene = self._renderer.scene
        if overlay.contact_bodies:
            geom_type = int(mujoco.mjtObj.mjOBJ_GEOM)
            for i in range(scene.ngeom):
                g = scene.geoms[i]
                if int(g.objtype) == geom_type and (
                    int(self._model.geom_bodyid[g.objid]) in overlay.contact_bodies
                ):
                    g.rgba[:] = _CONTACT_RGBA
        for point in overlay.targets:
            if scene.ngeom >= scene.maxgeom:
                return
            mujoco.mjv_initGeom(
                scene.geoms[scene.ngeom],
                int(mujoco.mjtGeom.mjGEOM_SPHERE),
                np.array([_TARGET_RADIUS_M, 0.0, 0.0]),
                np.asarray(point, dtype=float),
                np.eye(3).ravel(),
                _TARGET_RGBA,
            )
            scene.ngeom += 1
        path = overlay.path
        if len(path) > _MAX_PATH_SEGMENTS + 1:
            path = path[np.linspace(0, len(path) - 1, _MAX_PATH_SEGMENTS + 1).astype(int)]
        for a, b in itertools.pairwise(path):
            if scene.ngeom >= scene.maxgeom:
                return
            geom = scene.geoms[scene.ngeom]
            mujoco.mjv_initGeom(
                geom,
                int(mujoco.mjtGeom.mjGEOM_LINE),
                np.zeros(3),
                np.zeros(3),
                np.zeros(9),
                _PATH_RGBA,
            )
            mujoco.mjv_connector(
                geom,
                int(mujoco.mjtGeom.mjGEOM_LINE),
                _PATH_WIDTH_PX,
                a.astype(float),
                b.astype(float),
            )
            scene.ngeom += 1
