"""Property-based fuzzing of two readers with corrupted bytes (issue 57): the config reader and
the checkpoint reader of ``fewear run --resume``. Each either reads the file or raises
:class:`~fewear.errors.FewearInputError` (one line at the command line); no other exception
(a traceback), no hang.

Bounded and deterministic like tests/io/test_fuzz_cli.py: a fixed number of examples
(``FEWEAR_FUZZ_EXAMPLES``), derandomized, no example database.
"""

from __future__ import annotations

import os
import shutil
from datetime import timedelta

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from fewear.errors import FewearInputError  # noqa: E402
from fewear.io.config import default_config_text, load_config  # noqa: E402

EXAMPLES = int(os.environ.get("FEWEAR_FUZZ_EXAMPLES", "40"))
FUZZ = settings(max_examples=EXAMPLES, derandomize=True, database=None,
                deadline=timedelta(seconds=20),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])
DEFAULT_TEXT = default_config_text().encode()


def flipped(data: bytes, flips: list[tuple[int, int]]) -> bytes:
    """``data`` with the byte at each (position modulo its length) XORed with a non-zero mask."""
    changed = bytearray(data)
    for position, mask in flips:
        changed[position % len(changed)] ^= mask
    return bytes(changed)


FLIPS = st.lists(st.tuples(st.integers(0, 2**31), st.integers(1, 255)), min_size=1, max_size=8)


@FUZZ
@given(flips=FLIPS, cut=st.one_of(st.none(), st.integers(0, len(DEFAULT_TEXT))))
def test_the_config_reader_reads_or_names_the_problem(tmp_path_factory, flips, cut):
    """The default config with bytes flipped (and maybe cut short): read, or refused."""
    path = tmp_path_factory.mktemp("config") / "flipped.toml"
    path.write_bytes(flipped(DEFAULT_TEXT, flips)[:cut])
    try:
        load_config(path, ["mechanism", "integrator", "mesh", "bushing", "wear_loop"])
    except FewearInputError as exc:
        assert str(path) in str(exc)  # the message names the file


@pytest.fixture(scope="module")
def checkpoint(tmp_path_factory):
    """(the complete config, the checkpoint folder) of a small finished run."""
    from tests.loop.test_wear_loop import run, write_config

    folder = tmp_path_factory.mktemp("run")
    config = write_config(folder)
    assert run(config, folder / "out") == 0
    return config, folder / "out" / "fewear-checkpoint"


@FUZZ
@given(flips=FLIPS, target=st.sampled_from(["rigid.npz", "rigid-rod_slider-mesh-00001.npy"]),
       cut=st.one_of(st.none(), st.integers(0, 4096)))
def test_the_checkpoint_reader_reads_or_names_the_problem(tmp_path_factory, checkpoint, flips,
                                                          target, cut):
    """A checkpoint file with bytes flipped (and maybe cut short): resumed, or refused naming
    the checkpoint."""
    from fewear.loop.checkpoint import Checkpoint
    from fewear.loop.settings import run_sections

    config_path, saved = checkpoint
    out = tmp_path_factory.mktemp("resume")
    shutil.copytree(saved, out / "fewear-checkpoint")
    path = out / "fewear-checkpoint" / target
    data = path.read_bytes()
    path.write_bytes(flipped(data, flips)[:None if cut is None else len(data) - cut])
    store = Checkpoint(out, load_config(config_path, run_sections()))
    try:
        store.load(["rigid"], ["rod_slider"])
    except FewearInputError as exc:
        assert "checkpoint" in str(exc)
    store.saved_cycles()  # the interruption note's reader: never raises
