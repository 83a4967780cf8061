"""``fewear dynamics``: simulate the mechanism ([mechanism]: the paper's slider-crank, or a
mechanism file) and write the joint-load history of each clearance joint.

Outputs (all-or-nothing, in ``--out``): ``joint_history.csv`` (one row per time step of the
recorded cycles, in the form ``fewear run --joint-history`` reads: :mod:`fewear.io.joint_history`;
see fewear.mbd.history for frames and signs),
``summary.json`` (peak_contact_force_N, impacts, steps, wall_time_s, ... and the config used),
``forces.png`` and ``orbit.png``; with several clearance joints, ``joint_history_<joint>.csv``
and ``orbit_<joint>.png`` for each, and the summary's top-level figures are the first joint's
(all in ``joints``). A line per crank cycle goes to standard error.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.joint_history import write_joint_history
from fewear.io.limits import MAX_DYNAMICS_CYCLES
from fewear.io.mechanism import dynamics_inputs
from fewear.io.output import staged_output
from fewear.mbd.history import MODES, JointHistory
from fewear.mbd.mechanism import simulate as simulate_mechanism
from fewear.mbd.slider_crank import SECTIONS, UNINTEGRABLE_HINT


def main(args) -> int:
    config = load_config(args.config, SECTIONS)
    histories, summary, inputs = simulate(config, rod=args.rod, joint=args.joint,
                                          cycles=args.cycles, progress=True)
    used = {name: dict(table) for name, table in config.items()}
    for key, value in (("rod", args.rod), ("joint", args.joint),
                       ("recorded_cycles", args.cycles)):
        if value is not None:
            used["mechanism"][key] = value
    several = len(histories) > 1
    figures = {name: _figures(history) for name, history in histories.items()}
    with staged_output(args.out) as stage:
        for name, history in histories.items():
            write_joint_history(history, stage / (f"joint_history_{name}.csv" if several
                                                 else "joint_history.csv"))
        report = {
            **next(iter(figures.values()), {}),
            "steps": summary.steps,
            "rejected_steps": summary.rejected_steps,
            "newton_iterations": summary.newton_iterations,
            "wall_time_s": summary.wall_time_s,
            "wall_time_per_cycle_s": summary.wall_time_per_cycle_s,
            "smallest_step_s": summary.smallest_step_s,
            "joints": figures,
            "config": used,
        }
        (stage / "summary.json").write_text(json.dumps(report, indent=2) + "\n")
        from fewear.plot.dynamics import plot_forces, plot_orbit

        label = f"{used['mechanism']['rod']} rod, {used['mechanism']['joint']} joint"
        if inputs.mechanism.variable_body not in (None, "rod"):
            label = f"{used['mechanism']['rod']} {inputs.mechanism.variable_body}"
        plot_forces({f"{name}: {label}" if several else label: history
                     for name, history in histories.items()}, stage / "forces.png")
        for name, history in histories.items():
            plot_orbit(history, inputs.joints[name].nominal_clearance_m,
                       stage / (f"orbit_{name}.png" if several else "orbit.png"),
                       f"{name}: {label}" if several else label)
    return 0


def simulate(config: dict, rod: str | None = None, joint: str | None = None,
             cycles: int | None = None, progress: bool = False):
    """(histories per clearance joint, RunSummary, MechanismInputs) of the mechanism of
    ``config`` (loaded), the case (``rod``: the variable body's model), the joint models and the
    recorded cycles overridden when given; a collapsed step size is an input error.
    :func:`fewear.api.dynamics` calls it too."""
    if cycles is not None and not 1 <= cycles <= MAX_DYNAMICS_CYCLES:
        raise FewearInputError(f"--cycles {cycles}: expected a whole number from 1 to "
                               f"{MAX_DYNAMICS_CYCLES:,} (crank cycles, a few seconds each)")
    inputs = dynamics_inputs(config, rod)
    if joint is not None:
        inputs = replace(inputs, ideal_joints=joint == "ideal")
    if cycles is not None:
        inputs = replace(inputs, recorded_cycles=cycles)
    try:
        histories, summary, _ = simulate_mechanism(inputs, progress=progress)
    except RuntimeError as exc:  # the integrator's step size collapsed
        raise FewearInputError(
            f"the dynamics cannot integrate this mechanism ({exc}): {UNINTEGRABLE_HINT}; a "
            "smaller [integrator] min_step_s or a larger gap_tolerance_m may get past it") from None
    return histories, summary, inputs


def _figures(history: JointHistory) -> dict:
    """A joint's summary figures."""
    return {"peak_contact_force_N": history.peak_contact_force_N, "impacts": history.impacts,
            "recorded_steps": history.n_steps,
            "mode_fractions": {name: float(np.mean(history.mode == code))
                               for code, name in enumerate(MODES)}}


