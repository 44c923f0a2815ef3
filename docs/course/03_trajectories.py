# %% [markdown]
# # 3. Trajectories: types, continuity, Cartesian lines vs joint space
#
# A path says *where*; a trajectory says *when*. The report moves the arm through its
# pick-and-place poses P1…P5 with several trajectory types, and lynxsim implements
# each as an object sampled by time (`duration`, `sample(t)` → position, velocity,
# acceleration and jerk of every joint):
#
# | type | how | smooth up to |
# |---|---|---|
# | `free` | the report's linear joint increments | position |
# | `cubic` | a cubic per segment, zero end velocities | velocity |
# | `quintic` | a quintic per segment, zero end velocities and accelerations | acceleration |
# | `lspb` | linear segments with parabolic blends | velocity |
# | `line` | a straight tool line, IK at every sample | acceleration |
# | `ruckig` | time-optimal, jerk-limited (Ruckig) | acceleration |
#
# This chapter makes them, looks at their derivatives, and compares the tool paths of
# joint-space types with the straight line.

# %%
import matplotlib.pyplot as plt
import numpy as np
from checks import REPO, check_continuity, check_point_segment_distance, check_quintic_coefficients

from lynxsim.arm import tool_pose
from lynxsim.arm.motion import generate
from lynxsim.tasks import load_task

task = load_task(REPO / "tasks/pick_and_place.toml")
for pose in task.poses:
    print(
        pose.name,
        np.round(np.array(pose.position) * 1e3, 1),
        "mm, pitch",
        round(np.degrees(pose.pitch)),
        "deg",
    )

# %% [markdown]
# ## One second per segment, every type
#
# Sample each at 500 Hz and plot the shoulder joint (q2) with its velocity and
# acceleration. Look at the waypoints (the dotted lines).

# %%
kinds = ["free", "cubic", "quintic", "lspb", "ruckig"]
trajs = {k: generate(k, task.poses, 1.0 if k != "ruckig" else None, stretch=True) for k in kinds}
fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
for kind, traj in trajs.items():
    t = traj.times_at_rate(500.0)
    s = traj.sample(t)
    for ax, values in zip(axes, (s.q, s.qd, s.qdd), strict=True):
        ax.plot(t, values[:, 1], label=kind)
for ax, label in zip(axes, ("q2 [rad]", "q2' [rad/s]", "q2'' [rad/s²]"), strict=True):
    ax.set_ylabel(label)
    for tw in trajs["quintic"].waypoint_times:
        ax.axvline(tw, color="grey", ls=":", lw=0.8)
axes[0].legend(ncol=5, fontsize=8)
axes[2].set_xlabel("t [s]")
plt.tight_layout()
plt.show()

# %% [markdown]
# Numerically: the largest jump of velocity and of acceleration from one sample to the
# next (at 10 kHz a continuous quantity barely changes between samples; a jump stays).

# %%
jumps = {}
print(f"{'type':8} {'duration [s]':>12} {'max velocity step':>18} {'max acceleration step':>22}")
for kind, traj in trajs.items():
    s = traj.sample(traj.times_at_rate(10_000.0))
    dv = np.abs(np.diff(s.qd, axis=0)).max()
    da = np.abs(np.diff(s.qdd, axis=0)).max()
    print(f"{kind:8} {traj.duration:12.2f} {dv:18.4f} {da:22.4f}")
    jumps[kind] = (dv, da)
assert jumps["free"][0] > 0.1  # what the text below says
assert all(jumps[k][0] < 0.01 < 1.0 < jumps[k][1] for k in ("cubic", "lspb"))
assert all(jumps[k][1] < 0.1 for k in ("quintic", "ruckig"))

# %% [markdown]
# `free` jumps in velocity at every waypoint (the servos feel it as a kick), `cubic`
# and `lspb` in acceleration, `quintic` and `ruckig` in neither; `ruckig` also finds
# the shortest durations within the servo limits.
#
# ## Exercise 3.1 — the quintic
#
# Write `coefficients(q0, qf, T)`: a0…a5 of the quintic from q0 to qf in T seconds with
# zero velocity and acceleration at both ends. (The report's matrix for this, its
# eq. 52, has two typos; see the errata.)


# %%
def coefficients(q0, qf, T):
    h = qf - q0
    return np.array([q0, 0.0, 0.0, 10 * h / T**3, -15 * h / T**4, 6 * h / T**5])


check_quintic_coefficients(coefficients)

# %% [markdown]
# ## Cartesian lines vs joint space
#
# Joint-space types interpolate the *joints*; the tool then follows a curve. The `line`
# type solves the IK at every sample so that the tool moves on the straight segment
# between the poses. Compare the tool paths from P2 to P3 (a quarter turn of the base
# at 300 mm height):


# %%
def distance_to_segment(p, a, b):
    ab = b - a
    t = np.clip((p - a) @ ab / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


check_point_segment_distance(distance_to_segment)

line = generate("line", task.poses)
paths = {"quintic": trajs["quintic"], "line": line}
a, b = np.array(task.poses[1].position), np.array(task.poses[2].position)
fig, ax = plt.subplots(figsize=(5, 5))
for kind, traj in paths.items():
    t0, t1 = traj.waypoint_times[1], traj.waypoint_times[2]
    tool = tool_pose(traj.sample(np.linspace(t0, t1, 400)).q).position
    dev = distance_to_segment(tool, a, b).max() * 1e3
    ax.plot(tool[:, 0] * 1e3, tool[:, 1] * 1e3, label=f"{kind}: {dev:.1f} mm off the line")
ax.plot([a[0] * 1e3, b[0] * 1e3], [a[1] * 1e3, b[1] * 1e3], "k:", label="straight segment P2-P3")
ax.add_patch(plt.Circle((150, 150), 40, color="tab:red", alpha=0.4, label="the report's cylinder"))
ax.set(xlabel="x [mm]", ylabel="y [mm]", aspect="equal", title="tool path P2 → P3, seen from above")
ax.legend(fontsize=8)
plt.show()

# %% [markdown]
# The joint-space path swings around the base on an arc (q1 turns while the reach stays);
# the straight line cuts the corner — and here both meet the report's cylinder, which
# stands in the way. That is the next chapter.
#
# ## Exercise 3.2 — continuity
#
# From the plots and the table above: for each type, the highest derivative that stays
# continuous through the waypoints ("position", "velocity" or "acceleration").

# %%
check_continuity(
    {
        "free": "position",
        "cubic": "velocity",
        "quintic": "acceleration",
        "lspb": "velocity",
        "line": "acceleration",
        "ruckig": "acceleration",
    }
)
