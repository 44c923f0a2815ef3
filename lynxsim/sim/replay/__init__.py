"""Replays of recorded runs: a MuJoCo model and a run's log to the data a replay page draws.

:func:`~lynxsim.sim.replay.export.export_replay` makes the
:class:`~lynxsim.web.replay_data.ReplayData`; :func:`~lynxsim.sim.replay.export.save_replay`
writes it beside the run's report; :mod:`lynxsim.web.page` makes the page.
"""

from lynxsim.sim.replay.export import FREE_CAMERA, REPLAY_FPS, export_replay, save_replay

__all__ = ["FREE_CAMERA", "REPLAY_FPS", "export_replay", "save_replay"]
