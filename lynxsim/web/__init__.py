"""Web pages of runs: replay data, its file, the self-contained replay page, the demo's index.

Pure Python and NumPy (no MuJoCo): :mod:`~lynxsim.web.replay_data` (what a
replay holds), :mod:`~lynxsim.web.poses` (16-bit poses, interpolation, error
bound), :mod:`~lynxsim.web.replay_file` (``RUN.replay.npz``, checked on
reading), :mod:`~lynxsim.web.verdicts` (the run report read back and shown),
:mod:`~lynxsim.web.page` (the replay page), :mod:`~lynxsim.web.index` (the
demo's ``index.html``). The page's HTML, script and styles are package data in
``assets/``. Replays are made from a model and a log by :mod:`lynxsim.sim.replay`.
"""
