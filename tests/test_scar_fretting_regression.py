"""The fretting scar of `fewear scar` (case "fretting", the embedded config) pinned at what it
predicted, beside McColl, Ding & Leen 2004's measured scar (slow: about 90 s).

Why these figures are right to pin: they are converged in the three discretisation parameters
(18,000 cycles; rigid cylinder, the flat alone wears):

| element | increments/cycle | cycles/block | depth (um) | width 5 % (mm) | area (1e-3 mm^2) |
|---|---|---|---|---|---|
| 20 um (default) | 20 | 1000 | 3.296 | 0.4127 | 0.9298 |
| 40 um | 20 | 1000 | 3.294 | 0.4213 | 0.9300 |
| 20 um | 8  | 1000 | 3.308 | 0.4128 | 0.9328 |
| 20 um | 20 | 2000 | 3.304 | 0.4128 | 0.9320 |

(the whole profile's area; the summary's worn_area_m2 integrates over the 5 % width: 0.9251).
Against the measurement (2.892 um, 0.668 mm, 1.023e-3 mm^2 over its width, a U): depth +14 %
(the issue's goal: within 20 %), width -38 % (goal 10 %: missed), area -10 %, RMS 0.45 um, the
same U shape. The flat's scar is the unworn cylinder's arc swept by the stroke; LevelSetWear,
which wears the cylinder too (k = 1.9e-14 m^2/N), predicts 2.71 um and 0.52 mm.
"""

import json

import pytest

from fewear.cli import main


@pytest.mark.slow
def test_fretting_scar_as_predicted(tmp_path):
    config = tmp_path / "fretting.toml"
    config.write_text('[scar]\ncase = "fretting"\n')
    out = tmp_path / "out"
    assert main(["scar", "--config", str(config), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    predicted, measured = summary["predicted"], summary["measured"]
    print(f"\npredicted {predicted}\nmeasured {measured}\nRMS {summary['rms_difference_m']:.4g} m,"
          f" {summary['wall_time_s']:.1f} s")
    assert predicted["shape"] == measured["shape"] == "U"
    assert predicted["max_depth_m"] == pytest.approx(3.296e-6, rel=0.01)
    assert predicted["width_m"] == pytest.approx(0.4127e-3, rel=0.01)
    assert predicted["whole_worn_area_m2"] == pytest.approx(0.9298e-9, rel=0.005)
    assert summary["rms_difference_m"] == pytest.approx(0.455e-6, rel=0.03)
    # beside the measurement: the depth within the 20 %, the width short of it
    assert abs(predicted["max_depth_m"] / measured["max_depth_m"] - 1.0) < 0.2
    assert predicted["width_m"] / measured["width_m"] == pytest.approx(0.62, abs=0.02)
