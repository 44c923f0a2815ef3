"""lynxsim: the Lynxmotion arm and a 3-RRR parallel robot, simulated in MuJoCo.

Importing ``lynxsim`` loads neither MuJoCo nor Gymnasium; ``import lynxsim.envs``
registers the Gymnasium environments.
"""

__version__ = "0.1.0"
