"""The 3-RRR in MuJoCo: its closed-loop scene, playback, tasks and verification by simulation."""
