"""The package's version: one number, in pyproject.toml and ``fewear.__version__``, printed by
``fewear --version``."""

import subprocess
import sys
import tomllib
from pathlib import Path

import fewear

PYPROJECT = Path(__file__).resolve().parents[2] / "pyproject.toml"


def test_package_version_is_the_projects():
    with PYPROJECT.open("rb") as stream:
        project_version = tomllib.load(stream)["project"]["version"]
    assert fewear.__version__ == project_version


def test_cli_prints_the_version():
    completed = subprocess.run([sys.executable, "-m", "fewear.cli", "--version"],
                               capture_output=True, text=True, check=False)
    assert completed.returncode == 0, completed.stderr
    assert completed.stdout.strip() == f"fewear {fewear.__version__}"
