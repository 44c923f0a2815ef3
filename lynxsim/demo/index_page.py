"""The demo as one page: ``index.html`` in its output folder, over everything the demo wrote.

The summary table (each run linking its replay page, MP4 and JSON report),
then the arm's plots, the 3-RRR figures and the Figure 20 verdicts, the
obstacle maps and the expert's episode. Only files that exist are linked.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from lynxsim.demo.expert import EXPERT_SEED, EXPERT_VIDEO
from lynxsim.demo.obstacle_map import MapSummary
from lynxsim.demo.rrr import FIGURE20_FILE
from lynxsim.envs.evaluation import EpisodeStats
from lynxsim.fileio import file_stem
from lynxsim.sim.report import RunReport
from lynxsim.sim.rrr.playback import RRRMetrics
from lynxsim.web.index import IndexFigure, IndexRow, IndexSection, relative_link, write_index

__all__ = ["COLUMNS", "INDEX_FILE", "write_demo_index"]

INDEX_FILE = "index.html"
"""The page's name in the demo's output folder."""
COLUMNS = (
    "task",
    "type",
    "duration",
    "max err",
    "final",
    "collision",
    "clearance",
    "healthy",
)
"""The summary table's columns (those of the demo's printed summary)."""


def _row(out: Path, report: RunReport) -> IndexRow:
    stem = file_stem(report.task, report.trajectory)
    clearance = "-" if report.min_clearance_m is None else f"{report.min_clearance_m * 1e3:.1f} mm"
    collided = "-" if report.obstacle is None else ("YES" if report.collided else "no")
    links = tuple(
        (label, relative_link(out, out / f"{stem}{suffix}"))
        for label, suffix in (("replay", ".html"), ("video", ".mp4"), ("report", ".json"))
        if (out / f"{stem}{suffix}").is_file()
    )
    return IndexRow(
        cells=(
            report.task,
            report.trajectory,
            f"{report.duration_s:.2f} s",
            f"{report.tool_max_error_m * 1e3:.1f} mm",
            f"{report.tool_final_error_m * 1e3:.1f} mm",
            collided,
            clearance,
            "yes" if report.healthy else "NO",
        ),
        status="bad" if report.collided or not report.healthy else "ok",
        links=links,
    )


def _figures(out: Path, paths: Sequence[Path]) -> tuple[IndexFigure, ...]:
    return tuple(IndexFigure(p.stem, relative_link(out, p)) for p in paths if p.is_file())


def write_demo_index(out: Path, results: Sequence[object]) -> Path:
    """Write ``out/index.html`` over the demo's outputs.

    Args:
        out: The demo's output folder.
        results: What the demo's jobs returned (run reports, the expert's
            :class:`EpisodeStats`, the map's :class:`MapSummary`, None).

    Returns:
        The page's path.
    """
    reports = [r for r in results if isinstance(r, RunReport)]
    plots = sorted((out / "plots").glob("*.png"))
    rrr_stems = {
        file_stem(r.task, r.trajectory) for r in reports if isinstance(r.metrics, RRRMetrics)
    }
    rrr = [p for p in plots if p.stem in rrr_stems or p.stem.startswith("rrr_workspace")]
    sections = [
        IndexSection(
            "Arm: joint profiles and tool paths",
            figures=_figures(out, [p for p in plots if p not in rrr]),
        ),
    ]
    figure20 = out / FIGURE20_FILE
    sections.append(
        IndexSection(
            "3-RRR: paths, workspaces and the report's Figure 20 judged by simulation",
            preformatted=figure20.read_text(encoding="utf-8") if figure20.is_file() else "",
            figures=_figures(out, rrr),
            links=((FIGURE20_FILE, relative_link(out, figure20)),) if figure20.is_file() else (),
        )
    )
    for summary in (r for r in results if isinstance(r, MapSummary)):
        table = "\n".join(
            f"{task:20s} {kind:8s} {clear:5d} of {placements:5d} placements clear"
            for task, kind, placements, clear in summary.rows
        )
        sections.append(
            IndexSection(
                "Where may the report's cylinder stand? (obstacle maps)",
                preformatted=table,
                figures=_figures(out, list(summary.maps)),
            )
        )
    video = out / EXPERT_VIDEO
    for stats in (r for r in results if isinstance(r, EpisodeStats)):
        sections.append(
            IndexSection(
                "The scripted pick-and-place expert in the Gymnasium environment",
                text=(
                    f"Seed {EXPERT_SEED}: success {stats.success} after {stats.steps} steps, "
                    f"return {stats.episode_return:.1f}, arm-obstacle contact steps "
                    f"{stats.collision_steps}.",
                ),
                links=(("episode video", relative_link(out, video)),) if video.is_file() else (),
            )
        )
    intro = (
        f"{len(reports)} runs simulated by lynxsim demo. Each replay is a self-contained page: "
        "scrub the run in 3D, see its contacts, clearances and verdicts."
    )
    rows = [_row(out, r) for r in reports]
    return write_index(out / INDEX_FILE, "lynxsim demo", intro, COLUMNS, rows, sections)
