"""``LynxPickAndPlace-v1``/``-v2``: pick the cube up and put it at a goal, around the obstacles."""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from lynxsim.envs.base import FloatArray, LynxArmEnv, Obs, WorkColumn
from lynxsim.envs.config import real_option
from lynxsim.envs.episodes import farthest_apart, task_points
from lynxsim.envs.workspace import CARRY_HEIGHT_M, PolarRegion
from lynxsim.sim.arm.model import CUBE_BODY

__all__ = ["CUBE_HALF_SIZE_M", "PickAndPlaceEnv"]

CUBE_HALF_SIZE_M = 0.0125
"""Half the cube's edge [m] (the scene's 25 mm cube)."""


def _fields(*sizes: tuple[str, int]) -> dict[str, slice]:
    out, start = {}, 0
    for name, size in sizes:
        out[name] = slice(start, start + size)
        start += size
    return out


class PickAndPlaceEnv(LynxArmEnv):
    """Pick-and-place with the report's 5-DOF Lynxmotion arm, around its cylinder obstacle.

    A 25 mm cube rests on the table; the arm must grip it between its two fingers
    (friction only: no weld, no attachment), carry it and bring it to a goal
    point on the table or, like Fetch's pick-and-place, in the air above it. The
    report's obstacle (a cylinder of radius 40 mm at (150, 150) mm, 400 mm tall)
    stands on the table unless ``obstacles`` removes or moves it, or
    ``random_obstacles`` draws new obstacles at every reset. Units are SI;
    the frame is the arm's base frame (z up, table top at z = -12.5 mm).

    **Action space** ``Box(-1, 1, (5,), float32)`` with ``control="tool"`` (default):

    ====  ==========================================  ====================================
    idx   action                                      effect of +1
    ====  ==========================================  ====================================
    0-2   move the commanded tool point x, y, z       + ``position_step`` [m] (0.015)
    3     change the commanded tool pitch             + ``pitch_step`` [rad] (0.1)
    4     gripper opening (absolute)                  -1 closed (0 m) .. +1 open (0.03 m)
    ====  ==========================================  ====================================

    The commanded tool target moves by the action, is clipped to a box
    (x in [-0.30, 0.45], y in [-0.45, 0.45], z in [-0.004, 0.50] m) and a pitch in
    [-pi/2, pi/2], and the analytic IK (the solution nearest the current command,
    wrist roll held at pi) turns it into the five servo targets. A request that is
    out of reach, outside the joint ranges, or whose solution would move a joint by
    more than 0.5 rad in one step (a configuration flip) is not taken in full:
    ``-v1`` takes the feasible target nearest it (the farthest feasible point along
    the request, found by bisection, or the request's position with the pitch
    kept, or its pitch with the position kept, whichever ends nearer, measured in
    action units), so a policy that keeps asking for an unreachable pitch still
    moves the tool; ``-v0`` holds the previous target
    (``target_fallback="hold"``). ``info["target_status"]`` says why the request was
    not taken in full, ``info["target_held"]`` whether the target did not move at
    all, ``info["target_shortfall_m"]`` and ``info["target_shortfall_rad"]`` how far
    the commanded target is from the request; no exception is raised.
    With ``control="joint"`` the action is ``Box(-1, 1, (6,), float32)``: deltas of
    q1..q5 (+1 = + ``joint_step`` [rad], 0.05; clipped to the joint ranges), then
    the gripper as above.

    ``-v2`` (``control="tool_roll"``): ``Box(-1, 1, (6,), float32)``, the tool action
    above with the wrist roll inserted at index 4 (+1 = + ``roll_step`` [rad], 0.1;
    clipped to the roll joint's range 0..2 pi; pointing down, the fingers close
    along the azimuth ``q1 - (roll - pi)``), the gripper at index 5. A request the
    controller cannot take goes to the **nearest** feasible target (in action
    units; it slides along the reach boundary and the joint and pitch limits,
    :mod:`lynxsim.envs.tool_action`), and ``info["target_correction"]`` (shape (5,),
    commanded minus requested x, y, z [m], pitch, roll [rad]) says what changed.

    **Observation** (a dict, every array float64 and freshly allocated):
    ``achieved_goal`` is the cube's position, ``desired_goal`` the goal, both
    shape (3,) [m]; ``observation`` has shape (45,):

    =====  ====================================================  =======
    idx    observation                                           unit
    =====  ====================================================  =======
    0-2    tool point x, y, z                                    m
    3      tool pitch (q2 + q3 + q4)                             rad
    4      gripper opening (distance between the finger pads)    m
    5-7    cube position                                         m
    8-10   cube position minus tool point                        m
    11-14  cube orientation quaternion (w, x, y, z)              --
    15-17  tool-point velocity (difference over one step)        m/s
    18-20  cube linear velocity                                  m/s
    21-23  cube angular velocity, cube frame                     rad/s
    24-28  joint angles q1..q5                                   rad
    29-33  joint velocities                                      rad/s
    34     gripper opening rate                                  m/s
    35-39  commanded joint angles (servo targets)                rad
    40     commanded gripper opening                             m
    41-43  commanded tool point                                  m
    44     commanded tool pitch                                  rad
    =====  ====================================================  =======

    Positions come from the joint and free-joint coordinates after the step (the
    tool point through the analytic FK, which equals MuJoCo's ``tool`` site).
    :attr:`OBS_INDEX` names these slices. With ``pixels`` the dict also holds
    ``"pixels"``, uint8 images (see **Image observations**).

    **Image observations**: ``pixels=("front",)`` (cameras of the scene: ``"front"``,
    ``"top"``; a name or a sequence of distinct names) adds ``obs["pixels"]``, a new
    uint8 array of shape (``pixel_height``, ``pixel_width``, 3 x cameras) (84 x 84 by
    default), space ``Box(0, 255, shape, uint8)``: the RGB frames of the cameras in
    the order given, side by side along the channels (``pixels[..., 3k:3k+3]`` is
    camera k; one camera gives (H, W, 3)). One Box, channels last, is what
    Stable-Baselines3's ``MultiInputPolicy`` takes as an image (its CNN after
    ``VecTransposeImage``; its replay buffers and ``HerReplayBuffer`` accept no
    nested Dict), and the layout of Gymnasium's ``AddRenderObservation``
    ``"pixels"``. The frames are drawn with ``render_quality`` on GL contexts of
    their own (one per camera, apart from ``render()``'s and of their own size),
    made at the first ``reset``, in the process that steps the env (vector envs
    render in their workers; pickling drops the contexts); the poses drawn are
    those of the last physics step's start (2 ms before ``observation``).
    They show the arm, the table, the cube and the obstacles, never the goal
    (neither mark is drawn), so hindsight relabelling of ``desired_goal`` does not
    contradict the image. They are deterministic: one state gives one image,
    whatever was drawn before (two envs with one seed, or one env reset twice with
    one seed, give identical pixels). Cost on a busy 2-core CPU with Mesa's
    llvmpipe (``benchmarks/bench_env.py``, ``render_quality="fast"``): one camera
    adds about 6 ms to a step at 84 x 84 and 7 ms at 128 x 128 (the floor, not the
    pixels, dominates): 154 and 144 steps/s against 2,850 state-only; with
    ``render_quality="lean"`` (no floor drawn) about 0.5 ms at 84 x 84, 0.36-0.39x
    the state-only env's steps/s in CPU time (``benchmarks/bench_vector_env.py``).
    Without ``pixels`` (default) nothing is rendered and the observation is as above.

    **Rewards** (``compute_reward(achieved_goal, desired_goal, info)`` gives the
    same numbers, vectorised, for hindsight relabelling), with ``d`` the distance
    from the cube to the goal [m]:

    - ``reward_goal``: sparse (default) -1 if ``d > distance_threshold`` (0.025 m)
      else 0; dense ``-d``.
    - ``reward_collision``: ``-collision_penalty`` (default 0) on a step with
      arm–obstacle contact, else 0.

    The reward is their sum; both terms are in ``info``.

    **Starting state** (after ``reset``): joints at the ready pose (tool point at
    (0.18, 0, 0.08) m, pointing down, wrist roll pi), gripper open (0.03 m), all
    velocities zero, servo targets equal to the joints. The cube rests on the table
    (centre at z = 0), its faces turned towards the base axis, at a point drawn
    uniformly from 0.13..0.25 m from the base axis and azimuth -80..80 deg. The goal
    is drawn from the same ring, on the table (cube centre height) or, with
    probability ``goal_in_air_prob`` (0.5), 0.03 to 0.09 m above it. The gripper,
    pointing down, reaches both points and the carry height 7 cm above the table
    over them; the arm turned towards either keeps 2 cm from the obstacle; the goal is
    farther than ``distance_threshold`` from the cube. Everything is drawn with
    ``np_random``; ``reset`` sets the whole simulation state (``mj_resetData``:
    velocities, warm starts and time included).

    **Randomised obstacles**: with ``random_obstacles=(fewest, most)`` (or one
    number; at most 4) every ``reset`` draws, after the cube and the goal, a
    uniform number of obstacles in that range with
    :func:`lynxsim.random_scenes.random_obstacles` from ``np_random``: cylinders
    (radius 15-40 mm, 0.1-0.4 m tall), boxes (30-100 mm wide, 0.1-0.4 m tall, any
    yaw) and spheres (radius 20-45 mm, centre 0.05-0.35 m up), centred 0.12-0.30 m
    from the base axis at any heading. No obstacle comes within 60 mm of the cube,
    the goal or the ready tool point, and the arm keeps 15 mm
    (:data:`~lynxsim.envs.base.WORK_CLEARANCE_M`) from every obstacle at the ready
    pose, pointing down above the cube up to the carry height (with and without the
    cube in hand) and above the goal holding the cube
    (:func:`~lynxsim.envs.workspace.work_column`); a scene that fails is drawn
    again. :attr:`obstacles` lists the episode's obstacles and :attr:`scene` the
    scene. The model holds spare obstacle geoms (:mod:`lynxsim.sim.arm.slots`), so
    ids, spaces and the renderer stay; :attr:`collision_checker` sees the episode's
    obstacles. The scripted expert (:class:`~lynxsim.envs.PickAndPlaceExpert`)
    plans around them.

    **Domain randomisation** (off by default; ``randomize=`` a
    :class:`~lynxsim.envs.Randomization`, or per episode
    ``reset(options={"randomize": ...})``, None for none): every ``reset`` starts
    from the compiled model and draws from ``np_random``, before the cube and the
    goal, uniformly: the cube's edge (0.005..0.03 m; it rests on the table, and a
    goal on the table is at its centre height), mass and sliding friction; the
    five arm servos' ``kp`` (``gainprm[0]`` and ``biasprm[1] = -kp`` together) and
    the five arm joints' damping, each within ``1 +- tolerance`` (0.1 is a usual
    tolerance of a hobby servo motor's torque constant; the datasheets give
    nominal values only); each camera's position (+- ``camera_shift_m`` per axis)
    and orientation (turned about a random axis by up to ``camera_tilt_rad``).
    The cube's geom size, bounding box and radius, its body mass and inertia
    (a solid cube) are written and ``mj_setConst`` recomputes what depends on
    them, so the cube collides and moves like a cube compiled at that size (tested).
    :attr:`domain` reports the episode's values (nominal where not randomised).
    Default arguments leave everything, observations included, bit for bit as
    without the feature. The scripted expert assumes the 25 mm cube (it judges a
    grip from the finger opening: 21-27 mm).

    **Episode end**: no termination on success (``info["is_success"]`` reports it
    every step); with ``terminate_on_collision`` an arm–obstacle contact terminates.
    Truncation at ``max_episode_steps`` (200 steps = 8 s as registered).

    **Info** of ``step``: ``is_success`` (``d <= distance_threshold``), ``collision``
    (an arm collision geom touches the obstacle; checked on the contacts of the last
    physics step, or of every physics step with ``collision_check="physics_step"``),
    ``distance`` [m], ``reward_goal``, ``reward_collision``, ``target_status`` (a
    :class:`~lynxsim.envs.control.TargetStatus`), ``target_held``,
    ``target_shortfall_m`` [m] and ``target_shortfall_rad`` [rad]; ``-v2`` adds
    ``target_correction``.

    **Arguments** (all keyword): ``goal_in_air_prob`` (0.5) and those of
    :class:`~lynxsim.envs.base.LynxArmEnv`: ``render_mode`` (None, ``"rgb_array"``,
    ``"human"``), ``control`` (``"tool"``, ``"joint"``), ``target_fallback``
    (``"nearest"``, ``"hold"``), ``reward_type``
    (``"sparse"``, ``"dense"``), ``distance_threshold`` [m], ``obstacles`` (a
    sequence of :mod:`lynxsim.scene` obstacles; None: the report's cylinder),
    ``random_obstacles`` (None, a count or ``(fewest, most)``), ``collision_penalty``,
    ``terminate_on_collision``, ``collision_check``, ``control_dt`` [s] (0.04: 25 Hz
    over the 2 ms physics step; a non-multiple raises), ``position_step`` [m],
    ``pitch_step`` [rad], ``joint_step`` [rad], ``width``, ``height`` [px],
    ``camera`` (``"front"``, ``"top"``), ``render_quality`` (``"lean"``: for small
    image observations, ``"fast"``, ``"medium"``, ``"default"``), ``pixels`` (camera
    names; ``()``: none), ``pixel_width``, ``pixel_height`` [px] (84), ``randomize`` (None or a
    :class:`~lynxsim.envs.Randomization`).

    **Rendering**: ``render_mode="rgb_array"`` returns (height, width, 3) uint8 frames
    (MuJoCo's EGL off-screen context on a headless machine: import ``lynxsim`` or
    ``lynxsim.sim`` before ``mujoco`` so that ``MUJOCO_GL`` defaults to ``egl``); the
    goal is marked by an orange sphere and a green disc on the table below it.
    ``"human"`` opens a passive :mod:`mujoco.viewer` window (needs a display). Nothing
    is rendered inside ``step`` unless ``render_mode="human"``. The renderer is made at
    the first ``render()``, in the process that calls it, so ``gym.make_vec(...,
    vectorization_mode="async")`` renders in its workers; a process forked after its
    parent made a GL context cannot render (EGL deadlocks there, so it raises): then
    pass ``vector_kwargs={"context": "forkserver"}``.

    **For RL users**:

    - Check the env with ``gymnasium.utils.env_checker.check_env(env.unwrapped)``
      (``gym.make`` wraps it in ``PassiveEnvChecker`` and ``TimeLimit``).
    - Hindsight relabelling with ``collision_penalty > 0``: ``compute_reward``
      reads ``info["collision"]``, so Stable-Baselines3's ``HerReplayBuffer`` needs
      ``replay_buffer_kwargs={"copy_info_dict": True}``; without it the buffer
      passes empty infos and relabelled rewards silently lose the penalty.
    - Scales of ``observation`` (abs max over 20 expert episodes, 4,000 steps, seeds
      0-19, default arguments): positions (0-2, 5-10, 41-43) up to 0.25 m, gripper
      entries (4, 40) 0..0.03 m, angles (3, 24-28, 35-39, 44) up to pi rad,
      velocities (15-20) up to about 0.9 m/s, joint velocities (29-33) up to
      5 rad/s, the cube's angular velocity (21-23) up to about 12 rad/s
      when it tumbles, gripper rate (34) up to 0.12 m/s. Normalise per entry
      (e.g. ``VecNormalize``) rather than by one scale.
    - Constant in the default task (``control="tool"``): entry 39, the commanded
      wrist roll q5 = pi (std 2e-13 over those 20 episodes; the only entry with
      std < 1e-9); the measured q5 (28) varies by about 2e-5 rad only. Drop
      them or guard the normalisation's divisor against zero.
    - Image observations with PyTorch's CUDA wheels: import ``torch`` (and
      initialise CUDA) before the env makes its first GL context (the first
      ``render()``, or the first ``reset`` with ``pixels``); the other order can
      clash over the EGL/GPU driver libraries.

    **Version history**: v2: the wrist roll in the tool action (6-D), and an
    infeasible request goes to the nearest feasible target, sliding along the
    reach boundary and the pitch limits (was: the farthest feasible point along
    the request, which stops dead at the edge of the reach), with
    ``info["target_correction"]``; the observation is v1's (``control="tool_roll"``;
    v1 still registered). v1: an infeasible tool request moves the target as far as
    is feasible (was: held); ``random_obstacles``, ``pixels`` and ``randomize``
    (off by default). v0: first release (still registered, with
    ``target_fallback="hold"``).
    """

    _HAS_CUBE: ClassVar[bool] = True
    _GRIPPER_ACTION: ClassVar[bool] = True
    OBS_INDEX: ClassVar[dict[str, slice]] = _fields(
        ("tool_position", 3),
        ("tool_pitch", 1),
        ("gripper_opening", 1),
        ("cube_position", 3),
        ("cube_relative_position", 3),
        ("cube_quaternion", 4),
        ("tool_velocity", 3),
        ("cube_velocity", 3),
        ("cube_angular_velocity", 3),
        ("joint_angles", 5),
        ("joint_velocities", 5),
        ("gripper_rate", 1),
        ("commanded_joint_angles", 5),
        ("commanded_gripper_opening", 1),
        ("commanded_tool_position", 3),
        ("commanded_tool_pitch", 1),
    )
    """Slices of ``observation`` by name."""
    _OBS_SIZE: ClassVar[int] = 45

    CUBE_REGION = PolarRegion(
        radius=(0.13, 0.25), azimuth=(-math.radians(80), math.radians(80)), height=(0.0, 0.0)
    )
    """Where cubes start (centre z = 0: resting on the table)."""
    AIR_HEIGHT_M = (0.03, 0.09)
    """Range of goal heights above the resting height when in the air [m]."""

    def __init__(self, *, goal_in_air_prob: float = 0.5, **kwargs: Any) -> None:
        self.goal_in_air_prob = real_option(goal_in_air_prob, "goal_in_air_prob", 0.0, 1.0)
        super().__init__(**kwargs)
        m = self.model
        body = m.body(CUBE_BODY)
        joint = int(body.jntadr[0])
        self._cube_qpos = int(m.jnt_qposadr[joint])
        self._cube_dof = int(m.jnt_dofadr[joint])
        self._set_cube_half_size(CUBE_HALF_SIZE_M)

    def _set_cube_half_size(self, half: float) -> None:
        """Set where a cube of half-edge ``half`` [m] rests and where goals are drawn."""
        self._cube_half_m = half
        self._rest_z = self.table_top_z + half
        r, a = self.CUBE_REGION.radius, self.CUBE_REGION.azimuth
        self._table_region = PolarRegion(r, a, (self._rest_z, self._rest_z))
        lo, hi = self.AIR_HEIGHT_M
        self._air_region = PolarRegion(r, a, (self._rest_z + lo, self._rest_z + hi))

    def _check_feasible(self) -> None:
        self._set_cube_half_size(CUBE_HALF_SIZE_M)  # (runs within the base's __init__)
        cubes = task_points(self._table_region, self._obstacles)
        if not cubes.size:
            self._refuse(f"the obstacles block every cube start of {self._table_region}")
        goal_regions = [self._table_region] * (self.goal_in_air_prob < 1.0)
        goal_regions += [self._air_region] * (self.goal_in_air_prob > 0.0)
        for region in goal_regions:
            goals = task_points(region, self._obstacles)
            if farthest_apart(cubes, goals) <= self.distance_threshold:
                self._refuse(f"no goal of {region} lies outside distance_threshold of a cube")

    def _sample_task(self) -> None:
        size = self.domain.cube_size_m
        if size is not None and 0.5 * size != self._cube_half_m:
            self._set_cube_half_size(0.5 * size)
        cube = self._draw_point(self._table_region)
        in_air = self.np_random.uniform() < self.goal_in_air_prob
        goal = self._draw_point(self._air_region if in_air else self._table_region, cube)
        yaw = math.atan2(cube[1], cube[0])
        a = self._cube_qpos
        qpos = self.data.qpos
        qpos[a : a + 3] = cube
        qpos[a + 3 : a + 7] = (math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))
        self._set_goal(goal)

    def _work_columns(self) -> list[WorkColumn]:
        """Down to the cube and up with it or without it; down to the goal and up, holding it."""
        cube, goal = self.cube_position, self.goal
        return [
            WorkColumn(cube, CARRY_HEIGHT_M, False),
            WorkColumn(cube, CARRY_HEIGHT_M, True),
            WorkColumn(goal, max(float(goal[2]), CARRY_HEIGHT_M), True),
        ]

    def _observation(self) -> Obs:
        d = self.data
        qp = d.qpos.tolist()
        qv = d.qvel.tolist()
        q = [qp[i] for i in self._arm_qpos]
        x, y, z, pitch, vx, vy, vz = self._tool_state(q)
        f0, f1 = self._finger_qpos
        g0, g1 = self._finger_dof
        a, v = self._cube_qpos, self._cube_dof
        cx, cy, cz = qp[a : a + 3]
        cmd = self._controller
        o = [
            x, y, z, pitch, qp[f0] + qp[f1],
            cx, cy, cz, cx - x, cy - y, cz - z,
            *qp[a + 3 : a + 7],
            vx, vy, vz,
            *qv[v : v + 6],
            *q,
            *(qv[i] for i in self._arm_dof),
            qv[g0] + qv[g1],
            *cmd.q_cmd,
            float(d.ctrl[self._grip_act]),
            *cmd.target,
        ]  # fmt: skip
        return {
            "observation": np.array(o),
            "achieved_goal": np.array((cx, cy, cz)),
            "desired_goal": self._goal.copy(),
        }

    @property
    def cube_position(self) -> FloatArray:
        """The cube's centre now, shape (3,) [m] (a copy)."""
        a = self._cube_qpos
        position: FloatArray = self.data.qpos[a : a + 3].copy()
        return position
