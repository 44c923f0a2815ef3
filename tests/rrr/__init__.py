"""Tests of the 3-RRR kinematics (lynxsim.rrr) and its figures (its CLI: tests/cli)."""
