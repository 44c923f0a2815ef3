"""Suite-wide settings: seeded hypothesis, and how the suite splits over pytest-xdist's workers.

Hypothesis runs derandomized (seeded), so every run checks the same inputs;
``HYPOTHESIS_PROFILE=explore`` draws fresh random inputs instead, for a longer hunt.

The suite runs in two processes (``-n 2 --dist loadgroup`` in pyproject's addopts). Each
worker builds the fixtures it uses, so a test that shares a costly fixture stays on the
worker that built it: every test of a module with a fixture of module scope runs on one
worker, and so does every test of a folder whose ``conftest.py`` shares costly recorded
runs for the whole session (:data:`SHARED_SESSION_FOLDERS`). Every other test is sent to
whichever worker is free.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

SHARED_SESSION_FOLDERS = ("tests/replay",)
"""Folders whose session fixtures record runs or start a browser (seconds each): one worker."""


def _group(item: pytest.Item) -> str | None:
    """The worker group of a test: its folder, its module, or None (any worker)."""
    path = item.nodeid.split("::", 1)[0]
    for folder in SHARED_SESSION_FOLDERS:
        if path.startswith(folder + "/"):
            return folder
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return None
    for defs in info.name2fixturedefs.values():
        fixture = defs[-1]
        if fixture.scope == "module" and fixture.baseid:  # a fixture of the suite's own
            return path
    return None


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark each test that shares a costly fixture with its group (``xdist_group``).

    Only under ``--dist loadgroup`` (``-p no:xdist`` runs the suite in one process as before).
    """
    if getattr(config.option, "dist", None) != "loadgroup":
        return
    for item in items:
        if (group := _group(item)) is not None:
            item.add_marker(pytest.mark.xdist_group(group))
