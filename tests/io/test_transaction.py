"""Output folders as transactions (fewear/io/transaction.py): what a killed command left is
cleaned or restored and said, another command's results are refused unless --overwrite (then
replaced only once the new outputs are written), and the outputs name their command."""

import json

import pytest

from fewear.cli import main
from fewear.errors import FewearInputError
from fewear.io.output import staged_output, write_json
from fewear.io.transaction import folder_commands, output_folder, recover


def run_folder(out, command="run"):
    """A folder with a complete run's outputs (as `fewear run` names them)."""
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / "summary.json", {"command": command, "cases": {}})
    (out / "max_wear.csv").write_text("cycles,rigid_m\n0,0\n")
    (out / "rigid.xdmf").write_text("<Xdmf/>")
    return out


def test_a_killed_commands_staging_folder_is_removed_and_said(tmp_path):
    out = run_folder(tmp_path / "out")
    (out / ".fewear-staging-abc").mkdir()
    (out / ".fewear-staging-abc" / "contact.csv").write_text("half")
    notes = recover(out)
    assert len(notes) == 1 and "removed .fewear-staging-abc" in notes[0]
    assert sorted(path.name for path in out.iterdir()) == [
        "max_wear.csv", "rigid.xdmf", "summary.json"]


def test_an_earlier_run_set_aside_and_not_replaced_is_restored(tmp_path):
    aside = run_folder(tmp_path / "out" / ".fewear-previous-x1")
    before = {path.name: path.read_bytes() for path in aside.iterdir()}
    notes = recover(tmp_path / "out")
    assert len(notes) == 1 and "restored the earlier run" in notes[0]
    assert {path.name: path.read_bytes() for path in (tmp_path / "out").iterdir()} == before


def test_an_earlier_run_stays_aside_while_its_replacement_is_unfinished(tmp_path):
    out = tmp_path / "out"
    run_folder(out / ".fewear-previous-x1")
    (out / "fewear-checkpoint").mkdir()
    (out / "fewear-checkpoint" / "rigid.npz").write_bytes(b"case")
    notes = recover(out)
    assert len(notes) == 1 and "unfinished run" in notes[0] and "--resume" in notes[0]
    assert (out / ".fewear-previous-x1" / "summary.json").exists()
    assert not (out / "summary.json").exists()


def test_an_earlier_run_replaced_by_a_complete_one_is_removed(tmp_path):
    out = run_folder(tmp_path / "out")
    run_folder(out / ".fewear-previous-x1")
    notes = recover(out)
    assert len(notes) == 1 and "replaced by the complete run" in notes[0]
    assert not (out / ".fewear-previous-x1").exists() and (out / "summary.json").exists()


@pytest.mark.parametrize("files, expected", [
    ({"contact.csv": "", "summary.json": "{}"}, {"contact": ["summary.json", "contact.csv"]}),
    ({"summary.json": '{"command": "scar"}', "scar.png": ""}, {"scar": ["summary.json",
                                                                       "scar.png"]}),
    ({"joint_history.csv": ""}, {"dynamics": ["joint_history.csv"]}),
    ({"notes.txt": "", "summary.json": "{}"}, {}),
], ids=["contact-of-an-earlier-version", "scar", "dynamics-without-summary", "none"])
def test_the_command_that_made_a_folder_is_recognised(tmp_path, files, expected):
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    found = folder_commands(tmp_path)
    assert {command: [path.name for path in paths] for command, paths in found.items()} == \
        expected


def test_another_commands_results_are_refused_naming_it(tmp_path, capsys):
    out = run_folder(tmp_path / "out")
    before = {path.name: path.read_bytes() for path in out.iterdir()}
    assert main(["contact", "--force", "0", "100", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fewear: error: output folder {out} holds the results of `fewear "
                          "run` (summary.json, max_wear.csv"), err
    assert "`fewear contact --overwrite`" in err
    assert {path.name: path.read_bytes() for path in out.iterdir()} == before


def test_overwrite_replaces_the_other_commands_results_only_once_written(tmp_path):
    out = run_folder(tmp_path / "out")
    (out / "notes.txt").write_text("the user's own")
    with pytest.raises(RuntimeError), output_folder(out, "dynamics", overwrite=True):
        raise RuntimeError("the new command failed")
    assert (out / "max_wear.csv").exists()  # kept: nothing replaced it
    with output_folder(out, "dynamics", overwrite=True):
        with staged_output(out) as stage:
            write_json(stage / "summary.json", {"peak_contact_force_N": 1.0})
            (stage / "joint_history.csv").write_text("time_s\n0\n")
    assert sorted(path.name for path in out.iterdir()) == [
        "joint_history.csv", "notes.txt", "summary.json"]
    assert json.loads((out / "summary.json").read_text()) == {
        "command": "dynamics", "peak_contact_force_N": 1.0}


def test_plot_may_write_into_a_runs_folder(tmp_path):
    out = run_folder(tmp_path / "out")
    with output_folder(out, "plot", required=False):
        assert (out / ".fewear-lock").exists()
    with output_folder(tmp_path / "missing", "plot", required=False):
        pass
    assert not (tmp_path / "missing").exists()


@pytest.mark.parametrize("out, message", [
    ("", "--out '': an empty folder name"),
    ("run/fewear-checkpoint", "is inside the checkpoint folder of a run"),
    ("run/fewear-checkpoint/deeper", "is inside the checkpoint folder of a run"),
])
def test_output_folders_that_cannot_be_meant_are_refused(tmp_path, monkeypatch, out, message):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FewearInputError, match=message), output_folder(out, "run"):
        pass
    assert list(tmp_path.iterdir()) == []


def test_overwriting_an_unfinished_run_drops_the_earlier_run_it_was_to_replace(tmp_path):
    out = tmp_path / "out"
    run_folder(out / ".fewear-previous-x1")
    (out / "fewear-checkpoint").mkdir()
    (out / "fewear-checkpoint" / "rigid.npz").write_bytes(b"case")
    with output_folder(out, "contact", overwrite=True):
        with staged_output(out) as stage:
            write_json(stage / "summary.json", {"peak_pressure_Pa": 1.0})
    assert sorted(path.name for path in out.iterdir()) == ["summary.json"]
