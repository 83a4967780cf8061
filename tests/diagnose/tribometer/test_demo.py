"""The demo demos/diagnose_tribometer.py runs: it finds the running-in hidden in the synthetic data
set, and on the real published table its answer is what the demo's text says, next to what the
authors concluded (the tables' own numbers, not the diagnosis's)."""

import json
import runpy
from pathlib import Path

import numpy as np
import pytest

from fewear.data import SINGH2016_AL_SIC_CSV
from fewear.diagnose.tribometer.measured import read_measured_wear
from fewear.io.config import load_config
from fewear.wear.extensions import RunningIn, wear_extension_from_config
from tests.data_makers import make_running_in_pin_on_disc as made

DEMO = Path(__file__).resolve().parents[3] / "demos" / "diagnose_tribometer.py"
REAL = SINGH2016_AL_SIC_CSV
# Singh et al. (2016), Tables 5 and 6: wear rates [mm^3/(N m)] printed next to the weight losses,
# in the order of the data file's rows.
PRINTED_WEAR_RATES_mm3_N_m = np.array([
    4.662, 5.275, 6.216, 3.680, 3.987, 5.398, 2.349, 2.516, 3.168, 1.677, 1.733, 2.311,
    6.85, 7.003, 7.634, 5.009, 5.725, 5.964, 2.423, 2.750, 3.448, 1.770, 1.957, 2.454]) * 1e-5


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("FEWEAR_DEMO_OUT", str(out))
        patch.setenv("MPLBACKEND", "Agg")
        runpy.run_path(str(DEMO), run_name="__main__")
    return out


def test_demo_finds_the_hidden_running_in(outputs):
    summary = json.loads((outputs / "synthetic" / "diagnosis.json").read_text())
    assert summary["causes"] == ["running_in"]
    assert summary["gain"] > 0.5
    for name in ("fits.png", "residuals.png", "candidates.png", "report.md"):
        assert (outputs / "synthetic" / name).stat().st_size > 0
    extension = wear_extension_from_config(
        load_config(outputs / "synthetic" / "extended_wear.toml", sections=["wear"])["wear"])
    assert type(extension) is RunningIn
    # the parameters the data were made with (the data set's header): the extra wear of
    # running-in, (r - 1) s0, to 30 %; r and s0 each to a factor 2
    truth = RunningIn(made.K_INITIAL_OVER_STEADY, made.DISTANCE_SCALE_m)
    extra = (extension.k_initial_over_steady - 1) * extension.distance_scale_m
    assert extra == pytest.approx((truth.k_initial_over_steady - 1) * truth.distance_scale_m,
                                  rel=0.3)
    assert 0.5 < extension.k_initial_over_steady / truth.k_initial_over_steady < 2.0
    assert 0.5 < extension.distance_scale_m / truth.distance_scale_m < 2.0


def test_real_table_is_transcribed_consistently():
    """The mass losses and the printed densities reproduce the paper's printed wear rates."""
    data = read_measured_wear(REAL)
    rate_mm3_N_m = 1e9 * data.wear_volume_m3 / (data.normal_load_N * data.sliding_distance_m)
    np.testing.assert_allclose(rate_mm3_N_m, PRINTED_WEAR_RATES_mm3_N_m, rtol=0.005)
    assert set(data.factors) == {"material", "factor_lubrication"}


def test_real_table_answer_matches_the_demo_text(outputs):
    """What the demo's text says of the real table: four material groups, the composite's k
    below the alloy's and lubricated below dry; k rising with load and speed named; the
    distance/speed confusion said."""
    summary = json.loads((outputs / "singh2016" / "diagnosis.json").read_text())
    assert len(summary["material_groups"]) == 4
    assert summary["causes"][0] in ("thermal", "load_exponent", "mild_to_severe")
    assert "running_in" not in summary["causes"]
    assert any("distance and speed vary together" in note for note in summary["notes"])
    assert any("normal load F in its place" in note for note in summary["notes"])
    k = summary["baseline"]["k_per_test_m2_N"]
    alloy_dry = np.mean([v for name, v in k.items() if name.startswith("A-D")])
    composite_dry = np.mean([v for name, v in k.items() if name.startswith("C-D")])
    composite_lubricated = np.mean([v for name, v in k.items() if name.startswith("C-L")])
    assert composite_dry < 0.6 * alloy_dry and composite_lubricated < composite_dry


def test_shipped_data_set_is_what_its_script_makes(tmp_path):
    """The shipped CSV is reproducible from its script (the header says how it was made)."""
    regenerated = tmp_path / "again.csv"
    from tests.diagnose.tribometer.campaign_generator import write_measured_csv

    write_measured_csv(regenerated, made.make(), made.HEADER)
    assert regenerated.read_text() == made.OUTPUT.read_text()
