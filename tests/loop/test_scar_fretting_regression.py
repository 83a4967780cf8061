"""The fretting scar of `fewear scar` (case "fretting", the embedded config) pinned at what it
predicted, beside McColl, Ding & Leen 2004's measured scar (slow: about 20 s).

Why these figures are right to pin: they are converged in the three discretisation parameters.
18,000 cycles, flat and cylinder wearing (k = 2.9e-14, k_c = 1.9e-14 m^2/N; the flat's figures;
area: the whole profile's, 1e-3 mm^2):

| element | increments/cycle | cycles/block | depth (um) | width 5 % (mm) | area |
|---|---|---|---|---|---|
| 20 um | 8 (default) | 1000 | 2.731 | 0.4933 | 0.9363 |
| 20 um | 20 | 1000 | 2.725 | 0.4940 | 0.9331 |
| 20 um | 40 | 1000 | 2.723 | 0.4943 | 0.9322 |
| 40 um | 20 | 1000 | 2.726 | 0.5007 | 0.9332 |
| 10 um | 20 | 1000 | 2.724 | 0.4950 | 0.9329 |
| 20 um | 20 | 2000 | 2.769 | 0.4931 | 0.9359 |
| 20 um | 20 | 500 | 2.705 | 0.4941 | 0.9313 |

Increments and mesh: within 0.3 % (depth), 1.4 % (width, the 40 um elements), 0.4 % (area). Block
size: the depth converges at first order (2.769, 2.725, 2.705 um), so the default's 1000 cycles
is about 1.5 % deep of the limit; the width and area hold to 0.2 % and 0.5 %.

Against the measurement (2.892 um, 0.668 mm, 1.023e-3 mm^2 over its width, a U): depth -5.6 %
(the issue's goal: within 20 %), width -26 % (goal 10 %: missed), area over the width -8.9 %,
RMS 0.237 um, the same U shape. LevelSetWear (both bodies elastic and wearing, 180 blocks of
100 cycles): 2.71 um, about 0.52 mm, 0.937e-3 mm^2. The flat alone wearing (cylinder_wear_
coefficient_m2_N = 0): 3.296 um, 0.413 mm, 0.930e-3 mm^2 (20 um, 20 increments, 1000 cycles).
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
    print(f"\npredicted {predicted}\nmeasured {measured}\ncylinder {summary['cylinder']}\n"
          f"RMS {summary['rms_difference_m']:.4g} m, {summary['wall_time_s']:.1f} s")
    assert predicted["shape"] == measured["shape"] == "U"
    assert predicted["max_depth_m"] == pytest.approx(2.731e-6, rel=0.01)
    assert predicted["width_m"] == pytest.approx(0.4933e-3, rel=0.01)
    assert predicted["whole_worn_area_m2"] == pytest.approx(0.9363e-9, rel=0.005)
    assert summary["cylinder"]["worn_area_m2"] == pytest.approx(
        predicted["whole_worn_area_m2"] * 1.9 / 2.9, rel=2e-3)
    assert summary["rms_difference_m"] == pytest.approx(0.237e-6, rel=0.03)
    # beside the measurement: the depth within the 20 %, the width short of its 10 %
    assert abs(predicted["max_depth_m"] / measured["max_depth_m"] - 1.0) < 0.2
    assert predicted["width_m"] / measured["width_m"] == pytest.approx(0.87, abs=0.02)
