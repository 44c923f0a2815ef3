"""MkDocs hooks: the course's kernels find ``checks``, chapters are timed, Sphinx roles link.

mkdocs-jupyter executes a chapter while its page renders, between the
``on_page_markdown`` and ``on_page_content`` events, in a kernel started in the
directory mkdocs runs in; this hook puts ``docs/course`` on the kernels'
``PYTHONPATH`` (so that ``import checks`` works as it does beside the chapter) and
logs the time each chapter took and the total when the build ends.

lynxsim's docstrings cross-reference in Sphinx's style (``:class:`~lynxsim.traj.Trajectory```),
which mkdocstrings renders as the role's text beside a code span; this hook turns each
into an optional cross-reference of mkdocs-autorefs: a link where the name is documented
in the site, the plain name elsewhere (never a warning).
"""

from __future__ import annotations

import html
import logging
import os
import re
import time
from pathlib import Path
from typing import Any

log = logging.getLogger("mkdocs.hooks.build_hooks")

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


_IDENTIFIER = re.compile(r"^::: ([\w.]+)", re.MULTILINE)
_modules: dict[str, str] = {}


def on_page_markdown(markdown: str, page: Any, **kwargs: Any) -> str:
    """Start a chapter's clock; note an API page's first module (bare names resolve in it)."""
    if _is_chapter(page):
        _started[page.file.src_uri] = time.perf_counter()
    if found := _IDENTIFIER.search(markdown):
        _modules[page.file.src_uri] = found.group(1)
    return markdown


_ROLE = re.compile(r":(?:class|func|meth|mod|attr|data|exc|obj|const):<code>(~?)([\w.]+)</code>")


def _autoref(match: re.Match[str], module: str | None) -> str:
    short, name = match.group(1) == "~", match.group(2)
    shown = name.rsplit(".", 1)[-1] if short else name
    target = f"{module}.{name}" if module and "." not in name else name
    return f'<autoref identifier="{html.escape(target)}" optional><code>{shown}</code></autoref>'


def on_page_content(html_text: str, page: Any, **kwargs: Any) -> str:
    """Stop a chapter's clock (and log its execution time [s]); link the Sphinx roles."""
    if _is_chapter(page):
        taken = time.perf_counter() - _started.pop(page.file.src_uri)
        _taken[page.file.src_uri] = taken
        log.info("course: %s executed in %.1f s", page.file.src_uri, taken)
    module = _modules.get(page.file.src_uri)
    return _ROLE.sub(lambda m: _autoref(m, module), html_text)


def on_post_build(**kwargs: Any) -> None:
    """Log the whole course's execution time [s]."""
    if _taken:
        total = sum(_taken.values())
        log.info("course: %d chapters executed in %.1f s", len(_taken), total)
