"""Files of ``fewear contact``: the bore field (CSV), a summary (JSON) and the FE fields (XDMF).

CSV and JSON are written by rank 0 from the plain :class:`fewear.contact.result.ContactResult`
(every rank holds the whole bore); the XDMF file is written collectively by all ranks with
``dolfinx.io.XDMFFile``. DOLFINx is imported only inside :func:`write_fields_xdmf`.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any

import numpy as np

from fewear.contact.analytic import HertzLineContact, cosine_law_pressure_Pa
from fewear.errors import DiskFull

CSV_COLUMNS = ("angle_deg", "x_m", "y_m", "pressure_Pa", "gap_m", "slip_m")


def write_contact_csv(path: Path, result) -> None:
    """One row per bore node, sorted by angle: angle (deg), position (m), pressure (Pa), gap (m),
    slip increment (m)."""
    columns = (
        np.degrees(result.angle_rad), result.x_m, result.y_m,
        result.pressure_Pa, result.gap_m, result.slip_m,
    )
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(CSV_COLUMNS)
        for row in zip(*columns):
            writer.writerow([repr(float(value)) for value in row])


def contact_summary(
    result, hertz: HertzLineContact, config: dict, timings_s: dict[str, float], ranks: int,
    rotation_rad: float = 0.0, friction: bool = False,
) -> dict[str, Any]:
    """The figures of one contact solve, with the analytic references beside them (SI units).

    The Hertz and cosine-law references are frictionless; with friction they are only a guide.
    """
    force = np.asarray(result.applied_force_N, dtype=float)
    load_angle = math.atan2(force[1], force[0])
    geometry_radius = hertz.bore_radius_m
    cosine_peak = float(cosine_law_pressure_Pa(
        np.array([load_angle]), load_angle, hertz.force_N, geometry_radius, hertz.width_m)[0])
    return {
        "max_pressure_Pa": float(result.max_pressure_Pa),
        "contact_half_angle_deg": math.degrees(result.contact_half_angle_rad),
        "pin_centre_m": [float(value) for value in result.pin_centre_m],
        "force_balance_rel_error": float(result.force_balance_rel_error),
        "applied_force_N": force.tolist(),
        "resultant_force_N": [float(value) for value in result.resultant_force_N],
        "load_angle_deg": math.degrees(load_angle),
        "rotation_increment_rad": float(rotation_rad),
        "friction": bool(friction),
        "max_slip_m": float(np.max(result.slip_m)) if result.slip_m.size else 0.0,
        "newton_iterations": int(result.newton_iterations),
        "bore_nodes": int(len(result.angle_rad)),
        "wall_time_s": timings_s,
        "mpi_ranks": ranks,
        "references": {
            "hertz": {
                "source": "Johnson, Contact Mechanics 1985, ch. 4; rigid pin; valid if a << R_b",
                "contact_modulus_Pa": hertz.contact_modulus_Pa,
                "relative_radius_m": hertz.relative_radius_m,
                "line_load_N_per_m": hertz.line_load_N_per_m,
                "half_width_m": hertz.half_width_m,
                "peak_pressure_Pa": hertz.peak_pressure_Pa,
                "contact_half_angle_deg": math.degrees(hertz.contact_half_angle_rad),
            },
            "cosine_law": {
                "source": "conformal limit p = 2F/(pi R_b L) cos(theta); Persson (1964)",
                "peak_pressure_Pa": cosine_peak,
                "contact_half_angle_deg": 90.0,
            },
        },
        "config": config,
    }


def write_fields_xdmf(path: Path, displacement, pressure) -> None:
    """Displacement (m) and contact pressure (Pa) on the bushing mesh, for ParaView (collective).

    XDMF stores one value per geometry node, so each field is interpolated into the Lagrange space
    of the mesh's coordinate degree (Q2 on the 9-node quads): the serendipity dofs of the
    displacement are not nodal values.
    """
    from dolfinx import fem, io

    mesh = displacement.function_space.mesh
    degree = mesh.geometry.cmap.degree
    nodal_displacement = fem.Function(
        fem.VectorFunctionSpace(mesh, ("Lagrange", degree)), name="displacement_m")
    nodal_displacement.interpolate(displacement)
    nodal_pressure = fem.Function(fem.FunctionSpace(mesh, ("Lagrange", degree)), name="pressure_Pa")
    nodal_pressure.interpolate(pressure)
    needed_bytes = xdmf_bytes(mesh)
    h5_path = Path(path).with_suffix(".h5")
    if mesh.comm.bcast(_free_bytes(path) < needed_bytes if mesh.comm.rank == 0 else None):
        raise DiskFull(h5_path, needed_bytes)
    try:
        with io.XDMFFile(mesh.comm, str(path), "w") as xdmf:
            xdmf.write_mesh(mesh)
            xdmf.write_function(nodal_displacement)
            xdmf.write_function(nodal_pressure)
    except RuntimeError:
        if _free_bytes(path) < needed_bytes:  # the disk filled up while it was written
            raise DiskFull(h5_path, needed_bytes) from None
        raise


def xdmf_bytes(mesh) -> int:
    """About the size (bytes) of :func:`write_fields_xdmf`'s HDF5 file: per geometry node its
    x, y, the displacement (3 components) and the pressure, per cell 9 node numbers, all 8
    bytes, and 16 kB of headers (measured: 515,592 bytes on the default mesh, this 524,416)."""
    nodes = mesh.geometry.index_map().size_global
    cells = mesh.topology.index_map(mesh.topology.dim).size_global
    return 8 * (6 * nodes + 9 * cells) + 16_384


def _free_bytes(path: Path) -> int:
    """The bytes free on the disk holding ``path``'s folder. HDF5 writing onto a full disk
    printed pages of its diagnostics and a traceback: the write is not started without room."""
    import shutil

    return shutil.disk_usage(Path(path).parent).free
