"""Convergence of the wear step alone (`make bench`; prints its table, asserts nothing).

The default config's rigid rod to FEWEAR_BENCH_WEAR_STEP_CYCLES (default 50,000) crank cycles
with the dynamics of the unworn joint's first block reused for every wear step: the orbit, and
with it the cycle-to-cycle scatter that makes the full loop's runs differ by a few per cent, is
the same in every run, so what differs is the wear step and nothing else. The linearised step
(:func:`fewear.wear.archard.block_wear`, exponential Euler with the smoothing inside) at the
adaptive bound f = 0.0625, 0.03125, 0.015625 (the default), 0.0078125 of the bore element's
height per step and at fixed blocks of A = 160 and 400 cycles is compared with explicit steps
of A = 40 cycles (seed eq. 10 as printed, stable at that A): the reference. The reference's own
error is shown by a second pair, from the f = 0.015625 state at 20,000 cycles, 4,000 cycles
more with explicit steps of 40 and of 10 cycles.

Why a reference of small explicit steps: the linearised step holds the contact's active set and
its pressure response over the step, an error that depends on the step's depth increment;
explicit steps well inside their stability limit have no such linearisation. README
"Convergence and uncertainty" gives the figures.
"""

import math
import os
import time
from dataclasses import replace

import pytest
from mpi4py import MPI

from fewear.io.config import load_config
from fewear.loop import mechanism_adapter as adapter
from fewear.loop.block import JointRun, mechanism_dynamics, new_bushing, new_case, wear_block
from fewear.loop.settings import run_inputs_from_config, run_sections
from fewear.mbd.slider_crank import CLEARANCE_JOINT
from fewear.wear.extrapolation import ExtrapolationSettings

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_WEAR_STEP_CYCLES", "50000"))
BOUNDS = (0.0625, 0.03125, 0.015625, 0.0078125)
FIXED_STEP_CYCLES = (160, 400)
REFERENCE_STEP_CYCLES = 40


def step_settings(inputs, total_cycles: int, bound: float | None = None,
                  step_cycles: int | None = None, linearised: bool = False):
    """``inputs`` with the linearised adaptive step at ``bound``, or fixed steps of
    ``step_cycles``, explicit unless ``linearised``."""
    if bound is not None:
        extrapolation = ExtrapolationSettings("adaptive", max_depth_increment_fraction=bound)
        loop = replace(inputs.loop, extrapolation=extrapolation, implicit_wear_step=True)
    else:
        extrapolation = ExtrapolationSettings("fixed", factor=float(step_cycles))
        loop = replace(inputs.loop, extrapolation=extrapolation, implicit_wear_step=linearised)
    return replace(inputs, loop=replace(loop, total_cycles=total_cycles, wear_steps_per_block=1))


def wear_to(inputs, bushing, case, dynamics) -> float:
    """Wear ``case`` to ``inputs``' total cycles on the first block's ``dynamics`` (histories,
    summary, final mechanism, wall time) every block; the wall time (s)."""
    (histories, _, mechanism), seconds = dynamics
    start = time.perf_counter()
    while case.state.cycles < inputs.loop.total_cycles:
        wear_block({CLEARANCE_JOINT: JointRun("rigid rod", inputs, bushing, case)}, histories,
                   mechanism, seconds)
    return time.perf_counter() - start


def fresh(inputs):
    bushing = new_bushing(inputs, MPI.COMM_SELF)
    return bushing, new_case(bushing)


def test_wear_step_convergence_on_one_history():
    config = load_config(None, run_sections())
    inputs = run_inputs_from_config(config)
    radius = inputs.contact.geometry.inner_radius_m
    bushing, case = fresh(inputs)
    history = mechanism_dynamics("rigid", adapter.dynamics_inputs(config, "rigid"),
                                 {CLEARANCE_JOINT: inputs}, {CLEARANCE_JOINT: case.state}, None)
    runs = {}
    for label, kwargs in [*((f"linearised, f = {f:g}", {"bound": f}) for f in BOUNDS),
                          *((f"linearised, A = {a}", {"step_cycles": a, "linearised": True})
                            for a in FIXED_STEP_CYCLES),
                          (f"explicit, A = {REFERENCE_STEP_CYCLES}",
                           {"step_cycles": REFERENCE_STEP_CYCLES})]:
        settings = step_settings(inputs, CYCLES, **kwargs)
        bushing, case = fresh(settings)
        seconds = wear_to(settings, bushing, case, history)
        runs[label] = (case.state.depth_m.max(), case.state.worn_area_m2(radius),
                       case.state.blocks, seconds)
    reference = runs[f"explicit, A = {REFERENCE_STEP_CYCLES}"]
    print(f"\nrigid rod, {CYCLES:,} cycles on the first block's history (reference: explicit "
          f"steps of {REFERENCE_STEP_CYCLES} cycles)")
    print(f"  {'wear step':26s} {'steps':>6s} {'max depth um':>13s} {'diff':>7s} "
          f"{'worn area m^2':>14s} {'diff':>7s} {'time s':>7s}")
    for label, (peak, area, steps, seconds) in runs.items():
        print(f"  {label:26s} {steps:6d} {peak * 1e6:13.2f} {peak / reference[0] - 1:7.1%} "
              f"{area:14.4e} {area / reference[1] - 1:7.1%} {seconds:7.1f}")
    print_reference_check(inputs, history, radius)


def print_reference_check(inputs, history, radius):
    """From the f = 0.015625 state at 20,000 cycles: 4,000 cycles more in explicit steps of 40 and
    of 10 cycles (the reference's step and a quarter of it)."""
    start, span = 20000, 4000
    if CYCLES < start:
        return
    gains = {}
    for step_cycles in (REFERENCE_STEP_CYCLES, REFERENCE_STEP_CYCLES // 4):
        settings = step_settings(inputs, start, bound=0.015625)
        bushing, case = fresh(settings)
        wear_to(settings, bushing, case, history)
        before = case.state
        wear_to(step_settings(inputs, start + span, step_cycles=step_cycles), bushing, case,
                history)
        gains[step_cycles] = ((case.state.depth_m - before.depth_m).max(),
                              case.state.worn_area_m2(radius) - before.worn_area_m2(radius))
    (peak40, area40), (peak10, area10) = gains.values()
    print(f"  the reference's step: {span:,} cycles from the f = 0.015625 state at {start:,}: "
          f"explicit A = 40 against A = 10: largest depth increment {peak40 / peak10 - 1:+.2%}, "
          f"worn area {area40 / area10 - 1:+.2%} ({math.ceil(span / 10)} steps of 10)")
