"""`fewear plot` on files that are not a run's worn bushing (issue 57): a corrupted ``.h5``
(connectivity beyond the nodes crashed VTK with a segmentation fault), a NaN field, a
`fewear contact` folder (KeyError 'mesh_displacement_m'): one line naming the file, exit 2,
checked before VTK sees the arrays."""

import contextlib

import numpy as np
import pytest

from fewear.cli import main

# one biquadratic quadrilateral: the unit square, corners, mid-sides, centre (VTK order)
POINTS = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, 0], [1, 0.5, 0],
                   [0.5, 1, 0], [0, 0.5, 0], [0.5, 0.5, 0]], dtype=float)
CELLS = np.arange(9)[None, :]


def write_bushing(path, cells=CELLS, displacement=None, fields=("mesh_displacement_m",
                                                              "radial_displacement_m")):
    import meshio

    displacement = np.zeros((9, 3)) if displacement is None else displacement
    data = {"mesh_displacement_m": displacement, "radial_displacement_m": displacement[:, 0]}
    with contextlib.chdir(path.parent), meshio.xdmf.TimeSeriesWriter(path.name) as writer:
        writer.write_points_cells(POINTS, [("quad9", cells)])
        writer.write_data(0.0, point_data={name: data[name] for name in fields})
    return path


def plot_error(folder, capsys) -> str:
    assert main(["plot", str(folder)]) == 2
    err = capsys.readouterr().err
    (line,) = err.strip().splitlines()
    assert line.startswith("fewear: error:") and "Traceback" not in err
    return line


@pytest.mark.parametrize("cells, message", [
    (np.array([[0, 1, 2, 3, 4, 5, 6, 7, 90000]]), "its cells name nodes outside [0, 9)"),
    (np.array([[0, 1, 2, 3, 4, 5, 6, 7, -3]]), "its cells name nodes outside [0, 9)"),
])
def test_connectivity_beyond_the_nodes_is_refused_before_vtk(tmp_path, capsys, cells, message):
    path = write_bushing(tmp_path / "rigid-a.xdmf", cells=cells)
    line = plot_error(tmp_path, capsys)
    assert str(path) in line and message in line and "damaged" in line


def test_a_field_of_nan_is_refused(tmp_path, capsys):
    displacement = np.zeros((9, 3))
    displacement[4, 1] = np.nan
    write_bushing(tmp_path / "rigid-a.xdmf", displacement=displacement)
    assert "its mesh_displacement_m (shape (9, 3)) is not a finite field on its 9 nodes" in \
        plot_error(tmp_path, capsys)


def test_a_run_file_without_the_fields_names_them(tmp_path, capsys):
    write_bushing(tmp_path / "rigid-a.xdmf", fields=("radial_displacement_m",))
    assert "no mesh_displacement_m" in plot_error(tmp_path, capsys)


def test_a_contact_folder_is_no_run_to_plot(tmp_path, capsys):
    write_bushing(tmp_path / "bushing.xdmf", fields=())
    line = plot_error(tmp_path, capsys)
    assert "no <case>-<joint>.xdmf of a `fewear run` to plot" in line
    assert "bushing.xdmf is a `fewear contact` output" in line


def test_flipped_bytes_in_the_h5_end_in_a_message_or_a_figure(tmp_path):
    """Every 7th byte of the topology's and the fields' data flipped in turn (the header
    intact): the reader gives a sound block or a message naming the file; and `fewear plot` on
    a sample of the flips that read as sound draws or refuses in one line, never a crash (each
    in its own process, as a user's would be)."""
    import subprocess
    import sys

    from fewear.errors import FewearInputError
    from fewear.plot.worn_bushing import last_block

    path = write_bushing(tmp_path / "rigid-a.xdmf", displacement=np.full((9, 3), 1e-6))
    h5 = next(tmp_path.glob("*.h5"))
    intact = h5.read_bytes()
    sound = []
    for position in range(len(intact) - 800, len(intact), 7):
        changed = bytearray(intact)
        changed[position] ^= 0xFF
        h5.write_bytes(bytes(changed))
        try:
            last_block(path)
            sound.append(bytes(changed))
        except FewearInputError as exc:
            assert str(path) in str(exc)
    assert sound  # flips in the fields' low bits read as (slightly other) sound bushings
    for changed in (sound[0], sound[-1]):
        h5.write_bytes(changed)
        done = subprocess.run([sys.executable, "-m", "fewear.cli", "plot", str(tmp_path)],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode in (0, 2) and "Traceback" not in done.stderr, done.stderr
