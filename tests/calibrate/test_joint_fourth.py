"""`fewear diagnose` on joint data from the fourth generator (tests/calibrate/
fourth_joint_generator.py, written without reading the diagnosis): each cause by a law of its own,
measured from silicone replicas with a confocal scanner, diagnosed against the coarse believed
model. The first data set of each cause, as in the benchmark
tests/benchmarks/test_bench_joint_fourth.py (seed index 0); the misses measured there are strict
xfails, so a change that fixes one is seen.
"""

import json

import pytest

from tests.calibrate import fourth_joint_generator as generator
from tests.calibrate.diagnose_files import assert_names_the_hidden_cause, missed

pytestmark = pytest.mark.slow


def test_cli_names_no_cause_on_the_believed_model(tmp_path):
    """Null data: the believed model itself, measured from replicas: no cause, via the CLI."""
    from fewear.cli import main

    data = generator.write_data_set("none", generator.data_set_seed("none", 0), tmp_path / "data")
    out = tmp_path / "diagnosis"
    assert main(["diagnose", str(data.profiles_csv), str(data.max_wear_csv),
                 "--config", str(data.believed_toml), "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    assert summary["causes"] == []
    assert summary["unexplained"] == []


@pytest.mark.parametrize("cause", [
    "wear_coefficient",  # bronze at 298 HB, k x 0.79: gain 0.93
    "flexible_link",  # 6-element steel rod, E = 214 GPa, damping 1.5e-5 s: gain 0.18
    missed("friction", "measured: mu rising from 0.092 to 0.263 over N_g = 5,400 cycles is "
                       "'none', reported unexplained: the believed model misses the training "
                       "counts by only 1.5 um (4 x the scatter); the catalogue's friction is "
                       "one constant mu"),
    missed("impact_wear", "measured: cubic-speed impact wear shows only at the held-out count "
                          "(training misfit 0.7 um against 0.4 um scatter, held-out 9 um): "
                          "'none', reported as a late misfit"),
    missed("running_in", "measured: a bore-wide running-in warp of the cycles (r = 5.1, "
                         "N_r = 716, m - 1 falling as (1 + N / N_r)^-2) is 'none', reported "
                         "unexplained: the catalogue's running-in by cycles falls "
                         "exponentially and fits the training counts worse than the one by "
                         "sliding, whose fit (r at the bound 6) predicts the held-out count "
                         "29 % worse than the believed model"),
])
def test_names_the_hidden_cause(tmp_path, cause):
    """The hidden cause is the one named, and its extended run predicts the held-out profiles
    better than the believed model."""
    assert_names_the_hidden_cause(generator, cause, tmp_path)
