"""The three scripts of docs/python.md run as a reader would run them, from a folder that
has the repository's specs/ in it."""

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT


def scripts():
    text = (ROOT / "docs" / "python.md").read_text()
    found = {}
    for block in re.findall(r"```python\n(.*?)```", text, re.S):
        first = block.splitlines()[0]
        if re.fullmatch(r"# [a-z_]+\.py", first):
            found[first[2:]] = block
    return found


def test_the_page_has_its_three_scripts():
    assert sorted(scripts()) == ["duty_cycle.py", "face_width_study.py", "mesh_force_spectrum.py"]


@pytest.mark.parametrize("name", sorted(scripts()))
def test_script_runs(name, tmp_path):
    (tmp_path / "specs").symlink_to(ROOT / "specs")
    (tmp_path / name).write_text(scripts()[name])
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, name], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert p.stdout.strip()
    if name == "face_width_study.py":
        assert (tmp_path / "face_width_study.png").stat().st_size > 1000
