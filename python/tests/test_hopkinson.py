"""barimpact.hopkinson: the analysis from Python, on records whose waves are known."""
import numpy as np
import pytest

import barimpact

C0, E, AB, AS, LS = 5000.0, 200e9, 3e-4, 1e-4, 0.005


def _shape(tau):
    """A pulse of unit height: 5% just after 0, 1 from 19 us to 100 us, 0 at 121 us."""
    up = np.minimum(0.05 + tau / 20e-6, 1.0)
    down = (121e-6 - tau) / 21e-6
    return np.where((tau <= 0.05e-6) | (tau >= 121e-6), 0.0, np.where(tau < 100e-6, up, down))


def _write(tmp_path):
    t = np.arange(12001) * 1e-7
    foot = 100e-6
    incident = -1e-3 * _shape(t - foot) + 6e-4 * _shape(t - foot - 400e-6 - 3e-6)
    transmitted = -4e-4 * _shape(t - foot - 300e-6 - 1e-6)
    np.savetxt(tmp_path / "inc.csv", np.column_stack([t, incident]), delimiter=",", header="t,strain", comments="")
    np.savetxt(tmp_path / "tr.csv", np.column_stack([t, transmitted]), delimiter=",", header="t,strain", comments="")


def _setup(tmp_path):
    return {"bar": {"modulus": E, "density": 8000.0, "area": AB},
            "specimen": {"length": LS, "area": AS},
            "incident": {"signal": str(tmp_path / "inc.csv"), "gauge_to_specimen": 1.0},
            "transmitted": {"signal": str(tmp_path / "tr.csv"), "gauge_to_specimen": 0.5}}


def test_returns_the_table_as_numpy_arrays_with_the_formulas(tmp_path):
    _write(tmp_path)
    r = barimpact.hopkinson(_setup(tmp_path))
    assert isinstance(r, dict)
    assert list(r)[:11] == ["t", "strain_1w", "strain_rate_1w", "stress_1w", "strain_3w", "strain_rate_3w",
                            "stress_2w", "stress_3w", "force_front", "force_back", "equilibrium"]
    assert all(isinstance(v, np.ndarray) for v in r.values())
    assert r["t"][0] == 0.0 and len(r["t"]) == 1207
    ei, er, et = r["incident"], r["reflected"], r["transmitted"]
    # The formulas, to round-off of forces of 6e4 N.
    np.testing.assert_allclose(r["force_front"], -E * AB * (ei + er), rtol=0, atol=1e-6)
    np.testing.assert_allclose(r["stress_3w"], (r["force_front"] + r["force_back"]) / (2 * AS), rtol=0, atol=1e-2)
    np.testing.assert_allclose(r["strain_rate_3w"], C0 * (er + et - ei) / LS, rtol=0, atol=1e-7)
    assert r.summary["alignment"]["method"] == "trigger"
    assert r.summary["alignment"]["foot"] == pytest.approx(100e-6)


def test_a_setup_file_gives_the_same_table(tmp_path):
    _write(tmp_path)
    (tmp_path / "setup.toml").write_text(
        '[bar]\nmodulus = 200e9\ndensity = 8000.0\narea = 3e-4\n[specimen]\nlength = 0.005\narea = 1e-4\n'
        '[incident]\nsignal = "inc.csv"\ngauge_to_specimen = 1.0\n'
        '[transmitted]\nsignal = "tr.csv"\ngauge_to_specimen = 0.5\n')
    a = barimpact.hopkinson(tmp_path / "setup.toml")
    b = barimpact.hopkinson(_setup(tmp_path))
    np.testing.assert_array_equal(a["stress_3w"], b["stress_3w"])


def test_refuses_a_missing_column_in_one_line(tmp_path):
    _write(tmp_path)
    s = _setup(tmp_path)
    s["incident"]["strain"] = "eps"
    with pytest.raises(barimpact.InputError, match='no column "eps"'):
        barimpact.hopkinson(s)
