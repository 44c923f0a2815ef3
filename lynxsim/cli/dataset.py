"""``lynxsim dataset``: record seeded expert episodes with action noise as a dataset."""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from pathlib import Path
from typing import Any

from lynxsim.bounds import MAX_EPISODES
from lynxsim.cli.units import bounded_float, bounded_int, seed_int
from lynxsim.datasets.layout import DatasetFormat, check_dataset_id
from lynxsim.envs.noise import MAX_NOISE
from lynxsim.envs.registration import ENV_IDS, PICK_AND_PLACE_ID
from lynxsim.errors import InvalidInputError

__all__ = ["register"]


def _dataset_id(text: str) -> str:
    """Argparse type: a Minari-style dataset id (see :func:`check_dataset_id`)."""
    try:
        return check_dataset_id(text)
    except InvalidInputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from lynxsim.datasets.episode import Episode
    from lynxsim.datasets.record import write_dataset

    done = successes = 0
    bar: Any = None  # opened by the first episode: an argument error prints one line only

    def on_episode(episode: Episode) -> None:
        nonlocal bar, done, successes
        if bar is None:
            bar = tqdm(total=args.episodes, unit="ep", disable=args.quiet, file=sys.stderr)
        done += 1
        successes += episode.success
        bar.update(1)
        bar.set_postfix(success=f"{successes / done:.0%}")

    try:
        summary = write_dataset(
            args.out_dir,
            args.episodes,
            env_id=args.env,
            noise=args.noise,
            seed=args.seed,
            format=args.format,
            dataset_id=args.dataset_id,
            images=("front",) if args.images else (),
            image_size=args.image_size,
            videos=not args.no_videos,
            on_episode=on_episode,
        )
    finally:
        if bar is not None:
            bar.close()
    last = args.seed + args.episodes - 1
    print(f"{summary.path} ({summary.format.value}, dataset id {summary.dataset_id})")
    print(
        f"  {summary.episodes:,} episodes of {args.env}, {summary.steps:,} steps, "
        f"seeds {args.seed}..{last}, action noise {args.noise:g} x the action range"
    )
    print(
        f"  expert success   {summary.successes / summary.episodes:.1%}, "
        f"{summary.collision_episodes} episodes with arm-obstacle contact"
    )
    if summary.format is DatasetFormat.MINARI:
        load = f'import minari; ds = minari.load_dataset("{summary.dataset_id}")'
        root = shlex.quote(str(args.out_dir))
        print(f"  load with        MINARI_DATASETS_PATH={root} python -c {shlex.quote(load)}")
    elif summary.format is DatasetFormat.LEROBOT:
        path = shlex.quote(str(summary.path))
        print(f"  load with        python examples/load_lerobot.py {path}  (needs lerobot)")
    else:
        path = json.dumps(str(summary.path))
        load = f"from lynxsim.datasets import read_npz; episodes = read_npz({path})"
        print(f"  load with        python -c {shlex.quote(load)}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``dataset`` sub-command."""
    p = sub.add_parser(
        "dataset",
        help="record expert episodes with action noise as an NPZ, Minari or LeRobot dataset",
        description="Record seeded episodes (seeds S, S+1, ...) of a lynxsim Gymnasium env "
        "driven by its scripted expert, with Gaussian noise of NOISE x the action range added "
        "to every action (clipped to the action space), into DIR/DATASET_ID. The same "
        "arguments give byte-identical files; the dataset appears only once complete.",
    )
    p.add_argument("--env", choices=ENV_IDS, default=PICK_AND_PLACE_ID, help="the env id")
    p.add_argument(
        "--episodes",
        type=bounded_int(1, MAX_EPISODES),
        default=100,
        help=f"number of episodes, 1 to {MAX_EPISODES:,} (default 100)",
    )
    p.add_argument(
        "--noise",
        type=bounded_float(0.0, MAX_NOISE),
        default=0.1,
        help="standard deviation of the action noise as a fraction of the action range, "
        f"0 to {MAX_NOISE:g} (default 0.1)",
    )
    p.add_argument(
        "--out-dir",
        type=Path,
        required=True,
        metavar="DIR",
        help="datasets root folder; the dataset goes to DIR/DATASET_ID "
        "(for Minari: DIR is what MINARI_DATASETS_PATH points to)",
    )
    p.add_argument(
        "--format",
        choices=[f.value for f in DatasetFormat],
        default=DatasetFormat.NPZ.value,
        help="npz (NumPy only, default), minari or lerobot (LeRobotDataset v3.0); the last two "
        "need: pip install 'lynxsim[datasets]'",
    )
    p.add_argument("--seed", type=seed_int, default=0, help="seed of the first episode (default 0)")
    p.add_argument(
        "--dataset-id",
        type=_dataset_id,
        default=None,
        help="Minari-style id, also the folder under DIR "
        "(default lynxsim/<env>/expert-v0, e.g. lynxsim/pick-and-place-v1/expert-v0)",
    )
    p.add_argument(
        "--images",
        action="store_true",
        help="add the front camera's images to the observations (observations/pixels, uint8)",
    )
    p.add_argument(
        "--image-size",
        type=bounded_int(16, 512),
        default=84,
        metavar="PX",
        help="side of the images with --images, 16 to 512 px (default 84)",
    )
    p.add_argument(
        "--no-videos",
        action="store_true",
        help="with --format lerobot --images: store the images as PNG in the parquet files "
        "(lossless) instead of MP4 videos (H.264, near lossless)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_run)
