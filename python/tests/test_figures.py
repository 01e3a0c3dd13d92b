"""The figures' promises: large runs stay small, units on the axes, legends
naming only what differs, exact solutions drawn, reference slopes on
convergence plots, and the figures of a sweep."""
import csv
import html
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import barimpact
from barimpact.convergence import log_spaced, measured_order, plot_study, plot_sweep, sweep_dimensions
from barimpact.plot import Units, compare, legend_labels, load, peak_cells, screen_points
from conftest import CLI, EXAMPLES

RUN_FIGURES = ("displacement", "reaction", "energy", "stress_map", "snapshots", "impacts")


def svg_texts(path):
    """The texts of an SVG matplotlib wrote (it keeps each one as a comment beside its glyphs)."""
    return [html.unescape(t) for t in re.findall(r"<!-- (.*?) -->", path.read_text(encoding="utf-8"))]


def run_dir(tmp_path, case, *sets, name="run"):
    out = tmp_path / name
    args = [CLI, "run", str(case), "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return out


def with_units(directory, system):
    """The run directory's case.toml with `[units] system`, as the case reader writes it."""
    case = directory / "case.toml"
    text = case.read_text()
    assert '[units]\nsystem = "none"' in text, "the case reader writes [units]"
    case.write_text(text.replace('[units]\nsystem = "none"', f'[units]\nsystem = "{system}"'))
    return directory


# --- large runs ---------------------------------------------------------------------------

def test_a_large_run_plots_into_few_megabytes(tmp_path):
    """4,000 elements, 16,000 steps, 101 snapshots: every figure written,
    all of them under 5 MB (a point per step or a cell per node would make
    the SVGs tens of megabytes), the space-time map an image in the SVG."""
    times = ",".join(f"{0.04 * i:.2f}" for i in range(101))
    run = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "bar.elements=4000", "time.step=2.5e-4",
                  "output.every=1", f"output.fields_at=[{times}]")
    assert (run / "history.csv").stat().st_size > 1_500_000 and (run / "fields.csv").stat().st_size > 25_000_000
    p = subprocess.run([CLI, "plot", str(run)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    figures = run / "figures"
    for name in RUN_FIGURES:
        assert (figures / f"{name}.png").stat().st_size > 10_000, name
        assert (figures / f"{name}.svg").stat().st_size > 10_000, name
    total = sum(f.stat().st_size for f in figures.iterdir())
    assert total < 5_000_000, total
    assert "<image" in (figures / "stress_map.svg").read_text()


def test_screen_points_keep_every_peak():
    rng = np.random.default_rng(1)
    t = np.linspace(0.0, 1.0, 1_000_001)
    y = rng.normal(size=t.size)
    y[123_457], y[876_543] = 50.0, -60.0
    x, kept = screen_points(t, y, columns=1000)
    assert kept.size <= 2 * 1000 + 10
    assert kept.max() == 50.0 and kept.min() == -60.0
    assert np.all(np.diff(x) > 0)
    short = np.arange(100.0)
    assert screen_points(short, short)[1] is short


def test_peak_cells_keep_a_one_node_peak():
    field = np.zeros((3, 20_001))
    field[1, 12_345] = -7.0
    x, cells = peak_cells(field, np.linspace(0.0, 1.0, 20_001), 1000, axis=1)
    assert cells.shape == (3, x.size) and x.size <= 1001
    assert cells.min() == -7.0 and np.all(np.diff(x) > 0)


# --- units -------------------------------------------------------------------------------------

def test_si_labels_carry_units_and_none_leaves_them_bare(tmp_path):
    run = run_dir(tmp_path, EXAMPLES / "paper-example1-rigid.toml")
    plain = barimpact.plot(str(run), tmp_path / "plain")
    assert plain
    texts = svg_texts(tmp_path / "plain" / "reaction.svg")
    assert "obstacle reaction (compression +)" in texts and "time" in texts
    assert not any(re.search(r"\[(N|s)\]", t) for t in texts)
    with_units(run, "SI")
    barimpact.plot(str(run), tmp_path / "si")
    si = tmp_path / "si"
    assert {"time [s]", "near-end displacement (along x +) [m]"} <= set(svg_texts(si / "displacement.svg"))
    assert {"time [s]", "obstacle reaction (compression +) [N]"} <= set(svg_texts(si / "reaction.svg"))
    assert {"time [s]", "energy [J]"} <= set(svg_texts(si / "energy.svg"))
    assert {"position x [m]", "time [s]", "stress (compression +) [Pa]"} <= set(svg_texts(si / "stress_map.svg"))
    assert {"position x [m]", "displacement (along x +) [m]"} <= set(svg_texts(si / "snapshots.svg"))
    assert "exact" in svg_texts(si / "displacement.svg")  # [units] changes no number of the exact solution


def test_si_engineering_units_keep_numbers_readable():
    si, none = Units("SI"), Units("none")
    stress = si.axis("stress", "stress", [-3.2e8, 1e7])
    assert stress.label == "stress (compression +) [MPa]" and stress.factor == pytest.approx(1e-6)
    assert si.axis("time", "time", [0.0, 1.6e-4]).label == "time [µs]"
    assert si.axis("time", "time", [0.0, 0.12]).label == "time [ms]"  # a pile blow: ms, not 0.12 s
    assert si.axis("time", "time", [1.0, 1.0005]).label == "time [µs]"  # from the span, not the values
    assert si.axis("energy", "energy", [0.5]).label == "energy [J]"
    assert si.axis("energy", "energy", [3.9e4]).label == "energy [kJ]"
    assert si.axis("R", "force", [2.5e5]).label == "R (compression +) [kN]"
    assert si.axis("R", "force", [2.5e6], sign=False).label == "R [MN]"
    assert si.axis("time", "time", [0.0, 5000.0]).label == "time [s]"  # no kiloseconds
    assert si.axis("displacement", "displacement", [0.0088]).label == "displacement (along x +) [mm]"
    assert Units("SI", pile=True).axis("ram velocity", "velocity", [4.4]).label == "ram velocity (up +) [m/s]"
    assert si.axis("rate", "strain_rate", sign=False).label == "rate [1/s]"
    assert si.axis("plastic strain", "strain", [0.05]).label == "plastic strain (compression +) [-]"
    assert none.axis("stress", "stress", [3e8]).label == "stress (compression +)"
    assert none.axis("stress", "stress").factor == 1.0


# --- legends ------------------------------------------------------------------------------------

def test_legends_name_only_the_keys_that_differ(tmp_path, drawn):
    soft = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "obstacle.stiffness=50", name="soft")
    stiff = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "obstacle.stiffness=200", name="stiff")
    written = compare([soft, stiff], tmp_path / "both")
    assert {p.name for p in written} == {"compare_U.png", "compare_U.svg", "compare_R.png", "compare_R.svg"}
    legend = drawn["compare_R"][0]["legend"]
    assert legend == ["near-end stiffness = 50", "near-end stiffness = 200"]
    assert legend_labels([{"a": 1, "b": 2.0, "c": "x"}, {"a": 1, "b": 3.0, "c": "x"}], Units("SI")) == ["b = 2",
                                                                                                           "b = 3"]
    assert legend_labels([{"obstacle.stiffness": 100.0}, {"obstacle.stiffness": 200.0}],
                         Units("SI")) == ["obstacle stiffness = 100 N/m", "obstacle stiffness = 200 N/m"]


def test_plot_of_several_run_directories_compares_them(tmp_path):
    a = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "time.step=0.02", name="a")
    b = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "time.step=0.01", name="b")
    p = subprocess.run([sys.executable, "-m", "barimpact", "plot", str(a), str(b), "--out", str(tmp_path / "c")],
                       capture_output=True, text=True, env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    assert {"time step = 0.02", "time step = 0.01"} <= set(svg_texts(tmp_path / "c" / "compare_U.svg"))


# --- exact solutions ----------------------------------------------------------------------------------

def test_the_exact_solution_is_drawn_for_a_case_that_has_one(tmp_path, drawn):
    run = run_dir(tmp_path, EXAMPLES / "paper-example1-rigid.toml")
    barimpact.plot(str(run), tmp_path / "figs")
    for name, column in (("displacement", "U"), ("reaction", "R")):
        exact = [line for line in drawn[name][0]["lines"] if line[0] == "exact"]
        assert len(exact) == 1, name
        _, t, y = exact[0]
        # Exact solution (a): R = rho c |V| = 1 on (0, 2), then U = t - 2.
        if column == "R":
            assert np.allclose(y[(t > 0.05) & (t < 1.95)], 1.0)
        else:
            assert np.allclose(y[t > 2.05], t[t > 2.05] - 2.0, atol=1e-9)
    impacts = drawn["impacts"]
    assert any(line[0] == "exact" for ax in impacts for line in ax["lines"])


def test_a_run_at_the_auto_step_is_drawn_at_the_step_it_took(tmp_path, drawn):
    """case.toml says time.step = "auto": the figures take the step from summary.json."""
    auto = run_dir(tmp_path, EXAMPLES / "paper-example1-rigid.toml", "time.scheme=central-difference",
                   "time.step=auto", name="auto")
    assert 'step = "auto"' in (auto / "case.toml").read_text()
    barimpact.plot(auto, tmp_path / "figs")
    assert "exact (dashed, same colour)" in drawn["snapshots"][0]["legend"]
    given = run_dir(tmp_path, EXAMPLES / "paper-example1-rigid.toml", "time.scheme=central-difference",
                    "time.step=0.005", name="given")
    compare([auto, given], tmp_path / "both")
    assert drawn["compare_U"][0]["legend"] == ["time step = 0.009", "time step = 0.005"]


def test_no_exact_curve_without_an_exact_solution(tmp_path, drawn):
    with pytest.raises(barimpact.InputError):
        barimpact.exact(barimpact.Case(str(EXAMPLES / "paper-example2.toml")))
    barimpact.plot(barimpact.run(EXAMPLES / "paper-example2.toml"), tmp_path)
    assert not any(line[0] == "exact" for line in drawn["displacement"][0]["lines"])


# --- convergence -------------------------------------------------------------------------------------------

def test_convergence_plot_has_reference_slopes_and_names_the_schemes(tmp_path, drawn):
    out = tmp_path / "study"
    p = subprocess.run([CLI, "converge", str(EXAMPLES / "paper-example1-rigid.toml"), "--out", str(out),
                        "--levels", "3", "--schemes", "central-difference,characteristic"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    drawn.clear()
    plot_study(out)
    ax = drawn["convergence"][0]
    assert ax["xscale"] == "log" and ax["xlabel"] == "element length h"
    slopes = {label: np.diff(np.log(y)) / np.diff(np.log(x)) for label, x, y in ax["lines"]
              if label.startswith("slope")}
    assert set(slopes) == {"slope 1", "slope 2"}
    assert slopes["slope 1"] == pytest.approx([1.0]) and slopes["slope 2"] == pytest.approx([2.0])
    # The schemes differ, the rest is common: the legend names the schemes and what they measure.
    assert ax["legend"] == ["central-difference: order 1.00", "characteristic: at round-off", "slope 1", "slope 2"]
    assert "slope 1" not in drawn["work_precision"][0]["legend"]
    assert measured_order([0.1, 0.05, 0.025], [4e-2, 1e-2, 2.5e-3]) == pytest.approx(2.0)


# --- sweeps ------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def sweep_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep") / "penalty"
    p = subprocess.run([CLI, "sweep", str(EXAMPLES / "sweeps" / "penalty-to-rigid.toml"), "--out", str(out)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return out


def sweep_outputs(directory):
    with open(directory / "sweep.csv", newline="") as f:
        header = next(csv.reader(f))
    return [c for c in header[header.index("status") + 1:] if c not in ("message", "warnings")]


def test_a_sweep_gets_one_figure_per_output(sweep_dir, tmp_path, drawn):
    outputs = sweep_outputs(sweep_dir)
    assert {"max_reaction", "lift_off", "contacts", "energy_error_relative"} <= set(outputs)
    written = plot_sweep(sweep_dir, tmp_path / "figs")
    names = {p.name for p in written}
    for column in outputs:
        assert {f"{column}.png", f"{column}.svg"} <= names, column
        assert (tmp_path / "figs" / f"{column}.png").stat().st_size > 5_000
    ax = drawn["max_reaction"][0]
    # k = 100 ... 800 doubling: log-spaced; the zipped bar.elements goes with it; one curve per velocity.
    assert ax["xscale"] == "log" and ax["title"] == "Largest reaction against obstacle stiffness"
    assert ax["xlabel"] == "obstacle stiffness, with bar elements" and ax["xticks"] == [100.0, 200.0, 400.0, 800.0]
    velocities = ["initial velocity = -1", "initial velocity = -0.5", "initial velocity = -0.25"]
    assert ax["legend"] == velocities + ["has warnings (sweep.csv)"]
    assert [len(x) for label, x, _ in ax["lines"] if label in velocities] == [4, 4, 4]
    # k = 800 on a coarse step warns (penalty-unresolved): its three points are ringed.
    assert [x for label, x, _ in ax["lines"] if label.startswith("has warnings")][0].tolist() == [800.0] * 3
    assert len(drawn["runs_U"][0]["lines"]) == 12


def test_barimpact_plot_of_a_sweep_directory(sweep_dir, tmp_path):
    out = tmp_path / "figs"
    p = subprocess.run([sys.executable, "-m", "barimpact", "plot", str(sweep_dir), "--out", str(out)],
                       capture_output=True, text=True, env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    assert all((out / f"{c}.svg").is_file() for c in sweep_outputs(sweep_dir))
    cli = subprocess.run([CLI, "plot", str(sweep_dir), "--out", str(tmp_path / "cli")], capture_output=True, text=True)
    if cli.returncode == 2 and "no history.csv" in cli.stderr:
        pytest.skip("the command does not hand a sweep directory to the figures yet")
    assert cli.returncode == 0, cli.stderr
    assert all((tmp_path / "cli" / f"{c}.png").is_file() for c in sweep_outputs(sweep_dir))


def test_sweep_with_failed_cases_leaves_them_out(tmp_path, drawn):
    out = tmp_path / "sw"
    p = subprocess.run([CLI, "sweep", str(EXAMPLES / "sweeps" / "with-failures.toml"), "--out", str(out)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    plot_sweep(out)
    ax = drawn["lift_off"][0]
    # alpha = 0.25 and 0.5 (both warned: energy drift); 0 blew up, -0.1 was refused
    assert [len(x) for label, x, _ in ax["lines"] if not label.startswith("has warnings")] == [2]
    assert (out / "figures" / "lift_off.svg").is_file()


def test_log_spacing_and_zipped_keys():
    assert log_spaced([100.0, 200.0, 400.0, 800.0]) and log_spaced([1e-4, 1e-3, 1e-2])
    assert not log_spaced([0.0, 0.25, 0.5]) and not log_spaced([1.0, 2.0, 3.0, 4.0])
    assert log_spaced([1.0, 10.0, 20.0, 5000.0]) and not log_spaced([-1.0, -0.5, -0.25])
    rows = [{"k": str(k), "m": str(m), "v": v} for k, m in ((1, 10), (2, 20)) for v in ("a", "b")]
    assert sweep_dimensions(["k", "m", "v"], rows) == [["k", "m"], ["v"]]
    assert math.isclose(measured_order([1.0, 2.0], [1.0, 2.0]), 1.0)


def test_load_reads_what_the_run_wrote(tmp_path):
    run = run_dir(tmp_path, EXAMPLES / "lines" / "saint-venant.toml")
    data = load(run)
    r = barimpact.run(EXAMPLES / "lines" / "saint-venant.toml")
    assert np.array_equal(data.field_t, np.asarray(r.field_t))
    assert np.array_equal(data.u, np.asarray(r.u)) and np.array_equal(data.sigma, np.asarray(r.sigma))
    assert list(data.body) == list(r.field_body)
    assert np.array_equal(data.history["R"], np.asarray(r.R))
    # Columns by name, as a Result's: r["U"], r.U, columns.
    assert data.columns == tuple(r.columns)
    assert np.array_equal(data["joint.short-long.force"], np.asarray(r["joint.short-long.force"]))
    assert np.array_equal(data.U, np.asarray(r.U)) and "U" in data and "nothing" not in data
    with pytest.raises(KeyError, match="no history column"):
        data["nothing"]
    with pytest.raises(AttributeError):
        data.nothing


@pytest.mark.parametrize("example", ["lines/pile-hammer.toml", "plastic/paper-example1-yielding.toml",
                                     "pile/steel-pipe-sand.toml"])
def test_every_figure_drawn_is_in_the_list_the_directory_is_marked_with(example, tmp_path):
    """A figure missing from run/figure_names.hpp would leave, after a plot
    stopped half-way, a file barimpact does not own in figures/."""
    written = barimpact.plot(barimpact.run(EXAMPLES / example), tmp_path, formats=("png",))
    stems = {os.path.splitext(os.path.basename(p))[0] for p in written}
    assert stems, example
    assert stems <= set(barimpact._core._figure_names), stems - set(barimpact._core._figure_names)
