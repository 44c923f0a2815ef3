"""Tests of the 3-RRR kinematics (lynxsim.rrr), its figures and its CLI."""
