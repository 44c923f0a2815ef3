"""Shared figure set-up: a headless backend and atomic PNG saving."""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure

from lynxsim.fileio import atomic_path

__all__ = ["new_figure", "save_figure"]


def new_figure(width_in: float = 10.0, height_in: float = 7.0) -> Figure:
    """A figure not registered with pyplot (no global state, no leaks)."""
    return Figure(figsize=(width_in, height_in), layout="constrained")


def save_figure(fig: Figure, dest: str | os.PathLike[str], dpi: int = 110) -> None:
    """Save ``fig`` as PNG to ``dest`` atomically."""
    with atomic_path(dest) as tmp:
        fig.savefig(tmp, dpi=dpi, format="png")
