"""A digital twin's run: a motion played ideally and through a servo controller, compared.

The result types of a robot's real backend (:class:`lynxsim.sim.adapter.RealBackend`;
the arm's: :func:`lynxsim.sim.arm.ssc32.run_twin`): the command stream the board
would receive, what the board sends, the ideal playback and the twin's, and
their comparison. Robot-free.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from lynxsim.sim.report import RunReport
from lynxsim.sim.summary import Playback

if TYPE_CHECKING:
    from lynxsim.real.deviation import BoardMotion, StreamDeviation
    from lynxsim.real.stream import CommandStream

__all__ = ["TwinComparison", "TwinRun"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class TwinComparison:
    """The digital twin's run against the ideal playback of the same trajectory.

    Attributes:
        ideal: Report of the ideal playback (targets updated every physics step).
        twin: Report of the run through the board and the servos' dead bands.
        deviation: The board's interpolation against the trajectory.
    """

    ideal: RunReport
    twin: RunReport
    deviation: StreamDeviation

    @property
    def extra_tool_max_error_m(self) -> float:
        """Twin's largest tool tracking error minus the ideal's [m]."""
        return self.twin.tool_max_error_m - self.ideal.tool_max_error_m

    @property
    def extra_tool_rms_error_m(self) -> float:
        """Twin's RMS tool tracking error minus the ideal's [m]."""
        return self.twin.tool_rms_error_m - self.ideal.tool_rms_error_m

    @property
    def same_verdicts(self) -> bool:
        """Whether both runs collide alike: the same verdict and the same obstacles hit."""
        hit = [{o.name for o in r.obstacles if o.collided} for r in (self.ideal, self.twin)]
        return self.ideal.collided == self.twin.collided and hit[0] == hit[1]

    def lines(self) -> list[str]:
        """The comparison as readable lines (mm)."""
        verdict = {True: "collides", False: "clear"}
        return [
            "ssc32 twin vs ideal playback: tool error max "
            f"{self.twin.tool_max_error_m * 1e3:.2f} mm "
            f"(ideal {self.ideal.tool_max_error_m * 1e3:.2f} mm, extra "
            f"{self.extra_tool_max_error_m * 1e3:+.2f} mm), RMS "
            f"{self.twin.tool_rms_error_m * 1e3:.2f} mm (extra "
            f"{self.extra_tool_rms_error_m * 1e3:+.2f} mm)",
            f"verdicts: ideal {verdict[self.ideal.collided]}, twin {verdict[self.twin.collided]}"
            + ("" if self.same_verdicts else "  (THEY DIFFER)"),
        ]


@dataclass(frozen=True)
class TwinRun:
    """A trajectory's stream, board motion, ideal and twin playbacks.

    Attributes:
        stream: The command stream.
        motion: What the board sends.
        ideal: The ideal playback.
        twin: The twin's playback.
        comparison: The two compared.
    """

    stream: CommandStream
    motion: BoardMotion
    ideal: Playback
    twin: Playback
    comparison: TwinComparison

    def simulated_joints(self) -> tuple[FloatArray, FloatArray]:
        """The twin's simulated joints on the stream's clock: times (S,) [s], joints (S, n) [rad].

        The stream's clock starts when its first line is sent; the motion starts
        :attr:`BoardMotion.latency_s` later.
        """
        log = self.twin.log
        return log.time_s + self.motion.latency_s, log.q
