"""``fewear dynamics``: simulate the slider-crank and write the joint-load history.

Outputs (all-or-nothing, in ``--out``): ``joint_history.csv`` (one row per time step of the
recorded cycles, in the form ``fewear run --joint-history`` reads: :mod:`fewear.io.joint_history`;
see fewear.mbd.history for frames and signs),
``summary.json`` (peak_contact_force_N, impacts, steps, wall_time_s, ... and the config used),
``forces.png`` and ``orbit.png``. A line per crank cycle goes to standard error.
"""

from __future__ import annotations

import json

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.joint_history import write_joint_history
from fewear.io.limits import MAX_DYNAMICS_CYCLES
from fewear.io.output import staged_output
from fewear.mbd.history import MODES
from fewear.mbd.slider_crank import (
    SECTIONS,
    UNINTEGRABLE_HINT,
    joint_model_from_config,
    simulate_slider_crank,
)


def main(args) -> int:
    config = load_config(args.config, SECTIONS)
    if args.cycles is not None and not 1 <= args.cycles <= MAX_DYNAMICS_CYCLES:
        raise FewearInputError(f"--cycles {args.cycles}: expected a whole number from 1 to "
                               f"{MAX_DYNAMICS_CYCLES:,} (crank cycles, a few seconds each)")
    joint_model = joint_model_from_config(config)
    try:
        history, summary = simulate_slider_crank(config, rod=args.rod, joint=args.joint,
                                                 cycles=args.cycles, progress=True)
    except RuntimeError as exc:  # the integrator's step size collapsed
        raise FewearInputError(
            f"the dynamics cannot integrate this mechanism ({exc}): {UNINTEGRABLE_HINT}; a "
            "smaller [integrator] min_step_s or a larger gap_tolerance_m may get past it") from None
    used = {name: dict(table) for name, table in config.items()}
    for key, value in (("rod", args.rod), ("joint", args.joint),
                       ("recorded_cycles", args.cycles)):
        if value is not None:
            used["mechanism"][key] = value
    with staged_output(args.out) as stage:
        write_joint_history(history, stage / "joint_history.csv")
        report = {
            "peak_contact_force_N": history.peak_contact_force_N,
            "impacts": history.impacts,
            "steps": summary.steps,
            "rejected_steps": summary.rejected_steps,
            "newton_iterations": summary.newton_iterations,
            "wall_time_s": summary.wall_time_s,
            "wall_time_per_cycle_s": summary.wall_time_per_cycle_s,
            "smallest_step_s": summary.smallest_step_s,
            "recorded_steps": history.n_steps,
            "mode_fractions": {name: float(np.mean(history.mode == code))
                               for code, name in enumerate(MODES)},
            "config": used,
        }
        (stage / "summary.json").write_text(json.dumps(report, indent=2) + "\n")
        from fewear.plot.dynamics import plot_forces, plot_orbit

        label = f"{used['mechanism']['rod']} rod, {used['mechanism']['joint']} joint"
        plot_forces({label: history}, stage / "forces.png")
        plot_orbit(history, joint_model.nominal_clearance_m, stage / "orbit.png", label)
    return 0

