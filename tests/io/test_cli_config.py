"""`fewear config` prints a complete config that every command accepts back."""

import subprocess
import sys

from fewear.cli import main
from fewear.io.config import default_config, load_config


def test_printed_config_loads_back_whole(tmp_path, capsys):
    assert main(["config"]) == 0
    path = tmp_path / "all.toml"
    path.write_text(capsys.readouterr().out)
    assert load_config(path, list(default_config())) == default_config()


def test_config_out_refuses_to_overwrite(tmp_path, capsys):
    path = tmp_path / "mine.toml"
    path.write_text("keep me")
    assert main(["config", "--out", str(path)]) == 2
    assert "cannot write" in capsys.readouterr().err
    assert path.read_text() == "keep me"


def test_input_errors_exit_2_without_traceback(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[nonsense]\n")
    process = subprocess.run(
        [sys.executable, "-m", "fewear.cli", "contact", "--force", "0", "1", "--config", str(path),
         "--out", str(tmp_path / "out")],
        capture_output=True, text=True,
    )
    assert process.returncode == 2
    assert process.stderr.startswith("fewear: error:") and "[nonsense]" in process.stderr
    assert "Traceback" not in process.stderr
    assert not (tmp_path / "out").exists()
