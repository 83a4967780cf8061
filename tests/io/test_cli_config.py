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


def test_compiler_info_lines_stay_off_the_terminal():
    """cffi sets the root logger to INFO while FFCx's forms compile; the CLI's root handler passes
    warnings and errors only, so gcc command lines never reach the user (a fresh process: pytest
    holds handlers of its own on the root logger)."""
    import subprocess
    import sys

    script = (
        "import logging\n"
        "from fewear.cli import quiet_compiler_logs\n"
        "quiet_compiler_logs()\n"
        "import ffcx\n"  # installs its basicConfig handler unless one exists
        "logging.getLogger().setLevel(logging.INFO)\n"  # distutils' set_threshold in a compile
        "logging.info('x86_64-linux-gnu-gcc -c libffcx_forms.c')\n"
        "logging.warning('a real warning')\n")
    err = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True).stderr
    assert "gcc" not in err and "a real warning" in err
