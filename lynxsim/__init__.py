"""lynxsim: the Lynxmotion arm and a 3-RRR parallel robot, simulated in MuJoCo."""

__version__ = "0.1.0"
