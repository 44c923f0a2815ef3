"""``lynxsim env``: run a policy in a Gymnasium env and report success, return and collisions."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from lynxsim.bounds import MAX_EPISODES, MAX_RANDOM_OBSTACLES
from lynxsim.cli.units import bounded_float, bounded_int, count_range, seed_int
from lynxsim.envs.noise import MAX_NOISE
from lynxsim.envs.registration import ENV_IDS, PICK_AND_PLACE_ID

__all__ = ["register"]

RANDOMIZED_OBSTACLES = (1, 3)
"""Obstacles per episode of ``--randomize-obstacles`` (the experts' acceptance scenes)."""


def _run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from lynxsim.envs.evaluation import EpisodeStats, evaluate

    env_kwargs: dict[str, object] = {}
    scene = ""
    if args.no_obstacle:
        env_kwargs, scene = {"obstacles": ()}, ", no obstacle"
    elif args.random_obstacles is not None:
        fewest, most = args.random_obstacles
        env_kwargs = {"random_obstacles": args.random_obstacles}
        number = str(fewest) if fewest == most else f"{fewest}-{most}"
        scene = f", {number} random obstacles per episode"
    done = successes = 0
    with tqdm(total=args.episodes, unit="ep", disable=args.quiet, file=sys.stderr) as bar:

        def on_episode(stats: EpisodeStats) -> None:
            nonlocal done, successes
            done += 1
            successes += stats.success
            bar.update(1)
            bar.set_postfix(success=f"{successes / done:.0%}")

        summary = evaluate(
            args.env,
            args.policy,
            args.episodes,
            args.seed,
            video=args.video,
            video_episodes=args.video_episodes,
            env_kwargs=env_kwargs,
            action_noise=args.action_noise,
            on_episode=on_episode,
        )
    last = args.seed + args.episodes - 1
    print(
        f"{args.env}, {args.policy} policy, {args.episodes} episodes (seeds {args.seed}..{last})"
        f"{scene}{f', action noise {args.action_noise:g}' if args.action_noise else ''}"
    )
    print(f"  success rate     {summary.success_rate:.1%} (last step of each episode)")
    print(f"  mean return      {summary.mean_return:.2f}")
    print(
        f"  collisions       {summary.collision_episodes} episodes, "
        f"{summary.collision_steps} steps with arm-obstacle contact (every physics step checked)"
    )
    if args.video is not None:
        shown = min(args.video_episodes, args.episodes)
        print(f"  video            {args.video} ({shown} episode{'s' if shown > 1 else ''})")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``env`` sub-command."""
    p = sub.add_parser(
        "env",
        help="run the scripted expert or a random policy in a Gymnasium env",
        description="Run seeded episodes (seeds S, S+1, ...) of a lynxsim Gymnasium env with "
        "the scripted expert or uniformly random actions; print the success rate, the mean "
        "return and the arm-obstacle collisions.",
    )
    p.add_argument("--policy", choices=("expert", "random"), default="expert")
    p.add_argument(
        "--episodes",
        type=bounded_int(1, MAX_EPISODES),
        default=10,
        help=f"number of episodes, 1 to {MAX_EPISODES:,} (default 10)",
    )
    p.add_argument("--env", choices=ENV_IDS, default=PICK_AND_PLACE_ID, help="the env id")
    p.add_argument("--seed", type=seed_int, default=0, help="seed of the first episode (default 0)")
    p.add_argument("--video", type=Path, default=None, help="MP4 file of the first episode(s)")
    p.add_argument(
        "--video-episodes",
        type=bounded_int(1, 100),
        default=1,
        help="episodes recorded into --video (default 1)",
    )
    scene = p.add_mutually_exclusive_group()
    scene.add_argument("--no-obstacle", action="store_true", help="remove the cylinder obstacle")
    scene.add_argument(
        "--random-obstacles",
        type=count_range(0, MAX_RANDOM_OBSTACLES),
        default=None,
        metavar="N|LO-HI",
        help="instead of the cylinder, N (or LO to HI) random obstacles drawn at every reset "
        f"(at most {MAX_RANDOM_OBSTACLES})",
    )
    scene.add_argument(
        "--randomize-obstacles",
        action="store_const",
        const=RANDOMIZED_OBSTACLES,
        dest="random_obstacles",
        help=f"the same as --random-obstacles {RANDOMIZED_OBSTACLES[0]}-{RANDOMIZED_OBSTACLES[1]}",
    )
    p.add_argument(
        "--action-noise",
        type=bounded_float(0.0, MAX_NOISE),
        default=0.0,
        metavar="F",
        help="Gaussian noise on every action: standard deviation F times the action range "
        f"(0.1: 0.2 on [-1, 1]), clipped, seeded per episode; 0 to {MAX_NOISE:g} (default 0)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_run)
