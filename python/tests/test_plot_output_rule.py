"""Every path that draws figures writes by the library's output rule
(output_directory.hpp), as `barimpact run` does: a new or empty directory,
or one barimpact wrote; someone else's only with force; never $HOME, / or a
parent of the working directory, nor the directory it reads."""
import os
import subprocess
import sys

import pytest

import barimpact
from barimpact.convergence import plot_study, plot_sweep
from barimpact.plot import compare
from conftest import EXAMPLES

SHORT = {"time.end": 0.5, "output.fields_at": [0.25]}
PNG = ("png",)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Two run directories and the Result of the first."""
    base = tmp_path_factory.mktemp("runs")
    a = barimpact.run(EXAMPLES / "paper-example1.toml", out=base / "a", set=SHORT)
    barimpact.run(EXAMPLES / "paper-example1.toml", out=base / "b", set={**SHORT, "obstacle.stiffness": 200.0})
    return base / "a", base / "b", a


@pytest.fixture
def home(tmp_path, monkeypatch):
    """$HOME a directory of the test's, the working directory inside it."""
    h = tmp_path / "home"
    (h / "work").mkdir(parents=True)
    (h / "notes.txt").write_text("mine")
    monkeypatch.setenv("HOME", str(h))
    monkeypatch.chdir(h / "work")
    return h


def users_dir(path):
    """A user's directory holding a figure's name of their own."""
    path.mkdir()
    (path / "displacement.png").write_text("my figure")
    (path / "notes.txt").write_text("mine")
    return path


def kept(path):
    return (path / "displacement.png").read_text() == "my figure" and (path / "notes.txt").read_text() == "mine"


def python_plot(*args):
    return subprocess.run([sys.executable, "-m", "barimpact", "plot", *map(str, args)], capture_output=True,
                          text=True, env=dict(os.environ))


def refused(p, text):
    """Exit 2, one line naming --out and the rule."""
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "--out" in lines[0] and text in lines[0], p.stderr


def test_plot_of_a_result_never_writes_over_a_users_files(runs, tmp_path):
    mine = users_dir(tmp_path / "mine")
    with pytest.raises(barimpact.InputError, match="did not write.*--force"):
        barimpact.plot(runs[2], mine, formats=PNG)
    assert kept(mine) and sorted(p.name for p in mine.iterdir()) == ["displacement.png", "notes.txt"]
    written = barimpact.plot(runs[2], mine, force=True, formats=PNG)  # beside: the same names replaced
    assert (mine / "notes.txt").read_text() == "mine" and (mine / "energy.png").is_file() and written


def test_no_figure_goes_into_home_or_the_directory_plotted(runs, home):
    for source in (runs[2], runs[0]):
        for force in (False, True):
            with pytest.raises(barimpact.InputError, match="home directory"):
                barimpact.plot(source, os.path.expanduser("~"), force=force, formats=PNG)
    assert sorted(p.name for p in home.iterdir()) == ["notes.txt", "work"]
    for out in (runs[0], runs[0].parent):
        with pytest.raises(barimpact.InputError, match="this command reads"):
            barimpact.plot(runs[0], out, force=True, formats=PNG)
    assert not (runs[0].parent / "displacement.png").exists() and not (runs[0] / "displacement.png").exists()
    barimpact.plot(runs[2], formats=PNG)  # ./figures, new: written
    assert (home / "work" / "figures" / "displacement.png").is_file()


def test_the_comparison_follows_the_rule(runs, home, tmp_path):
    a, b, _ = runs
    mine = users_dir(tmp_path / "mine")
    refused(python_plot(a, b, "--out", mine), "did not write")
    refused(python_plot(a, b, "--out", home), "home directory")
    refused(python_plot(a, b, "--out", a), "this command reads")
    refused(python_plot(a, "--out", mine), "did not write")
    assert kept(mine) and not list(home.glob("compare_*"))  # (matplotlib keeps its caches in $HOME)
    p = python_plot(a, b, "--out", mine, "--force")
    assert p.returncode == 0, p.stderr
    assert kept(mine) and (mine / "compare_U.svg").is_file()
    with pytest.raises(barimpact.InputError, match="did not write"):
        compare([a, b], users_dir(tmp_path / "again"), formats=PNG)
    assert compare([a, b], tmp_path / "new", formats=PNG)


@pytest.mark.filterwarnings("ignore::barimpact.HealthWarning")
def test_a_sweeps_and_a_studys_figures_follow_the_rule(tmp_path):
    sweep = tmp_path / "sweep"
    barimpact.sweep({"case": str(EXAMPLES / "paper-example1.toml"), "set": {"time.end": 0.5, "output.fields_at": []},
                     "axis": [{"key": "obstacle.stiffness", "values": [100.0, 200.0]}]}, sweep, jobs=1)
    mine = users_dir(tmp_path / "mine")
    with pytest.raises(barimpact.InputError, match="did not write"):
        plot_sweep(sweep, mine, formats=PNG)
    with pytest.raises(barimpact.InputError, match="this command reads"):
        barimpact.plot(sweep, sweep, formats=PNG)
    assert kept(mine) and plot_sweep(sweep, formats=PNG)
    (mine / "convergence.csv").write_text("scheme,level\n")  # not a study barimpact wrote
    with pytest.raises(barimpact.InputError, match="converge"):
        plot_study(mine)
    assert not (mine / "convergence.png").exists()


def test_results_it_cannot_read_are_refused_with_nothing_made(tmp_path):
    """Issue 36: plot on an unreadable results.h5 left a marked, empty figures/."""
    pytest.importorskip("h5py")
    run_dir = tmp_path / "run"
    barimpact.run(EXAMPLES / "paper-example1.toml", out=run_dir, set={**SHORT, "output.format": "hdf5"})
    (run_dir / "results.h5").write_bytes(b"not HDF5")
    marker = (run_dir / ".barimpact").read_text()
    with pytest.raises(barimpact.InputError, match="results.h5: cannot be read"):
        barimpact.plot(run_dir, formats=PNG)
    assert not (run_dir / "figures").exists()
    assert (run_dir / ".barimpact").read_text() == marker
    with pytest.raises(barimpact.InputError, match="results.h5: cannot be read"):
        barimpact.load(run_dir)
