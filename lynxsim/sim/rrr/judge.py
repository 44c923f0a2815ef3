"""Platform poses judged by simulation: settled in every working mode, and pulled from home.

:func:`judge_poses` asks, of each target pose, the inverse kinematics (does any
working mode reach it?), :func:`~lynxsim.sim.rrr.verify.check_pose` in each
mode it is asked for (the IK's actuated angles commanded: does the platform
settle there, do the links overlap?) and
:func:`~lynxsim.sim.rrr.verify.pull_toward` (actuators off, the platform pulled
from home by a spring, no IK). The report's Figure 20
(:mod:`lynxsim.reproduce.figure20`) is judged this way.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.rrr import N_MODES, ik
from lynxsim.sim.rrr.model import RRRIds, load_rrr_scene
from lynxsim.sim.rrr.verify import PoseCheck, PullCheck, check_pose, pull_toward

__all__ = ["PoseJudgement", "judge_poses"]


@dataclass(frozen=True)
class PoseJudgement:
    """A platform pose judged by simulation.

    Attributes:
        ik_reachable: The inverse kinematics finds the pose (every working mode).
        failing_legs: 1-based legs that cannot reach it (empty when reachable).
        checks: :func:`~lynxsim.sim.rrr.verify.check_pose` in every working mode
            asked (empty when unreachable).
        pull: :func:`~lynxsim.sim.rrr.verify.pull_toward` from ``home``
            (actuators off, no IK).
    """

    ik_reachable: bool
    failing_legs: tuple[int, ...]
    checks: tuple[PoseCheck, ...]
    pull: PullCheck

    @property
    def reached_modes(self) -> tuple[int, ...]:
        """Working modes in which the commanded pose settled within tolerance."""
        return tuple(c.mode for c in self.checks if c.reached)

    @property
    def clear_modes(self) -> tuple[int, ...]:
        """Working modes in which no links overlap at the pose."""
        return tuple(c.mode for c in self.checks if not c.interference)

    @property
    def reachable(self) -> bool:
        """The simulation's verdict: reached in some working mode, or by the pull.

        Commanded with the IK's actuated angles, the platform settles at the
        pose in some working mode; or, where the IK finds nothing, the pulled
        platform gets there anyway.
        """
        return bool(self.reached_modes) or self.pull.reached


def judge_poses(
    targets: Sequence[npt.ArrayLike], *, modes: Sequence[int] = tuple(range(N_MODES))
) -> list[PoseJudgement]:
    """Judge platform poses by simulation, in the shipped 3-RRR scene.

    Args:
        targets: Poses (x, y, alpha), each (3,) [m, m, rad].
        modes: Working modes to settle each reachable pose in.

    Returns:
        One :class:`PoseJudgement` per pose, in order.
    """
    model = load_rrr_scene()
    data = mujoco.MjData(model)
    ids = RRRIds.from_model(model)
    out = []
    for pose in targets:
        target = np.asarray(pose, dtype=float)
        result = ik(target)
        ok = bool(result.ok)
        checks = (
            tuple(check_pose(model, data, target, int(m), ids=ids) for m in modes) if ok else ()
        )
        out.append(
            PoseJudgement(
                ik_reachable=ok,
                failing_legs=result.failing_legs(),
                checks=checks,
                pull=pull_toward(model, data, target, ids=ids),
            )
        )
    return out
