"""MkDocs hook: how long each course chapter took to execute, and all of them together.

mkdocs-jupyter executes a notebook while its page renders, between the
``on_page_markdown`` and ``on_page_content`` events; this hook logs the time
between them for every chapter and the total when the build ends.
"""

from __future__ import annotations

import logging
import time
from typing import Any

log = logging.getLogger("mkdocs.hooks.course_timing")

_started: dict[str, float] = {}
_taken: dict[str, float] = {}


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
