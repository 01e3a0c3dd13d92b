"""[output] format = "hdf5": results.h5 holds what history.csv and fields.csv
hold, the same doubles; plot and load read both."""
import subprocess
import sys
import tomllib

import h5py
import numpy as np
import pytest

import barimpact
from barimpact.plot import load
from conftest import CLI, EXAMPLES, cli_error

# A line (bodies, a joint, a gauge) and a yielding bar (eps_p not zero, SI units).
CASES = {"saint-venant": ("lines/saint-venant.toml", []),
         "taylor-bar": ("plastic/taylor-bar.toml", [])}


@pytest.fixture(scope="module")
def both_ways(tmp_path_factory):
    """Each case run twice by the command line: CSV and HDF5."""
    base = tmp_path_factory.mktemp("formats")
    out = {}
    for name, (case, sets) in CASES.items():
        csv, h5 = base / f"{name}-csv", base / f"{name}-h5"
        for d, extra in ((csv, []), (h5, ["--set", "output.format=hdf5"])):
            p = subprocess.run([CLI, "run", str(EXAMPLES / case), "--out", str(d), *sets, *extra],
                               capture_output=True, text=True)
            assert p.returncode == 0, p.stderr
        out[name] = csv, h5
    return out


def same_bits(a, b):
    """Equal doubles, bit for bit (NaN included)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


@pytest.mark.parametrize("name", list(CASES))
def test_results_h5_holds_the_csv_files_bit_for_bit(both_ways, name):
    csv, h5 = both_ways[name]
    assert not (h5 / "history.csv").exists() and not (h5 / "fields.csv").exists()
    assert not (csv / "results.h5").exists()
    with open(csv / "history.csv") as stream:
        header = stream.readline().strip().split(",")
    history = np.loadtxt(csv / "history.csv", delimiter=",", skiprows=1, ndmin=2)
    with open(csv / "fields.csv") as stream:
        fields_header = stream.readline().strip().split(",")
    numbers = np.loadtxt(csv / "fields.csv", delimiter=",", skiprows=1, usecols=range(6), ndmin=2)
    bodies = np.loadtxt(csv / "fields.csv", delimiter=",", skiprows=1, usecols=6, dtype=str, ndmin=1)
    with h5py.File(h5 / "results.h5", "r") as f:
        assert f.attrs["case"] == (h5 / "case.toml").read_text()
        assert f.attrs["units"] == tomllib.loads((h5 / "case.toml").read_text())["units"]["system"]
        g = f["history"]
        assert list(g.attrs["columns"]) == header
        assert sorted(g) == sorted(header)
        for i, column in enumerate(header):
            assert g[column].dtype == np.float64 and g[column].shape == (history.shape[0],), column
            assert same_bits(g[column][()], history[:, i]), column
        g = f["fields"]
        assert list(g.attrs["columns"]) == fields_header
        t, x = g["t"][()], g["x"][()]
        snapshots, nodes = t.size, x.size
        assert snapshots > 1 and snapshots * nodes == numbers.shape[0]
        assert same_bits(np.repeat(t, nodes), numbers[:, 0])
        assert same_bits(np.tile(x, snapshots), numbers[:, 1])
        for k, column in enumerate(("u", "v", "sigma", "eps_p"), start=2):
            assert g[column].shape == (snapshots, nodes), column
            assert same_bits(g[column][()].ravel(), numbers[:, k]), column
        names = np.array([str(n) for n in g["body"].attrs["names"]])
        assert np.array_equal(np.tile(names[g["body"][()]], snapshots), bodies)
        if name == "taylor-bar":
            assert np.abs(g["eps_p"][()]).max() > 0  # something to compare
            assert f.attrs["units"] == "SI"
    assert (h5 / "case.toml").read_text() == (csv / "case.toml").read_text().replace('format = "csv"',
                                                                                       'format = "hdf5"')


@pytest.mark.parametrize("name", list(CASES))
def test_load_gives_the_same_run_data_from_either_format(both_ways, name):
    csv, h5 = both_ways[name]
    for with_fields in (True, False):
        a, b = load(csv, with_fields), load(h5, with_fields)
        assert list(a.history) == list(b.history)
        for column in a.history:
            assert same_bits(a.history[column], b.history[column]), column
        for field in ("x", "field_t", "u", "sigma", "eps_p"):
            assert same_bits(getattr(a, field), getattr(b, field)), field
        assert (a.body is None) == (b.body is None) and np.array_equal(a.body, b.body)
        assert a.case["output"].pop("format") == "csv" and b.case["output"].pop("format") == "hdf5"
        assert a.case == b.case and a.units.system == b.units.system
        assert a.summary["contacts"] == b.summary["contacts"]


@pytest.mark.parametrize("name", list(CASES))
def test_plot_draws_the_same_figures_from_either_format(both_ways, name, tmp_path):
    written = {}
    for d in both_ways[name]:
        p = subprocess.run([CLI, "plot", str(d)], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        written[d] = sorted(path.name for path in (d / "figures").iterdir())
    csv, h5 = both_ways[name]
    assert written[csv] == written[h5] and "displacement.png" in written[csv]
    for figure in written[csv]:
        if figure.endswith(".png"):
            assert (csv / "figures" / figure).read_bytes() == (h5 / "figures" / figure).read_bytes(), figure
    marker = (h5 / ".barimpact").read_text()
    assert '"results.h5"' in marker and '"figures"' in marker


def test_without_h5py_an_hdf5_run_is_refused_in_one_line(both_ways, tmp_path):
    _, h5 = both_ways["saint-venant"]
    code = ("import sys; sys.modules['h5py'] = None\n"
            "from barimpact.__main__ import main\n"
            f"sys.exit(main(['plot', {str(h5)!r}, '--out', {str(tmp_path / 'figures')!r}]))")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "results.h5: reading it needs h5py" in lines[0] and "python3-h5py" in lines[0]


def test_a_bad_format_is_refused_naming_the_key(tmp_path):
    message = cli_error("run", str(EXAMPLES / "paper-example1.toml"), "--out", str(tmp_path / "x"), "--set",
                        "output.format=netcdf")
    assert 'output.format must be "csv" or "hdf5" (got "netcdf")' in message
    assert not (tmp_path / "x").exists()
    with pytest.raises(barimpact.InputError, match="output.format"):
        barimpact.Case(EXAMPLES / "paper-example1.toml", set={"output.format": "xlsx"})


def test_python_writes_and_reads_the_format_the_case_says(tmp_path):
    case = barimpact.Case(EXAMPLES / "paper-example2.toml",
                          set={"output.format": "hdf5", "time.end": 1.0, "output.fields_at": [0.5, 1.0]})
    r = barimpact.run(case, out=tmp_path / "run")
    assert (tmp_path / "run" / "results.h5").is_file() and not (tmp_path / "run" / "history.csv").exists()
    back = barimpact.load(tmp_path / "run")
    assert list(back.history) == list(r.columns)
    assert all(same_bits(back.history[c], r[c]) for c in r.columns)
    assert same_bits(back.u, r.u) and same_bits(back.field_t, r.field_t)
    with h5py.File(tmp_path / "run" / "results.h5", "r") as f:
        assert f["fields/u"].compression == "gzip" and f["fields/u"].shuffle and f["fields/u"].chunks
        assert f["history/t"].compression is None
    barimpact.run(case, out=tmp_path / "plain", set={"output.compression": 0})
    with h5py.File(tmp_path / "plain" / "results.h5", "r") as f:
        assert f["fields/u"].compression is None and same_bits(f["fields/u"][()], r.u)
    written = barimpact.plot(tmp_path / "run")
    assert any(p.name == "displacement.png" for p in written)


def test_a_sweep_of_hdf5_runs_draws_their_overlays(tmp_path):
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(f'case = "{EXAMPLES / "paper-example1.toml"}"\n[set]\noutput.format = "hdf5"\n'
                     'output.fields_at = []\n[[axis]]\nkey = "obstacle.stiffness"\nvalues = [50.0, 100.0]\n')
    table = barimpact.sweep(sweep, tmp_path / "out")
    assert list(table.status) == ["complete", "complete"]
    assert (tmp_path / "out" / "runs" / "0000" / "results.h5").is_file()
    p = subprocess.run([CLI, "plot", str(tmp_path / "out")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "out" / "figures" / "runs_U.png").is_file(), p.stdout
