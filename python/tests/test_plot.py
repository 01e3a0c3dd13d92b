import struct
import subprocess

import pytest

import barimpact
from conftest import CLI, EXAMPLES

FIGURES = ("displacement", "reaction", "energy", "stress_map", "snapshots", "impacts")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", head[16:24])


def check_figures(d):
    for name in FIGURES:
        png, svg = d / f"{name}.png", d / f"{name}.svg"
        assert png.stat().st_size > 10_000, name
        assert svg.stat().st_size > 10_000 and b"<svg" in svg.read_bytes()[:500], name
        assert png_size(png) == (960, 540), name


@pytest.mark.parametrize("name", ["paper-example1", "paper-example2"])
def test_barimpact_plot_writes_every_figure(cli_runs, name, tmp_path):
    out = tmp_path / "figs"
    p = subprocess.run([CLI, "plot", str(cli_runs[name]), "--out", str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    check_figures(out)
    assert len(p.stdout.split()) == 2 * len(FIGURES)


def test_plot_of_a_result(tmp_path):
    r = barimpact.run(EXAMPLES / "paper-example2.toml")
    written = barimpact.plot(r, tmp_path)
    assert len(written) == 2 * len(FIGURES)
    check_figures(tmp_path)


def test_plot_refuses_a_directory_that_is_not_a_run(tmp_path):
    p = subprocess.run([CLI, "plot", str(tmp_path)], capture_output=True, text=True)
    assert p.returncode == 2
    assert "no history.csv" in p.stderr


def test_the_exact_solution_is_drawn_only_when_it_applies():
    from barimpact.plot import exact_parameters
    case = {"body": [{"kind": "bar", "length": 2.0, "modulus": 4.0, "density": 1.0, "area": 1.0, "viscosity": 0.0,
                      "displacement": "0", "velocity": "-0.5"}],
            "near_end": {"law": "elastic", "gap": 0.0}, "load": {"body_force": "0", "gravity": 0.0}}
    assert exact_parameters(case) == (2.0, 4.0, 1.0, -0.5)
    case["load"]["body_force"] = "-1"
    assert exact_parameters(case) is None


def test_converge_draws_convergence_and_work_precision(tmp_path):
    out = tmp_path / "study"
    p = subprocess.run([CLI, "converge", str(EXAMPLES / "paper-example1-rigid.toml"), "--out", str(out), "--levels", "2",
                        "--schemes", "central-difference,characteristic"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    for name in ("convergence", "work_precision"):
        assert png_size(out / f"{name}.png") == (960, 540)
        assert (out / f"{name}.svg").stat().st_size > 5_000
    # The paths it prints are the ones that exist, and a rerun replaces the study.
    assert all((out / f"{name}.png").exists() for name in ("convergence", "work_precision"))
    assert ".partial" not in p.stdout
    again = subprocess.run([CLI, "converge", str(EXAMPLES / "paper-example1-rigid.toml"), "--out", str(out),
                            "--levels", "2", "--schemes", "central-difference,characteristic"],
                           capture_output=True, text=True)
    assert again.returncode == 0, again.stderr


def test_figures_of_a_run_are_barimpacts_and_go_with_it(tmp_path):
    run = tmp_path / "run"
    case = [str(EXAMPLES / "paper-example1.toml"), "--out", str(run), "--set", "time.end=0.5", "--set", "output.fields_at=[0.25]"]
    assert subprocess.run([CLI, "run", *case], capture_output=True).returncode == 0
    assert subprocess.run([CLI, "plot", str(run)], capture_output=True).returncode == 0
    assert (run / "figures" / "impacts.png").exists()
    # figures/ is listed in the marker, so a rerun may replace the directory.
    p = subprocess.run([CLI, "run", *case], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert not (run / "figures").exists()


def test_a_blow_gets_the_analysers_figures(tmp_path):
    """A pile's run: force and Z v at the head gauge, the toe, the stress
    envelopes; the envelopes in summary.json bound the extremes."""
    r = barimpact.run(EXAMPLES / "pile" / "steel-pipe-sand.toml")
    blow = r.summary["blow"]
    env = blow["envelope"]
    assert len(env["x"]) == len(env["compression"]) == len(env["tension"]) == 100
    assert max(env["compression"]) == blow["max_compression"]["value"]
    assert blow["impedance"] == pytest.approx(0.0105 * (210e9 * 7850.0) ** 0.5, rel=1e-12)
    written = [p.name for p in barimpact.plot(r, tmp_path)]
    for name in ("blow_head", "blow_toe", "blow_envelopes"):
        assert f"{name}.png" in written and f"{name}.svg" in written
        assert png_size(tmp_path / f"{name}.png") == (960, 540)
