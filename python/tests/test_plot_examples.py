"""`plot` over every example and over every scheme on the paper's examples,
with the case's step and with time.step = "auto" (the figures read the step
the run took, never case.toml's text)."""
import subprocess
import tomllib
import warnings

import pytest

import barimpact
from barimpact.style import column_words
from conftest import CLI, EXAMPLES
from figure_text import raw_names, time_units

# Sweep files, Hopkinson setups and pile records lie among the examples: not cases.
NOT_A_CASE = {"case", "axis", "zip", "incident", "transmitted", "record"}
CASES = sorted(p.relative_to(EXAMPLES).as_posix() for p in EXAMPLES.rglob("*.toml")
               if not NOT_A_CASE & set(tomllib.loads(p.read_text())))
PAPER = ("paper-example1.toml", "paper-example1-rigid.toml", "paper-example2.toml", "paper-example2-rigid.toml")
SCHEMES = ("paper", "newmark", "central-difference", "characteristic", "mass-redistribution", "paoli-schatzman",
           "moreau-jean")


def auto_step(path):
    """time.step = "auto" on the case's scheme, or on central differences when the case's is implicit."""
    try:
        return barimpact.Case(path, set={"time.step": "auto"})
    except barimpact.InputError:
        return barimpact.Case(path, set={"time.scheme": "central-difference", "time.step": "auto"})


def plot_run(case, out, formats=("png",)):
    """The run written, then its figures drawn from its directory, as `barimpact plot DIR`."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", barimpact.HealthWarning)
        barimpact.run(case, out=out)
    written = barimpact.plot(out, formats=formats)
    return {p.stem for p in written}


def test_the_examples_are_found():
    assert len(CASES) >= 15 and "paper-example1.toml" in CASES and "lines/saint-venant.toml" in CASES
    assert not {"hopkinson/analyse-run.toml", "sweeps/penalty-to-rigid.toml"} & set(CASES)


@pytest.mark.parametrize("example", CASES)
def test_plot_draws_every_example_with_its_step_and_auto(example, tmp_path, drawn):
    """The figures saved at "auto"; built (not saved) at the case's step,
    which other tests save. Each in the figures' style: every history
    column in the words table, no raw column name shown, one time unit a figure."""
    path = EXAMPLES / example
    plot_run(barimpact.Case(path), tmp_path / "given", formats=())
    saved = plot_run(auto_step(path), tmp_path / "auto")
    assert {"displacement", "reaction", "energy", "impacts"} <= saved, saved
    data = barimpact.load(tmp_path / "auto", with_fields=False)
    assert [c for c in data.columns if column_words(c, data.case) is None] == []
    assert raw_names(drawn) == []
    assert {name: units for name, axes in drawn.items() if len(units := time_units(axes)) > 1} == {}


def test_the_command_plots_a_run_whose_step_was_auto(tmp_path):
    run = tmp_path / "run"
    p = subprocess.run([CLI, "run", str(EXAMPLES / "paper-example1-rigid.toml"), "--out", str(run), "--set",
                        "time.scheme=central-difference", "--set", "time.step=auto"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    p = subprocess.run([CLI, "plot", str(run)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (run / "figures" / "snapshots.png").is_file() and (run / "figures" / "impacts.svg").is_file()


def test_the_schemes_listed_here_are_every_scheme():
    with pytest.raises(barimpact.InputError, match="must be one of") as e:
        barimpact.Case(EXAMPLES / "paper-example1.toml", set={"time.scheme": "none-such"})
    listed = str(e.value).split("must be one of ")[1].split(" (got")[0]
    assert sorted(listed.split(", ")) == sorted(SCHEMES)


def test_plot_draws_every_scheme_on_the_papers_examples(tmp_path):
    """Every scheme that takes a paper example, at its step and at "auto"
    (the explicit ones): the figures built whole, not saved (the test
    above saves them)."""
    plotted = set()
    for example in PAPER:
        for scheme in SCHEMES:
            for step in ({}, {"time.step": "auto"}):
                try:
                    case = barimpact.Case(EXAMPLES / example, set={"time.scheme": scheme, **step})
                except barimpact.InputError:
                    continue  # a scheme that does not take this obstacle, or this step
                out = tmp_path / f"{example}-{scheme}-{len(step)}"
                plot_run(case, out, formats=())
                plotted.add((scheme, bool(step)))
    assert {scheme for scheme, _ in plotted} == set(SCHEMES)
    assert {scheme for scheme, auto in plotted if auto} >= {"central-difference", "paoli-schatzman"}


@pytest.mark.parametrize("example", CASES)
def test_every_example_runs_clean_or_says_why(example):
    """An example runs without a health warning, or its header comment names
    each code it gives and why (the SHPB's contact chatter, a diesel on a
    rigid stop with no pile to rest)."""
    path = EXAMPLES / example
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", barimpact.HealthWarning)
        barimpact.run(barimpact.Case(path, set={"output.fields_at": []}))
    codes = {str(w.message).split(":")[0] for w in caught if issubclass(w.category, barimpact.HealthWarning)}
    header = "".join(line for line in path.read_text().splitlines(keepends=True) if line.startswith("#"))
    assert all(code in header for code in codes), (codes, example)
