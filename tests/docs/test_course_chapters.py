"""Every course chapter ends with exercises that call the checks, and the site lists it."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

COURSE = Path(__file__).resolve().parents[2] / "docs" / "course"
CHAPTERS = sorted(COURSE.glob("[0-9][0-9]_*.py"))


def test_there_are_chapters() -> None:
    assert len(CHAPTERS) >= 6


@pytest.mark.parametrize("chapter", CHAPTERS, ids=[c.stem for c in CHAPTERS])
def test_a_chapter_ends_with_checked_exercises(chapter: Path) -> None:
    text = chapter.read_text()
    assert text.startswith("# %% [markdown]\n# # "), "a chapter opens with its title cell"
    cells = re.split(r"^# %%.*$", text, flags=re.MULTILINE)
    code = [c for c in cells if c.strip() and not c.lstrip().startswith("# ")]
    last = ast.parse(code[-1])
    calls = {
        n.func.id
        for n in ast.walk(last)
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
    }
    assert any(name.startswith("check_") for name in calls), "the last code cell runs a check"
    assert re.search(r"^# (\*\*(Exercise )?\d+\.\d+\*\*|## Exercise)", text, flags=re.MULTILINE)


@pytest.mark.parametrize("chapter", CHAPTERS, ids=[c.stem for c in CHAPTERS])
def test_the_site_lists_the_chapter(chapter: Path) -> None:
    nav = (COURSE.parents[1] / "mkdocs.yml").read_text()
    index = (COURSE / "index.md").read_text()
    assert f"course/{chapter.name}" in nav
    assert f"({chapter.name})" in index


def test_the_site_build_executes_every_cell() -> None:
    """CI's docs step counts the chapters the build ran: it must run them all, errors fatal."""
    config = (COURSE.parents[1] / "mkdocs.yml").read_text()
    plugin = config[config.index("- mkdocs-jupyter:") : config.index("- mkdocstrings:")]
    for setting in ("execute: true", "allow_errors: false", "cache: false"):
        assert setting in plugin
    assert "execute_ignore" not in plugin
