"""barimpact's blow against Smith's (1960) discrete model (smith1960.py,
written apart from the library): at 400 segments each converges on the same
continuum, so their sets agree to 0.2% and their largest compressions to
0.5% (measured 0.02-0.04% and 0.07-0.19%: Smith's point weights sit at the
segments and his damping lags a step, barimpact's lumped nodes at the
element ends). At his coarse 10 to 20 segments the discrete model differs
from the converged blow by percents (docs/pile.md), and it closes in as the
segments shrink. Smith's model has no gravity: both blows run without it,
to 0.12 s (the examples run under gravity, where the ram falls back)."""
import pytest

import barimpact
import smith1960
from conftest import EXAMPLES


END = 0.12


def continuum(name, elements):
    case = barimpact.Case(str(EXAMPLES / "pile" / f"{name}.toml"),
                          set={"body.pile.elements": elements, "output.every": 50, "load.gravity": 0,
                               "time.end": END})
    return barimpact.run(case).summary["blow"]


@pytest.mark.parametrize("name", ["steel-pipe-sand", "concrete-clay"])
def test_smith_discrete_model_converges_on_the_blow(name):
    ours = continuum(name, 400)
    fine = smith1960.blow(EXAMPLES / "pile" / f"{name}.toml", 400, end=END)
    assert fine["set"] == pytest.approx(ours["set"], rel=2e-3)
    assert fine["max_compression"] == pytest.approx(ours["max_compression"]["value"], rel=5e-3)
    coarse = [smith1960.blow(EXAMPLES / "pile" / f"{name}.toml", n, end=END) for n in (10, 20)]
    errors = [abs(r["set"] - ours["set"]) for r in coarse + [fine]]
    assert errors[0] > errors[1] > errors[2], errors
