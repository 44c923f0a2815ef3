# %% [markdown]
# # 1. DH frames and forward kinematics
#
# The report describes the Lynxmotion arm with the *modified* (proximal, Craig)
# Denavit–Hartenberg convention: frame *i* is reached from frame *i−1* by
#
# `T(i-1, i) = RotX(alpha_{i-1}) · TransX(a_{i-1}) · RotZ(theta_i) · TransZ(d_i)`
#
# and the tool pose is the product of the five joint transforms and a fixed tool
# transform (98 mm along the last z axis). In this chapter you build that product
# yourself, compare it with `lynxsim.arm.fk`, reproduce the report's two worked
# examples and draw the frames.
#
# lynxsim works in SI units inside (metres, radians); the report's millimetres and
# degrees appear only at the edges.

# %%
import matplotlib.pyplot as plt
import numpy as np
from checks import check_dh_transform, check_fk_figure7, check_pitch_figure4

from lynxsim.arm import FRAME_NAMES, LYNX_ARM, fk, frame_transforms, tool_pose

# %% [markdown]
# ## The DH table
#
# `LYNX_ARM` holds the table once (a frozen dataclass); every other part of lynxsim,
# the MuJoCo model included, is checked against it.

# %%
print(
    f"{'i':>2} {'a_(i-1) [mm]':>13} {'alpha_(i-1) [deg]':>18} {'d_i [mm]':>9} {'offset [deg]':>13}"
)
for i, row in enumerate(LYNX_ARM.dh, start=1):
    print(
        f"{i:>2} {row.a * 1e3:13.1f} {np.degrees(row.alpha):18.1f} {row.d * 1e3:9.1f} "
        f"{np.degrees(row.theta_offset):13.1f}"
    )
print(f"tool: {LYNX_ARM.tool_length * 1e3:.0f} mm along the last z axis")
print("joint ranges [deg]:", np.degrees(LYNX_ARM.q_min).round(), np.degrees(LYNX_ARM.q_max).round())

# %% [markdown]
# ## Exercise 1.1 — the transform of one row
#
# Write `dh(alpha, a, theta, d)`, the 4×4 homogeneous transform of one row of the
# modified convention. (A solution follows; try it yourself first.)


# %%
def rot_x(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rot_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def translate(x, y, z):
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def dh(alpha, a, theta, d):
    return rot_x(alpha) @ translate(a, 0, 0) @ rot_z(theta) @ translate(0, 0, d)


check_dh_transform(dh)

# %% [markdown]
# ## Forward kinematics by hand
#
# Multiply the rows (joint angle plus the row's constant offset: joint 4 carries the
# report's −90°) and the tool transform, and compare with lynxsim on the report's
# first example (its Figure 4).


# %%
def my_fk(q):
    t = np.eye(4)
    for row, qi in zip(LYNX_ARM.dh, q, strict=True):
        t = t @ dh(row.alpha, row.a, qi + row.theta_offset, row.d)
    return t @ translate(0, 0, LYNX_ARM.tool_length)


q_fig4 = np.radians([-25.27, 100.5, -41.19, -13.62, 154.6])
print("by hand [mm]:", (my_fk(q_fig4)[:3, 3] * 1e3).round(2))
print("lynxsim [mm]:", (fk(q_fig4)[:3, 3] * 1e3).round(2))
print("report  [mm]: [107.31 -50.66 415.13]")
assert np.allclose(my_fk(q_fig4), fk(q_fig4), atol=1e-12)

# %% [markdown]
# `fk` is vectorised: any leading shape of joint vectors, one call. `tool_pose`
# names the parts: the tool point, the *pitch* (the angle of the wrist→tool line
# above the horizontal, q2 + q3 + q4) and the roll (q5, which turns the tool about its
# own axis and does not move the tool point).

# %%
pose = tool_pose(q_fig4)
print(
    "tool point [mm]:",
    (pose.position * 1e3).round(2),
    " pitch [deg]:",
    np.degrees(pose.pitch).round(2),
)
rng = np.random.default_rng(0)
q_many = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(10_000, 5))
print("10,000 poses at once:", fk(q_many).shape)

# %% [markdown]
# ## The frames, drawn
#
# `frame_transforms` gives every frame's pose (`frame_origins` just their origins); the
# links run between the origins. Each frame's x axis is drawn red and its z axis (the
# joint's axis) blue, 40 mm long: see how each z axis is the axis its joint turns about,
# and how frame 2's x axis lies along the upper arm (a_2 = 153 mm is measured along it).

# %%
fig = plt.figure(figsize=(12, 6.5))
cases = [
    ([-25.27, 100.5, -41.19, -13.62, 154.6], "report's Figure 4"),
    ([-6.61, 38.19, -144.24, 58.24, 63.00], "report's Figure 7"),
]
for k, (q_deg, title) in enumerate(cases):
    q = np.radians(q_deg)
    T = frame_transforms(q)
    p = T[:, :3, 3] * 1e3
    ax = fig.add_subplot(1, 2, k + 1, projection="3d")
    ax.plot(p[:, 0], p[:, 1], p[:, 2], "o-", color="grey", lw=3)
    for Ti in T:
        origin = Ti[:3, 3] * 1e3
        ax.quiver(*origin, *(Ti[:3, 0] * 40), color="tab:red")
        ax.quiver(*origin, *(Ti[:3, 2] * 40), color="tab:blue")
    for name, point in zip(FRAME_NAMES, p, strict=True):
        if name in ("frame2", "frame3", "frame4", "tool"):
            ax.text(*point, " " + name, fontsize=7)
    ax.set(xlabel="x [mm]", ylabel="y [mm]", zlabel="z [mm]", title=title)
    ax.set_xlim(-100, 250), ax.set_ylim(-175, 175), ax.set_zlim(-100, 450)
    ax.set_box_aspect((350, 350, 550))
plt.tight_layout()
plt.show()

# %% [markdown]
# ## Exercises
#
# **1.2** Compute the tool point, in millimetres, of the report's second example
# (its Figure 7): joints −6.61, 38.19, −144.24, 58.24, 63.00 degrees.
#
# **1.3** Compute the tool pitch of the report's first example, in degrees, from the
# joint angles alone (no FK).

# %%
tool_fig7_mm = fk(np.radians([-6.61, 38.19, -144.24, 58.24, 63.00]))[:3, 3] * 1e3
check_fk_figure7(tool_fig7_mm)

pitch_fig4_deg = 100.5 + (-41.19) + (-13.62)
check_pitch_figure4(pitch_fig4_deg)
