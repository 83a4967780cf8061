"""fewear.jit: the compile cache's state, as the wear run announces a first compile; a cache
folder that cannot be written is passed over, or said to cost a compile every run (issue 57)."""

import os
import subprocess
import sys
import types

import numba

from fewear import kernels
from fewear.jit import WARNED, holds_compiled_code
from fewear.kernels import compile_kernels


def test_an_empty_cache_holds_no_compiled_code_and_an_index_file_does(tmp_path):
    assert not holds_compiled_code(str(tmp_path))
    assert not holds_compiled_code(str(tmp_path / "missing"))
    (tmp_path / "fewear" / "contact").mkdir(parents=True)
    (tmp_path / "fewear" / "contact" / "newton.norm-245.py311.nbi").write_bytes(b"index")
    assert holds_compiled_code(str(tmp_path))


def test_a_warm_cache_compiles_without_a_word():
    """The suite's processes run on a filled cache (earlier tests compiled the kernels): no
    announcement of a minute's compile."""
    compile_kernels()
    said = []
    compile_kernels(said.append)
    assert holds_compiled_code(numba.config.CACHE_DIR) and said == []


def test_a_run_compiles_before_its_workers_only_into_an_empty_cache(tmp_path, monkeypatch):
    """An empty cache: compiled (and announced) once before the workers start; a filled one:
    nothing there, each worker loads what it uses."""
    compiles = []
    monkeypatch.setattr(kernels, "compile_kernels", compiles.append)
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    kernels.compile_kernels_unless_cached("report")
    assert compiles == ["report"]
    (tmp_path / "newton.norm-245.py311.nbi").write_bytes(b"index")
    kernels.compile_kernels_unless_cached("report")
    assert compiles == ["report"]


def blocked(tmp_path):
    """A folder no one, root included, can make: it would sit under a regular file."""
    (tmp_path / "a-file").write_text("")
    return str(tmp_path / "a-file" / "cache")


def test_an_unwritable_numba_cache_dir_falls_back_and_says_where(tmp_path):
    from fewear.jit import choose_cache_dir

    directory, warning = choose_cache_dir(blocked(tmp_path), "d1")
    assert directory.endswith("fewear-jit-d1") and not directory.startswith(str(tmp_path))
    assert warning.startswith(f"numba's cache folder {blocked(tmp_path)} (NUMBA_CACHE_DIR) "
                              "cannot be written")
    assert os.path.dirname(directory) in warning and "NUMBA_CACHE_DIR to a writable" in warning
    assert choose_cache_dir(str(tmp_path), "d1") == (str(tmp_path / "fewear-jit-d1"), "")


def test_no_writable_cache_dir_says_every_run_compiles(tmp_path, monkeypatch):
    import fewear.jit

    monkeypatch.setattr(fewear.jit, "HERE", blocked(tmp_path))
    monkeypatch.setattr(fewear.jit, "AppDirs",
                        lambda **kwargs: types.SimpleNamespace(user_cache_dir=blocked(tmp_path)))
    monkeypatch.setattr(fewear.jit.tempfile, "gettempdir", lambda: blocked(tmp_path))
    directory, warning = fewear.jit.choose_cache_dir(None, "d1")
    assert directory is None and "compiled again on every run" in warning


def test_the_warning_is_shown_once_per_command(tmp_path):
    """On screen at import, once: the worker processes a command spawns inherit the mark."""
    environment = {**os.environ, "NUMBA_CACHE_DIR": blocked(tmp_path)}
    environment.pop(WARNED, None)
    command = [sys.executable, "-c", "import fewear.jit"]
    shown = subprocess.run(command, env=environment, capture_output=True, text=True).stderr
    assert shown.count("fewear: warning: numba's cache folder") == 1, shown
    quiet = subprocess.run(command, env={**environment, WARNED: "1"}, capture_output=True,
                           text=True).stderr
    assert "warning" not in quiet
