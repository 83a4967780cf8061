"""The ``fewear`` command line's entry point: the argument parser and the edge where failures
become one line; the subcommands are the modules of :mod:`fewear.commands`.

Bad input is reported as ``fewear: error: <message>`` on standard error with exit status 2 and no
traceback; the stage modules raise :class:`fewear.errors.FewearInputError` for it. Handlers are
imported lazily so that, e.g., ``fewear dynamics`` never imports DOLFINx.
"""

from __future__ import annotations

import argparse
import errno
import importlib
import os
import signal
import sys

from fewear import __version__
from fewear.errors import (
    FewearInputError,
    Terminated,
    has_interrupt_note,
    interrupt_note,
    one_line,
    set_interrupt_note,
)
from fewear.parallel import launcher_rank_and_size

# subcommand -> "module:function" that takes the parsed arguments and returns an exit status
HANDLERS = {
    "config": "fewear.commands.config:main",
    "contact": "fewear.commands.contact:main",
    "dynamics": "fewear.commands.dynamics:main",
    "diagnose": "fewear.commands.diagnose:main",
    "run": "fewear.commands.run:main",
    "plot": "fewear.commands.plot:main",
    "scar": "fewear.commands.scar:main",
}


class _Parser(argparse.ArgumentParser):
    """argparse with the edge's one-line errors: ``fewear: error: <what>; see <command> --help``
    (exit status 2) instead of the usage block."""

    def error(self, message: str):
        _report("error", f"{self.prog}: {message}; see `{self.prog} --help`", 2)
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="fewear",
        description="Finite-element wear workbench for revolute clearance joints.",
    )
    parser.add_argument("--version", action="version", version=f"fewear {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND",
                                parser_class=_Parser)

    config = sub.add_parser("config", help="print the embedded default config (TOML)")
    config.add_argument("--out", metavar="FILE.toml", help="write it to FILE instead of stdout")

    contact = sub.add_parser("contact", help="pin-in-bushing FE contact for one joint force")
    contact.add_argument("--force", nargs=2, type=float, required=True, metavar=("FX", "FY"),
                         help="joint force on the pin in the bushing frame (N)")
    contact.add_argument("--rotation", type=float, default=0.0, metavar="RAD",
                         help="rotation increment of the pin relative to the bushing (rad): the "
                              "slip R_p |RAD| of the nodes in contact (default 0)")
    contact.add_argument("--friction", action="store_true",
                         help="add the Coulomb traction mu p against the slip ([joint] "
                              "friction_coefficient; needs --rotation)")
    _add_config_and_out(contact, "out/contact")
    _add_overwrite(contact)

    dynamics = sub.add_parser("dynamics", help="slider-crank dynamics with a clearance joint")
    dynamics.add_argument("--rod", choices=["rigid", "flexible"], default=None,
                          help="connecting rod model (default: the config's)")
    dynamics.add_argument("--joint", choices=["clearance", "ideal"], default=None,
                          help="rod-slider joint model (default: the config's)")
    dynamics.add_argument("--cycles", type=int, default=None, metavar="N",
                          help="crank cycles recorded after the settling cycles "
                               "(default: the config's)")
    _add_config_and_out(dynamics, "out/dynamics")
    _add_overwrite(dynamics)

    diagnose = sub.add_parser("diagnose", help="what a wear model gets wrong on measured data")
    diagnose.add_argument("measured", metavar="MEASURED.csv", nargs="+",
                          help="pin-on-disc readings, a measured wear scar (x_mm and heights "
                               "in um), or wear measured on the joint (bore profiles and/or "
                               "maximum-depth growth, with the model as --config)")
    _add_config_and_out(diagnose, "out/diagnose")
    _add_overwrite(diagnose)

    run = sub.add_parser("run", help="the paper's slider-crank wear prediction (main job)")
    _add_config_and_out(run, "out/run")
    run.add_argument("--resume", action="store_true",
                     help="continue the run whose checkpoint is in --out (same config)")
    run.add_argument("--overwrite", action="store_true",
                     help="replace an earlier run (checkpoint and outputs) in --out; without it "
                          "a run refuses a folder that holds one. The earlier run is kept "
                          "aside until the new one completes, and restored if it fails")
    run.add_argument("--jobs", type=int, default=None, metavar="N",
                     help="rod models run side by side in worker processes (default: one per "
                          "rod model, at most the CPU cores; 1: one after the other in this "
                          "process). Under mpirun the ranks are split among the rod models "
                          "instead, and a rod model's ranks among its clearance joints. With "
                          "--members, among the members of every rod model")
    run.add_argument("--members", type=int, default=None, metavar="N",
                     help="an ensemble: N runs of every rod model, member m with the crank (a "
                          "mechanism file's drivers) started m degrees further on; the run "
                          "writes the members' mean, standard deviation and range beside each "
                          "member's result (default: [wear_loop] members, 1)")
    run.add_argument("--joint-history", metavar="FILE.csv", default=None,
                     help="wear one bushing (the config's joint sections) with a joint history "
                          "made elsewhere instead of the dynamics, the same history every block, "
                          "no feedback ([wear_loop] joint_history). CSV, units in the header: "
                          "time_<s|ms>; force_x_<N|kN>, force_y_<N|kN> on the pin in the "
                          "bushing's frame, or global_force_x_, global_force_y_ with "
                          "bushing_angle_<rad|deg>; relative_angle_<rad|deg> or "
                          "relative_omega_<rad_s|deg_s|rpm> (pin minus bushing); optional "
                          "crank_angle_, eccentricity_x_/_y_ and penetration_<m|mm|um>, "
                          "normal_force_, friction_force_, mode. Spans recorded_cycles_per_block "
                          "whole cycles. `fewear dynamics` writes one")

    scar = sub.add_parser("scar", help="a block-on-ring or fretting wear scar beside the "
                                       "measured one(s)")
    _add_config_and_out(scar, "out/scar")
    _add_overwrite(scar)

    plot = sub.add_parser("plot", help="PyVista view of a run's worn bushing, coloured by depth")
    plot.add_argument("folder", metavar="DIR", help="the output folder of `fewear run`")
    plot.add_argument("--joint", metavar="NAME", default=None,
                      help="only this clearance joint (default: a row of panels per joint)")
    return parser


def _add_config_and_out(parser: argparse.ArgumentParser, default_out: str) -> None:
    parser.add_argument("--config", metavar="FILE.toml", default=None,
                        help="configuration (default: the embedded paper case; `fewear config`)")
    parser.add_argument("--out", metavar="DIR", default=default_out,
                        help=f"output folder (default: {default_out})")


def _add_overwrite(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--overwrite", action="store_true",
                        help="replace another command's results in --out (without it, a folder "
                             "that holds them is refused); they are removed once this "
                             "command's outputs are written")


def output_folder_of(args: argparse.Namespace):
    """The transaction on the folder the command writes (:func:`fewear.io.transaction.
    output_folder`): ``--out``, or the folder ``fewear plot`` writes its figure into."""
    from contextlib import nullcontext

    from fewear.io.transaction import output_folder

    if args.command == "plot":
        return output_folder(args.folder, "plot", required=False)
    if args.command == "config":
        return nullcontext()
    comm = None
    if launcher_rank_and_size()[1] > 1:
        from mpi4py import MPI

        comm = MPI.COMM_WORLD
    return output_folder(args.out, args.command, getattr(args, "overwrite", False), comm)


def main(argv: list[str] | None = None) -> int:
    """The command line's edge: every failure a user can cause ends here as one line on stderr.

    - bad input (:class:`FewearInputError`): ``fewear: error: ...``, exit status 2;
    - a file or folder the OS refuses (permissions, a full disk, ...): the same, naming the path;
    - Ctrl-C (exit status 130), SIGTERM (143) or SIGHUP (129): ``fewear: interrupted: ...``
      saying what was kept and how to go on (:func:`fewear.errors.set_interrupt_note`); the
      command's staging folder is removed on the way out, as for any failure.
    """
    args = build_parser().parse_args(argv)
    module_name, function_name = HANDLERS[args.command].split(":")
    set_interrupt_note(None)
    _without_petsc_signal_handlers()
    previous = _terminate_as_exception()
    try:
        handler = getattr(importlib.import_module(module_name), function_name)
        with output_folder_of(args):
            return int(handler(args) or 0)
    except FewearInputError as exc:
        message = naming_the_config(one_line(str(exc)), getattr(args, "config", None))
        return _report("error", message, 2)
    except OSError as exc:
        kept = interrupt_note() if has_interrupt_note() else ""
        return _report("error", os_error_message(exc) + (f"; {kept}" if kept else ""), 2)
    except (OverflowError, FloatingPointError) as exc:
        if getattr(args, "config", None) is None:
            raise  # the embedded defaults overflowed: a bug, not an input
        return _report("error", f"config {args.config}: a value is beyond what the computation "
                       f"can carry ({exc}); compare your values with `fewear config`", 2)
    except (KeyboardInterrupt, Terminated) as exc:
        return _report("interrupted", f"{interruption_name(exc)}: {interrupt_note()}",
                       130 if isinstance(exc, KeyboardInterrupt) else _signal_status(str(exc)))
    finally:
        set_interrupt_note(None)
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def naming_the_config(message: str, path: str | None) -> str:
    """``message`` prefixed with ``config PATH:`` when it is about a value of the user's config
    (``key = value`` of a config key) and does not name the file yet: the stages' checks name the
    section and key, the edge adds the file."""
    import re

    from fewear.io.config import default_config

    if path is None or str(path) in message:
        return message
    keys = {key for table in default_config().values() for key in table}
    named = re.findall(r"([A-Za-z_][A-Za-z0-9_]*)\]? =", message)
    return f"config {path}: {message}" if any(key in keys for key in named) else message


def _report(kind: str, message: str, status: int) -> int:
    if launcher_rank_and_size()[0] == 0:
        print(f"fewear: {kind}: {one_line(message)}", file=sys.stderr, flush=True)
    return status


def os_error_message(exc: OSError) -> str:
    """An OS error (permission, full disk, missing file, ...) as a sentence naming the path."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    paths = [str(path) for path in (exc.filename, exc.filename2) if path]
    if exc.errno == errno.ENOSPC:
        return disk_full_message(paths[0] if paths else None, getattr(exc, "needed_bytes", None))
    unwritable = (errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOTDIR)
    cache = jit_cache_holding(paths[0]) if paths and exc.errno in unwritable else None
    if cache is not None:
        return (f"DOLFINx's JIT cache folder {cache}, where it compiles the finite-element "
                f"forms, cannot be written ({paths[0]}: {reason}); make it writable, or set "
                "XDG_CACHE_HOME to a writable folder (the cache is $XDG_CACHE_HOME/fenics)")
    if exc.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        reason += " (choose a folder you may write to, or change its permissions)"
    return f"{' -> '.join(paths)}: {reason}" if paths else reason


def jit_cache_holding(path: str):
    """DOLFINx's JIT cache folder (``$XDG_CACHE_HOME/fenics`` unless its parameters say
    otherwise) when ``path`` is in it or on the way to it, else None. (DOLFINx is imported here
    if it is not yet: the error may come from a worker process.)"""
    from pathlib import Path

    try:
        from dolfinx.jit import get_parameters

        cache = Path(get_parameters()["cache_dir"]).absolute()
    except Exception:  # noqa: BLE001 (no DOLFINx, or a broken parameters file: no cache to name)
        return None
    path = Path(path).absolute()
    return cache if path == cache or cache in path.parents or path in cache.parents else None


def disk_full_message(path: str | None, needed_bytes: int | None) -> str:
    """No space left: on the disk holding the folder of ``path`` (its command's staging folder
    left out: the user knows the output folder), writing which file, how many bytes it needed."""
    if path is None:
        return ("No space left on device: the disk is full; free some space, or write to "
                "another --out")
    from pathlib import Path

    folder = Path(path).parent
    while folder.name.startswith(".fewear-") and folder.parent != folder:
        folder = folder.parent
    needed = f" needed {needed_bytes:,} bytes" if needed_bytes is not None else ""
    return (f"No space left on device: the disk holding {folder} is full (writing "
            f"{Path(path).name}{needed}); free some space, or write to another --out")


def interruption_name(exc: BaseException) -> str:
    """What stopped the command, in words: Ctrl-C, or the signal's name. Under ``mpirun`` the
    ranks never see Ctrl-C: Open MPI's mpirun (4.1) answers SIGINT and SIGTERM alike by sending
    SIGTERM to every rank (each rank runs in its own process group, out of the terminal's
    reach), so a rank's SIGTERM is named as either (the ranks exit with 143, mpirun with 1)."""
    if isinstance(exc, KeyboardInterrupt):
        return "Ctrl-C"
    name = str(exc) or "SIGTERM"
    if name == "SIGTERM" and launcher_rank_and_size()[1] > 1:
        return "SIGTERM (which mpirun also sends on Ctrl-C)"
    return name


def _signal_status(name: str) -> int:
    """The exit status of a command ended by signal ``name``: 128 + its number (SIGTERM: 143,
    SIGHUP: 129), as a shell reports it."""
    try:
        return 128 + signal.Signals[name].value
    except KeyError:
        return 128 + signal.SIGTERM.value


def _without_petsc_signal_handlers() -> None:
    """PETSc's own handlers (installed when it starts, over Python's) would turn SIGHUP into its
    "Caught signal" banner and MPI_ABORT; with this option Python's handlers stay."""
    options = os.environ.get("PETSC_OPTIONS", "")
    if "-no_signal_handler" not in options.split():
        os.environ["PETSC_OPTIONS"] = f"{options} -no_signal_handler".strip()


def _terminate_as_exception() -> dict:
    """SIGTERM and SIGHUP raise :class:`Terminated` (so the command unwinds and cleans up, like
    Ctrl-C); the previous handlers, to restore. Only the main thread may set handlers."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        return {}

    def terminate(signum, frame):
        raise Terminated(signal.Signals(signum).name)

    previous = {}
    for signum in (signal.SIGTERM, signal.SIGHUP):
        previous[signum] = signal.signal(signum, terminate)
    return previous


if __name__ == "__main__":
    sys.exit(main())
