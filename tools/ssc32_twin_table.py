"""Print the digital-twin table (docs/real_arm.md): every shipped arm task through the SSC-32U twin.

For each arm task of ``tasks/`` (its own trajectory type) and each stream (streamed
every 100 ms at 9600 baud, the board's default; streamed every 20 ms at 115200 baud;
one timed move per segment), and for a task whose own motion collides also its
``planned`` motion: the board's interpolation against the trajectory, and
the digital twin's tool tracking error against ideal playback, with both verdicts.

    python tools/ssc32_twin_table.py [--tasks DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import time

import numpy as np

from lynxsim.errors import CommandLimitError
from lynxsim.real.arm import load_arm_calibration
from lynxsim.real.stream import StreamOptions
from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.sim.arm.ssc32 import run_twin
from lynxsim.tasks import find_tasks

STREAMS = (
    ("streamed 100 ms, 9600 baud", 9600, StreamOptions(period_ms=100)),
    ("streamed 20 ms, 115200 baud", 115200, StreamOptions(period_ms=20)),
    ("waypoint moves, 9600 baud", 9600, StreamOptions(mode="waypoints")),
)


def main() -> None:
    """Print the table (markdown)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tasks", default="tasks")
    args = parser.parse_args()
    base = load_arm_calibration()
    print(
        "| task (type) | stream | board vs trajectory: worst joint / tool | ideal max tool error "
        "| twin max tool error | extra max / RMS | verdict ideal / twin |"
    )
    print("|---|---|---|---|---|---|---|")
    start = time.perf_counter()
    for task in find_tasks(args.tasks, "arm"):
        own = motion(ARM, task)
        # A motion that collides stalls against its obstacle (huge errors either way):
        # its planned motion around the obstacles shows what the board adds.
        kinds = (
            [own]
            if not run_twin(task, own, base).comparison.ideal.collided
            else [own, motion(ARM, task, "planned")]
        )
        for trajectory, (label, baud, options) in itertools.product(kinds, STREAMS):
            name = f"{task.name} ({trajectory.kind.value})"
            try:
                run = run_twin(task, trajectory, dataclasses.replace(base, baud=baud), options)
            except CommandLimitError as exc:
                print(f"| {name} | {label} | refused: {exc} | | | | |")
                continue
            c = run.comparison
            d = c.deviation
            joint = np.degrees(max(d.joint_max_rad))
            verdict = {True: "collides", False: "clear"}
            print(
                f"| {name} | {label} | {joint:.2f} deg / "
                f"{(d.tool_max_m or 0.0) * 1e3:.1f} mm | {c.ideal.tool_max_error_m * 1e3:.1f} mm "
                f"| {c.twin.tool_max_error_m * 1e3:.1f} mm | "
                f"{c.extra_tool_max_error_m * 1e3:+.1f} / {c.extra_tool_rms_error_m * 1e3:+.1f} mm "
                f"| {verdict[c.ideal.collided]} / {verdict[c.twin.collided]} |"
            )
    print(f"\n({time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
