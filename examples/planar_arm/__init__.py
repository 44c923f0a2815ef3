"""A planar three-link arm added to lynxsim from outside the library.

``import planar_arm`` registers it (:mod:`planar_arm.robot`); its task files
(``tasks/``) then load, and every lynxsim command runs them. See
docs/adding_a_robot.md.
"""

from planar_arm.robot import ROBOT

__all__ = ["ROBOT"]
