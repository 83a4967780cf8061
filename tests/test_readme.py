"""The README's examples run as written: the command-line block (each `fewear ...` line through
``python -m fewear.cli``) and the Python block (with exec), both in a scratch folder.

The blocks are the fenced ones that follow an ``<!-- example: cli -->`` or
``<!-- example: python -->`` marker.
"""

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def example_block(kind: str) -> str:
    """The fenced block right after the README's ``<!-- example: KIND -->`` marker."""
    pattern = rf"<!-- example: {kind} -->\s*```\w*\n(.*?)```"
    found = re.findall(pattern, README.read_text(encoding="utf-8"), flags=re.DOTALL)
    assert len(found) == 1, f"README.md needs exactly one '{kind}' example, has {len(found)}"
    return found[0]


def command_lines(block: str) -> list[list[str]]:
    """The block's commands, comments dropped, each split as a shell would."""
    return [shlex.split(line, comments=True) for line in block.splitlines()
            if shlex.split(line, comments=True)]


def test_cli_example_runs(tmp_path):
    commands = command_lines(example_block("cli"))
    assert commands, "the command-line example is empty"
    environment = {**os.environ, "MPLBACKEND": "Agg",
                   "PYTHONPATH": os.pathsep.join([str(README.parent),
                                                  os.environ.get("PYTHONPATH", "")])}
    for argv in commands:
        assert argv[0] == "fewear", f"not a fewear command: {argv}"
        completed = subprocess.run([sys.executable, "-m", "fewear.cli", *argv[1:]],
                                   cwd=tmp_path, env=environment, capture_output=True,
                                   text=True, check=False)
        assert completed.returncode == 0, f"{shlex.join(argv)}: {completed.stderr}"
    # what the prose after the block points the reader to
    assert (tmp_path / "my_case.toml").is_file()
    assert (tmp_path / "out" / "contact" / "summary.json").is_file()
    assert (tmp_path / "out" / "dynamics" / "orbit.png").is_file()


def test_python_example_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    exec(compile(example_block("python"), "README.md (python example)", "exec"), {})
