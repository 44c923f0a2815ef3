"""``lynxsim fk | ik | workspace``: the arm's kinematics at the command line.

Lengths in mm and angles in degrees unless ``--si`` is given (m, rad).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np

from lynxsim.arm import FRAME_NAMES, frame_origins, ik, sample_workspace, tool_pose
from lynxsim.bounds import MAX_SAMPLES
from lynxsim.cli.units import Units, add_unit_flags, bounded_int, finite_float, json_list, seed_int
from lynxsim.fileio import check_destination

__all__ = ["register"]


def _fk(args: argparse.Namespace) -> int:
    u = Units(args.si)
    q = np.array([u.angle_in(getattr(args, f"q{j}"), f"Q{j}") for j in range(1, 6)])
    pose = tool_pose(q)
    origins = frame_origins(q)
    out: dict[str, Any] = {
        "units": {"length": u.length, "angle": u.angle},
        "q": json_list(u.angle_out(q)),
        "tool_position": json_list(u.length_out(pose.position)),
        "pitch": json_list(u.angle_out(pose.pitch)),
        "roll": json_list(u.angle_out(pose.roll)),
        "frame_origins": {
            name: json_list(u.length_out(o)) for name, o in zip(FRAME_NAMES, origins)
        },
    }
    if args.json:
        print(json.dumps(out, indent=2))
        return 0
    x, y, z = (u.fmt_length(v) for v in out["tool_position"])
    print(
        f"tool  x {x:>10s}  y {y:>10s}  z {z:>10s} {u.length}   "
        f"pitch {u.fmt_angle(out['pitch']):>8s} {u.angle}   "
        f"roll {u.fmt_angle(out['roll']):>8s} {u.angle}"
    )
    for name, o in out["frame_origins"].items():
        coords = " ".join(f"{u.fmt_length(v):>10s}" for v in o)
        print(f"  {name:7s} {coords} {u.length}")
    return 0


def _ik(args: argparse.Namespace) -> int:
    u = Units(args.si)
    values = [args.x, args.y, args.z, args.pitch] + ([args.roll] if args.roll is not None else [])
    p = np.array([u.length_in(v, n) for v, n in ((args.x, "X"), (args.y, "Y"), (args.z, "Z"))])
    roll = None if args.roll is None else u.angle_in(args.roll, "ROLL")
    result = ik(p, u.angle_in(args.pitch, "PITCH"), roll)
    if not result.ok:
        target = ", ".join(f"{v:g}" for v in values)
        result.raise_for_status(
            context=f"no solution for target ({target}) [{u.length}, {u.angle}]"
        )
    if args.json:
        out = {
            "units": {"angle": u.angle},
            "q": json_list(u.angle_out(result.q)),
            "candidates": [
                {"q": json_list(u.angle_out(c)), "valid": bool(v)}
                for c, v in zip(result.candidates, result.valid)
            ],
        }
        print(json.dumps(out, indent=2))
        return 0
    q = json_list(u.angle_out(result.q))
    print("q1..q5 [" + u.angle + "]: " + "  ".join(u.fmt_angle(v) for v in q))
    n_valid = int(result.valid.sum())
    if n_valid > 1:
        print(f"({n_valid} valid solutions; --json lists them all)")
    return 0


def _workspace(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from lynxsim.plots.arm_workspace import plot_arm_workspace
    from lynxsim.plots.style import check_png

    check_destination(check_png(args.out, "--out"))
    rng = np.random.default_rng(args.seed)
    with tqdm(total=args.samples, unit="q", disable=args.quiet) as bar:
        samples = sample_workspace(
            args.samples, rng, progress=lambda done, n: bar.update(done - bar.n)
        )
    plot_arm_workspace(samples, args.out)
    p = samples.position * 1e3
    lo, hi = p.min(axis=0), p.max(axis=0)
    extent = ", ".join(f"{a} [{lo[i]:.0f}, {hi[i]:.0f}]" for i, a in enumerate("xyz"))
    print(
        f"wrote {args.out}: {args.samples:,} samples, {extent} mm, "
        f"{(p[:, 0] < 0).mean():.1%} behind the base plane (x < 0)"
    )
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``fk``, ``ik`` and ``workspace`` sub-commands."""
    p = sub.add_parser(
        "fk",
        help="tool pose from joint angles (deg by default)",
        description="Forward kinematics. Angles in degrees, output in mm "
        "and degrees, unless --si (rad in, m and rad out).",
    )
    for j in range(1, 6):
        p.add_argument(f"q{j}", type=finite_float, metavar=f"Q{j}", help=f"joint {j} angle")
    add_unit_flags(p)
    p.set_defaults(handler=_fk)

    p = sub.add_parser(
        "ik",
        help="joint angles for a tool target (mm, deg by default)",
        description="Inverse kinematics of a tool point X Y Z [mm], pitch "
        "[deg] and optional roll q5 [deg]; --si for m and rad.",
    )
    for name in ("x", "y", "z", "pitch"):
        p.add_argument(name, type=finite_float, metavar=name.upper())
    p.add_argument("roll", type=finite_float, nargs="?", default=None, metavar="ROLL")
    add_unit_flags(p)
    p.set_defaults(handler=_ik)

    p = sub.add_parser(
        "workspace",
        help="plot the reachable workspace (PNG)",
        description="Sample the joint ranges uniformly and plot the tool points.",
    )
    p.add_argument(
        "--out", type=Path, default=Path("workspace.png"), metavar="FILE", help="PNG file to write"
    )
    p.add_argument(
        "--samples",
        type=bounded_int(1, MAX_SAMPLES),
        default=1_000_000,
        help=f"joint samples, 1 to {MAX_SAMPLES:,} (default 10^6)",
    )
    p.add_argument("--seed", type=seed_int, default=0, help="random seed (0 to 2^63-1)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_workspace)
