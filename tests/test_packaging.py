"""The package as installed: subpackages listed, models shipped, public names resolve."""

from __future__ import annotations

import importlib
import tomllib
from pathlib import Path

import pytest

import lynxsim
from lynxsim.errors import InvalidInputError
from lynxsim.resources import available_models, model_path

ROOT = Path(__file__).resolve().parents[1]


def test_every_subpackage_is_listed_in_pyproject():
    listed = set(
        tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]
    )
    found = {
        ".".join(p.relative_to(ROOT).parent.parts) for p in (ROOT / "lynxsim").rglob("__init__.py")
    } | {"lynxsim.models"}
    assert found == listed


def test_models_resolve_by_name():
    for name in available_models():
        assert model_path(name).is_file()
    with pytest.raises(InvalidInputError, match=r"no model named 'nope\.xml'; available:"):
        model_path("nope.xml")


@pytest.mark.parametrize(
    "module",
    sorted(
        {
            ".".join(p.relative_to(ROOT).with_suffix("").parts)
            for p in (ROOT / "lynxsim").rglob("*.py")
        }
        - {"lynxsim.__main__"}
    ),
)
def test_every_name_in_all_resolves(module):
    mod = importlib.import_module(module.removesuffix(".__init__"))
    for name in getattr(mod, "__all__", ()):
        assert hasattr(mod, name), f"{module}.__all__ names missing {name}"


def test_version_is_set():
    assert lynxsim.__version__
