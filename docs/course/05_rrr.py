# %% [markdown]
# # 5. The 3-RRR: inverse kinematics, working modes, singularities
#
# The report's second robot is a planar parallel mechanism: three legs, each an
# actuated revolute joint at a base point B_i, a proximal link of 170 mm, a passive
# joint (the elbow), a distal link of 130 mm and a passive joint at the platform's
# joint P_i. The platform is a triangle whose joints lie on a 130 mm circle about its
# centre (x, y), turned by alpha.
#
# Inverse kinematics is *easy* for a parallel robot: given the platform pose, each
# P_i is known, and each leg is a two-link problem of its own. With d = P_i − B_i the
# proximal angle solves
#
# `d_x cos θ + d_y sin θ = (|d|² + s_a² − L²) / (2 s_a)`
#
# which has two solutions (the elbow on either side of the line B_i–P_i) when
# 40 mm ≤ |d| ≤ 300 mm. Three legs × two branches = the robot's **working modes**.
#
# The report's own code rotates the platform twice and the base once by alpha (see
# [the errata](../errata.md)); lynxsim implements the geometry as stated and lets the
# simulation judge.

# %%
import matplotlib.pyplot as plt
import numpy as np
from checks import check_leg_ik, check_unreachable_leg, check_working_modes

from lynxsim import rrr
from lynxsim.errors import UnreachablePlatformPoseError

g = rrr.RRR_ROBOT
print("base joints [mm]:\n", (np.asarray(g.base) * 1e3).round(2))

# %% [markdown]
# ## All working modes of one pose
#
# `rrr.ik` solves a batch of poses in every mode; `leg_points` gives the joints of each
# leg to draw. The report's first Figure 20 pose, (200, 150) mm, alpha = 0:

# %%
pose = np.array([0.200, 0.150, 0.0])
theta = rrr.ik_one(pose)
print("actuated angles of the 8 modes [deg]:\n", np.degrees(theta).round(1))

fig, axes = plt.subplots(2, 4, figsize=(12, 6))
for mode, ax in enumerate(axes.flat):
    legs = rrr.leg_points(pose, mode) * 1e3
    platform = rrr.platform_joints(pose) * 1e3
    ax.fill(platform[:, 0], platform[:, 1], color="tab:orange", alpha=0.5)
    for leg in legs:
        ax.plot(leg[:, 0], leg[:, 1], "o-", color="tab:blue")
    m = rrr.singularity_measures(pose, theta[mode])
    ax.set(
        title=f"mode {mode} ({rrr.mode_label(mode)})\nparallel {float(m.parallel):+.2f}",
        aspect="equal",
    )
    ax.set_xlim(-60, 560), ax.set_ylim(-60, 480)
    ax.tick_params(labelsize=6)
plt.tight_layout()
plt.show()

# %% [markdown]
# ## Singularities
#
# Two kinds matter (Gosselin and Angeles):
#
# * a **leg** (serial) singularity: a leg stretched or folded (its elbow's bend is 0
#   or 180°): the platform loses a direction of motion; `serial` measures it;
# * a **parallel** singularity: the distal links' lines meet in a point (or are
#   parallel): the platform gains a motion the actuators cannot resist; `parallel`
#   (the signed, normalised determinant of the platform Jacobian) measures it and
#   changes sign across one.
#
# The maps over the platform centre, alpha = 0 and 30°, in the report's working mode (7):
# white outside the workspace, colour the parallel measure, black its zero line (the
# parallel singularities the mode meets), triangles the base joints.

# %%
xs = np.linspace(0.005, 0.600, 240)
ys = np.linspace(0.005, 0.600, 240)
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
for ax, alpha_deg in zip(axes, (0.0, 30.0), strict=True):
    wmap = rrr.workspace_map(xs, ys, np.radians(alpha_deg))
    par = wmap.parallel[:, :, 7]
    im = ax.imshow(
        par, origin="lower", extent=(5, 600, 5, 600), cmap="coolwarm", vmin=-1.5, vmax=1.5
    )
    ax.contour(xs * 1e3, ys * 1e3, np.nan_to_num(par, nan=10.0), levels=[0.0], colors="k")
    ax.plot(*(np.asarray(g.base) * 1e3).T, "k^")
    ax.set(title=f"alpha = {alpha_deg:.0f} deg, mode 7", xlabel="x [mm]", ylabel="y [mm]")
fig.colorbar(im, ax=axes, label="parallel measure")
plt.show()
reach = np.isfinite(rrr.workspace_map(xs, ys, 0.0).serial)
print(f"reachable share of the square at alpha = 0: {reach.mean():.0%}")

# %% [markdown]
# ## Exercises
#
# **5.1** Solve one leg: `solve(b, p)` returns the two proximal angles [rad] for the base
# joint b and the platform joint p (mm). Write d_x cos θ + d_y sin θ = R cos(θ − φ) with
# R = |d| and φ = atan2(d_y, d_x).

# %%
SA, L = 170.0, 130.0


def solve(b, p):
    d = np.asarray(p, dtype=float) - np.asarray(b, dtype=float)
    rhs = (d @ d + SA**2 - L**2) / (2 * SA)
    phi = np.arctan2(d[1], d[0])
    half = np.arccos(np.clip(rhs / np.linalg.norm(d), -1.0, 1.0))
    return np.array([phi + half, phi - half])


check_leg_ik(solve)

# %% [markdown]
# **5.2** How many working modes has the 3-RRR?
#
# **5.3** The report draws the pose (300, 250, −40°) as reachable. Which leg cannot reach
# it, and how long would that leg need to be (|P_i − B_i|, mm)?

# %%
check_working_modes(2**3)

try:
    rrr.ik_one(np.array([0.300, 0.250, np.radians(-40.0)]))
except UnreachablePlatformPoseError as error:
    print(error)
span = rrr.ik(np.array([0.300, 0.250, np.radians(-40.0)])).leg_span * 1e3
leg = int(np.argmax(span)) + 1
check_unreachable_leg(leg, float(span.max()))
