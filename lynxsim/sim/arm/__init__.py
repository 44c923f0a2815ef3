"""The arm in MuJoCo: its scene built from a :class:`~lynxsim.scene.Scene`, playback, tasks."""
