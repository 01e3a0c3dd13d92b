"""A full disk: writing results that do not fit raises (the module's
InputError, or OSError: barimpact.OutputError is both) naming the path and
the system's reason (a figure: an OSError naming it, none half-written);
the interpreter lives on, nothing staged is left behind. The file systems
are small tmpfs mounts, which need root: without, the tests are skipped
(saying why). Each case runs in a child interpreter, which must end
normally: a crash (as HDF5's at exit) fails the test, not the whole
session."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import EXAMPLES

EX1 = EXAMPLES / "paper-example1.toml"


@pytest.fixture
def disk(tmp_path):
    """A new 200 KiB tmpfs, unmounted afterwards."""
    if os.geteuid() != 0:
        pytest.skip("not root: cannot mount a small tmpfs to fill")
    d = tmp_path / "disk"
    d.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=200k", "tmpfs", str(d)], capture_output=True,
                             text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs: {mounted.stderr.strip()}")
    yield d
    subprocess.run(["umount", str(d)], check=True)


def refusals(calls):
    """Each call's exception in a child interpreter (which must then exit
    normally, silently): a list of {kinds, message}, or None for a call
    that raised nothing."""
    script = textwrap.dedent("""
        import json, pathlib, sys
        import barimpact
        out = []
        for call in sys.argv[1:]:
            try:
                eval(call)
                out.append(None)
            except Exception as e:
                out.append({"kinds": [k.__name__ for k in type(e).__mro__], "message": str(e)})
        print(json.dumps(out))
    """)
    child = subprocess.run([sys.executable, "-c", script, *calls], capture_output=True, text=True)
    assert child.returncode == 0 and child.stderr == "", child.stderr
    return json.loads(child.stdout)


def leftovers(d):
    return sorted(str(p) for p in d.rglob("*") if ".partial-" in p.name or ".old-" in p.name)


def whole_figure(path):
    """A PNG up to its IEND chunk, an SVG up to its closing tag."""
    data = path.read_bytes()
    return data.endswith(b"IEND\xaeB`\x82") if path.suffix == ".png" else data.rstrip().endswith(b"</svg>")


def assert_refused(refused, path):
    assert refused is not None, f"{path} was written"
    assert "InputError" in refused["kinds"] and "OSError" in refused["kinds"]
    message = refused["message"]
    assert str(path) in message and "No space left on device" in message and "\n" not in message


def test_run_and_exact_on_a_full_disk_raise_and_the_interpreter_lives_on(disk):
    small = disk / "small"
    refused = refusals([
        f"barimpact.run({str(EX1)!r}, out={str(disk / 'ex1')!r})",
        f"barimpact.run({str(EX1)!r}, out={str(disk / 'h5')!r}, set={{'output.format': 'hdf5'}})",
        f"barimpact.exact({str(EXAMPLES / 'clamped-periodic.toml')!r}, out={str(disk / 'exact')!r},"
        " set={'bar.elements': 400})",
        f"barimpact.run({str(EX1)!r}, out={str(small)!r}, set={{'time.end': 0.5, 'output.fields_at': []}})",
        f"barimpact.plot({str(small)!r})",
    ])
    for r, name in zip(refused, ("ex1", "h5", "exact")):
        assert_refused(r, disk / name)
        assert not (disk / name).exists()
    assert refused[3] is None and (small / "summary.json").is_file()  # the module still works
    # Its figures do not fit: an OSError naming the figure, no part of it left.
    assert "OSError" in refused[4]["kinds"]
    assert str(small / "figures") in refused[4]["message"] and "No space left on device" in refused[4]["message"]
    figures = [p for p in (small / "figures").iterdir() if p.suffix in (".png", ".svg")]
    assert all(whole_figure(p) for p in figures), figures
    assert leftovers(disk) == []


def test_a_sweep_on_a_full_disk_raises(disk):
    sweep = EXAMPLES / "sweeps" / "penalty-to-rigid.toml"
    refused = refusals([f"barimpact.sweep({str(sweep)!r}, {str(disk / 'sweep')!r}, jobs=2)"])
    assert_refused(refused[0], disk / "sweep")
    assert leftovers(disk) == []
