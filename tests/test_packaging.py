"""The package as installed: subpackages listed, models shipped, public names resolve."""

from __future__ import annotations

import importlib
import subprocess
import tomllib
from pathlib import Path

import pytest

import lynxsim
from lynxsim.errors import InvalidInputError
from lynxsim.resources import available_models, model_path

ROOT = Path(__file__).resolve().parents[1]


SETUPTOOLS = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
MODELS_DIR = ROOT / "lynxsim" / "models"


def test_every_subpackage_is_listed_in_pyproject():
    found = {
        ".".join(p.relative_to(ROOT).parent.parts) for p in (ROOT / "lynxsim").rglob("__init__.py")
    }
    # Folders of package data only (the models' MJCF files, the web pages' assets) are
    # listed too: setuptools warns at install that they are importable but not listed.
    data = {
        ".".join(p.relative_to(ROOT).parts)
        for p in (ROOT / "lynxsim").rglob("*")
        if p.is_dir() and p.name != "__pycache__" and not (p / "__init__.py").exists()
    }
    assert data
    assert found | data == set(SETUPTOOLS["packages"])
    assert "package-dir" not in SETUPTOOLS  # every package lives in its own folder


def test_every_model_file_is_package_data():
    patterns = SETUPTOOLS["package-data"]["lynxsim.models"]
    shipped = {p for pattern in patterns for p in MODELS_DIR.glob(pattern)}
    files = {p for p in MODELS_DIR.rglob("*") if p.is_file() and p.suffix not in {".py", ".pyc"}}
    assert files
    left_out = sorted(str(p.relative_to(MODELS_DIR)) for p in files - shipped)
    assert not left_out, f"not shipped by package-data {patterns}: {left_out}"


def test_models_resolve_by_name_inside_the_package():
    names = available_models()
    assert {"lynx_arm/scene.xml", "rrr/scene.xml"} <= set(names)
    for name in names:
        assert model_path(name).is_file()
        assert model_path(name).is_relative_to(Path(lynxsim.__file__).parent / "models")
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


def test_what_the_suite_writes_is_not_tracked():
    # MuJoCo appends its warnings to MUJOCO_LOG.TXT in the working folder; the suite
    # provokes some, and a tracked log would change with every run.
    tracked = subprocess.run(
        ["git", "ls-files", "MUJOCO_LOG.TXT", "videos/*.json", "videos/*.npz"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert tracked == ""
    ignored = subprocess.run(
        ["git", "check-ignore", "MUJOCO_LOG.TXT"], cwd=ROOT, capture_output=True, text=True
    )
    assert ignored.returncode == 0, "MUJOCO_LOG.TXT is not ignored"
