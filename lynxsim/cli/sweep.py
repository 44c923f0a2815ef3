"""``lynxsim sweep``: many runs of table-scene tasks, varied by a sweep file, tabled and mapped."""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections import Counter
from pathlib import Path

from lynxsim.bounds import MAX_JOBS
from lynxsim.cli.units import bounded_int
from lynxsim.errors import InvalidInputError
from lynxsim.verdicts import Verdict

__all__ = ["register"]


def _sweep(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from lynxsim.fileio import check_destination, file_stem
    from lynxsim.sweep.maps import write_maps
    from lynxsim.sweep.runner import Backend, LocalBackend, run_sweep
    from lynxsim.sweep.spec import load_sweep

    if args.backend != "ray" and (args.address is not None or args.verbose):
        raise InvalidInputError("--address and --verbose apply to --backend ray only")
    spec = load_sweep(args.sweep)
    out: Path = args.out_dir
    stem = file_stem(spec.name)
    for suffix in (".csv", ".npz"):
        check_destination(out / f"{stem}{suffix}")
    backend: Backend
    if args.backend == "ray":
        from lynxsim.sweep.ray_backend import RayBackend, require_ray

        require_ray()  # before any work
        backend = RayBackend(address=args.address, verbose=args.verbose)
    else:
        backend = LocalBackend(args.jobs)
    with tqdm(
        total=1, unit="run", disable=args.quiet or args.json, file=sys.stderr, leave=False
    ) as bar:

        def progress(done: int, total: int) -> None:
            bar.total = total
            bar.n = done
            bar.refresh()

        def notice(line: str) -> None:
            bar.write(f"lynxsim: {line}", file=sys.stderr)

        outcome = run_sweep(spec, out, backend=backend, progress=progress, notice=notice)
    maps = [] if args.no_maps else write_maps(spec, outcome.table, out)
    table = outcome.table
    counts: dict[str, dict[str, dict[str, int]]] = {}
    for task, kind, verdict in zip(
        table["task"].tolist(), table["type"].tolist(), table["verdict"].tolist()
    ):
        counts.setdefault(task, {}).setdefault(kind, Counter())[verdict] += 1
    if args.json:
        print(
            json.dumps(
                {
                    "sweep": spec.name,
                    "runs": len(table["task"]),
                    "csv": str(outcome.csv),
                    "npz": str(outcome.npz),
                    "maps": [str(m) for m in maps],
                    "shards_computed": outcome.computed,
                    "shards_reused": outcome.reused,
                    "verdicts": {t: {k: dict(v) for k, v in c.items()} for t, c in counts.items()},
                },
                indent=2,
            )
        )
        return 0
    print(
        f"sweep {spec.name}: {len(table['task']):,} runs ({outcome.computed} shards computed, "
        f"{outcome.reused} reused)"
    )
    header = Verdict.labels()
    print(f"{'task':20s} {'type':10s} " + " ".join(f"{h:>13s}" for h in header))
    for task, kinds in counts.items():
        for kind, c in kinds.items():
            print(f"{task:20s} {kind:10s} " + " ".join(f"{c.get(h, 0):13,d}" for h in header))
    print(f"table: {outcome.csv} and {outcome.npz}")
    for path in maps:
        print(f"map: {path}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``sweep`` sub-command."""
    p = sub.add_parser(
        "sweep",
        help="many runs of table-scene tasks varied by a sweep file: a table and maps",
        description="Run every combination a sweep file asks for (tasks, trajectory types, "
        "obstacle placements on a grid or at random, radii, cube positions, planner seeds); "
        "write one table (CSV and NPZ, one row per run) and one map per task and type. "
        "Shards are saved as they finish; running the same sweep again skips them.",
    )
    p.add_argument(
        "sweep", type=Path, help="sweep file (TOML), e.g. sweeps/report_obstacle_map.toml"
    )
    p.add_argument(
        "--out-dir",
        type=Path,
        default=Path("videos") / "sweeps",
        metavar="DIR",
        help="output folder (default videos/sweeps)",
    )
    p.add_argument(
        "--backend",
        choices=("local", "ray"),
        default="local",
        help="local: worker processes on this machine; ray: Ray tasks (pip install "
        "'lynxsim[cluster]')",
    )
    p.add_argument(
        "--address",
        default=None,
        help="--backend ray: the cluster's address (e.g. ray://head:10001, or auto); "
        "default a new local Ray instance",
    )
    p.add_argument(
        "--jobs",
        type=bounded_int(1, MAX_JOBS),
        default=os.cpu_count() or 1,
        help="--backend local: worker processes (default: the CPU count)",
    )
    p.add_argument(
        "--verbose",
        action="store_true",
        help="--backend ray: Ray's own log lines on stderr (default: only its errors)",
    )
    p.add_argument("--no-maps", action="store_true", help="write the table only")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_sweep)
