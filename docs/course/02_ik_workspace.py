# %% [markdown]
# # 2. Inverse kinematics, its branches, and the workspace
#
# Inverse kinematics asks the opposite question: which joint angles put the tool at a
# point (x, y, z) with a pitch φ? The report solves it in closed form (its eqs. 10–34,
# one sign corrected, see [the errata](../errata.md)):
#
# 1. the base angle q1 = atan2(y, x) turns the arm's vertical plane towards the target;
# 2. the wrist point lies 98 mm back from the tool point along the pitch direction;
# 3. the shoulder and the elbow (q2, q3) are a **two-link planar problem**, 153 mm each,
#    with two solutions, elbow up and elbow down; with the two sides of the base
#    (q1 and q1 ± 180°, leaning back over the base) that makes **four candidates**;
# 4. q4 = φ − q2 − q3.
#
# The joint ranges then keep some candidates and discard the others.

# %%
import matplotlib.pyplot as plt
import numpy as np
from checks import check_elbow_p1, check_ik_p2, check_two_link_ik, check_wrist_reach

from lynxsim.arm import (
    LYNX_ARM,
    frame_origins,
    ik,
    ik_one,
    jacobian,
    manipulability,
    sample_workspace,
    tool_pose,
)
from lynxsim.errors import OutOfReachError

# %% [markdown]
# ## The four candidates
#
# `lynxsim.arm.ik` takes a batch of targets and returns, per target, the four
# candidates, which of them are valid, and the one it selects. The report's P1 — the
# cube on the table, the gripper pointing straight down:

# %%
p1 = np.array([[0.0, 0.3, 0.0]])
result = ik(p1, np.radians([-90.0]))
for k, (cand, valid) in enumerate(zip(result.candidates[0], result.valid[0], strict=True)):
    print(f"candidate {k}: {np.degrees(cand).round(2)} deg  valid: {bool(valid)}")
print("selected:", np.degrees(result.q[0]).round(2), "(report: 90, 15.89, -18.47, -87.42)")

# %% [markdown]
# Every candidate puts the tool on the target (FK maps it back), valid or not:
# the ranges, not the geometry, choose.

# %%
for cand in result.candidates[0]:
    print((tool_pose(cand).position * 1e3).round(6), np.degrees(tool_pose(cand).pitch).round(6))

# %% [markdown]
# Draw the two elbow branches that stay on the target's side of the base:

# %%
fig, ax = plt.subplots(figsize=(5, 4))
for cand, valid in zip(result.candidates[0], result.valid[0], strict=True):
    p = frame_origins(cand) * 1e3
    r = np.hypot(p[:, 0], p[:, 1]) * np.sign(p[:, 1] + 1e-12)
    style = "-o" if valid else "--o"
    ax.plot(
        r,
        p[:, 2],
        style,
        label=f"{np.degrees(cand[1:4]).round(1)} {'valid' if valid else 'out of range'}",
    )
ax.axhline(0, color="grey", lw=0.5)
ax.set(
    xlabel="signed reach in the arm's plane [mm]",
    ylabel="z [mm]",
    title="P1: the IK candidates",
    aspect="equal",
)
ax.legend(fontsize=7)
plt.show()

# %% [markdown]
# `ik_one` solves one target and raises a typed error when there is no solution:

# %%
print(np.degrees(ik_one(np.array([0.0, 0.3, 0.0]), np.radians(-90))).round(2))
try:
    ik_one(np.array([0.6, 0.0, 0.0]), 0.0)
except OutOfReachError as error:
    print("OutOfReachError:", error)

# %% [markdown]
# ## The workspace
#
# The *reachable* workspace (the report calls it "dexterous", which is something else:
# the points reachable with every orientation) is the set of tool points of all joint
# vectors in range. Sample it:

# %%
samples = sample_workspace(40_000, np.random.default_rng(0))
r = np.hypot(samples.position[:, 0], samples.position[:, 1]) * 1e3
z = samples.position[:, 2] * 1e3
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
axes[0].scatter(samples.position[:, 0] * 1e3, samples.position[:, 1] * 1e3, s=0.2, alpha=0.3)
axes[0].set(xlabel="x [mm]", ylabel="y [mm]", title="seen from above", aspect="equal")
sc = axes[1].scatter(r, z, s=0.2, c=np.degrees(samples.pitch), cmap="coolwarm", alpha=0.5)
axes[1].set(
    xlabel="distance from the base axis [mm]",
    ylabel="z [mm]",
    title="side view (colour: pitch)",
    aspect="equal",
)
fig.colorbar(sc, ax=axes[1], label="pitch [deg]")
plt.tight_layout()
plt.show()
print(f"farthest tool point from the base axis: {r.max():.0f} mm")

# %% [markdown]
# ## Where the two branches meet: the stretched elbow
#
# The elbow-up and elbow-down solutions merge when q3 = 0 (the arm stretched) — the
# boundary of the workspace. There the arm loses a direction of motion: the Jacobian of
# the tool point and pitch (`jacobian`, 4×5) drops rank, and Yoshikawa's manipulability
# √det(J Jᵀ) goes to zero.

# %%
q3 = np.radians(np.linspace(-145, 0, 300))
q = np.zeros((300, 5))
q[:, 1], q[:, 2], q[:, 3] = np.radians(60), q3, -np.radians(60) - q3
w = manipulability(q, kind="position_pitch")
plt.figure(figsize=(6, 3))
plt.plot(np.degrees(q3), w)
plt.xlabel("q3 [deg]")
plt.ylabel("manipulability [m³]")
plt.title("q2 = 60°, pitch 0: the stretched elbow (q3 = 0) is singular")
plt.show()
print(
    "rank of J at q3 = -60 deg:",
    np.linalg.matrix_rank(jacobian(q[np.argmin(abs(q3 + np.radians(60)))])),
)
print("rank of J at q3 = 0:", np.linalg.matrix_rank(jacobian(q[-1]), tol=1e-9))

# %% [markdown]
# ## Exercises
#
# **2.1** Write the two-link planar IK: `solve(r, z)` returns both branches
# `[(q2, q3), (q2, q3)]` [rad] for the wrist point (r, z) relative to the shoulder,
# with l2 = l3 = 153 mm (law of cosines for q3, then q2 from the angle to the target).

# %%
L2 = L3 = 153.0


def solve(r, z):
    c3 = (r**2 + z**2 - L2**2 - L3**2) / (2 * L2 * L3)
    branches = []
    for s3 in (np.sqrt(1 - c3**2), -np.sqrt(1 - c3**2)):
        q3 = np.arctan2(s3, c3)
        q2 = np.arctan2(z, r) - np.arctan2(L3 * s3, L2 + L3 * c3)
        branches.append((q2, q3))
    return branches


check_two_link_ik(solve)

# %% [markdown]
# **2.2** Solve P2 = (0, 250, 300) mm with pitch 0: q1..q4 in degrees.
#
# **2.3** Where is the elbow (the origin of joint 3's frame, `frame3`) at P1, in mm?
#
# **2.4** How far from the shoulder can the wrist be, in mm?

# %%
q_p2_deg = np.degrees(ik_one(np.array([0.0, 0.25, 0.3]), 0.0))
check_ik_p2(q_p2_deg)

elbow_p1_mm = frame_origins(ik_one(np.array([0.0, 0.3, 0.0]), np.radians(-90)))[3] * 1e3
check_elbow_p1(elbow_p1_mm)

check_wrist_reach((LYNX_ARM.upper_arm + LYNX_ARM.forearm) * 1e3)
