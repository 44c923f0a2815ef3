"""``python -m lynxsim`` runs the command line."""

from lynxsim.cli import run

run()
