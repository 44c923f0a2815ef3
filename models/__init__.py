"""MJCF models shipped with lynxsim (the repository's top-level models/ folder)."""
