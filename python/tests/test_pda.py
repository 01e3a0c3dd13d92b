"""barimpact.pda: the command's analysis of a pile's record from Python, its
table and summary, its directory and figures, its refusals."""
import json

import pytest

import barimpact
from conftest import EXAMPLES

RECORD = EXAMPLES / "pda" / "steel-pipe.toml"
KEYS = ("t1", "t2", "fmx", "vmx", "emx", "dmx", "csx", "tsx", "rmx", "rmx_time", "rsp", "bta", "bta_depth")


def test_pda_returns_the_table_and_the_summary():
    t = barimpact.pda(RECORD)
    assert isinstance(t, barimpact.PdaTable)
    assert t.columns[:6] == ("t", "force", "velocity_z", "wave_down", "wave_up", "displacement")
    assert list(t.summary)[:len(KEYS)] == list(KEYS)
    assert t.summary["fmx"] == t.force.max()
    assert t.summary["t1"] < t.summary["t2"]


def test_pda_writes_the_commands_directory(tmp_path):
    t = barimpact.pda(RECORD, out=tmp_path / "pda")
    assert json.loads((tmp_path / "pda" / "summary.json").read_text()) == t.summary
    assert (tmp_path / "pda" / "force_velocity.png").is_file() and (tmp_path / "pda" / "waves.png").is_file()
    again = barimpact.read_table(tmp_path / "pda")
    assert isinstance(again, barimpact.PdaTable) and again.summary["rmx"] == t.summary["rmx"]
    barimpact.pda(RECORD, out=tmp_path / "quiet", no_plot=True)
    assert not (tmp_path / "quiet" / "waves.png").exists()


def test_pda_takes_a_dict_and_refuses_in_one_line(tmp_path, monkeypatch):
    monkeypatch.chdir(EXAMPLES / "pda")
    record = {"pile": {"length": 19.2, "area": 0.0105, "modulus": 210e9, "density": 7850.0},
              "record": {"file": "steel-pipe.csv", "skip_rows": 1, "force": ["F1", "F2"], "velocity": ["V1", "V2"]},
              "case_method": {"damping": 0.5}}
    assert barimpact.pda(record).summary["rmx"] == barimpact.pda(RECORD).summary["rmx"]
    record["case_method"]["damping"] = 2.0
    with pytest.raises(barimpact.InputError, match=r"case_method.damping must be in \[0, 1\]") as e:
        barimpact.pda(record, out=tmp_path / "refused")
    assert "\n" not in str(e.value) and not (tmp_path / "refused").exists()
