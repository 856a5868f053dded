"""What the Python module's tests share: the repository, the gbxc program of the same build,
and a way to run it for the bytes to compare with."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(os.environ.get("GBX_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
GBXC = os.environ.get("GBXC", str(ROOT / "build" / "gbxc"))
SLOW_SPECS = {"marine_reducer.gbx", "electric_cylinder.gbx", "marine_tolerances.gbx"}


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: solves a spec that takes a minute (a heavy test)")


def cli(*args, cwd=None):
    """gbxc's stdout, stderr and exit status."""
    p = subprocess.run([GBXC, *args], capture_output=True, text=True, cwd=cwd)
    return p.stdout, p.stderr, p.returncode


@pytest.fixture
def spec_dir():
    return ROOT / "specs"
