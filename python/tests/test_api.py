"""The Python API mirrors the command: the same files, the same tables, the
same options under the same names, and type stubs that name all of it."""
import ast
import csv
import importlib.util
import inspect
import json
import os
import pickle
import re
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import barimpact
from conftest import CLI, EXAMPLES, cli_error
from test_hopkinson import _setup as hopkinson_setup
from test_hopkinson import _write as write_hopkinson_signals

PACKAGE = Path(barimpact.__file__).parent
HAVE_PANDAS = importlib.util.find_spec("pandas") is not None
RIGID = EXAMPLES / "paper-example1-rigid.toml"
STIFF = {"obstacle.stiffness": 1e4, "time.step": 1e-3, "time.end": 1.0, "output.fields_at": []}


def cli(*args):
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p


def csv_rows(path, drop=()):
    """A CSV's rows as dicts of text, without the columns in `drop` (timings)."""
    with open(path, newline="") as f:
        return [{k: v for k, v in r.items() if k not in drop} for r in csv.DictReader(f)]


def assert_tables_equal(a, b, drop=()):
    assert a.columns == b.columns
    for name in a.columns:
        if name in drop:
            continue
        if a[name].dtype.kind == "f":
            np.testing.assert_array_equal(a[name], b[name], err_msg=name)  # nan == nan here
        else:
            assert list(a[name]) == list(b[name]), name


# ---- a run's columns by name


def test_a_runs_columns_by_name_are_its_history(cli_runs):
    r = barimpact.run(EXAMPLES / "paper-example1.toml")
    history = np.loadtxt(cli_runs["paper-example1"] / "history.csv", delimiter=",", skiprows=1)
    with open(cli_runs["paper-example1"] / "history.csv") as f:
        header = f.readline().strip().split(",")
    assert r.columns == tuple(header) and r.keys() == header and list(r) == header and len(r) == len(header)
    for i, name in enumerate(header):
        assert np.array_equal(r[name], history[:, i]), name
        assert np.array_equal(r[name], getattr(r, name)), name
        assert name in r
    assert np.shares_memory(r["U"], r.U)
    assert "joint.a-b.force" not in r and 3 not in r
    assert set(dict(r)) == set(header)


def test_a_lines_extra_columns_are_listed_and_indexed():
    r = barimpact.run(EXAMPLES / "clamped-periodic.toml")
    assert r.columns[:11] == ("t", "U", "V", "R", "E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact",
                              "D_plastic")
    assert "far_end.force" in r.columns and "far_end.force" in r
    assert r["far_end.force"].shape == r.t.shape
    assert "<barimpact.Result complete" in repr(r)


@pytest.mark.skipif(not HAVE_PANDAS, reason="pandas is not installed")
def test_to_pandas_gives_history_csv_and_fields_csv(cli_runs, tmp_path):
    d = cli_runs["paper-example1"]
    r = barimpact.run(EXAMPLES / "paper-example1.toml")
    h = r.to_pandas()
    history = np.loadtxt(d / "history.csv", delimiter=",", skiprows=1)
    assert tuple(h.columns) == r.columns
    assert np.array_equal(h.to_numpy(), history)
    f = r.fields_to_pandas()
    with open(d / "fields.csv") as stream:
        header = stream.readline().strip().split(",")
    assert list(f.columns) == header
    numbers = np.loadtxt(d / "fields.csv", delimiter=",", skiprows=1, usecols=range(6))
    assert np.array_equal(f[header[:6]].to_numpy(), numbers)
    assert set(f["body"]) == {"bar"}
    cli("sweep", EXAMPLES / "sweeps" / "with-failures.toml", "--out", tmp_path / "sweep")
    t = barimpact.read_table(tmp_path / "sweep")
    assert list(t.to_pandas().columns) == list(t.columns)
    assert t.to_pandas()["status"].tolist() == list(t.status)


def test_to_pandas_without_pandas_says_what_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas then fails
    r = barimpact.run(EXAMPLES / "paper-example1.toml", set={"time.end": 0.1, "output.fields_at": [0.1]})
    for call in (r.to_pandas, r.fields_to_pandas, barimpact.Table({"a": np.zeros(2)}).to_pandas):
        with pytest.raises(ImportError, match="needs pandas.*python3-pandas"):
            call()
    assert r.fields_table().columns == ("t", "x", "u", "v", "sigma", "eps_p", "body")  # no pandas needed


# ---- Table


def test_a_table_is_a_dict_of_arrays_with_attributes():
    t = barimpact.Table({"id": np.array(["0", "1"]), "set": np.array([1.0, np.nan])}, {"k": 1})
    assert isinstance(t, dict) and t.columns == ("id", "set") and t.rows == 2
    assert t.set is t["set"] and t.summary == {"k": 1}
    assert t.row(0) == {"id": "0", "set": 1.0}
    assert "set" in dir(t) and "2 rows" in repr(t)
    with pytest.raises(AttributeError, match="no column or attribute 'nope'"):
        t.nope
    again = pickle.loads(pickle.dumps(t))
    assert again.summary == {"k": 1} and list(again.id) == ["0", "1"]
    assert barimpact.Table().rows == 0 and barimpact.Table().summary is None


# ---- converge


CONVERGE_STUDIES = [
    (RIGID, dict(levels=2, schemes="central-difference,characteristic", jobs=2),
     ["--levels", "2", "--schemes", "central-difference,characteristic", "--jobs", "2"]),
    (RIGID, dict(levels=3, ratio=3, refine="dt", schemes=["central-difference"], reference="finest"),
     ["--levels", "3", "--ratio", "3", "--refine", "dt", "--schemes", "central-difference", "--reference", "finest"]),
    (EXAMPLES / "paper-example1.toml",
     dict(vary=("obstacle.stiffness", "log:10:1000:3"), reference="rigid",
          set={"time.end": 3.0, "output.fields_at": []}),
     ["--vary", "obstacle.stiffness=log:10:1000:3", "--reference", "rigid", "--set", "time.end=3.0", "--set",
      "output.fields_at=[]"]),
]


@pytest.mark.parametrize("case,options,args", CONVERGE_STUDIES, ids=["schemes", "ratio-dt-finest", "vary-rigid"])
def test_converge_gives_the_commands_convergence_csv(tmp_path, case, options, args):
    cli("converge", case, "--out", tmp_path / "cli", *args)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        t = barimpact.converge(case, tmp_path / "py", **options)
    timing = ("cpu_seconds",)
    assert csv_rows(tmp_path / "py" / "convergence.csv", timing) == csv_rows(tmp_path / "cli" / "convergence.csv",
                                                                           timing)
    assert_tables_equal(t, barimpact.read_table(tmp_path / "cli"), drop=timing)
    assert set(t.status) <= {"complete", "reference"} and np.isfinite(t.order_U[1:]).any()
    # The command's warnings, one per line, as HealthWarnings.
    assert [str(w.message) for w in seen if w.category is barimpact.HealthWarning] == \
        [f"{s}-{int(lv):02}: {w}" for s, lv, ws in zip(t.scheme, t.level, t.warnings) if ws for w in ws.split(" | ")]
    assert all(w.filename == __file__ for w in seen if w.category is barimpact.HealthWarning)  # the caller's line
    assert t.summary["markdown"].startswith("    barimpact.converge(")
    md_py = (tmp_path / "py" / "convergence.md").read_text().splitlines()
    md_cli = (tmp_path / "cli" / "convergence.md").read_text().splitlines()
    assert md_py[2] == md_cli[2] == f"Reference: {t.summary['reference']}."
    marker_py = json.loads((tmp_path / "py" / ".barimpact").read_text())
    marker_cli = json.loads((tmp_path / "cli" / ".barimpact").read_text())
    assert marker_py["entries"] == marker_cli["entries"] and marker_py["command"] == "converge"
    assert sorted(p.name for p in (tmp_path / "py" / "runs").iterdir()) == \
        sorted(p.name for p in (tmp_path / "cli" / "runs").iterdir())
    assert (tmp_path / "py" / "convergence.png").is_file() and (tmp_path / "py" / "work_precision.svg").is_file()


def test_converge_in_memory_and_resumed_by_the_command(tmp_path):
    options = dict(levels=2, schemes="characteristic")
    memory = barimpact.converge(RIGID, **options)
    assert memory.summary["directory"] is None and not any(tmp_path.iterdir())
    written = barimpact.converge(RIGID, tmp_path / "study", no_plot=True, **options)
    assert_tables_equal(memory, written, drop=("cpu_seconds",))
    assert not (tmp_path / "study" / "convergence.png").exists()
    # The command takes the directory Python wrote as its own, and resumes it.
    p = cli("converge", RIGID, "--out", tmp_path / "study", "--levels", "2", "--schemes", "characteristic")
    assert "results in" in p.stdout


def test_converge_refuses_what_the_command_refuses(tmp_path):
    out = tmp_path / "never"
    for options, args in ((dict(vary="bar.elements"), ["--vary", "bar.elements"]),
                          (dict(schemes="paper,nope"), ["--schemes", "paper,nope"]),
                          (dict(refine="none"), ["--refine", "none"]),
                          (dict(levels=13), ["--levels", "13"]),
                          (dict(ratio=17), ["--ratio", "17"]),
                          (dict(vary="time.step=0.01,0.005", refine="both"),
                           ["--vary", "time.step=0.01,0.005", "--refine", "both"])):
        with pytest.raises(barimpact.InputError) as e:
            barimpact.converge(RIGID, out, **options)
        assert str(e.value) == cli_error("converge", str(RIGID), "--out", str(out), *args)
    with pytest.raises(barimpact.InputError, match="--refine: must be both, h, dt or none"):
        barimpact.converge(RIGID, out, refine="x")
    with pytest.raises(barimpact.InputError, match="--jobs"):
        barimpact.converge(RIGID, out, jobs=-1)
    assert not out.exists()
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(barimpact.InputError, match="did not write"):
        barimpact.converge(RIGID, mine, levels=2)
    barimpact.converge(RIGID, mine, levels=2, force=True, no_plot=True)
    assert (mine / "notes.txt").read_text() == "mine" and (mine / "convergence.csv").is_file()


def test_ctrl_c_ends_a_study_after_writing_it(tmp_path):
    case = barimpact.Case(RIGID, set={"bar.elements": 400, "time.step": 0.0025, "time.end": 2000.0,
                                      "output.every": 1000, "output.fields_at": []})
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        barimpact.converge(case, tmp_path / "study", levels=2, jobs=2)
    assert time.monotonic() - start < 10.0  # the study would take minutes
    rows = csv_rows(tmp_path / "study" / "convergence.csv")
    assert rows and {r["status"] for r in rows} == {"interrupted"}
    assert not (tmp_path / "study" / "convergence.png").exists()  # as the command: no figures when stopped


def test_a_study_releases_the_gil():
    case = barimpact.Case(RIGID, set={"bar.elements": 2000, "time.step": 0.0005, "output.fields_at": []})
    ticks, done = [], threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    barimpact.converge(case, levels=2, schemes="characteristic", jobs=1)
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    assert elapsed > 0.1  # a held GIL would freeze the counter this long
    assert len([t for t in ticks if start < t < start + elapsed]) > 0.3 * elapsed / 0.0011


# ---- sweep


def test_sweep_gives_the_commands_sweep_csv(tmp_path):
    source = EXAMPLES / "sweeps" / "with-failures.toml"
    cli("sweep", source, "--out", tmp_path / "cli")
    with pytest.warns(barimpact.HealthWarning, match="0000: energy-balance"):
        t = barimpact.sweep(source, tmp_path / "py", jobs=2)
    timing = ("run_seconds",)
    assert csv_rows(tmp_path / "py" / "sweep.csv", timing) == csv_rows(tmp_path / "cli" / "sweep.csv", timing)
    assert_tables_equal(t, barimpact.read_table(tmp_path / "cli" / "sweep.csv"), drop=timing)
    assert list(t.status) == ["non-finite", "refused", "complete", "complete"]
    assert t["time.alpha"].dtype == float and list(t["time.alpha"]) == [0.0, -0.1, 0.25, 0.5]
    assert t.steps_done.dtype == np.int64 and np.isnan(t.t_end[1])
    assert t.summary == {"cases": 4, "run": 4, "batched": t.summary["batched"], "resumed": 0, "complete": 2,
                         "directory": str(tmp_path / "py")}
    # A rerun resumes (the command's too): the complete cases are read back.
    with pytest.warns(barimpact.HealthWarning):  # read back with the rest of their rows
        again = barimpact.sweep(source, tmp_path / "py", no_batch=True)
    assert again.summary["resumed"] >= 2
    assert_tables_equal(t, again, drop=timing)
    assert "resumed" in cli("sweep", source, "--out", tmp_path / "py").stdout


def test_a_sweep_from_a_dict_is_the_sweep_file(tmp_path, monkeypatch):
    monkeypatch.chdir(EXAMPLES / "sweeps")
    source = {"case": "../paper-example1.toml", "set": {"output.fields_at": [], "time.step": 0.0025},
              "axis": [{"key": "obstacle.stiffness", "values": [100.0, 200.0]},
                       {"key": "bar.elements", "values": [100, 200]}],
              "zip": [["obstacle.stiffness", "bar.elements"]]}
    t = barimpact.sweep(source, tmp_path / "dict")
    (tmp_path / "s.toml").write_text(
        'case = "%s"\nzip = [["obstacle.stiffness", "bar.elements"]]\n[set]\noutput.fields_at = []\n'
        'time.step = 0.0025\n[[axis]]\nkey = "obstacle.stiffness"\nvalues = [100.0, 200.0]\n'
        '[[axis]]\nkey = "bar.elements"\nvalues = [100, 200]\n' % (EXAMPLES / "paper-example1.toml"))
    f = barimpact.sweep(tmp_path / "s.toml", tmp_path / "file")
    assert_tables_equal(t, f, drop=("run_seconds",))
    assert t.rows == 2 and list(t["bar.elements"]) == [100.0, 200.0]


# ---- bearing, hopkinson, plot, run, exact


def test_bearing_takes_the_commands_capacity_and_returns_a_table(tmp_path):
    pipe = EXAMPLES / "pile" / "steel-pipe-sand.toml"
    t = barimpact.bearing(pipe, tmp_path / "b", "1e6:5e7:2", toe_share=0.5, no_plot=True, jobs=2)
    assert isinstance(t, barimpact.Table) and t.capacity.tolist() == [1e6, 5e7]
    assert t.finished.dtype == bool and t.set is t["set"]
    assert t.summary["toe_share"] == 0.5 and t.summary["count"] == 2
    assert not (tmp_path / "b" / "bearing.png").exists()
    assert_tables_equal(t, barimpact.read_table(tmp_path / "b"))
    s = barimpact.bearing(pipe, tmp_path / "s", "1e6:2e6:2", set={"time.end": 0.05}, no_plot=True, jobs=2)
    assert s.rows == 2 and "end = 0.05\n" in (tmp_path / "s" / "runs" / "0001" / "case.toml").read_text()
    with pytest.raises(barimpact.InputError, match="--toe-share") as e:
        barimpact.bearing(pipe, tmp_path / "c", (1e6, 5e7, 2), toe_share=1.5)
    assert str(e.value) == cli_error("bearing", str(pipe), "--out", str(tmp_path / "c"), "--capacity", "1e6:5e7:2",
                                     "--toe-share", "1.5")  # the library's rule, the command's words
    assert not (tmp_path / "c").exists()


def test_drive_returns_drive_csv_as_a_table_with_its_totals(tmp_path):
    case = EXAMPLES / "pile" / "drive-pipe-drop.toml"
    t = barimpact.drive(case, tmp_path / "d", set={"drive.depths": [3.0, 8.0], "time.end": 0.03}, no_plot=True,
                        jobs=2)
    assert isinstance(t, barimpact.Table) and t.depth.tolist() == [3.0, 8.0]
    assert t.finished.dtype == bool and list(t)[:14] == [
        "depth", "shaft", "toe", "capacity", "long_term_capacity", "set", "blows_per_250mm", "blows_per_m",
        "max_compression", "max_tension", "enthru", "stroke", "cumulative_blows", "finished"]
    assert t.summary["total_blows"] == pytest.approx(t.cumulative_blows[-1])
    assert t.summary["refusal_depth"] is None
    assert_tables_equal(t, barimpact.read_table(tmp_path / "d"))
    with pytest.raises(barimpact.InputError, match="no \\[drive\\] section"):
        barimpact.drive(EXAMPLES / "pile" / "steel-pipe-sand.toml", tmp_path / "n")
    assert not (tmp_path / "n").exists()


def test_inspector_charts_the_blow_against_the_stroke(tmp_path):
    case = EXAMPLES / "pile" / "drive-pipe-drop.toml"
    t = barimpact.inspector(case, tmp_path / "i", (0.4, 1.0, 3), depth=8.0, set={"time.end": 0.03}, no_plot=True,
                            jobs=2)
    assert list(t)[:8] == ["stroke", "energy", "set", "blows_per_250mm", "blows_per_m", "max_compression",
                           "max_tension", "enthru"]
    assert t.stroke.tolist() == [0.4, 0.7, 1.0]  # up to the drop-4t's rated 1 m
    assert t.energy[1] == pytest.approx(4000.0 * 9.81 * 0.7)
    assert t.set[2] > t.set[0]  # a longer fall drives the pile further
    with pytest.raises(barimpact.InputError, match="--depth is required"):
        barimpact.inspector(case, tmp_path / "n", "0.4:1.2:3")


def test_hammers_lists_the_shipped_table():
    h = barimpact.hammers()
    assert h.rows >= 20 and "Vulcan 010" in list(h.name)
    assert set(h.kind) == {"drop", "hydraulic", "air-steam", "diesel"}
    assert all(s for s in h.source)


def test_hopkinson_writes_the_commands_directory(tmp_path):
    write_hopkinson_signals(tmp_path)
    setup = tmp_path / "setup.toml"
    setup.write_text('[bar]\nmodulus = 200e9\ndensity = 8000.0\narea = 3e-4\n[specimen]\nlength = 0.005\n'
                     'area = 1e-4\n[incident]\nsignal = "inc.csv"\ngauge_to_specimen = 1.0\n'
                     '[transmitted]\nsignal = "tr.csv"\ngauge_to_specimen = 0.5\n')
    cli("hopkinson", setup, "--out", tmp_path / "cli", "--no-plot")
    with pytest.warns(barimpact.HealthWarning, match="not in equilibrium"):
        r = barimpact.hopkinson(setup, tmp_path / "py")
    for name in ("hopkinson.csv", "summary.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert (tmp_path / "py" / "figures" / "stress_strain.png").is_file()
    assert isinstance(r, barimpact.HopkinsonTable) and isinstance(r, dict)
    assert np.array_equal(r.stress_3w, r["stress_3w"])
    back = barimpact.read_table(tmp_path / "py")
    assert isinstance(back, barimpact.HopkinsonTable) and back.summary == r.summary
    np.testing.assert_array_equal(back.stress_3w, r.stress_3w)
    assert json.loads((tmp_path / "py" / ".barimpact").read_text())["command"] == "hopkinson"
    with pytest.warns(barimpact.HealthWarning):
        d = barimpact.hopkinson(hopkinson_setup(tmp_path), tmp_path / "from-dict", no_plot=True)
    np.testing.assert_array_equal(d.stress_3w, r.stress_3w)
    assert not (tmp_path / "from-dict" / "figures").exists()


def test_a_study_or_analysis_never_writes_over_the_run_it_reads(tmp_path):
    """hopkinson analysing a run into that run's directory replaced it; a
    study of a run's case.toml into that run's directory resumed in it."""
    run = tmp_path / "shpb"
    barimpact.run(EXAMPLES / "hopkinson" / "shpb.toml", out=run)
    before = (run / "history.csv").read_bytes()
    setup = {"specimen": {"body": "specimen"}, "incident": {"run": str(run), "gauge": "incident"},
             "transmitted": {"run": str(run), "gauge": "transmitted"}}
    for out in (run, tmp_path):
        with pytest.raises(barimpact.InputError, match="a directory this command reads|is the directory this command"):
            barimpact.hopkinson(setup, out, force=True, no_plot=True)
    with pytest.raises(barimpact.InputError, match="which this command reads"):
        barimpact.converge(run / "case.toml", run, levels=2, force=True, no_plot=True)
    assert (run / "history.csv").read_bytes() == before and not (run / "runs").exists()


def test_plot_of_a_run_directory_follows_the_command(tmp_path):
    r = barimpact.run(barimpact.Case(EXAMPLES / "paper-example1.toml", set={"time.end": 0.5,
                                                                            "output.fields_at": [0.25]}),
                      out=tmp_path / "run")
    written = barimpact.plot(tmp_path / "run")
    assert written and all(Path(p).parent == tmp_path / "run" / "figures" for p in written)
    assert "figures" in json.loads((tmp_path / "run" / ".barimpact").read_text())["entries"]
    barimpact.plot(str(tmp_path / "run"))  # again: the figures are barimpact's, replaced
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(barimpact.InputError, match="did not write"):
        barimpact.plot(tmp_path / "run", mine)
    assert barimpact.plot(tmp_path / "run", mine, force=True) and (mine / "notes.txt").exists()
    with pytest.raises(barimpact.InputError, match="no history.csv"):
        barimpact.plot(tmp_path / "mine")
    assert barimpact.plot(r, tmp_path / "of-result", formats=("png",))


def test_plot_redraws_a_study_directory_where_the_command_draws(tmp_path):
    """A bearing written with --no-plot: barimpact.plot(DIR) draws bearing.png
    into it, as the command would, and lists it as barimpact's; --out for it
    is refused (before, "holds no history.csv")."""
    d = tmp_path / "b"
    cli("bearing", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", d, "--capacity", "1e6:2e6:2", "--no-plot")
    assert not (d / "bearing.png").exists()
    written = barimpact.plot(d)
    assert (d / "bearing.png") in [Path(p) for p in written]
    assert "bearing.png" in json.loads((d / ".barimpact").read_text())["entries"]
    with pytest.raises(barimpact.InputError, match="leave out --out"):
        barimpact.plot(d, tmp_path / "elsewhere")
    assert not (tmp_path / "elsewhere").exists()


def test_force_never_writes_over_the_case_being_run(tmp_path):
    """force=True into the case file's own directory: the user's case.toml
    stays as written (comments and all), the resolved case goes to
    case.resolved.toml, which is what reading the run back takes."""
    proj = tmp_path / "proj"
    proj.mkdir()
    text = "# my comments\n" + (EXAMPLES / "paper-example1.toml").read_text()
    (proj / "case.toml").write_text(text)
    short = {"time.end": 0.5, "output.fields_at": []}
    barimpact.run(proj / "case.toml", out=proj, force=True, set=short)
    assert (proj / "case.toml").read_text() == text
    assert "\nend = 0.5\n" in (proj / "case.resolved.toml").read_text()
    assert barimpact.load(proj).t[-1] == 0.5
    barimpact.exact(barimpact.Case(proj / "case.toml"), out=proj, force=True, set={**short, "time.end": 0.25})
    assert (proj / "case.toml").read_text() == text and barimpact.load(proj).t[-1] == 0.25
    barimpact.run(barimpact.Case(proj / "case.toml", set=short)).write(str(proj), force=True)
    assert (proj / "case.toml").read_text() == text and barimpact.load(proj).t[-1] == 0.5
    # A run directory of barimpact's holding the case being run is not replaced.
    barimpact.run(EXAMPLES / "paper-example1.toml", out=tmp_path / "run", set=short)
    before = (tmp_path / "run" / "history.csv").read_bytes()
    with pytest.raises(barimpact.InputError, match="case.toml, which this command reads"):
        barimpact.run(tmp_path / "run" / "case.toml", out=tmp_path / "run", force=True)
    assert (tmp_path / "run" / "history.csv").read_bytes() == before


def test_run_and_exact_write_with_the_commands_options(tmp_path, cli_runs):
    r = barimpact.run(EXAMPLES / "paper-example1.toml", out=tmp_path / "run")
    for f in ("history.csv", "fields.csv", "case.toml"):
        assert (tmp_path / "run" / f).read_bytes() == (cli_runs["paper-example1"] / f).read_bytes()
    assert r.complete
    e = barimpact.exact(EXAMPLES / "clamped-periodic.toml", out=tmp_path / "exact",
                        set={"time.end": 1.0, "output.fields_at": []})
    cli("exact", EXAMPLES / "clamped-periodic.toml", "--out", tmp_path / "exact-cli", "--set", "time.end=1.0", "--set",
        "output.fields_at=[]")
    assert (tmp_path / "exact" / "history.csv").read_bytes() == (tmp_path / "exact-cli" / "history.csv").read_bytes()
    assert json.loads((tmp_path / "exact" / ".barimpact").read_text())["command"] == "exact"
    assert e.t[-1] == 1.0


def test_warnings_and_strict(tmp_path):
    with pytest.warns(barimpact.HealthWarning, match="penalty-unresolved") as seen:
        barimpact.run(EXAMPLES / "paper-example1.toml", set=STIFF)
    assert {w.filename for w in seen} == {__file__}  # the caller's line, not the package's
    with pytest.raises(barimpact.StrictError) as e, pytest.warns(barimpact.HealthWarning):
        barimpact.run(EXAMPLES / "paper-example1.toml", set=STIFF, out=tmp_path / "run", strict=True)
    assert isinstance(e.value.result, barimpact.Result) and e.value.warnings
    assert (tmp_path / "run" / "summary.json").is_file()  # written all the same, as the command exits 4 after
    with pytest.raises(barimpact.StrictError) as e, pytest.warns(barimpact.HealthWarning):
        barimpact.sweep(EXAMPLES / "sweeps" / "with-failures.toml", tmp_path / "sweep", strict=True)
    assert isinstance(e.value.result, barimpact.Table) and (tmp_path / "sweep" / "sweep.csv").is_file()


# ---- the names: the command's options, the package's, the stubs'


def command_options(command):
    """The long options of `barimpact COMMAND --help`, as Python names."""
    text = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
    return {name.replace("-", "_") for name in re.findall(r"^\s+--([a-z][a-z-]*)", text, re.M)}


# Options of the command alone: `sweep --ranks N` starts mpiexec of the
# command itself, and the package runs its sweep in-process, without MPI.
COMMAND_ONLY = {"sweep": {"ranks"}}


@pytest.mark.parametrize("command", ["run", "exact", "converge", "sweep", "bearing", "hopkinson", "plot"])
def test_every_option_of_the_command_is_a_keyword(command):
    parameters = inspect.signature(getattr(barimpact, command)).parameters
    missing = command_options(command) - set(parameters) - COMMAND_ONLY.get(command, set())
    assert not missing, f"barimpact.{command} lacks the command's {sorted(missing)}"


def test_submodules_do_not_shadow_the_functions():
    import barimpact.bearing  # noqa: F401
    import barimpact.convergence  # noqa: F401
    import barimpact.hopkinson  # noqa: F401
    import barimpact.match  # noqa: F401
    import barimpact.pda  # noqa: F401
    import barimpact.plot  # noqa: F401
    for name in ("bearing", "hopkinson", "pda", "match", "plot"):
        assert inspect.isfunction(getattr(barimpact, name)), name


def stub_names(path):
    """The names a stub defines at its top level, and its functions' parameters."""
    tree = ast.parse(path.read_text())
    names, functions = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
            if isinstance(node, ast.FunctionDef):
                a = node.args
                functions[node.name] = [p.arg for p in a.posonlyargs + a.args + a.kwonlyargs]
        elif isinstance(node, ast.ImportFrom):
            names.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names, functions


def test_the_stubs_name_every_public_name_with_its_parameters():
    import types
    names, functions = stub_names(PACKAGE / "__init__.pyi")
    public = {n for n in dir(barimpact) if not n.startswith("_")
              and not isinstance(getattr(barimpact, n), types.ModuleType)}
    assert public == set(barimpact.__all__)
    assert public <= names, f"not in __init__.pyi: {sorted(public - names)}"
    assert ast.literal_eval(re.search(r"^__all__ = (\[.*?\])", (PACKAGE / "__init__.pyi").read_text(),
                                      re.S | re.M).group(1)) == barimpact.__all__
    for name, parameters in functions.items():
        runtime = list(inspect.signature(getattr(barimpact, name)).parameters)
        assert parameters == runtime, name
    core_names, _ = stub_names(PACKAGE / "_core.pyi")
    core = {n for n in dir(barimpact._core) if not n.startswith("__")}
    assert core <= core_names, f"not in _core.pyi: {sorted(core - core_names)}"
    result_stub = next(n for n in ast.parse((PACKAGE / "_core.pyi").read_text()).body
                       if isinstance(n, ast.ClassDef) and n.name == "Result")
    stubbed = {n.name for n in result_stub.body if isinstance(n, ast.FunctionDef)}
    missing = {n for n in dir(barimpact.Result) if not n.startswith("_")} - stubbed
    assert not missing, f"Result members not in _core.pyi: {sorted(missing)}"
    assert (PACKAGE / "py.typed").is_file()


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_stubtest_finds_the_stubs_true_to_the_module(tmp_path):
    # pybind11's classes have their own metaclass and no __init__: not the stubs' business.
    (tmp_path / "allow").write_text("barimpact(\\._core)?\\.(Case|Result)\nbarimpact(\\._core)?\\.Result\\.__init__\n")
    (tmp_path / "mypy.ini").write_text("[mypy]\nignore_missing_imports = True\n")
    env = dict(os.environ)
    if PACKAGE.parent.name not in ("site-packages", "dist-packages"):  # an installed package mypy finds itself
        env["MYPYPATH"] = str(PACKAGE.parent)
    p = subprocess.run([sys.executable, "-m", "mypy.stubtest", "barimpact", "--allowlist", str(tmp_path / "allow"),
                        "--mypy-config-file", str(tmp_path / "mypy.ini")], capture_output=True, text=True, env=env,
                       cwd=tmp_path, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr


# --- check -------------------------------------------------------------------------------

def test_check_reports_what_the_command_prints():
    sets = {"obstacle.stiffness": 1e4, "time.step": 0.001}
    k = barimpact.check(EXAMPLES / "paper-example1.toml", set=sets)
    assert k["steps"] == 4000 and k["nodes"] == 101 and k["stable_step"] is None
    [p] = k["penalties"]
    # Z = sqrt(rho a) = 1, k = 1e4: tau = 1e-4, ten times below the step.
    assert p["link"] == "obstacle" and p["basis"] == "Z/k" and p["tau"] == pytest.approx(1e-4, rel=1e-15)
    assert p["dt_over_tau"] == pytest.approx(10.0) and not p["resolved"]
    assert k["timed_steps"] == 4000 and k["estimate_seconds"] > 0 and k["trouble"] is None
    out = subprocess.run([CLI, "check", str(EXAMPLES / "paper-example1.toml"), "--set", "obstacle.stiffness=1e4",
                          "--set", "time.step=0.001"], capture_output=True, text=True, check=True).stdout
    # The same report but for the measured time.
    drop_time = lambda text: [line for line in text.splitlines() if not line.startswith("time estimate")]
    assert drop_time(out)[1:] == drop_time(k["text"])


def test_check_gives_the_explicit_schemes_stable_step_and_refuses_like_the_command():
    k = barimpact.check(EXAMPLES / "paper-example1-rigid.toml",
                        set={"time.scheme": "central-difference", "time.step": 0.005})
    assert k["stable_step"] == pytest.approx(0.01) and k["mass"] == "lumped"
    with pytest.raises(barimpact.InputError) as e:
        barimpact.check(EXAMPLES / "paper-example1.toml", set={"time.step": 0})
    assert str(e.value) == cli_error("check", str(EXAMPLES / "paper-example1.toml"), "--set", "time.step=0")


def test_plot_takes_a_sweep_directory_as_the_command_does(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", barimpact.HealthWarning)
        barimpact.sweep(EXAMPLES / "sweeps" / "penalty-to-rigid.toml", out=tmp_path / "sweep")
    written = barimpact.plot(tmp_path / "sweep")
    assert written and all(p.exists() for p in map(Path, written))
    assert (tmp_path / "sweep" / "figures" / "rebound_velocity.png").is_file()
