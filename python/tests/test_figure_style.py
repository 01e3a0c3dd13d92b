"""The figures' one style across the commands: words instead of column
names, a unit on every axis under SI, one time unit a figure, stress maps
only where snapshots are, Hopkinson figures in DIR/figures."""
import importlib
import json
import re
import subprocess
import tomllib

import numpy as np
import pytest

import barimpact
from barimpact.plot import SCREEN_COLUMNS
from barimpact.style import COLUMN_WORDS, UNIT_SYSTEMS, Units, choose_unit, column_words, words_of
from conftest import CLI, EXAMPLES
from figure_text import axes_without_unit, raw_names, time_units


def cli(*args):
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p


@pytest.fixture(scope="module")
def pile_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("pile") / "run"
    cli("run", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", out)
    return out


def test_a_pile_runs_figures_speak_the_engineers_words(pile_run, tmp_path, drawn):
    barimpact.plot(pile_run, tmp_path / "figs", formats=())
    assert raw_names(drawn) == []
    assert axes_without_unit(drawn) == []  # SI: every axis names its unit
    assert {name: u for name, axes in drawn.items() if len(u := time_units(axes)) != 1} == {"blow_envelopes": set()}
    assert time_units(drawn["stress_map"]) == {"ms"}
    assert drawn["reaction"][0]["title"] == "Toe resistance, Smith soil at the toe"
    assert drawn["reaction"][0]["ylabel"] == "toe resistance (compression +) [MN]"
    assert drawn["displacement"][0]["xlabel"] == "time [ms]"  # a 0.12 s blow in ms
    assert drawn["joint_forces"][0]["legend"] == ["pile cushion force", "capblock force"]
    assert drawn["masses"][0]["legend"] == ["helmet displacement", "ram displacement"]
    assert drawn["gauges"][0]["ylabel"] == "force (compression +) [MN]"
    assert drawn["blow_toe"][1]["ylabel"] == "toe penetration (down +) [mm]"


def test_a_gauges_force_is_drawn_compression_positive(pile_run, tmp_path, drawn):
    """gauge.head.force is tension positive in history.csv; the figures say
    compression + for every force, so it is drawn negated."""
    barimpact.plot(pile_run, tmp_path / "figs", formats=())
    data = barimpact.load(pile_run, with_fields=False)
    (_, _, y), = drawn["gauges"][0]["lines"]
    assert data["gauge.head.force"].min() < -1e6 and y.max() == pytest.approx(-1e-6 * data["gauge.head.force"].min())


def test_a_split_hopkinson_bars_gauges_are_named_by_their_bar():
    case = barimpact.Case(EXAMPLES / "lines" / "hopkinson.toml")
    toml = tomllib.loads(case.to_toml())
    assert words_of("gauge.incident.strain", toml) == "incident bar gauge strain"
    assert words_of("gauge.transmitted.force", toml) == "transmission bar gauge force"
    pile = tomllib.loads((EXAMPLES / "pile" / "steel-pipe-sand.toml").read_text())
    assert words_of("gauge.head.force", pile) == "head gauge force" and words_of("U", pile) == "toe displacement"
    assert words_of("R", {}) == "near-end force" and words_of("R", {"near_end": {"law": "rigid"}}) == "obstacle reaction"


def test_the_words_table_knows_every_kind_of_column():
    for column in ("t", "U", "V", "R", "E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic",
                   "joint.a.force", "joint.a.opening", "joint.a.pressure", "hammer.gas.force", "hammer.gas.opening",
                   "hammer.gas.pressure", "far_end.force", "far_end.opening",
                   "body.a.u", "body.a.v", "gauge.a.strain", "gauge.a.velocity", "gauge.a.force"):
        assert column_words(column) is not None, column
    assert column_words("not.a.column") is None and len(COLUMN_WORDS) == 24


def test_units_come_from_a_table_per_system():
    si = UNIT_SYSTEMS["SI"]
    assert choose_unit(si, "force", [2.5e6]) == ("MN", 1e6) and choose_unit(si, "stress", [2e8]) == ("MPa", 1e6)
    assert choose_unit(si, "time", [0.0, 4e-4], span=True) == ("µs", 1e-6)
    assert choose_unit({}, "force", [2.5e6]) is None  # a system without a table: no unit, numbers as they are
    assert Units("none").axis("force", "force", [2.5e6]).factor == 1.0


def test_us_customary_units_are_a_table_of_exact_factors():
    us = UNIT_SYSTEMS["US"]
    assert choose_unit(us, "force", [9e5]) == ("kip", 4448.2216152605)
    assert choose_unit(us, "stress", [2.2e8]) == ("ksi", 4448.2216152605 / 0.0254**2)
    assert choose_unit(us, "length", [20.0]) == ("ft", 0.3048) and choose_unit(us, "length", [0.5]) == ("in", 0.0254)
    assert choose_unit(us, "energy", [3.9e4]) == ("kip-ft", 4448.2216152605 * 0.3048)
    assert Units("US").value(5e9, "stiffness") == "2.855e+04 kip/in"
    assert Units("US").axis("stroke", "length", None, sign=False).label == "stroke [m]"  # SI numbers drawn as they are


US_FIGURE_UNITS = {"reaction": "toe resistance (compression +) [kip]", "gauges": "force (compression +) [kip]",
                   "displacement": "toe displacement (up +) [in]", "energy": "energy [kip-ft]"}


def test_a_us_pile_runs_figures_label_kip_ft_in_and_ksi(tmp_path, drawn):
    """[units] system = "US": the files in SI, the figures in kip, ft, in,
    ksi, kip-ft, ft/s (time still in ms); every axis names its unit."""
    out = tmp_path / "us"
    cli("run", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", out, "--set", "units.system=US")
    barimpact.plot(out, tmp_path / "figs", formats=())
    assert axes_without_unit(drawn) == [] and raw_names(drawn) == []
    assert {name: drawn[name][0]["ylabel"] for name in US_FIGURE_UNITS} == US_FIGURE_UNITS
    assert drawn["stress_map"][0]["xlabel"] == "height above the toe x [ft]"
    assert drawn["blow_envelopes"][0]["xlabel"] == "largest stress, a magnitude [ksi]"
    assert drawn["blow_toe"][1]["ylabel"] == "toe penetration (down +) [in]"
    assert time_units(drawn["reaction"]) == {"ms"}
    labels = " ".join(t for axes in drawn.values() for ax in axes for t in (ax["xlabel"], ax["ylabel"]))
    assert not re.search(r"\[(k?N|MN|mm|m|M?Pa|k?J|m/s)\]", labels), labels
    data = barimpact.load(out, with_fields=False)
    (_, _, toe), = drawn["reaction"][0]["lines"]
    assert toe.max() == pytest.approx(data["R"].max() / 4448.2216152605)  # drawn from the SI file in kip


def test_a_us_bearing_graph_counts_blows_per_foot(tmp_path, drawn):
    out = tmp_path / "bearing"
    p = cli("bearing", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", out, "--capacity", "0.5e6:1.5e6:2",
            "--set", "units.system=US", "--no-plot")
    assert "capacities from 112.4 to 337.2 kip" in p.stdout
    barimpact.plot(out, formats=())
    graph, stresses = drawn["bearing"]
    assert graph["xlabel"] == "blows/ft" and graph["ylabel"] == "static capacity [kip]"
    assert stresses["xlabel"] == "largest stress in the pile, a magnitude [ksi]"
    rows = importlib.import_module("barimpact.bearing").read_bearing(out)  # barimpact.bearing is the function
    assert graph["lines"][0][1] == pytest.approx([0.3048 * r["blows_per_m"] for r in rows])


def test_a_stress_map_is_drawn_only_over_its_snapshots(tmp_path, drawn):
    """Six snapshots up to 30 ms of a 120 ms blow: the map's rows span 0 to
    30 ms, none past the last snapshot (before, the last one was stretched
    to the run's end as a band); the title counts the snapshots and says the
    run goes on; the times are marked."""
    run = tmp_path / "run"
    cli("run", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", run, "--set",
        "output.fields_at=[0.0, 0.005, 0.01, 0.015, 0.02, 0.03]", "--set", "time.end=0.12")
    barimpact.plot(run, tmp_path / "figs", formats=())
    ax = drawn["stress_map"][0]
    assert "from 6 snapshots" in ax["title"] and "the run goes on to 120 ms" in ax["title"], ax["title"]
    cells = np.ma.asarray(ax["meshes"][0]).reshape(600, -1)  # MAP_ROWS rows over 0 .. 30 ms
    assert not np.ma.getmaskarray(cells).any()
    assert ax["ylim"] == pytest.approx((0.0, 30.0), abs=0.05)
    marks = [y for label, _, y in ax["lines"] if "snapshot times" in label]
    assert marks and np.allclose(marks[0], [0, 5, 10, 15, 20, 30], atol=0.05)  # the steps nearest them


def test_a_hopkinson_analysis_draws_into_dir_figures(tmp_path, drawn):
    run = tmp_path / "shpb"
    cli("run", EXAMPLES / "hopkinson" / "shpb.toml", "--out", run, "--set", "output.fields_at=[]")
    setup = tmp_path / "analyse.toml"
    setup.write_text((EXAMPLES / "hopkinson" / "analyse-run.toml").read_text().replace("../../out/shpb", str(run)))
    cli("hopkinson", setup, "--out", tmp_path / "hk")
    names = ("waves", "stress_strain", "strain_rate", "equilibrium")
    assert {p.name for p in (tmp_path / "hk" / "figures").glob("*.png")} == {f"{n}.png" for n in names}
    assert not list((tmp_path / "hk").glob("*.png"))
    cli("hopkinson", setup, "--out", tmp_path / "quiet", "--no-plot")
    assert not (tmp_path / "quiet" / "figures").exists()
    from barimpact.hopkinson import plot_hopkinson
    plot_hopkinson(tmp_path / "quiet", formats=())  # what barimpact plot DIR draws: in the hook only
    assert raw_names(drawn) == [] and axes_without_unit(drawn) == []
    assert drawn["stress_strain"][0]["ylabel"] == "engineering stress (compression +) [MPa]"
    assert drawn["waves"][0]["xlabel"].startswith("time [µs]")


def test_pda_figures_keep_one_time_unit_and_name_their_units(tmp_path, drawn):
    cli("pda", EXAMPLES / "pda" / "steel-pipe.toml", "--out", tmp_path / "pda", "--no-plot")
    from barimpact.pda import plot_pda
    plot_pda(tmp_path / "pda", formats=())
    assert axes_without_unit(drawn) == []
    assert {name: time_units(axes) for name, axes in drawn.items()} == {"force_velocity": {"ms"}, "waves": {"ms"}}


def test_long_records_are_thinned_to_the_screen(tmp_path, drawn):
    """A Hopkinson analysis of 200,000-sample records (about 24,000 rows):
    every curve drawn keeps at most two points a pixel column."""
    from test_hopkinson import _shape
    t = np.arange(200_000) * 5e-9
    incident = -1e-3 * _shape(t - 100e-6) + 6e-4 * _shape(t - 503e-6)
    transmitted = -4e-4 * _shape(t - 401e-6)
    for name, strain in (("inc", incident), ("tr", transmitted)):
        np.savetxt(tmp_path / f"{name}.csv", np.column_stack([t, strain]), delimiter=",", header="t,strain",
                   comments="")
    setup = tmp_path / "setup.toml"
    setup.write_text('[bar]\nmodulus = 200e9\ndensity = 8000.0\narea = 3e-4\n[specimen]\nlength = 0.005\n'
                     'area = 1e-4\n[incident]\nsignal = "inc.csv"\ngauge_to_specimen = 1.0\n'
                     '[transmitted]\nsignal = "tr.csv"\ngauge_to_specimen = 0.5\n')
    cli("hopkinson", setup, "--out", tmp_path / "hk", "--no-plot")
    assert sum(1 for _ in open(tmp_path / "hk" / "hopkinson.csv")) > 20_000
    from barimpact.hopkinson import plot_hopkinson
    plot_hopkinson(tmp_path / "hk", formats=())
    longest = max(x.size for axes in drawn.values() for ax in axes for _, x, _ in ax["lines"])
    assert 1000 < longest <= 2 * SCREEN_COLUMNS + 2


GALLERY = EXAMPLES.parent / "docs" / "figures.md"


def test_the_gallery_shows_each_command_once_small_and_made_by_its_script():
    text = GALLERY.read_text()
    shown = re.findall(r"\(figures/(gallery-[\w-]+\.png)\)", text)
    script = (GALLERY.parent / "figures" / "make_gallery.sh").read_text()
    picked = [f"gallery-{n}.png" for n in re.findall(r"^pick \S+ (\S+)$", script, re.M)]
    assert sorted(shown) == sorted(picked) and 10 <= len(shown) <= 14
    for name in shown:
        assert (GALLERY.parent / "figures" / name).stat().st_size < 150_000, name
    for command in ("run", "exact", "converge", "sweep", "bearing", "drive", "hopkinson", "pda", "match"):
        assert f"**{command}" in text, command


def test_the_docs_table_lists_every_column_pattern():
    text = GALLERY.read_text()
    for pattern, _, _ in COLUMN_WORDS:
        column = pattern.replace("(?P<name>.+)", "{name}").replace("\\.", ".")
        assert f"| `{column}` |" in text, column


def test_the_blow_figures_show_the_blow_not_the_ram_falling_back(tmp_path, drawn):
    """The steel pipe under gravity: its blow's soil last slips at 29 ms and
    the ram lands again at 394 ms of a 600 ms run. The head and toe figures
    span six round trips (2 L / c = 7.7 ms) past the last slip, 75 ms, never
    the second strike (before, they spanned the run, the blow a sliver)."""
    run = tmp_path / "run"
    cli("run", EXAMPLES / "pile" / "steel-pipe-sand.toml", "--out", run, "--set", "output.fields_at=[]")
    barimpact.plot(run, tmp_path / "figs", formats=())
    blow = json.loads((run / "summary.json").read_text())["blow"]
    trip = 2 * 20.0 / (210e9 / 7850.0) ** 0.5
    for name in ("blow_head", "blow_toe"):
        ax = drawn[name][0]
        assert "(the blow: to 75" in ax["title"] and "of a run to 600 ms)" in ax["title"], ax["title"]
        t_last = max(x[-1] for _, x, _ in ax["lines"] if x.size)
        assert t_last <= 1e3 * (blow["last_slip_time"] + 6 * trip) + 0.1 < 1e3 * blow["restrike_time"]
