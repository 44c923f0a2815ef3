"""Checks every shipped MJCF model must pass (menagerie's model tests)."""

from __future__ import annotations

import mujoco
import numpy as np

_OBJ = mujoco.mjtObj
NAMED_TYPES = {
    "body": (_OBJ.mjOBJ_BODY, "nbody"),
    "joint": (_OBJ.mjOBJ_JOINT, "njnt"),
    "geom": (_OBJ.mjOBJ_GEOM, "ngeom"),
    "site": (_OBJ.mjOBJ_SITE, "nsite"),
    "actuator": (_OBJ.mjOBJ_ACTUATOR, "nu"),
    "camera": (_OBJ.mjOBJ_CAMERA, "ncam"),
    "light": (_OBJ.mjOBJ_LIGHT, "nlight"),
    "tendon": (_OBJ.mjOBJ_TENDON, "ntendon"),
    "equality": (_OBJ.mjOBJ_EQUALITY, "neq"),
    "exclude": (_OBJ.mjOBJ_EXCLUDE, "nexclude"),
    "key": (_OBJ.mjOBJ_KEY, "nkey"),
    "material": (_OBJ.mjOBJ_MATERIAL, "nmat"),
    "texture": (_OBJ.mjOBJ_TEXTURE, "ntex"),
}
"""Element kinds that must carry a unique name: (object type, count attribute)."""


def assert_every_element_named(model: mujoco.MjModel) -> None:
    """Every element of :data:`NAMED_TYPES` has a name, unique within its kind."""
    for kind, (obj, count) in NAMED_TYPES.items():
        names = [mujoco.mj_id2name(model, int(obj), i) for i in range(getattr(model, count))]
        assert all(names), f"unnamed {kind}: ids {[i for i, n in enumerate(names) if not n]}"
        assert len(set(names)) == len(names), f"duplicate {kind} names: {names}"


def warnings_fired(data: mujoco.MjData) -> dict[str, int]:
    """MuJoCo warnings with a non-zero count, by name."""
    return {
        mujoco.mjtWarning(i).name: int(w.number) for i, w in enumerate(data.warning) if w.number
    }


def step_random_controls(
    model: mujoco.MjModel, data: mujoco.MjData, duration_s: float, control_period_s: float
) -> None:
    """Step ``duration_s`` [s] with controls drawn uniformly from the control ranges.

    The controls change every ``control_period_s`` [s]; the draw is seeded (7).
    """
    rng = np.random.default_rng(7)
    low, high = model.actuator_ctrlrange.T
    per_control = round(control_period_s / model.opt.timestep)
    for _ in range(round(duration_s / control_period_s)):
        data.ctrl[:] = rng.uniform(low, high)
        mujoco.mj_step(model, data, nstep=per_control)
