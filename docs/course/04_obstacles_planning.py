# %% [markdown]
# # 4. Obstacles, the report's via points, planning vs the potential field
#
# The report puts a cylinder (radius 40 mm, axis at (150, 150) mm, 400 mm tall) in the
# way of its pick-and-place and answers it with hand-placed via points. It never
# checks the answer: its collisions were "not considered". lynxsim checks them with
# MuJoCo: contacts at every physics step and exact distances (`mj_geomDistance`)
# between the arm (with the cube it carries) and every obstacle.
#
# This chapter asks three questions: does the plain task hit the cylinder (yes, every
# type), why do the via points work (only for straight tool lines), and how a planner
# finds a way where the potential field the report suggested gets stuck.

# %%
import html
import os

os.environ.setdefault("MUJOCO_GL", "egl")  # off-screen rendering; before mujoco is imported

import matplotlib.pyplot as plt
import mujoco
import numpy as np
from checks import (
    REPO,
    check_cylinder_distance,
    check_potential_field_failure,
    check_via_point_verdicts,
)
from IPython.display import HTML

from lynxsim import robots
from lynxsim.arm import tool_pose
from lynxsim.arm.motion import arm_lipschitz, generate
from lynxsim.arm.motion.planning import arm_plan_request
from lynxsim.errors import LynxsimError
from lynxsim.plan import potential_field_segment
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.planning import CheckerOracle
from lynxsim.sim.render import RenderSettings, SceneRenderer
from lynxsim.sim.replay import export_replay
from lynxsim.tasks import load_task
from lynxsim.web.page import replay_page

plain = load_task(REPO / "tasks/pick_and_place.toml")
via = load_task(REPO / "tasks/obstacle_avoidance.toml")
print("obstacles:", plain.scene.obstacles)
print("via points [mm]:", [tuple(round(c * 1e3) for c in p.position) for p in via.poses])

# %% [markdown]
# ## The collision checker
#
# `arm_checker` answers, for a batch of joint vectors and without stepping physics,
# whether each is in collision and how far it is from every obstacle (the cube in the
# gripper counts as part of the arm).

# %%
model = load_arm_scene(plain.scene)
checker = arm_checker(model)


def clearance_mm(traj, rate_hz=200.0):
    t = traj.times_at_rate(rate_hz)
    result = checker.check(traj.sample(t).q, grasped=True)
    return t, result.clearance_m[:, 0] * 1e3, result.in_collision


fig, axes = plt.subplots(1, 2, figsize=(11, 3.5), sharey=True)
verdicts = {}
for ax, task in zip(axes, (plain, via), strict=True):
    for kind in ("free", "cubic", "quintic", "lspb", "line"):
        traj = generate(kind, task.poses, None if kind == "line" else 1.0)
        t, c, hit = clearance_mm(traj)
        verdicts[(task.name, kind)] = bool(hit.any())
        ax.plot(t, c, label=f"{kind}: {'HITS' if hit.any() else 'clear'}, min {c.min():.1f} mm")
    ax.axhline(0, color="k", lw=0.8)
    ax.set(title=task.name, xlabel="t [s]")
    ax.legend(fontsize=7)
axes[0].set_ylabel("clearance to the cylinder [mm]")
plt.tight_layout()
plt.show()
kinds = ("free", "cubic", "quintic", "lspb", "line")
assert all(verdicts[("pick_and_place", k)] for k in kinds)  # what the text below says
assert [k for k in kinds if not verdicts[("obstacle_avoidance", k)]] == ["line"]

# %% [markdown]
# The plain task hits in every type. With the via points, only the straight line keeps
# clear (by about 13 mm): the via points were placed so that the *straight segments*
# between them pass the cylinder; interpolated in joint space the leg from (80, 250, 300)
# to (80, 0, 300) swings the hand around the base and through the cylinder — which
# the report did not notice.
#
# Seen from above, the tool paths through the via points (dots): the straight line turns
# at each via point and runs between the base and the cylinder (x = 80 mm, 30 mm from
# its surface); the quintic, interpolating the joints, bulges outwards between (80, 250)
# and (80, 0) — straight through the cylinder.

# %%
fig, ax = plt.subplots(figsize=(5, 5))
for kind in ("line", "quintic"):
    traj = generate(kind, via.poses, None if kind == "line" else 1.0)
    p = tool_pose(traj.sample(traj.times_at_rate(200.0)).q).position * 1e3
    ax.plot(p[:, 0], p[:, 1], label=kind)
vp = np.array([pose.position for pose in via.poses]) * 1e3
ax.plot(vp[:, 0], vp[:, 1], "ko", label="via points")
ax.add_patch(plt.Circle((150, 150), 40, color="tab:red", alpha=0.4, label="cylinder"))
ax.set(
    xlabel="x [mm]", ylabel="y [mm]", aspect="equal", title="obstacle_avoidance, seen from above"
)
ax.legend(fontsize=8)
plt.show()

# %% [markdown]
# ## In the physics
#
# The checker reasons about commanded joints; the simulation plays them through the
# torque-limited servos, with the cube gripped by friction. Here is the via-point line,
# and the plain quintic, and a frame of the latter at its first contact, rendered off-screen
# with EGL.

# %%
runs = {}
for task, kind in ((via, "line"), (plain, "quintic")):
    traj = generate(kind, task.poses, None if kind == "line" else 1.0)
    playback = run_arm_trajectory(traj, task=task.name, scene=task.scene)
    report = playback.report
    runs[kind] = playback
    first = report.obstacle.first_time_s if report.obstacle and report.obstacle.collided else None
    print(
        f"{task.name:20} {kind:8} collided: {first is not None} (first contact "
        f"{first if first is None else round(first, 3)} s), min clearance "
        f"{report.min_clearance_m * 1e3:.1f} mm, tool max error {report.tool_max_error_m * 1e3:.1f} mm"
    )

log = runs["quintic"].log
step = int(np.argmax(log.time_s >= runs["quintic"].report.obstacle.first_time_s))
data = mujoco.MjData(model)
data.qpos[:] = log.qpos[step]
mujoco.mj_kinematics(model, data)
mujoco.mj_camlight(model, data)
with SceneRenderer(model, RenderSettings(width=640, height=480, camera="front")) as renderer:
    frame = renderer.render(data)
plt.figure(figsize=(6.4, 4.8))
plt.imshow(frame)
plt.axis("off")
plt.title(f"pick_and_place, quintic, t = {log.time_s[step]:.2f} s: the hand meets the cylinder")
plt.show()

# %% [markdown]
# The same run as a replay page (`lynxsim play --html` writes one per run): drag to turn
# the view, scroll to zoom, scrub the time slider; contacts are marked on the timeline
# and painted red while they last, beside the clearance curve and the run's verdicts.

# %%
page = replay_page(
    export_replay(model, log, runs["quintic"].report, title="pick_and_place: quintic")
)
HTML(
    f'<div><iframe srcdoc="{html.escape(page)}" style="width: 100%; height: 900px; border: 0">'
    "</iframe></div>"
)

# %% [markdown]
# ## Exercise 4.1 — distance to the cylinder
#
# Write `distance(p_mm)`: the signed distance [mm] from points (N, 3) to the report's
# solid cylinder (negative inside). Then use it on the tool path of the via-point line:
# the *tool point* keeps much more than the 13 mm that the whole arm and cube keep.


# %%
def distance(p):
    radial = np.hypot(p[:, 0] - 150.0, p[:, 1] - 150.0) - 40.0
    axial = np.maximum(0.0 - p[:, 2], p[:, 2] - 400.0)
    outside = np.hypot(np.maximum(radial, 0.0), np.maximum(axial, 0.0))
    return np.where((radial <= 0) & (axial <= 0), np.maximum(radial, axial), outside)


check_cylinder_distance(distance)
line = generate("line", via.poses)
tool_mm = tool_pose(line.sample(line.times_at_rate(200.0)).q).position * 1e3
print(f"the via-point line's tool point keeps {distance(tool_mm).min():.1f} mm from the cylinder")

# %% [markdown]
# **4.2** Which of `line` and `quintic` collide on the via-point task?

# %%
check_via_point_verdicts(
    {
        "line": verdicts[("obstacle_avoidance", "line")],
        "quintic": verdicts[("obstacle_avoidance", "quintic")],
    }
)

# %% [markdown]
# ## Planning vs the potential field
#
# The report suggests a potential field as future work: descend an attraction to the
# goal plus a repulsion from the obstacles. lynxsim has one
# (`lynxsim.plan.potential_field_segment`) beside sampling-based planning: RRT-Connect,
# by default compiled with numba on a sphere cover of the arm (`planner="compiled"`; the
# first call in a fresh checkout compiles it, about a minute of CPU, then it is cached on
# disk), or any of OMPL's planners (`planner="RRTConnect"`, `"BITstar"`, ...). All work in
# joint space against the same world and certify every edge clear with a Lipschitz bound
# (no point of the arm moves more than L·|Δq|). Try them on the plain task, whose
# segment P2 → P3 is blocked:

# %%
request = arm_plan_request(plain.poses, grasped=True)
oracle = CheckerOracle(checker)
start = generate("quintic", plain.poses[:2], 1.0).sample(np.array([1.0])).q[0]
goals = request.goal_sets[1]
try:
    seg = potential_field_segment(
        start,
        goals,
        oracle,
        request.bounds.lower_array,
        request.bounds.upper_array,
        lipschitz=arm_lipschitz(),
        grasped=True,
        label="P2 -> P3",
    )
    print("potential field reached the goal:", seg.length_rad)
except LynxsimError as error:
    print(type(error).__name__, ":", error)

ompl_motion = robots.plan(robots.get("arm"), plain, planner="RRTConnect", seed=0)
print(f"OMPL's RRT-Connect: {ompl_motion.trajectory.duration:.2f} s of motion")
motion = robots.plan(robots.get("arm"), plain, seed=0)
print(f"compiled RRT-Connect (the default): {motion.trajectory.duration:.2f} s of motion")
for seg in motion.segments:
    print(
        f"{seg.label:10} {seg.planner:11} {seg.planning_time_s:6.3f} s  clearance >= {seg.min_clearance_m * 1e3:5.1f} mm"
    )
t, c, hit = clearance_mm(motion.trajectory)
print(
    f"planned: {motion.trajectory.duration:.2f} s of motion, collides: {hit.any()}, min clearance {c.min():.1f} mm"
)

# %%
fig, ax = plt.subplots(figsize=(5, 5))
for name, traj in (
    ("quintic", generate("quintic", plain.poses, 1.0)),
    ("planned", motion.trajectory),
):
    p = tool_pose(traj.sample(traj.times_at_rate(200.0)).q).position * 1e3
    ax.plot(p[:, 0], p[:, 1], label=name)
ax.add_patch(plt.Circle((150, 150), 40, color="tab:red", alpha=0.4, label="cylinder"))
ax.set(xlabel="x [mm]", ylabel="y [mm]", aspect="equal", title="tool paths, seen from above")
ax.legend()
plt.show()

# %% [markdown]
# The planner goes over or around; the potential field stops where the pull of the
# goal and the push of the cylinder cancel. Over 300 random blocked scenes
# ([benchmarks](../benchmarks.md)) RRT-Connect solves all, the potential field about
# one in five.
#
# **4.3** Why did the potential field stop? (a) the goal is out of reach, (b) a local
# minimum where attraction and repulsion cancel, (c) the obstacle moved, (d) a joint
# limit was violated.

# %%
check_potential_field_failure("b")
