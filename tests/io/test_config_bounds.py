"""Config values beyond what the model can mean (issue 57), each refused in one line naming the
key and the allowed range: a negative smoothing width (taken as 0 before), an angular offset
beyond half a turn, a k level of 1e9 (blamed on the data's cycles column before), a zero
significance."""

import pytest

from fewear.cli import main
from fewear.io.config import default_config_text


@pytest.mark.parametrize("section, key, value, message", [
    ("wear_loop", "wear_smoothing_width_deg", "-5.0",
     "[wear_loop] wear_smoothing_width_deg = -5.0: expected 0 (no smoothing) to 90 degrees"),
    ("joint_diagnose", "max_offset_deg", "1000.0",
     "[joint_diagnose] max_offset_deg = 1000.0: expected 0 to 180 degrees"),
    ("joint_diagnose", "max_k_scale", "1e9",
     "[joint_diagnose] max_k_scale = 1000000000.0: expected > 1 and <= 100"),
    ("joint_diagnose", "significance", "0.0", "[joint_diagnose] significance = 0.0"),
])
def test_values_beyond_the_models_reach_are_refused(tmp_path, capsys, section, key, value,
                                                    message):
    """`fewear diagnose` on joint data (the joint settings) and `fewear run` (the loop's)."""
    lines, current = [], None
    for line in default_config_text().splitlines():
        if line.startswith("["):
            current = line.strip("[]")
        if current == section and line.startswith(f"{key} ="):
            line = f"{key} = {value}"
        lines.append(line)
    config = tmp_path / "config.toml"
    config.write_text("\n".join(lines) + "\n")
    data = tmp_path / "max.csv"
    data.write_text("cycles,max_wear_depth_m\n0,0\n10000,4e-6\n20000,8e-6\n")
    out = tmp_path / "out"
    command = (["diagnose", str(data)] if section == "joint_diagnose" else ["run"])
    assert main([*command, "--config", str(config), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("fewear: error:") and message in err and "\n" not in err
    assert not out.exists()
