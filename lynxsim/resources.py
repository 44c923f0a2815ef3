"""Finding the MJCF models that ship with lynxsim.

The models live in the package (``lynxsim/models/``, package data of
:mod:`lynxsim.models`), so editable and regular installs find them alike.
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path

from lynxsim.errors import InvalidInputError

__all__ = ["available_models", "model_path"]


def _models_root() -> Path:
    """The folder of the shipped models (``lynxsim/models/`` of the installed package)."""
    return Path(str(importlib.resources.files("lynxsim.models")))


def available_models() -> list[str]:
    """Names of every shipped model file, e.g. ``"lynx_arm/scene.xml"``."""
    root = _models_root()
    return sorted(str(p.relative_to(root)) for p in root.rglob("*.xml"))


def model_path(name: str) -> Path:
    """Absolute path of a shipped model file.

    Args:
        name: Path relative to the models folder, e.g. ``"lynx_arm/scene.xml"``.

    Raises:
        InvalidInputError: If no such model ships; the message lists those that do.
    """
    path = _models_root() / name
    if not path.is_file():
        raise InvalidInputError(
            f"no model named {name!r}; available: {', '.join(available_models()) or 'none'}"
        )
    return path
