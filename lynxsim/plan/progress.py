"""Progress reports of long planning runs, for a caller's callback (a CLI's progress bar)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

__all__ = ["PlanProgress", "ProgressCallback", "Stage"]

Stage = Literal["planning", "shortening", "timing", "done"]
"""What happens: a segment's planning or shortening starts, the timing of the
motion starts, or a segment (or, with ``segment == segments``, the run) is done."""


@dataclass(frozen=True)
class PlanProgress:
    """One progress report.

    Attributes:
        segment: 0-based index of the segment concerned; ``segments`` for the
            run as a whole (``"timing"``, the final ``"done"``).
        segments: Number of segments of the run.
        label: The segment's label ("" if none).
        stage: What starts now.
        elapsed_s: Wall-clock time since the run started [s].
    """

    segment: int
    segments: int
    label: str
    stage: Stage
    elapsed_s: float


ProgressCallback = Callable[[PlanProgress], None]
"""Called with each :class:`PlanProgress`; its return value is ignored."""
