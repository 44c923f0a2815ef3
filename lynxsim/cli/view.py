"""``lynxsim view``: the replay page of a saved run, from its report and replay data."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["register"]


def _view(args: argparse.Namespace) -> int:
    from lynxsim.errors import InvalidInputError
    from lynxsim.fileio import check_destination
    from lynxsim.web.page import page_from_file
    from lynxsim.web.replay_file import REPLAY_SUFFIX
    from lynxsim.web.verdicts import canonical_json, read_report

    report_path: Path = args.report
    if report_path.suffix.lower() != ".json":
        raise InvalidInputError(f"REPORT must be a run report .json file, got {report_path}")
    out: Path = args.out or report_path.with_suffix(".html")
    if out.suffix.lower() not in (".html", ".htm"):
        raise InvalidInputError(f"--out must name an .html file, got {out}")
    check_destination(out)
    report = read_report(report_path)
    replay = report_path.with_suffix(REPLAY_SUFFIX)
    if not replay.is_file():
        raise InvalidInputError(
            f"{report_path}: no replay data beside it ({replay}); 'lynxsim play' saves it"
        )
    page_from_file(replay, out, report_json=canonical_json(report))
    if not args.quiet:
        print(f"replay: {out}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``view`` sub-command."""
    p = sub.add_parser(
        "view",
        help="make the replay page of a saved run (REPORT.json and REPORT.replay.npz)",
        description="Write the self-contained replay page of a run that 'lynxsim play' or "
        "'lynxsim demo' saved: the 3D replay with a time slider, contacts, clearances and the "
        "run report's verdicts, from REPORT.json and the replay data REPORT.replay.npz beside "
        "it (both checked; they must be one run's). The page opens offline in any browser.",
    )
    p.add_argument("report", type=Path, metavar="REPORT.json", help="a run report of lynxsim play")
    p.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="FILE",
        help="the page (default REPORT.html beside the report)",
    )
    p.add_argument("--quiet", action="store_true", help="print nothing on success")
    p.set_defaults(handler=_view)
