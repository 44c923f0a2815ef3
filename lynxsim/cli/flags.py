"""Flags more than one sub-command takes, defined once: ``--quality``.

``lynxsim demo`` and ``lynxsim play`` render with the same presets and the
same default, :data:`DEFAULT_QUALITY` (``medium``: shadows without
multisampling, the look of ``default`` at half its cost), so that a run's
video is the same whichever command made it.
"""

from __future__ import annotations

import argparse

from lynxsim.sim.quality import Quality

__all__ = ["DEFAULT_QUALITY", "add_quality_flag", "quality_of"]

DEFAULT_QUALITY = Quality.MEDIUM
"""The rendering preset of the commands' videos unless ``--quality`` says otherwise."""


def add_quality_flag(parser: argparse.ArgumentParser) -> None:
    """Add ``--quality {lean,fast,medium,default}`` (default :data:`DEFAULT_QUALITY`)."""
    parser.add_argument(
        "--quality",
        choices=[q.value for q in Quality],
        default=DEFAULT_QUALITY.value,
        help="rendering preset: lean (small images: no shadows or skybox, coarse shapes), "
        "fast (no shadows), medium (shadows; default) or default "
        "(shadows and multisampling, twice the cost of medium)",
    )


def quality_of(args: argparse.Namespace) -> Quality:
    """The preset ``--quality`` chose."""
    return Quality(args.quality)
