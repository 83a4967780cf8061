"""A full disk while a checkpoint's case file or a run's mesh snapshots (XDMF + HDF5) are
written (issue 57): a :class:`DiskFull` naming the file and the bytes it needed, and nothing else:
no half-written file left, nothing printed after the command's message (sys.unraisablehook hears
of none; HDF5 writing straight onto the full disk printed a traceback per dataset and crashed at
exit); the edge's line names the output folder, not the staging folder."""

import errno
import gc
import io
import sys

import numpy as np
import pytest

from fewear.cli import os_error_message
from fewear.errors import DiskFull
from fewear.io import output
from fewear.loop import checkpoint
from fewear.loop.outputs import write_xdmf
from tests.loop.test_checkpoint_integrity import progress


class FullDisk(io.BufferedWriter):
    """A file on a disk with ``room`` bytes left: a write beyond it raises ENOSPC."""

    room = 100

    def write(self, data):
        if len(data) > self.room:
            raise OSError(errno.ENOSPC, "No space left on device")
        return super().write(data)


@pytest.fixture
def full_disk(monkeypatch):
    """The disk is full for fewear's whole-file writes; the unraisable exceptions heard."""
    unraisable = []
    monkeypatch.setattr(sys, "unraisablehook", unraisable.append)
    monkeypatch.setattr(output, "open", lambda path, mode: FullDisk(io.FileIO(path, mode)),
                        raising=False)
    return unraisable


def test_a_full_disk_raises_the_write_error_alone(tmp_path, full_disk):
    target = tmp_path / "rigid.npz"
    arrays = {"x": np.arange(10_000.0), "meta": np.array("{}")}
    with pytest.raises(DiskFull) as error:
        checkpoint.write_npz(target, arrays)
    gc.collect()
    assert error.value.errno == errno.ENOSPC and error.value.filename == str(target)
    assert error.value.needed_bytes > 80_000  # the 10,000 doubles zipped
    assert full_disk == [] and list(tmp_path.iterdir()) == []


def test_a_full_disk_while_writing_the_mesh_snapshots_names_the_file(tmp_path, full_disk):
    with pytest.raises(DiskFull) as error:
        write_xdmf(tmp_path / "rigid-rod_slider.xdmf", progress())
    gc.collect()
    assert error.value.filename == str(tmp_path / "rigid-rod_slider.h5")
    assert error.value.needed_bytes > 3 * 9 * 3 * 8  # three snapshots of 9 nodes x 3 doubles
    assert full_disk == [] and list(tmp_path.iterdir()) == []


def test_with_room_the_files_read_back(tmp_path):
    import meshio

    target = tmp_path / "rigid.npz"
    checkpoint.write_npz(target, {"x": np.arange(5.0)})
    with np.load(target) as data:
        np.testing.assert_array_equal(data["x"], np.arange(5.0))
    assert list(tmp_path.iterdir()) == [target]
    case = progress()
    write_xdmf(tmp_path / "rigid-rod_slider.xdmf", case)
    with meshio.xdmf.TimeSeriesReader(str(tmp_path / "rigid-rod_slider.xdmf")) as reader:
        points, _ = reader.read_points_cells()
        cycles, point_data, _ = reader.read_data(2)
    np.testing.assert_array_equal(points[:, :2], case.snapshots[0])
    assert cycles == 4000
    np.testing.assert_allclose(point_data["mesh_displacement_m"][:, :2],
                               case.snapshots[2] - case.snapshots[0])


def test_the_edge_names_the_output_folder_the_file_and_the_size():
    message = os_error_message(DiskFull("/data/out/.fewear-staging-x1/rigid-rod_slider.h5",
                                        178_944))
    assert message == ("No space left on device: the disk holding /data/out is full (writing "
                       "rigid-rod_slider.h5 needed 178,944 bytes); free some space, or write to "
                       "another --out")
