"""`fewear diagnose` on joint data it was not built around (tests/calibrate/
independent_joint_generator.py): each cause of the catalogue hidden at random parameters in a
coarse wear-loop run (or, for impact wear, our own impulse rule on top of it), measured by our own
lab model, and diagnosed against the coarse believed model. The first data set of each cause, as
in the benchmark tests/benchmarks/test_bench_joint_independent.py (seed index 0).
"""

import json

import pytest

from tests.calibrate import independent_joint_generator as generator
from tests.calibrate.diagnose_files import assert_names_the_hidden_cause, missed

pytestmark = pytest.mark.slow


def test_cli_names_no_cause_on_the_believed_model(tmp_path):
    """Null data: the believed model itself, measured by the lab: no cause, via the CLI."""
    from fewear.cli import main

    data = generator.write_data_set("none", generator.data_set_seed("none", 0), tmp_path / "data")
    out = tmp_path / "diagnosis"
    assert main(["diagnose", str(data.profiles_csv), str(data.max_wear_csv),
                 "--config", str(data.believed_toml), "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    assert summary["cause"] == "none"
    assert summary["causes"] == []


@pytest.mark.parametrize("cause", [
    "wear_coefficient",
    "flexible_link",  # modulus x1.03, height x1.01: named, gain 0.58 (a k level before the grid)
    # power-law running-in (r = 2.7, s0 = 2,900 cycles of sliding): named running_in, power
    # law, gain 0.73, once its fit is refined on runs at its own parameters (a k level before,
    # gain 0.70: the time map of the believed run predicted the later counts 2 % better)
    "running_in",
    missed("friction", "measured: mu = 0.033 (believed 0.1) is 'none', reported unexplained and "
                       "block-limited: refined on the run at its fitted mu, friction predicts "
                       "the held-out count 14 % worse than the believed model; the believed "
                       "config's blocks move its bore by 9.5 um when halved, as far as the "
                       "misfit (with blocks of <= 500 cycles in truth and model it is named "
                       "friction, mu = 0.030, gain 0.61)"),
    missed("impact_wear", "measured: impulse-proportional impact wear above a force "
                          "threshold, removing 17 % of the sliding volume, is named 'none', "
                          "reported unexplained (seed 301: wear_coefficient). With the "
                          "catalogue's impulse form too, the energy form fits the training "
                          "counts better, gain 0.097 against the 0.1 criterion; with blocks of "
                          "<= 500 cycles (energy form alone) a k level, whose full run "
                          "predicted 5 % worse"),
])
def test_names_the_hidden_cause(tmp_path, cause):
    """The hidden cause is the one named, and its extended run predicts the held-out profiles
    better than the believed model."""
    assert_names_the_hidden_cause(generator, cause, tmp_path)
