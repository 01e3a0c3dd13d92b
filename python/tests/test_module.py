import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import barimpact
from conftest import CLI, EXAMPLES, cli_error


def read_history(d):
    return np.loadtxt(Path(d) / "history.csv", delimiter=",", skiprows=1)


@pytest.mark.parametrize("name", ["paper-example1", "paper-example2"])
def test_same_bits_as_the_command_line(cli_runs, name):
    # history.csv holds shortest round-trip decimals: parsing gives the same doubles.
    r = barimpact.run(EXAMPLES / f"{name}.toml")
    assert np.array_equal(r.history, read_history(cli_runs[name]))
    f = np.loadtxt(cli_runs[name] / "fields.csv", delimiter=",", skiprows=1, usecols=range(5))
    nodes = r.x.size
    assert np.array_equal(r.u.ravel(), f[:, 2]) and np.array_equal(r.sigma.ravel(), f[:, 4])
    assert np.array_equal(np.repeat(r.field_t, nodes), f[:, 0])


def test_columns_are_views_of_the_history():
    r = barimpact.run(EXAMPLES / "paper-example1.toml")
    assert r.columns == ("t", "U", "V", "R", "E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact",
                         "D_plastic")
    assert np.shares_memory(r.U, r.history) and np.shares_memory(r.t, r.history)
    assert np.array_equal(r.R, r.history[:, 3])
    assert not r.U.flags.writeable
    assert r.u.shape == (101, 101) and r.v.shape == r.u.shape
    del r  # the views keep the result alive
    r2 = barimpact.run(EXAMPLES / "paper-example1.toml").U
    assert r2[0] == 0.0 and r2.size == 401


def test_case_from_file_text_dict_and_overrides_agree():
    path = EXAMPLES / "paper-example1.toml"
    a = barimpact.Case(path)
    b = barimpact.Case(str(path))
    c = barimpact.Case(path.read_text())
    d = barimpact.Case({
        "bar": {"length": 1.0, "elements": 100},
        "initial": {"velocity": "-1"},
        "time": {"end": 4.0, "step": 0.01},
        "output": {"fields_at": [round(0.04 * i, 2) for i in range(101)]},
    })
    assert a.to_toml() == b.to_toml() == c.to_toml() == d.to_toml()
    e = barimpact.Case(path, set={"bar.elements": 50, "obstacle.kind": "none", "time.lambda": 0.25})
    assert "elements = 50" in e.to_toml() and '[near_end]\nlaw = "free"' in e.to_toml()
    assert barimpact.Case(path, set=["bar.elements=50"]).steps == 400


def test_errors_carry_the_command_lines_messages():
    path = str(EXAMPLES / "paper-example1.toml")
    with pytest.raises(barimpact.InputError) as e:
        barimpact.Case(path, set=["bar.stiffness=-1"])
    assert str(e.value) == cli_error("run", path, "--out", "/tmp/never-written", "--set", "bar.stiffness=-1")
    with pytest.raises(barimpact.InputError) as e:
        barimpact.Case("/nonexistent/case.toml")
    assert str(e.value) == cli_error("run", "/nonexistent/case.toml", "--out", "/tmp/never-written")
    with pytest.raises(ValueError, match="bar.elements must be >= 1"):
        barimpact.Case({"bar": {"elements": 0}})
    with pytest.raises(ValueError, match="unknown key bar.mass"):
        barimpact.run({"bar": {"mass": 1}})
    with pytest.raises(ValueError, match=r'unknown name "q"'):
        barimpact.Case("[load]\nbody_force = \"q\"\n")
    assert not Path("/tmp/never-written").exists()


def test_progress_is_reported_and_can_stop_the_run():
    seen = []
    r = barimpact.run(EXAMPLES / "paper-example1.toml", progress=lambda p: seen.append(p))
    assert seen and seen[0]["steps"] == 400 and r.complete
    stop = barimpact.run(EXAMPLES / "paper-example1.toml", progress=lambda p: False)
    assert not stop.complete and stop.summary["status"] == "stopped"


def test_an_exception_in_the_callback_reaches_the_caller():
    def boom(p):
        raise RuntimeError("from the callback")
    with pytest.raises(RuntimeError, match="from the callback"):
        barimpact.run(EXAMPLES / "paper-example1.toml", progress=boom)


def test_the_gil_is_released_during_a_run():
    case = barimpact.Case(EXAMPLES / "paper-example1.toml",
                          set={"bar.elements": 20000, "time.step": 0.0005, "time.end": 4, "output.every": 100,
                               "output.fields_at": []})
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    barimpact.run(case)
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    during = [t for t in ticks if start < t < start + elapsed]
    # A held GIL would freeze the counter for the whole run (> 0.1 s here).
    assert elapsed > 0.1
    assert len(during) > 10


def test_exact_tabulates_like_the_command_line(tmp_path):
    import subprocess
    case = EXAMPLES / "clamped-periodic.toml"
    e = barimpact.exact(case)
    subprocess.run([CLI, "exact", str(case), "--out", str(tmp_path / "ex")], check=True, capture_output=True)
    assert np.array_equal(e.history, read_history(tmp_path / "ex")[:, :11])  # then far_end.force, far_end.opening
    r = barimpact.run(case)
    assert np.max(np.abs(r.U - e.U)) < 1e-12  # characteristic is exact here
    with pytest.raises(barimpact.InputError, match="no exact solution"):
        barimpact.exact(EXAMPLES / "paper-example2.toml")


def test_exact_example1_broadcasts():
    x = np.linspace(0, 1, 5)
    e = barimpact.exact_example1(x[:, None], np.array([0.0, 0.5, 3.0])[None, :])
    assert e["u"].shape == (5, 3)
    assert np.allclose(e["u"][:, 2], 1.0)  # after lift-off at t = 2: U = t - 2
    assert np.allclose(e["R"][:, 1], 1.0)
    assert e["u"][0, 1] == 0.0


def test_write_gives_the_run_directory(tmp_path, cli_runs):
    r = barimpact.run(EXAMPLES / "paper-example1.toml")
    r.write(str(tmp_path / "run"))
    for f in ("history.csv", "fields.csv", "case.toml"):
        assert (tmp_path / "run" / f).read_bytes() == (cli_runs["paper-example1"] / f).read_bytes()


def test_write_follows_the_output_rule(tmp_path):
    r = barimpact.run(barimpact.Case(EXAMPLES / "paper-example1.toml", set={"time.end": 0.5, "output.fields_at": []}))
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("my notes")
    with pytest.raises(barimpact.InputError, match="did not write"):
        r.write(str(mine))
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
    r.write(str(mine), force=True)
    assert (mine / "notes.txt").read_text() == "my notes"
    assert (mine / "history.csv").exists()


def test_summary_lists_warnings():
    healthy = barimpact.run(EXAMPLES / "paper-example1.toml")
    assert healthy.summary["warnings"] == []
    stiff = barimpact.run(barimpact.Case(EXAMPLES / "paper-example1.toml",
                                         set={"obstacle.stiffness": 1e4, "time.step": 1e-3}))
    kinds = {w.split(":")[0] for w in stiff.summary["warnings"]}
    assert {"energy-balance", "penalty-unresolved"} <= kinds


def test_ctrl_c_stops_a_long_run():
    # SIGINT from another thread while the run holds no GIL: the run ends
    # after the step under way and KeyboardInterrupt reaches the caller.
    import os
    import signal
    case = barimpact.Case(EXAMPLES / "paper-example1.toml",
                          set={"bar.elements": 2000, "time.step": 1e-4, "time.end": 1e4, "output.every": 10000,
                               "output.fields_at": []})
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        barimpact.run(case)
    assert time.monotonic() - start < 5.0  # the whole run would take minutes


def test_a_line_of_bodies_by_name():
    # The new spelling from a dict, the line's columns by name (views), and the
    # fields' body of each row.
    r = barimpact.run({
        "body": [{"name": "a", "length": 1.0, "elements": 50, "velocity": "1"},
                 {"name": "b", "length": 2.0, "elements": 100}],
        "joint": [{"between": ["a", "b"], "law": "rigid", "gap": 0.05}],
        "time": {"scheme": "central-difference", "step": 0.01, "end": 4.0},
        "output": {"fields_at": [1.0]},
    })
    assert r.history_columns[9:13] == ["D_contact", "D_plastic", "joint.a-b.force", "joint.a-b.opening"]
    force = r["joint.a-b.force"]
    assert force.shape == r.t.shape and np.max(force) > 0.4
    assert np.shares_memory(r.t, r["t"])
    assert set(r.field_body) == {"a", "b"} and len(r.field_body) == 51 + 101
    total = r.E_kin + r.E_strain + r.E_obstacle - r.W_ext + r.D_visc + r.D_contact + r.D_plastic
    assert np.max(np.abs(total - total[0])) < 1e-12  # central differences' identity with rigid links
    with pytest.raises(KeyError):
        r["joint.nope.force"]


def test_an_elastic_plastic_bar():
    # A yielding bar from a dict: D_plastic grows, the budget closes, eps_p is
    # a field like sigma, the summary names the largest plastic strain.
    r = barimpact.run({
        "body": [{"name": "rod", "elements": 100, "velocity": "-1", "material": "plastic", "yield_stress": 0.4,
                  "hardening_modulus": 0.2, "hardening": "isotropic"}],
        "near_end": {"law": "rigid"},
        "time": {"scheme": "central-difference", "step": 0.005, "end": 2.0},
        "output": {"fields_at": [0.5, 2.0]},
    })
    assert r.D_plastic[-1] > 0.05 and np.all(np.diff(r.D_plastic) >= -1e-15)
    total = r.E_kin + r.E_strain + r.E_obstacle - r.W_ext + r.D_visc + r.D_contact + r.D_plastic
    assert np.max(np.abs(total[1:] - total[1])) < 1e-12
    assert r.eps_p.shape == r.sigma.shape and np.min(r.eps_p) < 0.0
    assert r.summary["plastic"]["body"] == "rod" and r.summary["plastic"]["largest_strain"] < 0.0


def test_bearing_from_python_matches_the_command_line(tmp_path):
    """barimpact.bearing writes what `barimpact bearing` writes, and returns its columns."""
    pipe = EXAMPLES / "pile" / "steel-pipe-sand.toml"
    cols = barimpact.bearing(pipe, tmp_path / "py", (1e6, 5e7, 3), plot=False)
    subprocess.run([CLI, "bearing", str(pipe), "--out", str(tmp_path / "cli"), "--capacity", "1e6:5e7:3",
                    "--no-plot"], check=True, capture_output=True)
    py_rows = (tmp_path / "py" / "bearing.csv").read_text().splitlines()
    cli_rows = (tmp_path / "cli" / "bearing.csv").read_text().splitlines()
    assert [r.split(",")[:11] for r in py_rows] == [r.split(",")[:11] for r in cli_rows]
    assert list(cols["capacity"]) == [1e6, 2.55e7, 5e7]
    assert cols["set"][0] > 0 and cols["blows_per_250mm"][-1] == float("inf")
    summary = barimpact.run(pipe).summary["blow"]
    assert summary["set"] > 0 and summary["max_compression"]["body"] == "pile"


def test_bad_input_is_input_error_everywhere(tmp_path):
    """Issue 36: integers beyond 64 bits in a dict (RuntimeError), a `set` that is
    neither a dict nor a list (TypeError) and a case too large for the memory
    (MemoryError: std::bad_alloc, from check) were other Python errors."""
    with pytest.raises(barimpact.InputError, match=r"bar\.elements = 1000000000000000000000000000000 is beyond"):
        barimpact.Case({"bar": {"elements": 10**30}})
    with pytest.raises(barimpact.InputError, match=r"output\.fields_at = .* is beyond"):
        barimpact.Case({"output": {"fields_at": [-10**30]}})
    with pytest.raises(barimpact.InputError, match=r"body\.elements"):
        barimpact.Case({"body": [{"elements": 2**64}]})
    with pytest.raises(barimpact.InputError, match="set: must be a dict"):
        barimpact.Case(EXAMPLES / "paper-example1.toml", set=5)
    one = barimpact.Case(EXAMPLES / "paper-example1.toml", set="bar.elements=7")  # one override as text
    assert "elements = 7" in one.to_toml()
    # Refused before it is built (about 340 GB with its 101 snapshots held): the same error, naming the key.
    with pytest.raises(barimpact.OutOfMemoryError, match=r"bar\.elements.*output\.fields_at"):
        barimpact.run(EXAMPLES / "paper-example1.toml", set={"bar.elements": 100000000})
    # Beyond a 1 GiB address-space limit: refused by the estimate, still a MemoryError.
    script = (
        "import resource, barimpact\n"
        "resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))\n"
        "try:\n"
        f"    barimpact.check({str(EXAMPLES / 'paper-example1.toml')!r}, set={{'bar.elements': 100000000}})\n"
        "except barimpact.InputError as e:\n"
        "    print(type(e).__name__, isinstance(e, MemoryError), e)\n")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.stdout.startswith("OutOfMemoryError True the run needs about"), out.stdout + out.stderr
