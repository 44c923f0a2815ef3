"""lynxsim.plan is pure (no MuJoCo, no Gymnasium) and leaves nothing on stderr at exit."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import lynxsim.plan

ROOT = Path(__file__).resolve().parents[2]


def run(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )


def test_importing_the_planner_leaves_mujoco_and_gymnasium_out():
    done = run(
        """
        import sys
        import lynxsim.plan
        bad = [m for m in sys.modules if m.split(".")[0] in ("mujoco", "gymnasium")]
        print(bad)
        """
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


PLAN = """
    import numpy as np
    from lynxsim.plan import NoPathError, plan_segment
    from tests.plan.worlds import ENCLOSED_GOAL, LOWER_2D, UPPER_2D, WALL
    result = plan_segment([-0.5, 0.0], [[0.5, 0.2]], WALL, LOWER_2D, UPPER_2D,
                          lipschitz=1.0, seed=2)
    assert result.path.shape[0] >= 3
    try:
        plan_segment([0.0, 0.0], [[0.5, 0.5]], ENCLOSED_GOAL, LOWER_2D, UPPER_2D,
                     lipschitz=1.0, time_limit_s=0.1)
    except NoPathError:
        print("no path")
"""


def test_planning_then_exiting_prints_nothing_on_stderr():
    done = run(PLAN)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "no path"
    assert done.stderr == ""  # no "nanobind: leaked ...", no OMPL log lines


def test_every_name_in_all_resolves():
    for name in lynxsim.plan.__all__:
        assert getattr(lynxsim.plan, name) is not None
