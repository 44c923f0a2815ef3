"""MJCF models shipped with lynxsim; :mod:`lynxsim.resources` finds them by name."""
