"""The one collision definition: what is the robot, what counts as a hit, how far from one.

* the **robot** is every colliding geom of the robot's bodies (arm, fingers;
  for the 3-RRR its links); the **payload** (the cube) counts as part of the
  robot against obstacles, since whatever the robot carries must not touch them
  either, but its contacts with the robot (a grip) and the table (resting) are not hits;
* an **obstacle hit** is a contact at zero or negative distance between a robot
  or payload geom and an obstacle geom;
* a **self hit** is such a contact between two robot geoms (MuJoCo has already
  filtered parent–child pairs and excluded bodies);
* a **table hit** is such a contact between a robot geom and the table or floor;
* the **clearance** to an obstacle is the smallest signed distance between it and
  any robot or payload geom [m] (negative: penetration), computed exactly
  (``mj_geomDistance``) only for the pairs that a lower bound says could be the
  nearest, below the cap (in penetration: the depth of the pairs the bound
  leaves, which for shallow contacts is the deepest).

Playback's per-step verdict (:class:`ContactTracker`), the environments'
``info["collision"]`` and the batch :class:`CollisionChecker` all use
:func:`classify_contacts` and :func:`clearances` (or its batch form
:func:`clearances_of_states`); nothing else decides.
"""

from lynxsim.sim.collision.checker import CollisionCheck, CollisionChecker
from lynxsim.sim.collision.clearance import (
    CLEARANCE_CAP_M,
    ClearanceGeometry,
    ClearancePlan,
    clearances,
    clearances_of_states,
    obstacle_boxes,
)
from lynxsim.sim.collision.groups import CollisionGroups, ContactClasses, classify_contacts
from lynxsim.sim.collision.tracker import ContactTracker

__all__ = [
    "CLEARANCE_CAP_M",
    "ClearanceGeometry",
    "ClearancePlan",
    "CollisionCheck",
    "CollisionChecker",
    "CollisionGroups",
    "ContactClasses",
    "ContactTracker",
    "classify_contacts",
    "clearances",
    "clearances_of_states",
    "obstacle_boxes",
]
