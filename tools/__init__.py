"""Campaign scripts (fuzzing); importable by the tests as ``tools.<name>``."""
