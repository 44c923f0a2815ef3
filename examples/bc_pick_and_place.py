"""Behaviour cloning of the scripted pick-and-place expert on ``LynxPickAndPlace-v2``.

The script records (unless it is there already) a dataset of ``--episodes``
episodes of lynxsim's scripted expert (:class:`lynxsim.envs.PickAndPlaceExpert`)
with Gaussian action noise of ``--noise`` x the action range on every step, with
:func:`lynxsim.datasets.write_dataset` (episode i reset with seed ``--seed`` + i).
The noise drives the arm off the expert's path, and every step stores the
expert's clean action for the state reached (``infos/expert_action``): the
policy clones those labels (DART-style), so it also learns how the expert
recovers from the small errors a clone makes.

The expert is a phase machine (approach, align, plunge, grasp, lift, carry,
place, release, retreat; hold for a goal in the air) with step counters and
thresholds of a few millimetres, so one observation often allows two expert
actions: above the cube it may still be settling or already descending,
depending on a phase it does not show. A policy of the observation alone
stalls there (a regression averages the two; 0.2-0.6 held-out success in our
runs). So the policy also learns the phase: the expert is deterministic given
its observations, and replaying it on each recorded episode (reset with the
episode's seed, fed the recorded observations) gives back the recorded clean
actions, which this script checks, and the expert's phase after each step.
The policy predicts that phase along with the action and feeds its own
prediction back as an input at the next step (with the number of steps spent
in it): a learned phase machine. The expert is used only to label the
dataset; the evaluated policy runs on its own.

The policy is an MLP (PyTorch). Inputs: the 45-D observation, the goal, five
relative vectors (goal minus cube, tool point and commanded tool point; cube
minus tool point and commanded tool point), the same on a logarithmic scale
(``asinh(v / 2 mm)``, which separates the millimetres the expert's decisions
hang on), the tool point's and the command's offsets from the obstacle's axis
and distances to its surface, how many steps ago the commanded gripper last
switched, and the phase (one-hot) with its step count; each entry is
normalised with the dataset's mean and standard deviation, the latter floored
at 1e-3 so that constant entries (the commanded wrist roll) stay finite.
Outputs: for each arm action (tool deltas x, y, z and pitch) a categorical
distribution over 41 values from -1 to 1 (trained on two-hot targets, acted on
by its mode), the logit of "gripper open" (the expert's gripper action is
always -1 or +1) and the phase logits. Loss: arm cross-entropy + 0.25 gripper
binary cross-entropy + phase cross-entropy, Adam with a cosine step size.

Every ``--eval-every`` epochs (and before training and after the last epoch)
the deterministic policy runs on ``--eval-seeds`` held-out episodes reset with
seeds 10_000 + i (the dataset's seeds must lie below 10_000); success is
``info["is_success"]`` at an episode's last step, and an episode with any
arm–obstacle contact (``info["collision"]``) counts as a contact episode.
Written into ``--out``, each file to a temporary name and then renamed:

- ``curve.csv``: epoch, wall-clock seconds since the start (recording
  included), mean training loss of the epoch, held-out success rate, contact
  episodes, mean final cube–goal distance [m] (rewritten after each evaluation);
- ``curve.png``: held-out success and contact episodes against epochs, and the
  training loss in a second panel;
- ``model.pt``: the final policy; ``torch.load(path, weights_only=False)`` gives
  a dict with the MLP's ``state_dict``, its ``hidden`` widths, ``bins``, the
  features' normalisation ``mean`` and ``std``, the ``phases``' names, the
  ``obstacles`` the features use and the arguments.

Run it from the repository root, in the project's virtualenv with ``torch``
installed (lynxsim never imports torch, nor this file)::

    .venv/bin/python examples/bc_pick_and_place.py

A dataset folder from an earlier run is reused; one that the library's expert
no longer replays (the expert changed since) is refused with a message: remove
it, or pass another ``--dataset``.

Budget and result: the defaults (200 episodes at noise 0.1, 150 epochs, an
evaluation every 10 epochs on 50 held-out seeds, one torch thread) take about
6 minutes of wall-clock time on a shared 2-core x86-64 CPU (recording 35 s,
replay 15 s, training 3 min, 16 evaluations of 5 s) and end at a held-out
success rate of about 0.9 (45/50 in our run; see the report printed at the
end), with arm–obstacle contact in about 5 of the 50 episodes (on ``-v1``; on
``-v2``: 0.90, 45/50, contact in 5, 16 minutes at load 5-7). The expert
itself, without noise, succeeds on all 50 held-out seeds without contact.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
import time
from collections.abc import Sequence
from dataclasses import astuple, dataclass, fields
from pathlib import Path
from typing import Any

import gymnasium as gym
import matplotlib

matplotlib.use("Agg")

# isort: split
import matplotlib.pyplot as plt
import numpy as np
import numpy.typing as npt
import torch
from torch import nn

import lynxsim.envs
from lynxsim.datasets import Episode, read_npz, write_dataset
from lynxsim.datasets.layout import default_dataset_id
from lynxsim.fileio import atomic_path

ENV_ID = lynxsim.envs.PICK_AND_PLACE_V2_ID
"""The env cloned on (``LynxPickAndPlace-v2``: tool x, y, z, pitch, roll, then the gripper)."""
EVAL_SEED_BASE = 10_000
"""Held-out episode i is reset with seed ``EVAL_SEED_BASE + i``; dataset seeds stay below."""
STD_FLOOR = 1e-3
"""Smallest divisor of a feature's normalisation (in its units: m, rad, m/s, steps)."""
FINE_M = 0.002
"""Scale of the logarithmic relative positions [m]."""
GRIP_HALF_OPEN_M = 0.015
"""A commanded gripper opening below this [m] counts as closing (gripper action < 0)."""
COUNT_CAP = 30
"""The step counters of the policy's memory stop at this."""
GRIP_WEIGHT = 0.25
"""Weight of the gripper's binary cross-entropy in the loss."""
OBS_KEYS = ("observation", "achieved_goal", "desired_goal")
"""The entries of the env's observation dict."""

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


@dataclass(frozen=True)
class EvalPoint:
    """One evaluation on the held-out episodes.

    Attributes:
        epoch: Training epochs done when it ran.
        wall_s: Wall-clock time since the script started [s].
        train_loss: Mean training loss of the last epoch (NaN before training).
        success_rate: Fraction of episodes with ``info["is_success"]`` at their last step.
        contact_episodes: Episodes with an arm–obstacle contact on any step.
        mean_final_distance_m: Mean cube–goal distance at the last step [m].
    """

    epoch: int
    wall_s: float
    train_loss: float
    success_rate: float
    contact_episodes: int
    mean_final_distance_m: float


def parse_args(argv: Sequence[str] | None = None) -> argparse.Namespace:
    """Parse the command line.

    Args:
        argv: The arguments (None: ``sys.argv[1:]``).

    Returns:
        The parsed arguments.
    """
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n", 1)[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    p.add_argument(
        "--dataset",
        type=Path,
        default=Path("datasets_scratch/bc_pick_and_place"),
        metavar="DIR",
        help=f"datasets root; the dataset is DIR/{default_dataset_id(ENV_ID)}, recorded if absent",
    )
    p.add_argument("--episodes", type=int, default=200, help="episodes in the dataset")
    p.add_argument(
        "--noise", type=float, default=0.1, help="action noise of the dataset (x action range)"
    )
    p.add_argument("--eval-seeds", type=int, default=50, help="held-out episodes per evaluation")
    p.add_argument("--epochs", type=int, default=150, help="training epochs (passes over the data)")
    p.add_argument("--eval-every", type=int, default=10, help="epochs between evaluations")
    p.add_argument(
        "--seed",
        type=int,
        default=0,
        help="seed of the dataset's first episode and of training (weights, batches)",
    )
    p.add_argument("--out", type=Path, default=Path("runs/bc_pick_and_place"), help="output folder")
    p.add_argument(
        "--hidden", type=int, nargs="+", default=[256, 256, 256], help="hidden layer widths"
    )
    p.add_argument("--batch-size", type=int, default=256, help="samples per gradient step")
    p.add_argument("--lr", type=float, default=1e-3, help="initial Adam step size (cosine decay)")
    p.add_argument(
        "--bins",
        type=int,
        default=41,
        help="values per arm action of the categorical head (0: mean-squared-error regression)",
    )
    p.add_argument(
        "--phases",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="learn and track the expert's phase (labels replayed from the dataset)",
    )
    p.add_argument(
        "--successful-only",
        action="store_true",
        help="train only on the episodes that ended in success",
    )
    args = p.parse_args(argv)
    if min(args.episodes, args.eval_seeds, args.epochs, args.eval_every, args.batch_size) < 1:
        p.error("--episodes, --eval-seeds, --epochs, --eval-every, --batch-size must be >= 1")
    if args.seed < 0 or args.seed + args.episodes > EVAL_SEED_BASE:
        p.error(
            f"the dataset's seeds, --seed .. --seed + --episodes - 1, must lie in "
            f"0..{EVAL_SEED_BASE - 1} (the held-out seeds start at {EVAL_SEED_BASE})"
        )
    if args.bins == 1 or args.bins < 0:
        p.error("--bins must be 0 or >= 2")
    return args


def load_or_record(root: Path, episodes: int, noise: float, seed: int) -> tuple[Episode, ...]:
    """The dataset's episodes, recorded with the library's current expert if absent.

    Args:
        root: Datasets root folder (the dataset is ``root / default id``).
        episodes: Number of episodes.
        noise: Action noise, as a fraction of the action range.
        seed: Seed of the first episode.

    Returns:
        The episodes, in order.

    Raises:
        SystemExit: An existing dataset was recorded with other arguments.
    """
    folder = root / default_dataset_id(ENV_ID)
    if not folder.exists():
        print(f"recording {episodes} episodes (noise {noise:g}, seeds {seed}..) into {folder}")
        start = time.perf_counter()
        done = successes = 0

        def progress(episode: Episode) -> None:
            nonlocal done, successes
            done += 1
            successes += episode.success
            if done % 20 == 0 or done == episodes:
                print(
                    f"  recorded {done:4d}/{episodes}  expert successes {successes:4d}  "
                    f"{time.perf_counter() - start:6.1f} s",
                    flush=True,
                )

        write_dataset(root, episodes, env_id=ENV_ID, noise=noise, seed=seed, on_episode=progress)
    meta = json.loads((folder / "metadata.json").read_text(encoding="utf-8"))
    found = (meta["env_id"], meta["total_episodes"], meta["action_noise"], meta["first_seed"])
    wanted = (ENV_ID, episodes, noise, seed)
    if found != wanted:
        raise SystemExit(
            f"{folder} holds (env, episodes, noise, first seed) = {found}, not {wanted}: "
            "pass another --dataset (or remove that folder to record it again)"
        )
    return read_npz(folder)


def expert_phases(episodes: Sequence[Episode]) -> tuple[list[IntArray], list[str]]:
    """Replay the scripted expert on the recorded observations: its phase after each step.

    The expert is deterministic given its observations (its planner is seeded
    per episode), so feeding it an episode's observations after a reset with
    the episode's seed gives back its recorded clean actions, and its phase on
    the way. A recorded action that does not come back means that the dataset
    was recorded by another version of the expert.

    Args:
        episodes: The dataset's episodes.

    Returns:
        Per episode, the index of the expert's phase after each step, shape (T,),
        and the phases' names (index 0: the phase an episode starts in).

    Raises:
        SystemExit: The dataset does not replay (recorded by another expert).
    """
    env = gym.make(ENV_ID)
    expert = lynxsim.envs.PickAndPlaceExpert(env)
    names: list[str] = []
    out = []
    for e in episodes:
        env.reset(seed=e.seed)
        expert.reset()
        if not names:
            names.append(str(getattr(expert.phase, "value", expert.phase)))
        after = np.zeros(e.steps, dtype=np.int64)
        for t in range(e.steps):
            action = expert({k: e.observations[k][t] for k in OBS_KEYS})
            if not np.allclose(action, e.infos["expert_action"][t + 1], atol=1e-5):
                env.close()
                raise SystemExit(
                    f"episode with seed {e.seed}, step {t}: the library's expert now acts "
                    "otherwise than the recorded one (the expert changed since the dataset "
                    "was recorded): remove the dataset to record it again"
                )
            name = str(getattr(expert.phase, "value", expert.phase))
            if name not in names:
                names.append(name)
            after[t] = names.index(name)
        out.append(after)
    env.close()
    return out, names


class Memory:
    """What the policy carries from step to step: its phase and a gripper timer.

    The phase is the one the policy predicted at the previous step (in training:
    the expert's), with the number of steps since it began; the timer counts
    the steps since the commanded gripper last switched between closing and
    opening. One class updates both the training features and the evaluation's,
    step by step, so that they cannot differ.

    Args:
        observation: The episode's first observation (``obs["observation"]``).
        phases: Number of phases (0: no phase).
    """

    def __init__(self, observation: FloatArray, phases: int) -> None:
        self.phases = phases
        self.phase = 0
        self.in_phase = 0
        self.closing = bool(observation[ix("commanded_gripper_opening")][0] < GRIP_HALF_OPEN_M)
        self.timer = COUNT_CAP

    def update(self, observation: FloatArray, phase: int) -> None:
        """Take in the observation after a step and the phase that step ended in."""
        self.in_phase = min(self.in_phase + 1, COUNT_CAP) if phase == self.phase else 0
        self.phase = phase
        closing = bool(observation[ix("commanded_gripper_opening")][0] < GRIP_HALF_OPEN_M)
        self.timer = 0 if closing != self.closing else min(self.timer + 1, COUNT_CAP)
        self.closing = closing

    def features(self) -> FloatArray:
        """The gripper timer, then the phase one-hot and its step count (with phases)."""
        if not self.phases:
            return np.array([float(self.timer)])
        one_hot = np.zeros(self.phases)
        one_hot[self.phase] = 1.0
        return np.concatenate([[self.timer], one_hot, [self.in_phase]])


def ix(name: str) -> slice:
    """The slice of an observation entry by name (``PickAndPlaceEnv.OBS_INDEX``)."""
    return lynxsim.envs.PickAndPlaceEnv.OBS_INDEX[name]


def features(
    observation: FloatArray, goal: FloatArray, memory: FloatArray, obstacles: FloatArray
) -> FloatArray:
    """The policy's inputs.

    Args:
        observation: ``obs["observation"]``, shape (N, 45).
        goal: ``obs["desired_goal"]``, shape (N, 3) [m].
        memory: :meth:`Memory.features` of each, shape (N, M).
        obstacles: The obstacles as rows (x, y, radius) [m], shape (K, 3).

    Returns:
        Shape (N, 78 + 6 K + M): the observation, the goal, five relative vectors
        (the goal minus the cube, minus the tool point and minus the commanded tool
        point; the cube minus the tool point and minus the commanded tool point
        [m]), the same on a logarithmic scale (``asinh(v / FINE_M)``: millimetres
        apart near zero, where the expert's decisions are taken, a few units apart
        far away), for each obstacle the horizontal offsets of the tool point and
        of the commanded one from its axis and their distances to its surface [m],
        then the memory.
    """
    cube = observation[:, ix("cube_position")]
    tool = observation[:, ix("tool_position")]
    cmd = observation[:, ix("commanded_tool_position")]
    relative = np.concatenate([goal - cube, goal - tool, goal - cmd, cube - tool, cube - cmd], 1)
    around = []
    for x, y, radius in obstacles:
        for point in (tool, cmd):
            offset = point[:, :2] - (x, y)
            around += [offset, np.hypot(offset[:, 0], offset[:, 1])[:, None] - radius]
    return np.concatenate(
        [observation, goal, relative, np.arcsinh(relative / FINE_M), *around, memory], axis=1
    )


def obstacle_rows(env: gym.Env[Any, Any]) -> FloatArray:
    """The env's obstacles as rows (x, y, radius) [m] (a box: its circumscribed radius).

    Args:
        env: A reset ``LynxPickAndPlace`` env (default arguments: the report's cylinder).

    Returns:
        Shape (K, 3).
    """
    rows = []
    for o in env.unwrapped.obstacles:  # type: ignore[attr-defined]
        radius = getattr(o, "radius", None)
        if radius is None:
            radius = 0.5 * math.hypot(*o.size[:2])
        rows.append((o.position[0], o.position[1], radius))
    return np.array(rows, dtype=float).reshape(-1, 3)


def training_arrays(
    episodes: Sequence[Episode],
    phases: Sequence[IntArray] | None,
    n_phases: int,
    obstacles: FloatArray,
) -> tuple[FloatArray, npt.NDArray[np.float32], IntArray]:
    """Rows (features of the observation at step t; the expert's action; its phase after it).

    Args:
        episodes: The episodes trained on.
        phases: Per episode, the expert's phase after each step (None: no phases).
        n_phases: Number of phases (0 without).
        obstacles: See :func:`features`.

    Returns:
        Features (N, F), the expert's clean actions (N, A) and phases (N,) (zeros
        without phases).
    """
    xs, ys, targets = [], [], []
    for i, e in enumerate(episodes):
        obs = e.observations["observation"]
        after = np.zeros(e.steps, dtype=np.int64) if phases is None else phases[i]
        memory = Memory(obs[0], n_phases)
        rows = []
        for t in range(e.steps):
            rows.append(memory.features())
            memory.update(obs[t + 1], int(after[t]))
        goal = e.observations["desired_goal"][:-1]
        xs.append(features(obs[:-1], goal, np.stack(rows), obstacles))
        # Row t + 1 of expert_action is the expert's action for the observation of row t.
        ys.append(e.infos["expert_action"][1:])
        targets.append(after)
    return np.concatenate(xs), np.concatenate(ys).astype(np.float32), np.concatenate(targets)


def mlp(inputs: int, hidden: Sequence[int], outputs: int) -> nn.Sequential:
    """A multilayer perceptron with SiLU activations."""
    layers: list[nn.Module] = []
    width = inputs
    for h in hidden:
        layers += [nn.Linear(width, h), nn.SiLU()]
        width = h
    layers.append(nn.Linear(width, outputs))
    return nn.Sequential(*layers)


class Policy(nn.Module):
    """MLP from features to the arm actions, the gripper and the phase after the step.

    Each of the ``arm`` arm actions (tool deltas x, y, z, pitch and, with ``-v2``, roll;
    the gripper is the action's last entry) is a categorical
    distribution over ``bins`` evenly spaced values from -1 to 1, trained on
    "two-hot" targets (an action between two values is split between them in
    proportion); the deterministic action is its mode (the most probable value,
    refined by the mean over it and its two neighbours), which commits to one of
    two expert actions where a regression would stall between them. With
    ``bins=0`` the arm actions are regressed (mean squared error). The gripper
    is a binary classification (open or closed), the phase a categorical one.

    Args:
        mean: Features' mean, shape (F,).
        std: Features' standard deviation (floored), shape (F,).
        hidden: Hidden layer widths.
        bins: Values per arm action (0: regression).
        phases: Number of phases (0: none).
        arm: Number of arm actions (the action's entries before the gripper).
    """

    def __init__(
        self,
        mean: FloatArray,
        std: FloatArray,
        hidden: Sequence[int],
        bins: int,
        phases: int,
        arm: int,
    ) -> None:
        super().__init__()
        self.register_buffer("mean", torch.as_tensor(mean, dtype=torch.float32))
        self.register_buffer("std", torch.as_tensor(std, dtype=torch.float32))
        self.register_buffer("values", torch.linspace(-1.0, 1.0, max(bins, 2)))
        self.bins = bins
        self.phases = phases
        self.arm = arm
        self.net = mlp(mean.shape[0], hidden, arm * max(bins, 1) + 1 + phases)

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Arm logits (N, arm, bins) or values (N, arm), gripper-open logit (N,), phase logits."""
        out: torch.Tensor = self.net((x - self.mean) / self.std)
        k = out.shape[1] - self.phases - 1
        arm = out[:, :k].reshape(len(x), self.arm, -1) if self.bins else out[:, :k]
        return arm, out[:, k], out[:, k + 1 :]

    def loss(self, x: torch.Tensor, action: torch.Tensor, phase: torch.Tensor) -> torch.Tensor:
        """Arm loss + ``GRIP_WEIGHT`` x gripper cross-entropy + phase cross-entropy.

        Args:
            x: Features (N, F).
            action: The expert's actions (N, arm + 1).
            phase: The expert's phase after the step (N,).

        Returns:
            The mean loss (a scalar).
        """
        arm, grip, phase_logits = self(x)
        opened = (action[:, -1] > 0).float()
        loss = GRIP_WEIGHT * nn.functional.binary_cross_entropy_with_logits(grip, opened)
        if self.phases:
            loss = loss + nn.functional.cross_entropy(phase_logits, phase)
        if not self.bins:
            return loss + nn.functional.mse_loss(arm, action[:, :-1])
        # Two-hot target: the share of each of the two values around the action.
        position = (action[:, :-1].clamp(-1.0, 1.0) + 1.0) * 0.5 * (self.bins - 1)
        low = position.floor().long().clamp(max=self.bins - 2)[..., None]
        high_share = (position - low[..., 0])[..., None]
        logp = nn.functional.log_softmax(arm, dim=-1)
        nll = -((1.0 - high_share) * logp.gather(-1, low) + high_share * logp.gather(-1, low + 1))
        return loss + nll.sum(dim=(1, 2)).mean()

    @torch.no_grad()
    def act(self, x: FloatArray) -> tuple[npt.NDArray[np.float32], IntArray]:
        """Deterministic actions (N, arm + 1) for features (N, F), and the phases after them (N,).

        The arm actions are in [-1, 1], the gripper's -1 (close) or +1 (open); the
        phase is the most probable one (0 without phases).
        """
        arm, grip, phase_logits = self(torch.as_tensor(x, dtype=torch.float32))
        if self.bins:
            p = torch.softmax(arm, dim=-1)
            top = p.argmax(dim=-1, keepdim=True)
            w = p * ((torch.arange(self.bins) - top).abs() <= 1)
            arm = (w * self.values).sum(-1) / w.sum(-1)
        out = torch.cat([arm.clamp(-1.0, 1.0), torch.where(grip[:, None] > 0, 1.0, -1.0)], 1)
        phase = phase_logits.argmax(dim=1) if self.phases else torch.zeros(len(x))
        return out.numpy().astype(np.float32), phase.numpy().astype(np.int64)


def evaluate(
    policy: Policy, envs: Sequence[gym.Env[Any, Any]], seed_base: int, obstacles: FloatArray
) -> tuple[float, int, float]:
    """Run the deterministic policy on held-out episodes, all envs in lockstep.

    Args:
        policy: The policy.
        envs: One env per episode; env i is reset with seed ``seed_base + i``.
        seed_base: Seed of the first episode.
        obstacles: See :func:`features`.

    Returns:
        Success rate, number of episodes with arm–obstacle contact, mean final
        cube–goal distance [m].
    """
    policy.eval()
    n = len(envs)
    obs = [env.reset(seed=seed_base + i)[0] for i, env in enumerate(envs)]
    memories = [Memory(o["observation"], policy.phases) for o in obs]
    success = np.zeros(n, dtype=bool)
    contact = np.zeros(n, dtype=bool)
    distance = np.full(n, math.nan)
    running = list(range(n))
    while running:
        o = np.stack([obs[i]["observation"] for i in running])
        g = np.stack([obs[i]["desired_goal"] for i in running])
        m = np.stack([memories[i].features() for i in running])
        actions, phases = policy.act(features(o, g, m, obstacles))
        still = []
        for i, action, phase in zip(running, actions, phases.tolist()):
            obs[i], _, terminated, truncated, info = envs[i].step(action)
            memories[i].update(obs[i]["observation"], phase)
            contact[i] |= bool(info["collision"])
            success[i] = bool(info["is_success"])
            distance[i] = float(info["distance"])
            if not (terminated or truncated):
                still.append(i)
        running = still
    return float(success.mean()), int(contact.sum()), float(distance.mean())


def write_csv(dest: Path, curve: Sequence[EvalPoint]) -> None:
    """Write the curve as CSV, one row per evaluation, atomically.

    Args:
        dest: The CSV file.
        curve: The evaluations, in order.
    """
    with atomic_path(dest) as tmp, tmp.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow([field.name for field in fields(EvalPoint)])
        for point in curve:
            w.writerow(astuple(point))


def plot_curve(
    dest: Path, curve: Sequence[EvalPoint], losses: Sequence[float], args: argparse.Namespace
) -> None:
    """Plot held-out success and contacts, and the training loss, against epochs, atomically.

    Args:
        dest: The PNG file.
        curve: The evaluations, in order.
        losses: Mean training loss of each epoch so far.
        args: The arguments (for the title).
    """
    fig, (top, bottom) = plt.subplots(
        2, 1, figsize=(6.4, 6.0), dpi=120, sharex=True, height_ratios=(3, 2)
    )
    epochs = [p.epoch for p in curve]
    top.plot(epochs, [p.success_rate for p in curve], "o-", color="tab:blue", label="success")
    top.plot(
        epochs,
        [p.contact_episodes / args.eval_seeds for p in curve],
        "s--",
        color="tab:red",
        label="arm–obstacle contact",
    )
    top.set_ylabel(f"fraction of the {args.eval_seeds} held-out episodes")
    top.set_ylim(-0.02, 1.02)
    top.grid(alpha=0.3)
    top.legend(loc="center right", fontsize=8)
    top.set_title(
        f"{ENV_ID}: behaviour cloning of the scripted expert\n"
        f"({args.episodes} episodes at action noise {args.noise:g}; deterministic policy, "
        f"seeds {EVAL_SEED_BASE}..{EVAL_SEED_BASE + args.eval_seeds - 1})",
        fontsize=9,
    )
    bottom.plot(range(1, len(losses) + 1), losses, "-", color="tab:gray")
    bottom.set_yscale("log")
    bottom.set_ylabel(
        f"training loss per sample\n(arm CE + {GRIP_WEIGHT:g} gripper BCE + phase CE)", fontsize=8
    )
    bottom.set_xlabel("epoch")
    bottom.set_xlim(left=0)
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    with atomic_path(dest) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> int:
    """Record the dataset if needed, train, evaluate periodically, write curve and model.

    Args:
        argv: The arguments (None: ``sys.argv[1:]``).

    Returns:
        The exit status (0).
    """
    args = parse_args(argv)
    start = time.perf_counter()
    torch.set_num_threads(1)
    torch.manual_seed(args.seed)
    rng = np.random.default_rng(args.seed)
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)

    episodes = load_or_record(args.dataset, args.episodes, args.noise, args.seed)
    record_s = time.perf_counter() - start
    t = time.perf_counter()
    phases, names = expert_phases(episodes) if args.phases else (None, [])
    replay_s = time.perf_counter() - t
    if args.successful_only:
        keep = [i for i, e in enumerate(episodes) if e.success]
        episodes = tuple(episodes[i] for i in keep)
        phases = None if phases is None else [phases[i] for i in keep]
    probe = gym.make(ENV_ID)
    probe.reset(seed=args.seed)
    obstacles = obstacle_rows(probe)
    probe.close()
    x, y, phase = training_arrays(episodes, phases, len(names), obstacles)
    mean = x.mean(axis=0)
    std = np.maximum(x.std(axis=0), STD_FLOOR)
    print(
        f"dataset: {args.episodes} episodes ({record_s:.0f} s); training on {len(episodes)} "
        f"episodes, {sum(e.success for e in episodes)} successful, {len(x)} steps, "
        f"{x.shape[1]} features; phases ({replay_s:.0f} s replay): {', '.join(names) or 'off'}",
        flush=True,
    )

    policy = Policy(mean, std, args.hidden, args.bins, len(names), y.shape[1] - 1)
    optimizer = torch.optim.Adam(policy.parameters(), lr=args.lr)
    batches = math.ceil(len(x) / args.batch_size)
    schedule = torch.optim.lr_scheduler.CosineAnnealingLR(optimizer, args.epochs * batches)
    xt = torch.as_tensor(x, dtype=torch.float32)
    yt = torch.as_tensor(y)
    pt = torch.as_tensor(phase)
    envs = [gym.make(ENV_ID) for _ in range(args.eval_seeds)]
    curve: list[EvalPoint] = []
    losses: list[float] = []
    train_s = eval_s = 0.0

    def run_evaluation(epoch: int) -> None:
        nonlocal eval_s
        t = time.perf_counter()
        success, contacts, distance = evaluate(policy, envs, EVAL_SEED_BASE, obstacles)
        eval_s += time.perf_counter() - t
        loss = losses[-1] if losses else math.nan
        point = EvalPoint(epoch, time.perf_counter() - start, loss, success, contacts, distance)
        curve.append(point)
        print(
            f"epoch {epoch:4d}  wall {point.wall_s:7.1f} s  loss {loss:7.4f}  "
            f"held-out success {success:5.2f}  contact episodes {contacts:3d}  "
            f"final distance {1000 * distance:6.1f} mm",
            flush=True,
        )
        write_csv(out / "curve.csv", curve)
        plot_curve(out / "curve.png", curve, losses, args)

    run_evaluation(0)
    for epoch in range(1, args.epochs + 1):
        t = time.perf_counter()
        policy.train()
        order = torch.as_tensor(rng.permutation(len(x)))
        total = 0.0
        for b in range(batches):
            idx = order[b * args.batch_size : (b + 1) * args.batch_size]
            loss = policy.loss(xt[idx], yt[idx], pt[idx])
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            schedule.step()
            total += loss.item() * len(idx)
        losses.append(total / len(x))
        train_s += time.perf_counter() - t
        if epoch % args.eval_every == 0 or epoch == args.epochs:
            run_evaluation(epoch)

    model = {
        "state_dict": policy.state_dict(),
        "hidden": list(args.hidden),
        "bins": args.bins,
        "mean": mean,
        "std": std,
        "phases": names,
        "obstacles": obstacles,
        "features": "features() and Memory of examples/bc_pick_and_place.py",
        "args": {k: str(v) if isinstance(v, Path) else v for k, v in vars(args).items()},
    }
    with atomic_path(out / "model.pt") as tmp:
        torch.save(model, tmp)
    for env in envs:
        env.close()
    final = curve[-1]
    print(
        f"done in {time.perf_counter() - start:.0f} s (dataset {record_s:.0f} s, replay "
        f"{replay_s:.0f} s, training {train_s:.0f} s, evaluations {eval_s:.0f} s): held-out "
        f"success {final.success_rate:.2f} ({round(final.success_rate * args.eval_seeds)}/"
        f"{args.eval_seeds}), contact episodes {final.contact_episodes}; wrote "
        f"{out / 'curve.csv'}, {out / 'curve.png'}, {out / 'model.pt'}",
        flush=True,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
