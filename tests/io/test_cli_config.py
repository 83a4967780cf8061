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


def test_a_first_form_compile_prints_no_info_lines(tmp_path):
    """DOLFINx compiles a new form with gcc through cffi, which logs the gcc command lines at
    INFO on the root logger, where FFCx put a handler: with fewear imported none reaches stderr
    (a fresh process and an empty form cache, so that the form compiles); the same compile
    without fewear prints them (the check can fail)."""
    import os
    import subprocess
    import sys

    script = ("import sys\n"
              "if sys.argv[1] == 'fewear':\n"
              "    import fewear\n"
              "from mpi4py import MPI\n"
              "import ufl\n"
              "from dolfinx import fem, mesh\n"
              "domain = mesh.create_unit_square(MPI.COMM_SELF, 2, 2)\n"
              "space = fem.FunctionSpace(domain, ('Lagrange', 1))\n"
              "fem.form(ufl.inner(ufl.TrialFunction(space), ufl.TestFunction(space)) * ufl.dx)\n")
    errs = {}
    for name in ("fewear", "plain"):
        env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / name)}
        errs[name] = subprocess.run([sys.executable, "-c", script, name], capture_output=True,
                                    text=True, check=True, env=env).stderr
    assert "INFO" not in errs["fewear"] and "gcc" not in errs["fewear"]
    assert "INFO:root:" in errs["plain"] and "gcc" in errs["plain"]
