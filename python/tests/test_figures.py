"""The figures' promises: large runs stay small, units on the axes, legends
naming only what differs, exact solutions drawn."""
import html
import importlib
import re
import subprocess

import numpy as np
import pytest

import barimpact
from barimpact.plot import Units, compare, legend_labels, load, peak_cells, screen_points
from conftest import CLI, EXAMPLES

plot_module = importlib.import_module("barimpact.plot")  # barimpact.plot is the function
RUN_FIGURES = ("displacement", "reaction", "energy", "stress_map", "snapshots", "impacts")


def svg_texts(path):
    """The texts of an SVG matplotlib wrote (it keeps each one as a comment beside its glyphs)."""
    return [html.unescape(t) for t in re.findall(r"<!-- (.*?) -->", path.read_text(encoding="utf-8"))]


@pytest.fixture
def drawn(monkeypatch):
    """What each saved figure holds, by name: per axes its labels, scales,
    legend texts and lines (label, x, y)."""
    figures = {}
    save = plot_module._save

    def record(fig, out, name, formats, written):
        figures[name] = [{"xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(), "xscale": ax.get_xscale(),
                          "yscale": ax.get_yscale(),
                          "legend": [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else [],
                          "lines": [(ln.get_label(), np.asarray(ln.get_xdata(), float),
                                     np.asarray(ln.get_ydata(), float)) for ln in ax.get_lines()]}
                         for ax in fig.axes]
        save(fig, out, name, formats, written)

    monkeypatch.setattr(plot_module, "_save", record)
    return figures


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
    case.write_text(case.read_text() + f'\n[units]\nsystem = "{system}"\n')
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
    assert "R" in texts and "t" in texts and not any(re.search(r"\((N|s)\)", t) for t in texts)
    with_units(run, "SI")
    barimpact.plot(str(run), tmp_path / "si")
    si = tmp_path / "si"
    assert {"t (s)", "U (m)"} <= set(svg_texts(si / "displacement.svg"))
    assert {"t (s)", "R (N)"} <= set(svg_texts(si / "reaction.svg"))
    assert {"t (s)", "energy (J)"} <= set(svg_texts(si / "energy.svg"))
    assert {"x (m)", "t (s)", "sigma (Pa), tension > 0"} <= set(svg_texts(si / "stress_map.svg"))
    assert {"x (m)", "u (m)"} <= set(svg_texts(si / "snapshots.svg"))
    assert "exact" in svg_texts(si / "displacement.svg")  # [units] changes no number of the exact solution


def test_si_prefixes_keep_numbers_readable():
    si, none = Units("SI"), Units("none")
    stress = si.axis("sigma", "stress", [-3.2e8, 1e7])
    assert stress.label == "sigma (MPa)" and stress.factor == pytest.approx(1e-6)
    assert si.axis("t", "time", [0.0, 1.6e-4]).label == "t (µs)"
    assert si.axis("E", "energy", [0.5]).label == "E (J)" and si.axis("R", "force", [2.5e5]).label == "R (kN)"
    assert si.axis("t", "time", [0.0, 5000.0]).label == "t (s)"  # no kiloseconds
    assert si.axis("v", "velocity", [30.0]).label == "v (m/s)"
    assert si.axis("rate", "strain_rate").label == "rate (1/s)"
    assert si.axis("eps_p", "strain", [0.05]).label == "eps_p (-)"
    assert none.axis("sigma", "stress", [3e8]).label == "sigma" and none.axis("sigma", "stress").factor == 1.0


# --- legends ------------------------------------------------------------------------------------

def test_legends_name_only_the_keys_that_differ(tmp_path, drawn):
    soft = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "obstacle.stiffness=50", name="soft")
    stiff = run_dir(tmp_path, EXAMPLES / "paper-example1.toml", "obstacle.stiffness=200", name="stiff")
    written = compare([soft, stiff], tmp_path / "both")
    assert {p.name for p in written} == {"compare_U.png", "compare_U.svg", "compare_R.png", "compare_R.svg"}
    legend = drawn["compare_R"][0]["legend"]
    assert legend == ["near_end.stiffness = 50", "near_end.stiffness = 200"]
    assert legend_labels([{"a": 1, "b": 2.0, "c": "x"}, {"a": 1, "b": 3.0, "c": "x"}], Units("SI")) == ["b = 2",
                                                                                                           "b = 3"]
    assert legend_labels([{"obstacle.stiffness": 100.0}, {"obstacle.stiffness": 200.0}],
                         Units("SI")) == ["obstacle.stiffness = 100 N/m", "obstacle.stiffness = 200 N/m"]


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


def test_no_exact_curve_without_an_exact_solution(tmp_path, drawn):
    with pytest.raises(barimpact.InputError):
        barimpact.exact(barimpact.Case(str(EXAMPLES / "paper-example2.toml")))
    barimpact.plot(barimpact.run(EXAMPLES / "paper-example2.toml"), tmp_path)
    assert not any(line[0] == "exact" for line in drawn["displacement"][0]["lines"])


def test_load_reads_what_the_run_wrote(tmp_path):
    run = run_dir(tmp_path, EXAMPLES / "lines" / "saint-venant.toml")
    data = load(run)
    r = barimpact.run(EXAMPLES / "lines" / "saint-venant.toml")
    assert np.array_equal(data.field_t, np.asarray(r.field_t))
    assert np.array_equal(data.u, np.asarray(r.u)) and np.array_equal(data.sigma, np.asarray(r.sigma))
    assert list(data.body) == list(r.field_body)
    assert np.array_equal(data.history["R"], np.asarray(r.R))
