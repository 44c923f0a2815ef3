"""Tests of the ``lynxsim`` command line (lynxsim.cli)."""
