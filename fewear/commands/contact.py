"""``fewear contact --force FX FY [--rotation RAD [--friction]] [--config FILE.toml] [--out DIR]``.

One FE contact solve. Reads the ``[bushing] [pin] [joint] [mesh] [contact]`` sections, solves the
pin-in-bushing contact for the joint force on the pin (N, bushing frame) and the pin's rotation
increment relative to the bushing (rad; it sets the slip, and with ``--friction`` the Coulomb
traction) with the full DOLFINx solver, and writes, all or nothing
(:func:`fewear.io.output.staged_output`):

- ``contact.csv``  bore nodes sorted by angle: angle_deg, x_m, y_m, pressure_Pa, gap_m, slip_m;
- ``summary.json`` peak pressure, contact half-angle, pin centre, force-balance error, Newton
  iterations, wall times, the Hertz and cosine-law references and the config used;
- ``bushing.xdmf`` (+ ``.h5``) displacement and pressure fields for ParaView (written by all ranks);
- ``pressure.png`` pressure against angle with the Hertz curve, and the bushing cross-section.

Runs under ``mpirun -n N``; only rank 0 writes CSV, JSON and PNG.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

from fewear.errors import FewearInputError
from fewear.io.limits import MIN_FORCE_N


def checked_force_N(force: list[float] | tuple[float, float]) -> tuple[float, float]:
    """The joint force (FX, FY) in N; both components must be finite numbers."""
    force_x, force_y = (float(value) for value in force)
    for name, value in (("FX", force_x), ("FY", force_y)):
        if not math.isfinite(value):
            raise FewearInputError(
                f"--force {name} = {value!r} N: expected a finite number of newtons")
    magnitude = math.hypot(force_x, force_y)
    if 0.0 < magnitude < MIN_FORCE_N:
        raise FewearInputError(
            f"--force {force_x!r} {force_y!r}: |F| = {magnitude:.3g} N is below {MIN_FORCE_N:g} N, "
            "a load whose contact the model cannot resolve (the pin's approach is below the "
            f"solver's tolerance); give 0 0 for no load, or at least {MIN_FORCE_N:g} N")
    return force_x, force_y


MAX_ROTATION_RAD = 4.0 * math.pi
"""A rotation increment beyond two turns is no step of a joint's motion (1e300 rad wrote a slip
of 9.5e297 m)."""


def checked_rotation_rad(rotation: float, friction: bool) -> float:
    """The pin's rotation increment (rad): finite, and non-zero when friction is asked for."""
    rotation = float(rotation)
    if not (math.isfinite(rotation) and abs(rotation) <= MAX_ROTATION_RAD):
        raise FewearInputError(
            f"--rotation = {rotation!r} rad: expected a finite increment of at most "
            f"{MAX_ROTATION_RAD:.3g} rad (two turns) either way: one step's rotation of the pin "
            "in the bushing")
    if friction and rotation == 0.0:
        raise FewearInputError(
            "--friction needs a non-zero --rotation: the Coulomb traction opposes the slip")
    return rotation


def main(args: argparse.Namespace) -> int:
    from mpi4py import MPI

    from fewear.contact.analytic import hertz_reference
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.io.config import load_config
    from fewear.io.output import staged_output

    comm = MPI.COMM_WORLD
    force_N = checked_force_N(args.force)
    rotation_rad = checked_rotation_rad(args.rotation, args.friction)
    config = load_config(args.config, CONFIG_SECTIONS)
    problem = contact_problem_from_config(config)
    hertz = hertz_reference(problem, math.hypot(*force_N))
    if comm.rank == 0:
        from fewear.io.limits import mesh_size

        print(f"fewear contact: meshing the bushing (about {mesh_size(config)[1]:,} "
              "quadrilaterals) and solving the contact", file=sys.stderr, flush=True)
    with staged_output(args.out, comm) as stage:
        solver, result, timings_s = _solve(problem, force_N, rotation_rad, args.friction, comm)
        _write_outputs(stage, solver, result, hertz, config, timings_s, rotation_rad,
                       args.friction, comm)
    return 0


def _solve(problem, force_N, rotation_rad, friction, comm):
    from fewear.contact.solver import BushingContactSolver

    start = time.perf_counter()
    solver = BushingContactSolver(problem, comm=comm)
    built = time.perf_counter()
    result = solver.solve(force_N, rotation_increment_rad=rotation_rad, friction=friction)
    solved = time.perf_counter()
    timings_s = {"mesh_and_setup": built - start, "solve": solved - built}
    return solver, result, timings_s


def _write_outputs(stage, solver, result, hertz, config, timings_s, rotation_rad, friction,
                   comm) -> None:
    from fewear.contact.output import (
        contact_summary,
        write_contact_csv,
        write_fields_xdmf,
    )
    from fewear.io.output import write_json
    from fewear.plot.contact import plot_contact_pressure

    write_fields_xdmf(stage / "bushing.xdmf", solver.displacement, solver.pressure_function())
    if comm.rank == 0:
        write_contact_csv(stage / "contact.csv", result)
        write_json(stage / "summary.json", contact_summary(
            result, hertz, config, timings_s, comm.size, rotation_rad, friction))
        plot_contact_pressure(stage / "pressure.png", result, hertz,
                              title=f"fewear contact, F = ({result.applied_force_N[0]:g}, "
                                    f"{result.applied_force_N[1]:g}) N")
