# %% [markdown]
# # 6. A first learning agent
#
# `lynxsim.envs` registers Gymnasium environments of the arm. `LynxReach-v1` is the
# easy one: move the tool point to a goal (a point above the table) within 100 steps
# of 40 ms, the report's cylinder standing by. Actions move the commanded tool point
# by up to 15 mm per step along x, y, z (and the pitch by 0.1 rad); the closed-form IK
# turns them into servo targets. The observation is a dict: the goal, the achieved
# point, and 26 numbers about the arm.
#
# A learner does not need to know any of the kinematics of the previous chapters. Here
# is a small one that learns in seconds on a CPU: **random search** over a linear
# policy (Mania, Guy and Recht, 2018), `action = clip(W · features)`, features the
# goal's offset from the commanded tool point (in steps of 15 mm) and a constant.

# %%
import os

os.environ.setdefault("MUJOCO_GL", "egl")  # off-screen rendering; before mujoco is imported

import gymnasium as gym
import matplotlib.pyplot as plt
import numpy as np
from checks import check_agent, check_sparse_reward

import lynxsim.envs

gym.register_envs(lynxsim.envs)
env = gym.make("LynxReach-v1")
print(env.action_space, env.observation_space["observation"].shape, env.spec.max_episode_steps)
IDX = env.unwrapped.OBS_INDEX

# %% [markdown]
# ## The goal-conditioned reward
#
# The env's reward is sparse: −1 while the tool point is farther than 25 mm from the
# goal, 0 within. `compute_reward(achieved, desired, info)` recomputes it for any goals,
# vectorised — what hindsight experience replay (HER) relabels with.
#
# **Exercise 6.1** Write that reward yourself, vectorised: `reward(achieved, desired)`.


# %%
def reward(achieved, desired):
    distance = np.linalg.norm(np.asarray(achieved) - np.asarray(desired), axis=-1)
    return np.where(distance > 0.025, -1.0, 0.0)


check_sparse_reward(reward)
obs, info = env.reset(seed=0)
fake = np.stack([obs["desired_goal"] + [0.0, 0.0, dz] for dz in (0.0, 0.02, 0.03)])
goals = np.repeat(obs["desired_goal"][None], 3, axis=0)
print("env:", env.unwrapped.compute_reward(fake, goals, {}), " yours:", reward(fake, goals))

# %% [markdown]
# ## Random search
#
# Each iteration tries a few random perturbations δ of W, each both ways (W ± νδ), on the
# same goal, scores every rollout by its summed negative distance (a dense score, so
# the search sees progress before the first success), and steps W along the
# differences, normalised by their spread.


# %%
def features(obs):
    offset = (obs["desired_goal"] - obs["observation"][IDX["commanded_tool_position"]]) / 0.015
    return np.append(offset, 1.0)


def rollout(W, seed, steps=60):
    obs, info = env.reset(seed=seed)
    score = 0.0
    for _ in range(steps):
        action = np.append(np.clip(W @ features(obs), -1.0, 1.0), 0.0).astype(np.float32)
        obs, _reward, _terminated, _truncated, info = env.step(action)
        score -= np.linalg.norm(obs["achieved_goal"] - obs["desired_goal"])
    return score, bool(info["is_success"])


rng = np.random.default_rng(0)
W = np.zeros((3, 4))
nu, step_size, directions = 0.5, 0.3, 6
history = []
for _ in range(30):
    deltas = rng.standard_normal((directions, 3, 4))
    seed = int(rng.integers(10_000))
    plus = np.array([rollout(W + nu * d, seed)[0] for d in deltas])
    minus = np.array([rollout(W - nu * d, seed)[0] for d in deltas])
    spread = np.concatenate([plus, minus]).std() + 1e-9
    W += step_size / (directions * spread) * np.einsum("k,kij->ij", plus - minus, deltas)
    history.append(np.mean(np.concatenate([plus, minus])))
plt.figure(figsize=(6, 3))
plt.plot(history, "o-")
plt.xlabel("iteration")
plt.ylabel("mean score (−Σ distance [m])")
plt.title("random search on LynxReach-v1")
plt.show()
print("learned W:\n", W.round(2))
assert all(np.argmax(np.abs(W[i, :3])) == i for i in range(3))  # the diagonal dominates

# %% [markdown]
# The learned W is dominated by its diagonal: move towards the goal along each axis.
# Evaluate it on goals it never trained on (seeds 20000 on), a full episode each:

# %%
held_out = [rollout(W, 20_000 + k, steps=100)[1] for k in range(20)]
rate = float(np.mean(held_out))
print(f"success on 20 held-out goals: {rate:.0%}")

# %% [markdown]
# What it looks like at the end of a held-out episode (an EGL frame of the env's own
# renderer; the goal is the small green sphere):

# %%
viewer = gym.make("LynxReach-v1", render_mode="rgb_array")
obs, info = viewer.reset(seed=20_000)
for _ in range(100):
    action = np.append(np.clip(W @ features(obs), -1.0, 1.0), 0.0).astype(np.float32)
    obs, _reward, _terminated, _truncated, info = viewer.step(action)
plt.figure(figsize=(6.4, 4.8))
plt.imshow(viewer.render())
plt.axis("off")
plt.title(f"distance to the goal: {info['distance'] * 1e3:.1f} mm")
plt.show()
viewer.close()

# %% [markdown]
# **Exercise 6.2** Train and evaluate your agent (the cells above); the check wants at
# least 80 % over at least 20 held-out episodes. For more, the repository's
# `examples/sac_her_reach.py` trains SAC with HER on the same env (see
# [learning](../learning.md)).

# %%
check_agent(rate, len(held_out))
env.close()
