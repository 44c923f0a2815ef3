"""One browsable page over a folder of outputs: a table of runs with their links, then figures.

:func:`write_index` writes ``index.html`` into the folder it describes; every
link is relative to it (the folder can be moved or zipped) and names a file
that exists when the page is written (:func:`relative_link` refuses others).
Text is escaped, never markup. Pure Python.
"""

from __future__ import annotations

import html
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Literal
from urllib.parse import quote

from lynxsim.errors import InvalidInputError
from lynxsim.fileio import atomic_path

__all__ = ["IndexFigure", "IndexRow", "IndexSection", "index_page", "relative_link", "write_index"]


@dataclass(frozen=True)
class IndexRow:
    """One run of the table.

    Attributes:
        cells: Its values, one per column (text).
        status: ``"bad"`` shows the row as a failure (a collision, an unhealthy run).
        links: ``(label, href)`` of its files, hrefs relative to the page.
    """

    cells: tuple[str, ...]
    status: Literal["ok", "bad"]
    links: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class IndexFigure:
    """An image of a section: its caption and href relative to the page."""

    caption: str
    href: str


@dataclass(frozen=True)
class IndexSection:
    """A part of the page under the table.

    Attributes:
        title: Its heading.
        text: Paragraphs of text.
        preformatted: A block shown as it is (a table of text), or "".
        figures: Its images.
        links: ``(label, href)`` of files it points to.
    """

    title: str
    text: tuple[str, ...] = ()
    preformatted: str = ""
    figures: tuple[IndexFigure, ...] = ()
    links: tuple[tuple[str, str], ...] = field(default_factory=tuple)


def relative_link(page_dir: str | os.PathLike[str], target: str | os.PathLike[str]) -> str:
    """``target``'s href from a page in ``page_dir``: relative, URL-quoted, POSIX.

    Raises:
        InvalidInputError: ``target`` is not a file inside ``page_dir``.
    """
    folder, path = Path(page_dir).resolve(), Path(target).resolve()
    if not path.is_file() or not path.is_relative_to(folder):
        raise InvalidInputError(f"{target} is not a file inside {page_dir}")
    return quote(path.relative_to(folder).as_posix())


def _links(links: Sequence[tuple[str, str]]) -> str:
    return " ".join(f'<a href="{html.escape(h)}">{html.escape(label)}</a>' for label, h in links)


def _section(s: IndexSection) -> str:
    parts = [f"<section><h2>{html.escape(s.title)}</h2>"]
    parts += [f"<p>{html.escape(t)}</p>" for t in s.text]
    if s.preformatted:
        parts.append(f"<pre>{html.escape(s.preformatted)}</pre>")
    if s.links:
        parts.append(f'<p class="links">{_links(s.links)}</p>')
    if s.figures:
        parts.append('<div class="figures">')
        for f in s.figures:
            h, c = html.escape(f.href), html.escape(f.caption)
            parts.append(
                f'<figure><a href="{h}"><img src="{h}" alt="{c}"></a>'
                f"<figcaption>{c}</figcaption></figure>"
            )
        parts.append("</div>")
    parts.append("</section>")
    return "\n".join(parts)


def index_page(
    title: str,
    intro: str,
    columns: Sequence[str],
    rows: Sequence[IndexRow],
    sections: Sequence[IndexSection],
) -> str:
    """The page as HTML text (its styles inside; it loads only the files it links)."""
    css = resources.files("lynxsim.web").joinpath("assets", "index.css").read_text("utf-8")
    head = "".join(f"<th>{html.escape(c)}</th>" for c in (*columns, "files"))
    body = "\n".join(
        f'<tr class="{r.status}">'
        + "".join(f"<td>{html.escape(c)}</td>" for c in r.cells)
        + f"<td>{_links(r.links)}</td></tr>"
        for r in rows
    )
    return "\n".join(
        [
            "<!DOCTYPE html>",
            '<html lang="en"><head><meta charset="utf-8">',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>{html.escape(title)}</title><style>\n{css}</style></head><body>",
            f"<header><h1>{html.escape(title)}</h1><p>{html.escape(intro)}</p></header>",
            "<main><section><h2>Runs</h2>",
            f'<table class="runs"><thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table>',
            "</section>",
            *(_section(s) for s in sections),
            "</main></body></html>",
            "",
        ]
    )


def write_index(
    dest: str | os.PathLike[str],
    title: str,
    intro: str,
    columns: Sequence[str],
    rows: Sequence[IndexRow],
    sections: Sequence[IndexSection],
) -> Path:
    """Write :func:`index_page` to ``dest``, atomically; returns the path.

    Raises:
        InvalidInputError: A row has another number of cells than ``columns``.
        OutputPathError: ``dest`` is not a regular file or its folder cannot be made.
    """
    for r in rows:
        if len(r.cells) != len(columns):
            raise InvalidInputError(f"a row has {len(r.cells)} cells for {len(columns)} columns")
    text = index_page(title, intro, columns, rows, sections)
    with atomic_path(dest) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(dest)
