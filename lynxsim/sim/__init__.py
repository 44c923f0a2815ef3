"""Simulation layer: the only part of lynxsim that imports MuJoCo.

Importing this package defaults ``MUJOCO_GL`` to ``egl`` when no display is
present (:func:`lynxsim.sim.gl.default_gl_backend`); MuJoCo reads it once, when
``mujoco`` is first imported, so import :mod:`lynxsim.sim` before ``mujoco``.

The shared parts are :mod:`~lynxsim.sim.collision` (the collision definition
and the batch checker), :mod:`~lynxsim.sim.rollout` (stepping),
:mod:`~lynxsim.sim.sensors` and :mod:`~lynxsim.sim.records` (what a natively
stepped run records, and its records), :mod:`~lynxsim.sim.overlap` (stepping
shared between threads), :mod:`~lynxsim.sim.batch` (many runs stepped
natively, the same logs),
:mod:`~lynxsim.sim.summary` (log to report), :mod:`~lynxsim.sim.recording`
(log to video); each robot has its folder (:mod:`lynxsim.sim.arm`,
:mod:`lynxsim.sim.rrr`).
"""

from lynxsim.sim.gl import default_gl_backend

default_gl_backend()
