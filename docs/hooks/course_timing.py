"""MkDocs hook: the course's kernels find ``checks``; each chapter's execution time is logged.

mkdocs-jupyter executes a chapter while its page renders, between the
``on_page_markdown`` and ``on_page_content`` events, in a kernel started in the
directory mkdocs runs in; this hook puts ``docs/course`` on the kernels'
``PYTHONPATH`` (so that ``import checks`` works as it does beside the chapter) and
logs the time each chapter took and the total when the build ends.
"""

from __future__ import annotations

import logging
import os
import time
from pathlib import Path
from typing import Any

log = logging.getLogger("mkdocs.hooks.course_timing")

_started: dict[str, float] = {}
_taken: dict[str, float] = {}


def on_config(config: Any, **kwargs: Any) -> Any:
    """Put the course folder on the PYTHONPATH that the chapters' kernels inherit."""
    course = str(Path(config["docs_dir"]) / "course")
    paths = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    if course not in paths:
        os.environ["PYTHONPATH"] = os.pathsep.join([course, *paths])
    return config


def _is_chapter(page: Any) -> bool:
    path = str(page.file.src_uri)
    return path.startswith("course/") and path.endswith(".py")


def on_page_markdown(markdown: str, page: Any, **kwargs: Any) -> str:
    """Start a chapter's clock."""
    if _is_chapter(page):
        _started[page.file.src_uri] = time.perf_counter()
    return markdown


def on_page_content(html: str, page: Any, **kwargs: Any) -> str:
    """Stop it and log the chapter's execution time [s]."""
    if _is_chapter(page):
        taken = time.perf_counter() - _started.pop(page.file.src_uri)
        _taken[page.file.src_uri] = taken
        log.info("course: %s executed in %.1f s", page.file.src_uri, taken)
    return html


def on_post_build(**kwargs: Any) -> None:
    """Log the whole course's execution time [s]."""
    if _taken:
        total = sum(_taken.values())
        log.info("course: %d chapters executed in %.1f s", len(_taken), total)
