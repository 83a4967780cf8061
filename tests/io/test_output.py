"""Outputs are all-or-nothing: a failure part-way leaves the output folder as it was."""

import pytest

from fewear.errors import FewearInputError
from fewear.io.output import staged_output


def test_success_moves_every_file(tmp_path):
    out = tmp_path / "result"
    with staged_output(out) as stage:
        (stage / "a.csv").write_text("1")
        (stage / "b.json").write_text("{}")
    assert sorted(p.name for p in out.iterdir()) == ["a.csv", "b.json"]


def test_failure_leaves_nothing_and_removes_the_new_folder(tmp_path):
    out = tmp_path / "result"
    with pytest.raises(RuntimeError):
        with staged_output(out) as stage:
            (stage / "a.csv").write_text("1")
            raise RuntimeError("solver diverged")
    assert not out.exists()


def test_failure_keeps_earlier_results(tmp_path):
    out = tmp_path / "result"
    out.mkdir()
    (out / "a.csv").write_text("old")
    with pytest.raises(RuntimeError):
        with staged_output(out) as stage:
            (stage / "a.csv").write_text("new")
            raise RuntimeError
    assert [p.name for p in out.iterdir()] == ["a.csv"]
    assert (out / "a.csv").read_text() == "old"


def test_unwritable_folder_is_an_input_error(tmp_path):
    blocker = tmp_path / "file.txt"
    blocker.write_text("")
    with pytest.raises(FewearInputError, match="file.txt"):
        with staged_output(blocker / "out"):
            pass
