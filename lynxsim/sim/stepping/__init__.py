"""Stepping: a robot's commands played in MuJoCo, one run or many, into logs.

Robot-free; a robot's folder (:mod:`lynxsim.sim.arm`, :mod:`lynxsim.sim.rrr`)
samples its motion on :func:`~lynxsim.sim.stepping.commands.physics_grid` and
calls these.

- :mod:`~lynxsim.sim.stepping.commands`: the physics grid, commands checked and
  laid out as the controls of every step;
- :mod:`~lynxsim.sim.stepping.rollout`: one run, in a Python loop or natively
  (:mod:`~lynxsim.sim.stepping.native`: ``mujoco.rollout`` in chunks);
- :mod:`~lynxsim.sim.stepping.batch`: many runs of one model, natively, the same logs;
- :mod:`~lynxsim.sim.stepping.sensors` and :mod:`~lynxsim.sim.stepping.records`:
  what a natively stepped run records, and its records;
- :mod:`~lynxsim.sim.stepping.overlap`: native stepping shared between threads;
- :mod:`~lynxsim.sim.stepping.log`: the records made into a run's log.
"""
