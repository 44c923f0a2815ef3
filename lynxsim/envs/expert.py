"""Scripted experts: pick-and-place and reach, planning around the obstacles.

The experts drive the default tool-space action. Every move between places
(from the start to above the cube, from above the cube to above the goal,
to a reach goal) is a collision-free joint path planned with
:func:`lynxsim.plan.plan_segment` in the env's own scene
(:attr:`~lynxsim.envs.base.LynxArmEnv.collision_checker`, the cube held on the
carry), with the wrist roll held as the env holds it and the tool pitch
within the env's range. The path becomes a dense list of tool poses (the FK of
its joints) that the expert follows, each one reachable within one action;
a dry run through a copy of the env's controller checks beforehand that the
IK it answers with is the planned joints (the same branch, no clipping;
:mod:`lynxsim.envs.routes`).
The moves at the cube and the goal (down, grasp, up; down, release, up) are
straight vertical lines, kept clear by the env
(:func:`~lynxsim.envs.workspace.work_column`). The analytic IK picks the tool
pitch of each place: pointing down where that is reachable, else the nearest
pitch that is.

Usage::

    env = gym.make("LynxPickAndPlace-v2", random_obstacles=(1, 3))
    expert = PickAndPlaceExpert(env)
    obs, _ = env.reset(seed=0)
    expert.reset()
    obs, reward, terminated, truncated, info = env.step(expert(obs))
"""

from __future__ import annotations

import enum
import math
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.angles import quat_yaw
from lynxsim.envs.expert_moves import (
    across_along,
    grasp_roll,
    per_axis,
    pitch_for,
    straight,
    tool_env,
)
from lynxsim.envs.pick_and_place import CUBE_HALF_SIZE_M, PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.routes import (
    ARRIVED_RAD,
    Mover,
    Planner,
    Point,
    Pose,
    SearchWorld,
)
from lynxsim.envs.tool_action import ToolRollController
from lynxsim.envs.workspace import CARRY_HEIGHT_M, GRIP_ROLL_RAD, TOP_DOWN_PITCH_RAD

__all__ = ["PickAndPlaceExpert", "ReachExpert"]

FloatArray = npt.NDArray[np.float64]

_SETTLED_M = 0.004
"""The arm counts as settled when the tool point is this close to its command [m] ..."""
_SETTLED_SPEED = 0.04
"""... and moves slower than this [m/s]."""
_NEAR_M = 0.008
"""A tool point this close to its command [m] may go on to the next phase unsettled."""
_SLOW = 0.4
"""Fraction of the full speed for the moves down to the table."""
_FINGERTIP_M = 0.008
"""How far the fingertips reach below the tool point [m]."""
_ALIGN_ABOVE_TOP_M = 0.002
"""Fingertip height above the cube's top while centring over it [m]: one full step
down takes them past it."""
_ON_TOP_SLACK_M = 0.0025
"""A plunging tool point higher above the cube's centre than half the cube plus the
fingertip reach, less this [m], has its fingertips on the cube's top: the plunge is
given up at once."""
_GRASP_ABOVE_M = 0.003
"""Tool height above the cube's centre at the grasp [m]: the pads cover its faces, the
palm stays off its top."""
_CENTRED_ACROSS_M = 0.005
"""The plunge starts when the tool point is this close to the cube's centre along the
fingers' closing axis [m] ... Loose on purpose: at action noise 0.1 the tool strays
~4 mm (std) per axis from its target at every step, with no correlation from one step
to the next (the servos overshoot each step's 3 mm of command noise), so waiting for a
centred tool predicts nothing about the next step and only uses up the episode; cheap
retries win (a 30 mm opening leaves 2.5 mm each side of a 25 mm cube)."""
_CENTRED_ALONG_M = 0.005
"""... and this close along the pads' width (18 mm wide pads) [m]."""
_PRESS_M = 0.006
"""A plunging command goes at most this far below the tool point [m]: a finger that
lands on the cube presses it no harder (hard presses tip it over)."""
_PRE_GRASP_WAIT = 3
"""Steps the centring may take before the expert plunges anyway (see above)."""
_PLUNGE_STEPS = 6
"""Steps a plunge may take to bring the cube between the fingers."""
_AROUND_M = 0.004
"""The cube counts as between the fingers when the tool point is this close to its
centre horizontally and this little above it [m]."""
_MAX_WAIT_STEPS = 15
"""Steps to wait at most for the arm to settle."""
_HOVER_M = 0.05
"""Height of the tool above the cube before it descends [m]."""
_HOVER_NEAR_M = 0.008
"""A command this close to the hover point [m] goes on to centre over the cube (the
route's last millimetres, braking under noise, took tens of steps)."""
_GRIP_CLOSE_STEPS = 6
"""Steps the gripper gets to close before the lift."""
_GRIP_STALL_STEPS = 3
"""Steps more a closing gripper gets to reach the cube's width before the grasp counts as
missed (the fingers have stopped by then: on a tipped cube, or closed past it)."""
_IN_HAND_M = 0.02
"""Largest cube-to-tool distance of a held cube [m]."""
_RELEASE_STEPS = 3
"""Steps the gripper gets at least to open before the arm backs off ..."""
"""... until the fingers stand 2.5 mm wider than the cube."""
_REOPEN_STEPS = 5
"""Steps the gripper gets to open after a missed grasp."""
_ON_GOAL_M = 0.006
"""A cube put down this close to the goal horizontally [m] is let go at once."""
_DOWN_M = 0.004
"""A cube within this of its resting height [m] may be let go."""
_PLACE_ABOVE_M = 0.002
"""The cube is let go this high above its resting height [m]."""
_JITTER_MEMORY = 0.9
"""Weight of the past in the running mean of the command's squared jitter [-]."""
_JITTER_MARGIN = 2.5
"""Fingertips hover this many jitter deviations higher above the cube's top [-]."""
_OPEN_FOR_PLUNGE_M = 0.003
"""The fingers must stand this much wider than the cube before a plunge [m]."""
_BESIDE_ALONG_M = 0.007
"""With ``-v2``, a plunge has the cube between the fingers within this along the pads [m]
(18 mm wide on a 25 mm cube)."""
_HOLD_JITTER_M = 0.0022
"""Above this estimated jitter per step and axis [m] (action noise ~0.07) a
cube put down on a table goal is held there, not let go: fingers opening and rising
around it under that noise knocked it off the goal in most lost episodes."""
_PRESSED_M = 0.004
"""A cube this far below its resting height is pressed into the table by a finger [m]."""


class _Phase(enum.Enum):
    APPROACH = "approach"
    ALIGN = "align"
    PLUNGE = "plunge"
    GRASP = "grasp"
    REOPEN = "reopen"
    LIFT = "lift"
    CARRY = "carry"
    PLACE = "place"
    RELEASE = "release"
    RETREAT = "retreat"
    HOLD = "hold"


class PickAndPlaceExpert:
    """Scripted pick-and-place: approach, descend, grasp, lift, carry around the obstacles, place.

    The approach and the carry are planned (module docstring); a goal above the
    table's resting height is held in the air (the cube stays gripped); a goal
    on the table is placed and released, and the arm backs off straight up;
    under action noise (the command's estimated jitter per step, how far it
    strays from where the last action put it, above :data:`_HOLD_JITTER_M`) it is
    held there instead (opening and rising around it knocked it off the goal).
    With the ``-v2`` action (``control="tool_roll"``) the wrist roll turns the
    fingers, above the cube, to close across two of its faces however the cube
    is turned about the vertical, and holds the roll it has in the other phases
    (the planned moves hold it too). Its grasp also copes with noisy actions: it
    hovers that jitter higher above the cube, plunges when the fingers stand open
    and the tool and the command are roughly centred (it waits no longer for a
    centred tool: under noise that does not predict the next step, and retries
    are cheaper), takes the fingertips past the cube's top in one step, and gives a
    plunge up as soon as a finger presses the cube into the table.
    Closed loop: every step decides from the observation; a grasp that misses is
    opened and tried again, a cube that slips out or is knocked off the goal is
    picked up again, a command pushed off a planned route is re-planned.

    Args:
        env: A ``LynxPickAndPlace`` env (wrapped or not) with ``control="tool"``.
        search: Where the moves are searched: ``"cover"`` (the arm's sphere cover,
            default) or ``"exact"`` (:class:`~lynxsim.envs.routes.Planner`).

    Raises:
        InvalidInputError: Another env or control mode, or an unknown ``search``.
    """

    def __init__(self, env: gym.Env[Any, Any], search: SearchWorld = "cover") -> None:
        u, controller = tool_env(env, PickAndPlaceEnv)
        self._controller = controller
        self._rolls = isinstance(controller, ToolRollController)
        self._planner = Planner(u, controller, search)
        self._mover = Mover(self._planner, u.q_ready)
        self._idx = PickAndPlaceEnv.OBS_INDEX
        self._env = u
        self._threshold = u.distance_threshold
        self.reset()

    def reset(self) -> None:
        """Forget the episode and read its cube's size (call after every ``env.reset``)."""
        size = self._env.domain.cube_size_m or 2 * CUBE_HALF_SIZE_M
        half = 0.5 * size
        self._rest_z = self._env.table_top_z + half
        self._align = half + _FINGERTIP_M + _ALIGN_ABOVE_TOP_M
        self._on_top = half + _FINGERTIP_M - _ON_TOP_SLACK_M
        self._gripped = (size - 0.004, size + 0.002)
        self._opened = size + 0.0025
        self._size = size
        self.phase = _Phase.APPROACH
        self._count = 0
        self._offset: Point = (0.0, 0.0, 0.0)
        self._hold_at: Pose = (0.0, 0.0, 0.0, 0.0)
        self._roll_now = self._roll_held = self._roll_grasp = GRIP_ROLL_RAD
        self._jitter_sq = self._jitter_now = 0.0
        self._last: tuple[Pose, list[float]] | None = None
        self._mover.route = None
        self._planner.reset()

    def _enter(self, phase: _Phase) -> None:
        self.phase = phase
        self._count = 0
        self._mover.route = None
        self._roll_held = self._roll_now

    def _jitter(self, cmd: Pose) -> float:
        """Running estimate of the command's jitter per step and axis [m] (action noise).

        The command should be the last one moved by the last action; what it is
        beyond that is noise (or the env's correction of an unreachable request).
        """
        if self._last is not None:
            last, arm = self._last
            s = self._controller.position_step
            miss = sum((cmd[i] - last[i] - max(-1.0, min(1.0, arm[i])) * s) ** 2 for i in range(3))
            self._jitter_sq = _JITTER_MEMORY * self._jitter_sq + (1.0 - _JITTER_MEMORY) * miss / 3
        return math.sqrt(self._jitter_sq)

    def _roll_action(self, phase: _Phase) -> float:
        """Roll action: to the grasp roll above and at the cube, else holding the phase's."""
        aligning = phase in (_Phase.ALIGN, _Phase.PLUNGE, _Phase.GRASP, _Phase.REOPEN)
        want = self._roll_grasp if aligning else self._roll_held
        c = self._controller
        step = c.roll_step if isinstance(c, ToolRollController) else 1.0
        return max(-1.0, min(1.0, (want - self._roll_now) / step))

    def _transit(
        self, cmd: Pose, tool: Point, q_cmd: FloatArray, dest: Point, *, grasped: bool
    ) -> tuple[list[float], bool]:
        """A planned move to ``dest``, the gripper pointing down if the IK reaches it so."""
        pose = (*dest, pitch_for(dest, q_cmd))
        return self._mover.step(cmd, tool, q_cmd, pose, grasped=grasped)

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (5,) (``-v2``: (6,)), float32 in [-1, 1]."""
        o = observation["observation"]
        ix = self._idx
        x, y, z = o[ix["commanded_tool_position"]].tolist()
        cmd: Pose = (x, y, z, float(o[ix["commanded_tool_pitch"]][0]))
        tool: Point = tuple(o[ix["tool_position"]].tolist())
        tool_speed = math.hypot(*o[ix["tool_velocity"]].tolist())
        q_cmd = o[ix["commanded_joint_angles"]]
        opening = float(o[ix["gripper_opening"]][0])
        cube: Point = tuple(observation["achieved_goal"].tolist())
        goal: Point = tuple(observation["desired_goal"].tolist())
        lag = max(abs(tool[i] - cmd[i]) for i in range(3))
        settled = lag < _SETTLED_M and tool_speed < _SETTLED_SPEED
        near = lag < _NEAR_M  # close enough to go on (noisy actions never settle)
        in_hand = math.dist(cube, tool) < _IN_HAND_M
        c = self._controller
        self._count += 1
        phase = self.phase
        grip = 1.0
        closing = float(q_cmd[0])  # azimuth along which the fingers close
        align = self._align
        self._jitter_now = self._jitter(cmd)
        if self._rolls:
            self._roll_now = float(q_cmd[4])
            closing -= self._roll_now - GRIP_ROLL_RAD
            align += _JITTER_MARGIN * self._jitter_now

        if phase is _Phase.APPROACH:
            hover = (cube[0], cube[1], cube[2] + _HOVER_M)
            arm, at = self._transit(cmd, tool, q_cmd, hover, grasped=False)
            at = at or math.dist(cmd[:3], hover) < _HOVER_NEAR_M
            if at and (settled or near or self._count > _MAX_WAIT_STEPS):
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.ALIGN:
            # Above the cube, fingertips clear of its top, until centred over it.
            point = (cube[0], cube[1], cube[2] + align)
            arm, at = straight(cmd, (*point, pitch_for(point, q_cmd)), c, _SLOW)
            if self._rolls:
                yaw = quat_yaw(*o[ix["cube_quaternion"]].tolist())
                self._roll_grasp = grasp_roll(float(q_cmd[0]), yaw, self._roll_grasp)
                at = at and abs(self._roll_grasp - self._roll_now) < ARRIVED_RAD
            across, along = across_along(tool[0] - cube[0], tool[1] - cube[1], closing)
            centred = (
                abs(across) < _CENTRED_ACROSS_M
                and abs(along) < _CENTRED_ALONG_M
                and abs(tool[2] - point[2]) < _AROUND_M
            )
            if self._rolls:  # the command too: the next step starts from it
                across_cmd, along_cmd = across_along(cmd[0] - cube[0], cmd[1] - cube[1], closing)
                centred = (
                    centred
                    and abs(across_cmd) < _CENTRED_ACROSS_M
                    and abs(along_cmd) < _CENTRED_ALONG_M
                    and abs(self._roll_grasp - self._roll_now) < ARRIVED_RAD
                    and opening > self._size + _OPEN_FOR_PLUNGE_M
                )
            if centred or (at and self._count > _PRE_GRASP_WAIT):
                # Down at once: one more step of noisy actions would undo the centring.
                self._enter(_Phase.PLUNGE)
                phase = _Phase.PLUNGE
        if phase is _Phase.PLUNGE:
            # Down past the cube's top in as few steps as possible, then close. Heights
            # count from the resting centre: a cube pressed into the table reads lower.
            base = max(cube[2], self._rest_z)
            point = (cube[0], cube[1], max(base + _GRASP_ABOVE_M, c.box[0][2]))
            press_from = tool[2]
            if self._rolls:  # the press limit counts from where the fingertips reach the top
                press_from = min(press_from, base + self._align - _ALIGN_ABOVE_TOP_M)
            dive = (*point[:2], max(point[2], press_from - _PRESS_M))
            arm = per_axis(cmd, (*dive, pitch_for(point, q_cmd)), c)
            if self._rolls:  # the pads are wide: an offset along them does no harm
                across, along = across_along(tool[0] - cube[0], tool[1] - cube[1], closing)
                beside = abs(across) < _AROUND_M and abs(along) < _BESIDE_ALONG_M
            else:
                beside = math.dist(tool[:2], cube[:2]) < _AROUND_M
            around = beside and tool[2] - base < _GRASP_ABOVE_M + _AROUND_M
            pressed = self._rolls and cube[2] < self._rest_z - _PRESSED_M
            if around and not pressed:
                self._enter(_Phase.GRASP)
                self._hold_at = point_pose = (cmd[0], cmd[1], point[2], TOP_DOWN_PITCH_RAD)
                arm, _ = straight(cmd, point_pose, c, _SLOW)
            elif (
                self._count > _PLUNGE_STEPS
                or (self._count >= 1 and tool[2] - base > self._on_top)
                or pressed
            ):  # landed on the cube or beside it: up and again
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.GRASP:  # close, holding the arm where the grasp began
            arm, _ = straight(cmd, self._hold_at, c, _SLOW)
            grip = -1.0
            if self._count >= _GRIP_CLOSE_STEPS:
                if self._gripped[0] <= opening <= self._gripped[1]:
                    self._enter(_Phase.LIFT)
                elif self._count > _GRIP_CLOSE_STEPS + _GRIP_STALL_STEPS:
                    self._enter(_Phase.REOPEN)
        elif phase is _Phase.REOPEN:
            point = (cmd[0], cmd[1], cube[2] + align)
            arm, _ = straight(cmd, (*point, cmd[3]), c, _SLOW)
            if self._count >= _REOPEN_STEPS:
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.LIFT:
            # Straight up from where the grasp began (noisy actions must not walk it off).
            arm, at = straight(cmd, (*self._hold_at[:2], CARRY_HEIGHT_M, cmd[3]), c)
            grip = -1.0
            if at and (settled or near or self._count > _MAX_WAIT_STEPS):
                if in_hand:
                    self._offset = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])
                    self._enter(_Phase.CARRY)
                else:
                    self._enter(_Phase.APPROACH)
        elif phase in (_Phase.CARRY, _Phase.PLACE, _Phase.HOLD):
            arm, grip = self._carry(phase, cmd, q_cmd, tool, cube, goal, settled)
            if not in_hand:
                self._enter(_Phase.APPROACH)
        elif phase is _Phase.RELEASE:  # open, holding the arm where the cube was put down
            arm, _ = straight(cmd, self._hold_at, c, _SLOW)
            opened = opening > self._opened
            if self._count >= _RELEASE_STEPS and (opened or self._count > _MAX_WAIT_STEPS):
                self._enter(_Phase.RETREAT)
        elif phase is _Phase.RETREAT:  # straight up (a jerk up drags the cube along the fingers)
            above = (*self._hold_at[:2], goal[2] + _HOVER_M, cmd[3])  # where it was let go
            arm, _ = straight(cmd, above, c, _SLOW)
            # Knocked off the goal: again (a cube still within the success radius is
            # left alone: picking it up again would risk more than it can win).
            if math.dist(cube, goal) > self._threshold:
                self._enter(_Phase.APPROACH)
        self._last = (cmd, arm)
        if self._rolls:
            return np.array([*arm, self._roll_action(self.phase), grip], dtype=np.float32)
        return np.array([*arm, grip], dtype=np.float32)

    def _carry(
        self,
        phase: _Phase,
        cmd: Pose,
        q_cmd: FloatArray,
        tool: Point,
        cube: Point,
        goal: Point,
        settled: bool,
    ) -> tuple[list[float], float]:
        """Carry to the goal, then place (table goal) or hold (goal in the air)."""
        off = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])  # the cube in the hand
        if phase is _Phase.CARRY:
            # The planned destination follows the hold measured at rest (a swinging
            # cube would move it, and re-plan the route, at every step).
            if settled:
                self._offset = off
            on_table = goal[2] <= self._rest_z + 1e-3
            held = self._offset
            height = CARRY_HEIGHT_M if on_table else goal[2] - held[2]
            dest = (goal[0] - held[0], goal[1] - held[1], height)
            arm, at = self._transit(cmd, tool, q_cmd, dest, grasped=True)
            if at:
                self._enter(_Phase.PLACE if on_table else _Phase.HOLD)
            return arm, -1.0
        # At the goal the cube itself is steered, with the hold as it is now.
        over = (goal[0] - off[0], goal[1] - off[1])
        if phase is _Phase.PLACE:
            point = (*over, goal[2] + _PLACE_ABOVE_M - off[2])
            arm, at = straight(cmd, (*point, pitch_for(point, q_cmd)), self._controller, _SLOW)
            down = cube[2] - goal[2] < _DOWN_M  # the cube (almost) rests on the table
            on_goal = math.dist(cube[:2], goal[:2]) < _ON_GOAL_M
            if (
                (at or on_goal)
                and (down or self._count > _MAX_WAIT_STEPS)
                and (on_goal or self._count > 2 * _MAX_WAIT_STEPS)
            ):
                if self._jitter_now > _HOLD_JITTER_M:
                    self._enter(_Phase.HOLD)  # held on the goal: a release under noise knocks it
                    return arm, -1.0
                self._enter(_Phase.RELEASE)
                self._hold_at = cmd
                return [0.0, 0.0, 0.0, 0.0], 1.0
            return arm, -1.0
        # HOLD: follow the cube's offset in the hand (a table goal: the cube just above it).
        lift = _PLACE_ABOVE_M if goal[2] <= self._rest_z + 1e-3 else 0.0
        point = (*over, goal[2] + lift - off[2])
        arm, _ = straight(cmd, (*point, pitch_for(point, q_cmd)), self._controller)
        return arm, -1.0


class ReachExpert:
    """Scripted reach: a planned move of the tool point to the goal.

    The goal's pitch is pointing down where the IK reaches the goal so, else the
    nearest pitch that does.

    Args:
        env: A ``LynxReach`` env (wrapped or not) with ``control="tool"``.
        search: ``"cover"`` (default) or ``"exact"``, as :class:`PickAndPlaceExpert`'s.

    Raises:
        InvalidInputError: Another env or control mode, or an unknown ``search``.
    """

    def __init__(self, env: gym.Env[Any, Any], search: SearchWorld = "cover") -> None:
        u, controller = tool_env(env, ReachEnv)
        self._controller = controller
        self._roll_step = (
            controller.roll_step if isinstance(controller, ToolRollController) else 0.0
        )
        self._planner = Planner(u, controller, search)
        self._mover = Mover(self._planner, u.q_ready)
        self._idx = ReachEnv.OBS_INDEX
        self.reset()

    def reset(self) -> None:
        """Forget the episode (call after every ``env.reset``)."""
        self._mover.route = None
        self._planner.reset()

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (4,) (``-v2``: (5,)), float32 in [-1, 1].

        With the ``-v2`` action the roll is held at :data:`GRIP_ROLL_RAD`.
        """
        o = observation["observation"]
        ix = self._idx
        x, y, z = o[ix["commanded_tool_position"]].tolist()
        cmd: Pose = (x, y, z, float(o[ix["commanded_tool_pitch"]][0]))
        q_cmd = o[ix["commanded_joint_angles"]]
        goal: Point = tuple(observation["desired_goal"].tolist())
        dest = (*goal, pitch_for(goal, q_cmd))
        tool: Point = tuple(o[ix["tool_position"]].tolist())
        arm, _ = self._mover.step(cmd, tool, q_cmd, dest, grasped=False)
        if self._roll_step:
            roll = (GRIP_ROLL_RAD - float(q_cmd[4])) / self._roll_step
            arm.append(max(-1.0, min(1.0, roll)))
        return np.array(arm, dtype=np.float32)
