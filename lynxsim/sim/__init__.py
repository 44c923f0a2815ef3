"""Simulation layer: the only part of lynxsim that imports MuJoCo.

Importing this package defaults ``MUJOCO_GL`` to ``egl`` when no display is
present (:func:`lynxsim.sim.gl.default_gl_backend`); MuJoCo reads it once, when
``mujoco`` is first imported, so import :mod:`lynxsim.sim` before ``mujoco``.

The shared parts are :mod:`~lynxsim.sim.collision` (the collision definition
and the batch checker), :mod:`~lynxsim.sim.stepping` (stepping one run or many,
natively where it can, into logs), :mod:`~lynxsim.sim.summary` (log to report),
:mod:`~lynxsim.sim.recording` (log to video), :mod:`~lynxsim.sim.adapter` (the
protocol every robot's simulation side implements) and the generic joint robot
of the table scene (:mod:`~lynxsim.sim.scene_build`, :mod:`~lynxsim.sim.joint_robot`,
:mod:`~lynxsim.sim.joint_playback`, :mod:`~lynxsim.sim.joint_sim`,
:mod:`~lynxsim.sim.planning`); each robot has its folder (:mod:`lynxsim.sim.arm`,
:mod:`lynxsim.sim.rrr`), which generic code never imports.
"""

from lynxsim.sim.gl import default_gl_backend

default_gl_backend()
