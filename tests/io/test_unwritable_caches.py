"""Caches that cannot be written (issue 57): DOLFINx's JIT cache is named as such, with how to
fix it (it was reported as a read-only ``.../fenics`` folder, as if it were the output folder)."""

import errno

import pytest

from fewear.cli import main, os_error_message


@pytest.fixture
def unwritable_dolfinx_cache(tmp_path, monkeypatch):
    """DOLFINx's JIT cache under a regular file: no one, root included, can make it."""
    import dolfinx.jit

    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    cache = blocker / "fenics"
    default = dolfinx.jit.DOLFINX_DEFAULT_JIT_PARAMETERS["cache_dir"]
    monkeypatch.setitem(dolfinx.jit.DOLFINX_DEFAULT_JIT_PARAMETERS, "cache_dir",
                        (cache, default[1]))
    return cache


def test_a_contact_with_an_unwritable_jit_cache_names_the_cache(tmp_path, capsys,
                                                                unwritable_dolfinx_cache):
    assert main(["contact", "--force", "0", "-500", "--out", str(tmp_path / "out")]) == 2
    last = capsys.readouterr().err.splitlines()[-1]
    assert last.startswith(f"fewear: error: DOLFINx's JIT cache folder {unwritable_dolfinx_cache}")
    assert "set XDG_CACHE_HOME to a writable folder" in last
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("where", ["cache", "inside", "parent"])
def test_an_error_in_or_on_the_way_to_the_cache_names_it(unwritable_dolfinx_cache, where):
    path = {"cache": unwritable_dolfinx_cache, "inside": unwritable_dolfinx_cache / "lib.c",
            "parent": unwritable_dolfinx_cache.parent}[where]
    message = os_error_message(OSError(errno.EROFS, "Read-only file system", str(path)))
    assert message.startswith(f"DOLFINx's JIT cache folder {unwritable_dolfinx_cache}")
    assert f"({path}: Read-only file system)" in message


def test_an_error_elsewhere_is_not_blamed_on_the_cache(tmp_path, unwritable_dolfinx_cache):
    message = os_error_message(OSError(errno.EACCES, "Permission denied", str(tmp_path / "out")))
    assert message == (f"{tmp_path / 'out'}: Permission denied (choose a folder you may write to, "
                       "or change its permissions)")
