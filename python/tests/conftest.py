import os
import signal
import subprocess
from pathlib import Path

import pytest

# Python leaves SIGINT ignored when it starts with it ignored (a job started
# in the background by a non-interactive shell, as CI may be): the Ctrl-C
# tests need its usual KeyboardInterrupt.
signal.signal(signal.SIGINT, signal.default_int_handler)

ROOT = Path(os.environ.get("BARIMPACT_ROOT", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("BARIMPACT_CLI", str(ROOT / "build" / "release" / "barimpact"))
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def cli_runs(tmp_path_factory):
    """Both paper examples run once by the command line."""
    out = {}
    base = tmp_path_factory.mktemp("cli")
    for name in ("paper-example1", "paper-example2"):
        d = base / name
        subprocess.run([CLI, "run", str(EXAMPLES / f"{name}.toml"), "--out", str(d)], check=True,
                       capture_output=True)
        out[name] = d
    return out


def cli_error(*args):
    """The command line's one-line error for bad input, without its prefix."""
    p = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    line = p.stderr.strip()
    assert line.startswith("barimpact: error: ")
    return line[len("barimpact: error: "):]


@pytest.fixture
def drawn(monkeypatch):
    """What each figure drawn holds, by name (figure_text.figure_texts),
    from the hook every figure passes before it is saved."""
    import importlib

    from figure_text import figure_texts
    plot_module = importlib.import_module("barimpact.plot")  # barimpact.plot is the function
    figures = {}
    monkeypatch.setattr(plot_module, "SAVE_HOOKS", [lambda fig, name: figures.__setitem__(name, figure_texts(fig))])
    return figures
