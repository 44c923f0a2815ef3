"""Suite-wide settings: hypothesis runs derandomized (seeded), so every run checks the same inputs.

``HYPOTHESIS_PROFILE=explore`` draws fresh random inputs instead, for a longer hunt.
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
