"""lynxsim: the Lynxmotion arm and a 3-RRR parallel robot, simulated in MuJoCo."""

__version__ = "0.1.0"

from lynxsim.envs.registration import register_envs

register_envs()
