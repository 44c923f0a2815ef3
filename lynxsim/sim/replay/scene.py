"""What a replay draws of a MuJoCo model: its visible primitives, moving bodies and cameras.

MuJoCo itself decides what is drawn and in which colour: the model's abstract
scene (``mjv_updateScene`` with the default options, as the off-screen videos
use) lists the visible geoms and sites (groups 0-2) with the colour each is
drawn in (a textured material's colour is its texture's mean times its
``rgba``). Meshes, height fields and SDFs are not primitives and are left out.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.web.replay_data import GEOM_KINDS, ReplayCamera, ReplayGeoms

__all__ = ["SceneParts", "bounding_radius", "scene_parts"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

_GEOM = int(mujoco.mjtObj.mjOBJ_GEOM)
_SITE = int(mujoco.mjtObj.mjOBJ_SITE)
_ORTHOGRAPHIC = int(mujoco.mjtProjection.mjPROJ_ORTHOGRAPHIC)
_SPHERE, _CAPSULE, _ELLIPSOID, _CYLINDER, _BOX = (
    int(mujoco.mjtGeom.mjGEOM_SPHERE),
    int(mujoco.mjtGeom.mjGEOM_CAPSULE),
    int(mujoco.mjtGeom.mjGEOM_ELLIPSOID),
    int(mujoco.mjtGeom.mjGEOM_CYLINDER),
    int(mujoco.mjtGeom.mjGEOM_BOX),
)


@dataclass(frozen=True)
class SceneParts:
    """A model's drawn primitives and where they come from.

    Attributes:
        geoms: The primitives (G).
        bodies: MuJoCo body id of each moving body, (B,): bodies not welded to
            the world that carry a primitive.
        body_names: Their names, (B,).
        reach_m: Per moving body, the farthest point of its primitives from its origin, (B,) [m].
        model_geom: Per primitive, the MuJoCo geom id it draws, or -1 for a site, (G,).
        cameras: The cameras fixed to the world.
    """

    geoms: ReplayGeoms
    bodies: IntArray
    body_names: tuple[str, ...]
    reach_m: FloatArray
    model_geom: IntArray
    cameras: tuple[ReplayCamera, ...]


def bounding_radius(kind: int, size: npt.ArrayLike) -> float:
    """Radius of the sphere about a primitive's centre that holds it [m].

    Args:
        kind: MuJoCo geom type (a key of :data:`~lynxsim.web.replay_data.GEOM_KINDS`).
        size: Its MuJoCo size parameters, (3,) [m].
    """
    s = np.asarray(size, dtype=float)
    if kind == _SPHERE:
        return float(s[0])
    if kind == _CAPSULE:
        return float(s[0] + s[1])
    if kind == _CYLINDER:
        return float(np.hypot(s[0], s[1]))
    if kind == _ELLIPSOID:
        return float(s.max())
    if kind == _BOX:
        return float(np.linalg.norm(s))
    return float(np.linalg.norm(s[:2]))  # a plane: its half sizes


def _texture_means(model: mujoco.MjModel) -> FloatArray:
    """Mean RGB of each texture, (ntex, 3) in [0, 1]."""
    out = np.ones((model.ntex, 3))
    data = np.asarray(model.tex_data)
    for t in range(model.ntex):
        w, h, c = int(model.tex_width[t]), int(model.tex_height[t]), int(model.tex_nchannel[t])
        adr = int(model.tex_adr[t])
        if c >= 3 and w * h:
            pixels = data[adr : adr + w * h * c].reshape(-1, c)[:, :3]
            out[t] = pixels.mean(axis=0) / 255.0
    return out


def _drawn(model: mujoco.MjModel, data: mujoco.MjData) -> list[tuple[int, int, FloatArray]]:
    """(object type, id, rgba) of each geom and site MuJoCo draws with the default options."""
    scene = mujoco.MjvScene(model, maxgeom=model.ngeom + model.nsite + 100)
    mujoco.mjv_updateScene(
        model,
        data,
        mujoco.MjvOption(),
        None,
        mujoco.MjvCamera(),
        int(mujoco.mjtCatBit.mjCAT_ALL),
        scene,
    )
    means = _texture_means(model)
    out = []
    for g in scene.geoms[: scene.ngeom]:
        objtype = int(g.objtype)
        if objtype not in (_GEOM, _SITE):
            continue
        rgba = np.array(g.rgba, dtype=float)
        if int(g.texid) >= 0:
            rgba[:3] *= means[int(g.texid)]
        out.append((objtype, int(g.objid), np.clip(rgba, 0.0, 1.0)))
    return out


def _cameras(model: mujoco.MjModel, data: mujoco.MjData) -> tuple[ReplayCamera, ...]:
    out = []
    for c in range(model.ncam):
        if int(model.cam_bodyid[c]) != 0 or not model.camera(c).name:
            continue  # a camera riding on a body would need a pose per frame
        out.append(
            ReplayCamera(
                name=model.camera(c).name,
                pos=np.array(data.cam_xpos[c]),
                xmat=np.array(data.cam_xmat[c]).reshape(3, 3),
                fovy=float(model.cam_fovy[c]),
                orthographic=int(model.cam_projection[c]) == _ORTHOGRAPHIC,
            )
        )
    return tuple(out)


def scene_parts(model: mujoco.MjModel) -> SceneParts:
    """The primitives, moving bodies and cameras of a model, posed at ``qpos0``.

    A primitive on a body welded to the world is posed in the world; any other
    in its body's frame (the replay poses the body per frame).
    """
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    weld = np.asarray(model.body_weldid)
    rows = []
    for objtype, i, rgba in _drawn(model, data):
        geom = objtype == _GEOM
        kind = int(model.geom_type[i] if geom else model.site_type[i])
        if kind not in GEOM_KINDS:
            continue
        body = int(model.geom_bodyid[i] if geom else model.site_bodyid[i])
        if weld[body] == 0:
            xpos = data.geom_xpos[i] if geom else data.site_xpos[i]
            xmat = data.geom_xmat[i] if geom else data.site_xmat[i]
            quat = np.empty(4)
            mujoco.mju_mat2Quat(quat, np.asarray(xmat, dtype=float))
            pos, body = np.array(xpos), -1
        else:
            pos = np.array(model.geom_pos[i] if geom else model.site_pos[i])
            quat = np.array(model.geom_quat[i] if geom else model.site_quat[i])
        size = np.array(model.geom_size[i] if geom else model.site_size[i])
        name = model.geom(i).name if geom else model.site(i).name
        rows.append((kind, size, rgba, body, pos, quat / np.linalg.norm(quat), name, i, geom))
    bodies = np.array(sorted({r[3] for r in rows if r[3] >= 0}), dtype=np.intp)
    index = {int(b): k for k, b in enumerate(bodies.tolist())}
    reach = np.zeros(len(bodies))
    for kind, size, _, body, pos, *_ in rows:
        if body >= 0:
            k = index[body]
            reach[k] = max(reach[k], float(np.linalg.norm(pos)) + bounding_radius(kind, size))
    geoms = ReplayGeoms(
        kind=np.array([r[0] for r in rows], dtype=np.intp),
        size=np.array([r[1] for r in rows], dtype=float).reshape(-1, 3),
        rgba=np.array([r[2] for r in rows], dtype=float).reshape(-1, 4),
        body=np.array([index.get(r[3], -1) for r in rows], dtype=np.intp),
        pos=np.array([r[4] for r in rows], dtype=float).reshape(-1, 3),
        quat=np.array([r[5] for r in rows], dtype=float).reshape(-1, 4),
        names=tuple(r[6] for r in rows),
    )
    return SceneParts(
        geoms=geoms,
        bodies=bodies,
        body_names=tuple(model.body(int(b)).name for b in bodies),
        reach_m=reach,
        model_geom=np.array([r[7] if r[8] else -1 for r in rows], dtype=np.intp),
        cameras=_cameras(model, data),
    )
