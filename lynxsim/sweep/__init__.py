"""Sweeps: many runs of the tasks of any robot in the table scene, varied, judged, tabled, mapped.

A sweep file (:mod:`lynxsim.sweep.spec`) names tasks, trajectory types and
what varies: where an obstacle stands (a grid or random placements), its
radius, the cube's start, the planner's seed. :func:`run_sweep` computes the
rows shard by shard on a backend (this process, a process pool, or Ray:
:mod:`lynxsim.sweep.ray_backend`, imported only when asked for) and writes one
table (:mod:`lynxsim.sweep.table`). Obstacle placements are judged
(:mod:`lynxsim.sim.sweep_judge`) on one physics run per (task, type, cube)
recorded without the obstacle (:mod:`lynxsim.sim.recorded` says why that is
exact), which makes a map of thousands of placements cost about one run.

Ray is never imported by this package itself.
"""

from lynxsim.sim.recorded import RecordedRun, ReplayMismatchError
from lynxsim.sim.sweep_judge import PlacementJudge, PlacementResults
from lynxsim.sweep.runner import (
    Group,
    LocalBackend,
    Shard,
    SweepOutcome,
    compute_shard,
    groups,
    run_sweep,
    shards,
)
from lynxsim.sweep.spec import ObstacleSweep, SweepFileError, SweepSpec, load_sweep, parse_sweep
from lynxsim.sweep.table import COLUMNS, VERDICTS, Table, read_npz, write_csv, write_npz
from lynxsim.verdicts import Verdict

__all__ = [
    "COLUMNS",
    "VERDICTS",
    "Group",
    "LocalBackend",
    "ObstacleSweep",
    "PlacementJudge",
    "PlacementResults",
    "RecordedRun",
    "ReplayMismatchError",
    "Shard",
    "SweepFileError",
    "SweepOutcome",
    "SweepSpec",
    "Table",
    "Verdict",
    "compute_shard",
    "groups",
    "load_sweep",
    "parse_sweep",
    "read_npz",
    "run_sweep",
    "shards",
    "write_csv",
    "write_npz",
]
