"""The robot interface every command uses: robot records, registered by name.

A robot is a :class:`Robot` record (its row of :mod:`lynxsim.registry`, the
types it builds, its pure task -> motion builder, its simulation side
``"module:attribute"``, cameras, run options, joint kinematics, planning
request and real backend, each where it has one), registered with
:func:`register` (as Gymnasium's ``register``), looked up with :func:`get`.
The built-in records are ``lynxsim.robots.arm:ROBOT`` and
``lynxsim.robots.rrr:ROBOT``; an installed package offers more through the
entry point group ``lynxsim.robots``. Every command goes through
:func:`motion`, :func:`plan`, :func:`simulation` and :func:`real_backend`,
which check the record's fields, never its name. docs/adding_a_robot.md walks
through adding one.

Importing this package imports neither MuJoCo nor any robot.
"""

from lynxsim.robots.catalog import every, get, names, register, restore, rows, unregister
from lynxsim.robots.commands import motion, plan, real_backend, simulation, with_capability
from lynxsim.robots.robot import MotionBuilder, PlanningBuilder, Robot

__all__ = [
    "MotionBuilder",
    "PlanningBuilder",
    "Robot",
    "every",
    "get",
    "motion",
    "names",
    "plan",
    "real_backend",
    "register",
    "restore",
    "rows",
    "simulation",
    "unregister",
    "with_capability",
]
