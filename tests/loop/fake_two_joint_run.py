"""`fewear run --config CONFIG --out OUT` on the fake two-joint mechanism of
tests/loop/test_several_joints.py, for ``mpirun -n 2`` (a test's monkeypatch does not reach
the ranks' processes)."""

import sys
import tempfile

import pytest

from fewear.cli import main
from tests.loop.test_several_joints import fake_mechanism, two_histories

if __name__ == "__main__":
    config, out = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as folder, pytest.MonkeyPatch.context() as monkeypatch:
        from pathlib import Path

        fake_mechanism(monkeypatch, two_histories(Path(folder)), ["a", "b"])
        sys.exit(main(["run", "--config", config, "--out", out]))
