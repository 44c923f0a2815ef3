"""Tasks: named sequences of poses read from small TOML files.

A task file is declarative and in the report's units, each key naming its
unit; the loader validates it and converts to SI. Example::

    name = "pick_and_place"
    description = "Report Table 4"
    robot = "arm"                    # "arm" (5-DOF arm) or "rrr" (planar 3-RRR)

    [trajectory]
    type = "quintic"                 # default type: free, cubic, quintic, lspb, line, ruckig
    segment_duration_s = 1.0         # one number, or one per segment; leave out for the shortest
    stretch = true                   # lengthen segments the joint limits cannot fit (default false)
    pass_through = false             # ruckig: pass intermediate poses without stopping

    [[poses]]                        # an arm pose: tool point and pitch (roll optional) ...
    name = "P1"
    position_mm = [0.0, 300.0, 0.0]
    pitch_deg = -90.0
    roll_deg = 0.0

    [[poses]]                        # ... or joints directly
    name = "home"
    q_deg = [0.0, 90.0, -90.0, 0.0, 0.0]

    [[obstacles]]                    # any number (none: no obstacle); names unique
    name = "cylinder"
    shape = "cylinder"               # cylinder, box or sphere
    position_mm = [150.0, 150.0, 0.0]  # cylinder, box: centre of the bottom face; sphere: centre
    radius_mm = 40.0                 # cylinder, sphere
    height_mm = 400.0                # cylinder

    [[obstacles]]
    name = "box"
    shape = "box"
    position_mm = [150.0, -150.0, 0.0]
    size_mm = [100.0, 60.0, 350.0]   # full extents along the box's own x, y, z
    yaw_deg = -45.0                  # about the vertical, optional (default 0)

    [[obstacles]]
    name = "ball"
    shape = "sphere"
    position_mm = [200.0, 60.0, 300.0]
    radius_mm = 30.0

    [cube]                           # optional, every key too: lynxsim.scene.REPORT_CUBE's
    position_mm = [0.0, 300.0, 0.0]  # its centre at the start
    size_mm = 25.0                   # edge length
    yaw_deg = 0.0                    # about the vertical
    mass_kg = 0.01
    friction = 1.0                   # sliding friction

Poses of the 3-RRR robot are platform poses: ``x_mm``, ``y_mm``, ``alpha_deg``.

The scene (:class:`~lynxsim.scene.Scene`, ``Task.scene``) is in the arm's base
frame, like the poses. The table top lies at ``TABLE.top_z`` = -12.5 mm, half a
cube below the base plane, so a tool point at z = 0 is the centre of a resting
cube. A cylinder or box whose bottom face lies between the table top and the
base plane (-12.5 mm <= z <= 0) stands on the table: its bottom moves down to
the table top, its top stays at z + height (the report's cylinder above spans
-12.5 to 400 mm and equals :data:`~lynxsim.scene.REPORT_CYLINDER`). A bottom
face higher than 0 is kept (a raised obstacle); one lower than the table top,
a sphere or cube reaching below it, is refused. An obstacle may not enclose
the robot's base (the origin) or the cube's start (its centre). Arm tasks
without ``[cube]`` get the report's cube; 3-RRR tasks have neither obstacles
nor cube (both keys are refused).

Sanity bounds. Most come from :mod:`lynxsim.bounds`, the one place they are
set: every coordinate (pose ``position_mm``, ``x_mm``, ``y_mm``, obstacle and
cube positions) within +-``MAX_COORDINATE_M`` (10 m, 10000 mm), every segment
duration within ``MIN_SEGMENT_S`` .. ``MAX_SEGMENT_S`` (1 ms to 1 h), every angle
(``pitch_deg``, ``roll_deg``, ``q_deg``, ``alpha_deg``, ``yaw_deg``) within
+-``MAX_ANGLE_RAD`` (two turns, +-720 deg; larger ones only make the arithmetic
lose precision). Those of every scene (:mod:`lynxsim.scene`): sizes (radius,
height, edge) 0.1 mm up to the coordinate bound, the cube's mass 0.1 g to 100 kg
and its friction at most 10.

Text. Names (the task's ``name``, pose and obstacle names) are 1 to 100
characters; the ``description`` at most 1000. Both are printable text, one
line: letters, digits, marks, punctuation, symbols and the space of any script;
no control character (NUL, tab, newline, escape sequences), no other
whitespace or invisible format character (``str.isprintable``). A task without
``name`` takes the file's stem, which must pass the same check.

Every problem is reported as a :class:`~lynxsim.errors.TaskFileError` naming
the file and the field (``poses[2].pitch_deg``, ``obstacles[1].radius_mm``,
indices from 0).
"""

from lynxsim.poses import PlanarPose
from lynxsim.tasks.loader import find_tasks, load_task
from lynxsim.tasks.task import Task, TaskPose

__all__ = ["PlanarPose", "Task", "TaskPose", "find_tasks", "load_task"]
