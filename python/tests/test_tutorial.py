import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

SCRIPTS = sorted((ROOT / "examples" / "python").glob("*.py"))


def test_there_are_tutorial_scripts():
    assert len(SCRIPTS) >= 3


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_tutorial_script_runs(script, tmp_path):
    p = subprocess.run([sys.executable, str(script), str(tmp_path / "out")], cwd=tmp_path, capture_output=True,
                       text=True, env=dict(os.environ), timeout=600)
    assert p.returncode == 0, p.stderr
    assert any(f.suffix == ".png" for f in (tmp_path / "out").rglob("*"))
    # Clean, or its docstring names each health warning it gives and why.
    codes = set(re.findall(r"HealthWarning: ([a-z][a-z-]*)", p.stderr))
    said = script.read_text().split('"""')[1]
    assert all(code in said for code in codes), (codes, p.stderr)
