"""Flags and settings more than one sub-command takes, defined once: ``--quality``.

``lynxsim demo`` and ``lynxsim play`` render with the same presets and the
same default, :data:`DEFAULT_QUALITY` (``medium``: shadows without
multisampling, the look of ``default`` at half its cost), so that a run's
video is the same whichever command made it.
"""

from __future__ import annotations

import argparse
import warnings

from lynxsim.sim.quality import Quality

__all__ = ["DEFAULT_QUALITY", "add_quality_flag", "quality_of", "quiet_env_versions"]

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


def quiet_env_versions() -> None:
    """Keep Gymnasium's note that a newer env version exists off the command line's stderr.

    The commands default to the ``-v1`` envs on purpose
    (:data:`lynxsim.envs.registration.LATEST_ENV_IDS`); the note would break the
    one-line rule of stderr. Gymnasium adds its own filter when it is imported, so
    it is imported first and this one goes in front of it.
    """
    import gymnasium.logger  # noqa: F401  (its filter first)

    warnings.filterwarnings(
        "ignore",
        message=r".*The environment Lynx\w+-v\d+ is out of date",
        category=DeprecationWarning,
    )
