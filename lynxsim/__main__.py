"""``python -m lynxsim`` runs the command line."""

import sys

from lynxsim.cli import main

sys.exit(main())
