"""fewear's public Python API: the functions and result types a script or a notebook uses.

Each function does what its command does (the same library path; progress lines go to standard
error as the command's do) and returns the result as data instead of only writing files:

- :func:`run`: the wear prediction of ``fewear run`` -> :class:`RunResult`;
- :func:`solve_contact`: one FE contact solve of ``fewear contact`` -> :class:`ContactResult`;
- :func:`dynamics`: the slider-crank of ``fewear dynamics`` -> :class:`DynamicsResult`;
- :func:`diagnose_data`: the diagnosis of ``fewear diagnose`` -> :class:`Diagnosis`;
- :func:`scar`: the wear scar of ``fewear scar`` -> :class:`ScarResult`;
- :func:`load_config`, :func:`default_config`: the configuration as nested dicts.

A ``config`` argument is a path to a TOML file, a dict of sections (only what differs from the
defaults, as in a file) or None (the embedded defaults, the paper's case). Bad input raises
:class:`fewear.errors.FewearInputError` with a one-line message. Everything here is re-exported
as ``fewear.<name>``; everything not exported here is internal and may change.

The contact and diagnosis functions are not named ``fewear.contact`` and ``fewear.diagnose``:
those names are the packages :mod:`fewear.contact` and :mod:`fewear.diagnose`.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from fewear.contact.result import ContactResult
from fewear.errors import FewearInputError
from fewear.loop.scar import ScarResult

if TYPE_CHECKING:
    from fewear.mbd.history import JointHistory
    from fewear.mbd.slider_crank import RunSummary
    from fewear.wear.state import WearState

__all__ = [
    "ContactResult", "Diagnosis", "DynamicsResult", "RunResult", "ScarResult", "default_config",
    "diagnose_data", "dynamics", "load_config", "run", "scar", "solve_contact",
]

ConfigLike = str | os.PathLike | dict | None


@dataclass(frozen=True)
class RunResult:
    """The wear prediction of every case (rod model) and clearance joint of a run.

    Attributes
    ----------
    wear : dict[str, dict[str, WearState]]
        Case -> joint -> the worn bore after the last block: ``angle_rad`` and ``depth_m`` of the
        bore nodes (m, radial, in the bushing body's frame), ``cycles``, ``blocks``. The paper's
        slider-crank has one joint, ``"rod_slider"``.
    summary : dict
        What ``summary.json`` holds: per case and joint
        (``summary["cases"][case]["joints"][joint]``) the maximum depth and its angle, the worn
        volume, cycles, blocks, wall times; the config used. An ensemble (``[wear_loop] members``
        > 1): ``wear`` and ``cases`` are member 0's (the configured start), and
        ``summary["ensemble"]`` holds the members' statistics and each member's figures
        (:mod:`fewear.loop.outputs`).
    out : Path or None
        The output folder, or None when the outputs were not kept.

    Under ``mpirun`` rank 0 holds the result; the other ranks get empty ``wear`` and
    ``summary``.
    """

    wear: dict[str, dict[str, WearState]]
    summary: dict
    out: Path | None


@dataclass(frozen=True)
class DynamicsResult:
    """The mechanism's recorded cycles.

    Attributes
    ----------
    histories : dict of str to JointHistory
        Each clearance joint (by name, in the mechanism's order) per time step, in its bushing
        body's frame: ``time_s``, ``crank_angle_rad``, ``eccentricity_m``, ``normal_force_N``,
        ``reaction_force_N`` (on the pin), ``mode``, ...
    summary : RunSummary
        Steps, rejected steps, Newton iterations, wall time, smallest step.
    """

    histories: dict[str, JointHistory]
    summary: RunSummary

    @property
    def history(self) -> JointHistory:
        """The first clearance joint's history (the paper's slider-crank has one)."""
        return next(iter(self.histories.values()))


@dataclass(frozen=True)
class Diagnosis:
    """What a wear model gets wrong on measured data.

    Attributes
    ----------
    kind : str
        The data's kind, which chose the diagnosis: ``"tribometer"``, ``"joint"`` or ``"scar"``.
    report : dict
        What ``diagnosis.json`` holds: the verdict, the causes tried, their gains.
    out : Path or None
        The output folder, or None when the outputs were not kept.
    """

    kind: str
    report: dict
    out: Path | None


def default_config() -> dict:
    """The embedded default config (the paper's case) as nested dicts.

    Returns
    -------
    dict
        Section name -> {key: value}, SI units.

    Examples
    --------
    >>> import fewear
    >>> fewear.default_config()["bushing"]["inner_radius_m"]
    0.01
    """
    from fewear.io.config import default_config as embedded

    return embedded()


def load_config(path: str | os.PathLike | None = None) -> dict:
    """A config file's values over the embedded defaults, checked.

    Parameters
    ----------
    path : str, PathLike or None
        A TOML file holding what differs from the defaults; None: the defaults.

    Returns
    -------
    dict
        The complete config, section name -> {key: value}.

    Raises
    ------
    FewearInputError
        The file cannot be read, or names an unknown section or key, or a value of the wrong type
        or beyond a limit.

    Examples
    --------
    >>> import fewear
    >>> fewear.load_config()["mesh"] == fewear.default_config()["mesh"]
    True
    """
    from fewear.io.config import default_config as embedded
    from fewear.io.config import load_config as load

    return load(path, list(embedded()))


def run(config: ConfigLike = None, *, out: str | os.PathLike | None = None,
        resume: bool = False, overwrite: bool = False, jobs: int | None = None) -> RunResult:
    """The wear prediction of ``fewear run``: every rod model of ``[wear_loop]``, block by block.

    Parameters
    ----------
    config : str, PathLike, dict or None
        The run's config (the embedded default: the paper's case, tens of minutes).
    out : str, PathLike or None
        The output folder (the files of ``fewear run``); None: a temporary folder, removed after.
    resume : bool
        Continue the run whose checkpoint is in ``out``.
    overwrite : bool
        Replace an earlier run in ``out`` (without it, a folder holding one is refused).
    jobs : int or None
        Rod models run side by side in worker processes (None: one per rod model, at most the
        CPU cores; 1: one after the other in this process).

    Returns
    -------
    RunResult

    Raises
    ------
    FewearInputError
        A bad config, ``resume`` with ``overwrite``, or ``out`` holding another run.

    Examples
    --------
    >>> result = fewear.run("coarse.toml", out="out/run")  # doctest: +SKIP
    >>> result.wear["rigid"]["rod_slider"].depth_m.max()  # doctest: +SKIP
    """
    from fewear.commands.run import predict_and_write
    from fewear.io.config import load_config as load
    from fewear.loop.outputs import SUMMARY
    from fewear.loop.settings import run_sections

    if resume and overwrite:
        raise FewearInputError("resume and overwrite: choose one")
    loaded = load(config, run_sections())
    with _folder(out) as folder:
        args = argparse.Namespace(out=str(folder), resume=resume, overwrite=overwrite, jobs=jobs,
                                  config=_path_or_none(config))
        cases = predict_and_write(loaded, args)
        summary = json.loads((folder / SUMMARY).read_text()) if cases else {}
    return RunResult({case: {joint: progress.state for joint, progress in joints.items()}
                      for case, joints in cases.items()}, summary,
                     None if out is None else Path(out))


def solve_contact(force_N, *, rotation_rad: float = 0.0, friction: bool = False,
                  config: ConfigLike = None) -> ContactResult:
    """One FE contact solve of ``fewear contact``: the pin in the bushing under a joint force.

    Parameters
    ----------
    force_N : sequence of two floats
        The joint force (FX, FY) on the pin in the bushing frame (N).
    rotation_rad : float
        The pin's rotation increment relative to the bushing (rad): the slip R_p |rotation| of
        the nodes in contact.
    friction : bool
        Add the Coulomb traction mu p against the slip (``[joint] friction_coefficient``; needs a
        non-zero ``rotation_rad``).
    config : str, PathLike, dict or None
        The ``[bushing] [pin] [joint] [mesh] [contact]`` sections (None: the defaults).

    Returns
    -------
    ContactResult
        Per bore node: ``angle_rad``, ``pressure_Pa``, ``gap_m``, ``slip_m``; the pin's centre,
        the resultant force, ``max_pressure_Pa`` and ``contact_half_angle_rad``.

    Raises
    ------
    FewearInputError
        A force that is not finite or below the solver's resolution, friction without rotation,
        a bad config, or a load the bushing cannot carry.

    Examples
    --------
    >>> result = fewear.solve_contact((0.0, -1000.0))  # doctest: +SKIP
    >>> result.max_pressure_Pa  # doctest: +SKIP
    """
    from mpi4py import MPI

    from fewear.commands.contact import checked_force_N, checked_rotation_rad
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.contact.solver import BushingContactSolver
    from fewear.io.config import load_config as load

    force = checked_force_N(force_N)
    rotation = checked_rotation_rad(rotation_rad, friction)
    problem = contact_problem_from_config(load(config, CONFIG_SECTIONS))
    solver = BushingContactSolver(problem, comm=MPI.COMM_WORLD)
    return solver.solve(force, rotation_increment_rad=rotation, friction=friction)


def dynamics(config: ConfigLike = None, *, rod: str | None = None, joint: str | None = None,
             cycles: int | None = None) -> DynamicsResult:
    """The mechanism of ``fewear dynamics``: settling, then the recorded driver cycles.

    Parameters
    ----------
    config : str, PathLike or dict or None
        The mechanism's config (None: the defaults, the paper's slider-crank; ``[mechanism]
        file`` names a mechanism file, docs/mechanisms.md).
    rod : {"rigid", "flexible"} or None
        The model of the mechanism's variable body (the connecting rod; None: the config's).
    joint : {"clearance", "ideal"} or None
        The clearance joints' model (None: the config's).
    cycles : int or None
        Crank cycles recorded after the settling ones (None: the config's).

    Returns
    -------
    DynamicsResult
        Each clearance joint's history over the recorded cycles and the integrator's counts.

    Raises
    ------
    FewearInputError
        A bad config or model name, ``cycles`` out of range, or a mechanism the integrator cannot
        integrate.

    Examples
    --------
    >>> result = fewear.dynamics(joint="ideal", cycles=1)  # doctest: +SKIP
    >>> result.history.reaction_force_N.shape  # doctest: +SKIP
    """
    from fewear.commands.dynamics import simulate
    from fewear.io.config import load_config as load
    from fewear.mbd.slider_crank import SECTIONS

    histories, summary, _ = simulate(load(config, SECTIONS), rod=rod, joint=joint,
                                     cycles=cycles)
    return DynamicsResult(histories, summary)


def diagnose_data(measured, *, config: ConfigLike = None,
                  out: str | os.PathLike | None = None) -> Diagnosis:
    """The diagnosis of ``fewear diagnose``: what a wear model gets wrong on measured data.

    Parameters
    ----------
    measured : str, PathLike or a sequence of them
        Pin-on-disc readings, a measured wear scar, or wear measured on the joint (bore profiles
        and/or maximum-depth growth): the first file's header decides which.
    config : str, PathLike, dict or None
        The believed model and the diagnosis settings (None: the defaults).
    out : str, PathLike or None
        The output folder (the files of ``fewear diagnose``); None: a temporary folder, removed
        after.

    Returns
    -------
    Diagnosis

    Raises
    ------
    FewearInputError
        An unreadable or malformed data file, or a bad config.

    Examples
    --------
    >>> diagnosis = fewear.diagnose_data("readings.csv")  # doctest: +SKIP
    >>> diagnosis.report["verdict"]  # doctest: +SKIP
    """
    from importlib import import_module

    from fewear.commands.diagnose import data_kind

    paths = [measured] if isinstance(measured, (str, os.PathLike)) else list(measured)
    if not paths:
        raise FewearInputError("no measured data file given")
    kind = data_kind(paths[0])
    with _folder(out) as folder:
        args = argparse.Namespace(measured=[str(path) for path in paths], config=config,
                                  out=str(folder))
        import_module(f"fewear.diagnose.{kind}.command").run(args)
        report = json.loads((folder / "diagnosis.json").read_text())
    return Diagnosis(kind, report, None if out is None else Path(out))


def scar(config: ConfigLike = None, *, out: str | os.PathLike | None = None) -> ScarResult:
    """The wear scar of ``fewear scar``: predicted on the flat, beside the measured one(s).

    Parameters
    ----------
    config : str, PathLike, dict or None
        ``[scar] case`` ("block_on_ring", the default, or "fretting") and its sections.
    out : str, PathLike or None
        The output folder (the files of ``fewear scar``); None: nothing written.

    Returns
    -------
    ScarResult
        The worn flat (``state.x_m``, ``state.depth_m``), the measured profiles and the summary
        (depths, widths, worn areas, predicted and measured).

    Raises
    ------
    FewearInputError
        A bad config (an unknown case, a contact zone too small for the scar, ...).

    Examples
    --------
    >>> result = fewear.scar()  # doctest: +SKIP
    >>> result.summary["predicted"]["max_depth_m"]  # doctest: +SKIP
    """
    from mpi4py import MPI

    from fewear.commands.scar import predict_and_write
    from fewear.io.config import load_config as load
    from fewear.loop.scar import SCAR_SECTIONS, predict_scar, scar_case_from_config

    comm = MPI.COMM_WORLD
    loaded = load(config, SCAR_SECTIONS)
    if out is not None:
        return predict_and_write(loaded, out, comm)
    return predict_scar(scar_case_from_config(loaded), loaded, comm, _say("fewear scar"))


def _say(prefix: str):
    def say(text: str) -> None:
        print(f"{prefix}: {text}", file=sys.stderr, flush=True)
    return say


def _path_or_none(config: ConfigLike) -> str | None:
    """The config's file for the commands' messages (a dict has none)."""
    return None if config is None or isinstance(config, dict) else str(config)


class _folder:
    """``out`` as a Path, or a temporary folder (removed on leaving) when ``out`` is None."""

    def __init__(self, out):
        self.out, self.temporary = out, None

    def __enter__(self) -> Path:
        if self.out is not None:
            return Path(self.out)
        self.temporary = tempfile.TemporaryDirectory(prefix="fewear-")
        return Path(self.temporary.name) / "out"

    def __exit__(self, *exc) -> None:
        if self.temporary is not None:
            self.temporary.cleanup()
