"""A full disk while a checkpoint's case file is written (issue 57): the write's OSError, and
nothing else: no half-written file left, no "Exception ignored ... ZipFile.__del__" printed after
the command's message (sys.unraisablehook hears of none)."""

import errno
import gc
import io
import sys

import numpy as np
import pytest

from fewear.loop import checkpoint


class FullDisk(io.BufferedWriter):
    """A file on a disk with ``room`` bytes left: a write beyond it raises ENOSPC."""

    room = 100

    def write(self, data):
        if len(data) > self.room:
            raise OSError(errno.ENOSPC, "No space left on device")
        return super().write(data)


def test_a_full_disk_raises_the_write_error_alone(tmp_path, monkeypatch):
    unraisable = []
    monkeypatch.setattr(sys, "unraisablehook", unraisable.append)
    monkeypatch.setattr(checkpoint, "open",
                        lambda path, mode: FullDisk(io.FileIO(path, mode)), raising=False)
    target = tmp_path / "rigid.npz"
    arrays = {"x": np.arange(10_000.0), "meta": np.array("{}")}
    with pytest.raises(OSError) as error:
        checkpoint.write_npz(target, arrays)
    gc.collect()
    assert error.value.errno == errno.ENOSPC
    assert unraisable == [] and list(tmp_path.iterdir()) == []


def test_with_room_the_file_reads_back(tmp_path):
    target = tmp_path / "rigid.npz"
    checkpoint.write_npz(target, {"x": np.arange(5.0)})
    with np.load(target) as data:
        np.testing.assert_array_equal(data["x"], np.arange(5.0))
    assert list(tmp_path.iterdir()) == [target]
