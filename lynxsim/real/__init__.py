"""The real arm: SSC-32U command streams, calibration files, an emulated board, a serial driver.

Pure Python and numpy (no MuJoCo); the serial driver imports pyserial (the
optional extra ``lynxsim[real]``) only when it opens a port. The digital twin,
which plays a stream's pulses through the MuJoCo servos, is
:mod:`lynxsim.sim.arm.ssc32`.

::

    calibration = load_arm_calibration()            # the default file
    stream = command_stream(trajectory, calibration, StreamOptions(mode="streamed"))
    deviation = stream_deviation(trajectory, stream, calibration, arm_tool_points)
"""

from lynxsim.real.arm import DEFAULT_CALIBRATION, arm_tool_points, load_arm_calibration
from lynxsim.real.board import FRAME_S, Ssc32Board, virtual_run
from lynxsim.real.calibration import (
    Calibration,
    GripperCalibration,
    JointCalibration,
    load_calibration,
)
from lynxsim.real.deviation import BoardMotion, StreamDeviation, board_motion, stream_deviation
from lynxsim.real.stream import CommandStream, StreamOptions, TimedLine, command_stream

__all__ = [
    "DEFAULT_CALIBRATION",
    "FRAME_S",
    "BoardMotion",
    "Calibration",
    "CommandStream",
    "GripperCalibration",
    "JointCalibration",
    "Ssc32Board",
    "StreamDeviation",
    "StreamOptions",
    "TimedLine",
    "arm_tool_points",
    "board_motion",
    "command_stream",
    "load_arm_calibration",
    "load_calibration",
    "stream_deviation",
    "virtual_run",
]
