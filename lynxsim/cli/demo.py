"""``lynxsim demo``: the main job, reproducing the report in simulation."""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np

from lynxsim.arm import frame_origins, ik, tool_pose
from lynxsim.cli.flags import add_quality_flag, quality_of
from lynxsim.cli.units import bounded_int
from lynxsim.reproduce.arm_tables import FK_CASES, TABLE4

__all__ = ["register"]


def _kinematics_tables() -> None:
    print("Forward kinematics (report Figures 4 and 7)")
    print(f"{'q1..q5 [deg]':44s} {'x, y, z [mm] (report)':36s} {'lynxsim':26s} pitch")
    for case in FK_CASES:
        pose = tool_pose(np.radians(case.q_deg))
        p = pose.position * 1e3
        qs = ", ".join(f"{v:g}" for v in case.q_deg)
        ref = ", ".join(f"{v:.2f}" for v in case.position_mm)
        got = ", ".join(f"{v:.2f}" for v in p)
        print(
            f"{qs:44s} {ref:36s} {got:26s} {math.degrees(pose.pitch):.2f} "
            f"(report {case.pitch_deg:.2f})"
        )
    print()
    print("Inverse kinematics of the pick-and-place poses (report Table 4, errata applied)")
    print(f"{'pose':5s} {'x, y, z [mm], pitch [deg]':30s} {'q1..q4 report [deg]':32s} lynxsim")
    for row in TABLE4:
        r = ik(np.array(row.position_mm) * 1e-3, math.radians(row.pitch_deg))
        r.raise_for_status()
        target = ", ".join(f"{v:g}" for v in (*row.position_mm, row.pitch_deg))
        ref = ", ".join(f"{v:.2f}" for v in row.q_deg)
        got = ", ".join(f"{v:.2f}" for v in np.degrees(r.q[:4]))
        print(f"{row.name:5s} {target:30s} {ref:32s} {got}")
    origins = frame_origins(ik(np.array(TABLE4[0].position_mm) * 1e-3, math.radians(-90.0)).q) * 1e3
    print(
        f"P1 elbow origin {np.round(origins[3], 2).tolist()} mm, "
        f"wrist origin {np.round(origins[4], 2).tolist()} mm "
        "(report (0, 147.16, 104.89), (0, 300, 98))"
    )


def _simulations(args: argparse.Namespace) -> None:
    from tqdm import tqdm

    from lynxsim.cli.play import SUMMARY_HEADER, summary_row
    from lynxsim.demo.expert import EXPERT_SEED, EXPERT_VIDEO, expert_job
    from lynxsim.demo.index_page import write_demo_index
    from lynxsim.demo.jobs import Job, run_jobs
    from lynxsim.demo.obstacle_map import MAP_DIR, MAP_STEP_MM, MapSummary, map_job
    from lynxsim.demo.rrr import FIGURE20_FILE, rrr_jobs
    from lynxsim.demo.runs import demo_jobs, demo_runs, demo_tasks
    from lynxsim.envs.evaluation import EpisodeStats
    from lynxsim.envs.registration import PICK_AND_PLACE_ID
    from lynxsim.sim.render import RenderSettings
    from lynxsim.sim.report import RunReport
    from lynxsim.sweep.maps import REPORT_MAP_TASKS

    out: Path = args.out_dir
    runs = list(demo_runs(demo_tasks(args.tasks), lambda m: print(f"skipped: {m}")))
    counts: dict[str, int] = {}
    for run in runs:
        counts[run.robot.name] = counts.get(run.robot.name, 0) + 1
    quality = quality_of(args)
    render = RenderSettings(quality=quality)
    jobs: list[Job[RunReport | EpisodeStats | MapSummary | None]] = [
        *demo_jobs(runs, out, render),
        *rrr_jobs(out, tasks=args.tasks),
        expert_job(out, quality),
    ]
    n_other = len(jobs)
    if all((args.tasks / name).is_file() for name in REPORT_MAP_TASKS):
        jobs.append(map_job(out, args.tasks))
    else:
        print(f"skipped: the obstacle map needs {', '.join(REPORT_MAP_TASKS)} in {args.tasks}")
    workers = min(args.jobs, len(jobs))
    print(
        f"\nSimulating {', '.join(f'{n} {name} runs' for name, n in counts.items()) or 'no runs'}"
        ", an expert episode"
        f"{f' and a {MAP_STEP_MM:g} mm obstacle map' if len(jobs) > n_other else ''} into "
        f"{out}/ ({len(jobs)} jobs, {workers} at a time, {quality.value} rendering)"
    )
    with tqdm(total=len(jobs), unit="job", disable=args.quiet, file=sys.stderr) as bar:

        def progress(k: int, fraction: float) -> None:
            bar.n = min(len(jobs), k + fraction)
            bar.refresh()

        results = run_jobs(jobs, progress, workers=workers)
    print(SUMMARY_HEADER)
    for report in results:
        if isinstance(report, RunReport):
            print(summary_row(report))
    print(f"\n3-RRR Figure 20 poses judged by simulation: {out / FIGURE20_FILE}")
    print((out / FIGURE20_FILE).read_text().rstrip())
    for stats in results:
        if isinstance(stats, EpisodeStats):
            first = "-" if stats.first_success_step is None else str(stats.first_success_step)
            print(
                f"\n{PICK_AND_PLACE_ID}, scripted expert, seed {EXPERT_SEED}: success "
                f"{stats.success} (first at step {first} of {stats.steps}), return "
                f"{stats.episode_return:.1f}, arm-obstacle contact steps {stats.collision_steps}; "
                f"video {out / EXPERT_VIDEO}"
            )
    for summary in results:
        if isinstance(summary, MapSummary):
            print(
                f"\nWhere may the report's cylinder stand? Its centre on a {MAP_STEP_MM:g} mm grid "
                "over the table: share of placements each motion clears"
            )
            for task, kind, placements, clear in summary.rows:
                share = clear / placements if placements else 0.0
                print(f"  {task:20s} {kind:8s} {clear:5d} of {placements:5d} ({share:.0%})")
            print(f"  maps in {out / MAP_DIR}/")
    print(f"\nVideos and JSON reports in {out}/, plots in {out / 'plots'}/")
    print(f"All of it on one page: {write_demo_index(out, results)}")


def _demo(args: argparse.Namespace) -> int:
    if not args.tasks.is_dir():  # before any work: a mistyped folder is not "no tasks"
        raise NotADirectoryError(f"--tasks {args.tasks}: no such folder of task files")
    _kinematics_tables()
    _simulations(args)
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``demo`` sub-command."""
    p = sub.add_parser(
        "demo",
        help="run the main job: reproduce the report in simulation",
        description="Print the report's kinematic tables reproduced, then simulate every task "
        "of the tasks folder with every trajectory type: MP4s, run reports, plots, a summary.",
    )
    p.add_argument("--tasks", type=Path, default=Path("tasks"), help="folder of task files")
    p.add_argument(
        "--out-dir",
        type=Path,
        default=Path("videos"),
        metavar="DIR",
        help="output folder (default videos/)",
    )
    add_quality_flag(p)
    p.add_argument(
        "--jobs",
        type=bounded_int(1, 64),
        default=os.cpu_count() or 1,
        help="jobs (runs, plots, the expert episode) run at the same time, one process each "
        "(default: the CPU count)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_demo)
