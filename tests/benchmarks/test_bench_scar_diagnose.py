"""`fewear diagnose` on the two published scars with the default (converged) scar models: the
fitted k factor, its folds, the held-out RMS of the believed and the fitted model, p, effective
observations, forward runs and wall time, printed (block on ring: 6 runs of about 2.2 s of CPU;
fretting: 11 runs of about 5 s of CPU, the two causes' fits side by side; docs/performance.md).

Asserted: the verdict measured when the room was written (no cause named on either scar: the
source's k predicts the held-out points as well as a fitted one) and that every fit converged.
"""

import json

import pytest

from fewear.cli import main
from fewear.data import BLOCK_ON_RING_CRUZADO2010_CSV, FRETTING_MCCOLL2004_CSV

pytestmark = pytest.mark.benchmark


@pytest.mark.parametrize("case, data", [("block_on_ring", BLOCK_ON_RING_CRUZADO2010_CSV),
                                        ("fretting", FRETTING_MCCOLL2004_CSV)])
def test_published_scar_diagnosis(case, data, tmp_path):
    config = tmp_path / "case.toml"
    config.write_text(f'[scar]\ncase = "{case}"\n')
    out = tmp_path / "out"
    assert main(["diagnose", str(data), "--config", str(config), "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    print(f"\n{case}: {summary['wall_time_s']:.0f} s, cause {summary['cause']}")
    for entry in summary["candidates"]:
        rms = entry["held_out_rms_m"]
        print(f"  {entry['cause']}: fitted x{entry['fitted_factor']:.4f}, folds "
              + ", ".join(f"{factor:.4f}" for factor in entry["fold_factors"])
              + f"; held-out RMS {rms['believed'] * 1e6:.3f} -> {rms['fitted'] * 1e6:.3f} um "
              f"(gain {entry['gain']:.1%}); p {entry['p_value']:.3g} on "
              f"{entry['effective_observations']} effective observations; AICc "
              f"{entry['aicc_improvement']:+.2f}; {entry['forward_runs']} runs in "
              f"{entry['forward_wall_time_s']:.0f} s; converged {entry['converged']}")
    assert summary["cause"] == "none"
    assert all(entry["converged"] for entry in summary["candidates"])
