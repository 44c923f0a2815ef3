"""Load a lynxsim dataset in LeRobot's format with ``lerobot`` itself, and check what it gives.

Record one first (lynxsim needs no lerobot for it)::

    lynxsim dataset --format lerobot --episodes 50 --images --out-dir datasets_scratch

then, in an environment with lerobot (the current lerobot needs Python >= 3.12;
lerobot 0.4.x, which reads the same format v3.0, installs on Python 3.10 and 3.11)::

    pip install lerobot
    python examples/load_lerobot.py datasets_scratch/lynxsim/pick-and-place-v1/expert-v0

It opens the folder with ``LeRobotDataset`` (no Hub access: the folder is the
root), prints its counts, features and one frame, then checks that the frames
lerobot returns are the dataset's: every frame's episode and index, the actions
and states of the parquet files (read with pyarrow), each camera image against
the frame of its video at the episode's offset (decoded by PyAV), and that a
``torch`` DataLoader batches them.
It imports nothing of lynxsim, so it runs where lynxsim is not installed.
Exit status 0 when every check holds.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import av
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import torch
from lerobot.datasets.lerobot_dataset import LeRobotDataset


def _decode(path: Path) -> np.ndarray:
    """Every frame of a video, (N, H, W, 3) uint8."""
    with av.open(str(path)) as container:
        return np.stack([f.to_ndarray(format="rgb24") for f in container.decode(video=0)])


def main() -> int:
    """Load the dataset, check it, print what lerobot returns; 0 when every check holds."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=Path, help="the dataset's folder (with meta/info.json)")
    parser.add_argument(
        "--video-backend",
        default="pyav",
        help="lerobot's video decoder: pyav (default: its wheel carries FFmpeg) or torchcodec "
        "(needs the system's FFmpeg libraries)",
    )
    args = parser.parse_args()
    info = json.loads((args.folder / "meta" / "info.json").read_text())
    dataset = LeRobotDataset(
        repo_id="lynxsim/local", root=args.folder, video_backend=args.video_backend
    )
    print(dataset)
    print(f"episodes {dataset.num_episodes}, frames {dataset.num_frames}, fps {dataset.fps}")
    print("features:", ", ".join(dataset.features))
    first = dataset[0]
    for key, value in first.items():
        shape = tuple(value.shape) if isinstance(value, torch.Tensor) else value
        print(f"  {key}: {shape}")

    failures = []
    if (dataset.num_episodes, dataset.num_frames) != (info["total_episodes"], info["total_frames"]):
        failures.append("counts differ from info.json")
    files = sorted((args.folder / "data").glob("chunk-*/file-*.parquet"))  # in frame order
    data = pa.concat_tables([pq.read_table(f) for f in files])
    rows = len(data)
    step = max(1, rows // 25)  # 25 frames spread over the episodes
    episode_index = data.column("episode_index").to_pylist()
    actions = np.stack(data.column("action").to_pylist())
    states = np.stack(data.column("observation.state").to_pylist())
    cameras = [k for k, f in info["features"].items() if f["dtype"] in ("video", "image")]
    videos: dict[Path, np.ndarray] = {}  # every frame of a video file, decoded by PyAV
    for i in range(0, rows, step):
        item = dataset[i]
        if int(item["index"]) != i or int(item["episode_index"]) != episode_index[i]:
            failures.append(f"frame {i}: index or episode differs")
        if not np.array_equal(item["action"].numpy(), actions[i]):
            failures.append(f"frame {i}: action differs")
        if not np.array_equal(item["observation.state"].numpy(), states[i]):
            failures.append(f"frame {i}: observation.state differs")
        for key in cameras:
            h, w, c = info["features"][key]["shape"]
            if tuple(item[key].shape) != (c, h, w):
                failures.append(f"frame {i}: {key} is {tuple(item[key].shape)}, not {(c, h, w)}")
            elif info["features"][key]["dtype"] == "video":
                e = int(item["episode_index"])
                path = args.folder / dataset.meta.get_video_file_path(e, key)
                if path not in videos:
                    videos[path] = _decode(path)
                start = dataset.meta.episodes[e][f"videos/{key}/from_timestamp"]
                position = round((start + float(item["timestamp"])) * info["fps"])
                frame = videos[path][position].astype(np.float32) / 255
                if np.abs(item[key].numpy().transpose(1, 2, 0) - frame).max() > 1 / 255:
                    failures.append(f"frame {i}: {key} is not frame {position} of its video")
        if item["task"] != dataset.meta.tasks.index[0]:
            failures.append(f"frame {i}: task {item['task']!r}")
    batch = next(iter(torch.utils.data.DataLoader(dataset, batch_size=8, shuffle=False)))
    if tuple(batch["action"].shape) != (8, actions.shape[1]):
        failures.append(f"a batch of 8 has actions {tuple(batch['action'].shape)}")
    print(f"checked {len(range(0, rows, step))} frames and a batch of 8 against the parquet files")
    for failure in failures:
        print("FAILED:", failure)
    print("lerobot loaded the dataset" + (" with failures" if failures else "; every check holds"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
