"""barimpact.match: the command's signal matching of a pile's record from
Python, its tables and summary, its directory and figures (and the
command's), its refusals."""
import json
import os
import signal
import subprocess
import threading
import time
import tomllib

import numpy as np
import pytest

import barimpact
from barimpact.match import plot_match
from conftest import CLI, EXAMPLES

RECORD = EXAMPLES / "pda" / "steel-pipe.toml"
COLUMNS = ("t", "force_measured", "force_computed", "velocity_z", "wave_up_measured", "wave_up_computed")
KEYS = ("capacity", "shaft", "toe", "match_quality", "evaluations", "iterations", "starts", "spread")
FIGURES = ("force_match", "resistance", "static_test")


@pytest.fixture(scope="module")
def fitted():
    return barimpact.match(RECORD, jobs=2)


def test_match_finds_the_forward_models_soil(fitted):
    """The record was made by a forward model with 600 kN on the shaft and
    900 kN at the toe."""
    t = fitted
    assert isinstance(t, barimpact.MatchTable)
    assert t.columns == COLUMNS and t.rows == t.summary["samples_matched"]
    assert list(t.summary)[:len(KEYS)] == list(KEYS)
    assert t.summary["capacity"] == pytest.approx(1.5e6, rel=0.02)
    assert t.summary["shaft"] == pytest.approx(600e3, rel=0.05)
    assert t.summary["t1"] < t.summary["t2"] and t.summary["match_quality"] < 0.01


def test_soil_and_static_are_tables_of_their_files(fitted):
    soil, static, s = fitted.soil, fitted.static, fitted.summary
    assert soil.columns == ("segment", "top", "bottom", "resistance", "quake", "damping")
    assert list(soil.segment) == [str(i) for i in range(1, s["segments"] + 1)] + ["toe"]
    assert soil.resistance[:-1].sum() == pytest.approx(s["shaft"]) and soil.resistance[-1] == s["toe"]
    assert soil.top[-1] == soil.bottom[-1] == s["length"] and np.all(np.diff(soil.top) >= 0)
    assert static.columns == ("settlement", "load") and static.settlement[0] == 0.0
    assert static.load.max() == pytest.approx(s["capacity"]) and static.settlement.max() > s["s_c"]


def test_match_writes_the_commands_directory(tmp_path, fitted):
    t = barimpact.match(RECORD, out=tmp_path / "match", jobs=2)
    d = tmp_path / "match"
    assert json.loads((d / "summary.json").read_text()) == t.summary
    assert np.array_equal(t.force_computed, fitted.force_computed)  # the same fit with or without `out`
    for name in FIGURES:
        for fmt in ("png", "svg"):
            assert (d / f"{name}.{fmt}").stat().st_size > 0
    entries = json.loads((d / ".barimpact").read_text())["entries"]
    assert {"match.csv", "soil.csv", "static.csv", "summary.json", "force_match.png"} <= set(entries)
    again = barimpact.read_table(d)
    assert isinstance(again, barimpact.MatchTable) and again.summary["capacity"] == t.summary["capacity"]
    assert np.array_equal(again.soil.resistance, t.soil.resistance) and np.array_equal(again.static.load, t.static.load)
    barimpact.match(RECORD, out=tmp_path / "quiet", no_plot=True, jobs=2)
    assert not (tmp_path / "quiet" / "resistance.png").exists()


def test_the_command_writes_the_same_files_and_the_figures(tmp_path):
    p = subprocess.run([CLI, "match", str(RECORD), "--out", str(tmp_path / "cli")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    barimpact.match(RECORD, out=tmp_path / "py", no_plot=True)
    for name in ("match.csv", "soil.csv", "static.csv"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    for name in FIGURES:
        for fmt in ("png", "svg"):
            assert (tmp_path / "cli" / f"{name}.{fmt}").stat().st_size > 0


def test_match_takes_a_dict_and_refuses_in_one_line(tmp_path, monkeypatch, fitted):
    monkeypatch.chdir(EXAMPLES / "pda")  # the record's file, relative
    record = tomllib.loads(RECORD.read_text())
    assert barimpact.match(record, jobs=2).summary["capacity"] == fitted.summary["capacity"]
    record["match"]["segments"] = 0
    with pytest.raises(barimpact.InputError, match=r"match\.segments") as e:
        barimpact.match(record, out=tmp_path / "refused")
    assert "\n" not in str(e.value) and not (tmp_path / "refused").exists()
    with pytest.raises(barimpact.InputError, match="--jobs"):
        barimpact.match(RECORD, jobs=2000)


def test_a_users_directory_is_refused_before_the_fit(tmp_path):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(barimpact.InputError, match="--out") as e:
        barimpact.match(RECORD, out=mine)
    assert "\n" not in str(e.value) and sorted(p.name for p in mine.iterdir()) == ["notes.txt"]


def test_ctrl_c_ends_the_fit_and_writes_nothing(tmp_path):
    # SIGINT while the fit holds no GIL: it ends at its next iterations, and
    # KeyboardInterrupt reaches the caller with nothing written, as the
    # command exits then.
    record = tomllib.loads(RECORD.read_text())
    record["record"]["file"] = str(RECORD.with_name(record["record"]["file"]))
    record["match"].update(segments=50, starts=32)  # about a minute on one thread
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        barimpact.match(record, out=tmp_path / "stopped", no_plot=True, jobs=1)
    timer.join()
    assert time.monotonic() - start < 5.0
    assert list(tmp_path.iterdir()) == []


def test_the_figures_go_only_into_a_match_directory(tmp_path):
    barimpact.pda(RECORD, out=tmp_path / "pda", no_plot=True)
    with pytest.raises(barimpact.InputError, match="not a directory barimpact match wrote"):
        plot_match(tmp_path / "pda")
    assert not (tmp_path / "pda" / "force_match.png").exists()


def test_an_uneven_record_warns_and_strict_raises_after_writing(tmp_path, monkeypatch):
    """An unevenly sampled record is matched unfiltered: a HealthWarning
    (summary.json's match-unfiltered), and strict=True raises StrictError
    with the results written, as --strict exits 4."""
    rows = (EXAMPLES / "pda" / "steel-pipe.csv").read_text().splitlines()
    cells = rows[299].split(",")
    cells[0] = repr(float(cells[0]) + 5e-6)
    rows[299] = ",".join(cells)
    (tmp_path / "uneven.csv").write_text("\n".join(rows) + "\n")
    record = tomllib.loads(RECORD.read_text())
    record["record"]["file"] = str(tmp_path / "uneven.csv")
    record["match"]["starts"] = 1
    with pytest.warns(barimpact.HealthWarning, match="match-unfiltered"):
        table = barimpact.match(record, jobs=2)
    assert table.summary["low_pass"] is None
    with pytest.warns(barimpact.HealthWarning), pytest.raises(barimpact.StrictError):
        barimpact.match(record, out=tmp_path / "strict", no_plot=True, strict=True, jobs=2)
    assert (tmp_path / "strict" / "summary.json").is_file()
