"""Shared figure set-up: a headless backend, plain text and atomic PNG saving."""

from __future__ import annotations

import functools
import os
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import ParamSpec, TypeVar

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure

from lynxsim.errors import OutputPathError
from lynxsim.fileio import atomic_path

__all__ = ["check_png", "new_figure", "plain_text", "save_figure"]

P = ParamSpec("P")
R = TypeVar("R")


def plain_text(plot: Callable[P, R]) -> Callable[P, R]:
    """Run a plotting function with every text it makes shown as written.

    Names come from task and sweep files: a ``$`` in one must not start
    Matplotlib's mathtext (``"x $_$ y"`` would fail to parse), and a letter
    that the font lacks is drawn as a box without a warning per glyph on
    stderr. Only the function's own texts are affected, not the caller's
    other figures.
    """

    @functools.wraps(plot)
    def plotted(*args: P.args, **kwargs: P.kwargs) -> R:
        with matplotlib.rc_context({"text.parse_math": False}), warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=r"Glyph \d+ .* missing from font")
            return plot(*args, **kwargs)

    return plotted


def new_figure(width_in: float = 10.0, height_in: float = 7.0) -> Figure:
    """A figure not registered with pyplot (no global state, no leaks)."""
    return Figure(figsize=(width_in, height_in), layout="constrained")


def check_png(dest: str | os.PathLike[str], name: str = "dest") -> Path:
    """``dest`` as a path if it names a ``.png`` file (a figure is PNG bytes).

    Raises:
        OutputPathError: Another suffix (``x.jpg`` would hold PNG bytes).
    """
    path = Path(dest)
    if path.suffix.lower() != ".png":
        raise OutputPathError(f"{name} must name a .png file (the figure is PNG), got {path}")
    return path


def save_figure(fig: Figure, dest: str | os.PathLike[str], dpi: int = 110) -> None:
    """Save ``fig`` as PNG to ``dest`` atomically.

    Raises:
        OutputPathError: ``dest`` does not name a ``.png`` file (:func:`check_png`).
    """
    check_png(dest)
    with atomic_path(dest) as tmp:
        fig.savefig(tmp, dpi=dpi, format="png")
