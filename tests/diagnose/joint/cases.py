"""Joint wear data with a hidden cause, as a profilometer would give them: the wear loop run with
the effect switched on at random parameters (:mod:`fewear.diagnose.joint.forward`), measured by
the independent instrument model of :mod:`tests.diagnose.joint.profilometer` (random sampling step,
unknown angular origin, 0.5 um noise, 0.01 um resolution, stylus filter)."""

from __future__ import annotations

import copy
import math

import numpy as np

from fewear.diagnose.joint.forward import (
    cycle_on_worn_bore,
    impact_measures_per_cycle,
    model_config,
    simulate_wear,
    worn_volume_per_cycle_m3,
)
from fewear.diagnose.joint.measured import ForceTrace, JointMeasurements
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics
from tests.diagnose.joint.profilometer import max_wear_growth, measure_profile

PROFILE_CYCLES = (4000, 8000, 12000, 16000)
BELIEVED = """
[mechanism]
rod_density_kg_m3 = 7800.0
[mesh]
bore_element_size_m = {size!r}
radial_element_count = 4
[wear_loop]
rod_models = ["rigid"]
load_steps_per_cycle = 40
# the coarse test model keeps one wear step per block at the former bound (cheap; the wear step's
# convergence is tests/benchmarks/test_bench_wear_step.py)
max_depth_increment_fraction = 0.25
wear_steps_per_block = 1
"""
"""The believed model of the tests: the paper's joint with a rigid steel rod (7800 kg/m^3, the
density these tests were built and validated with), on a coarse mesh."""


def believed_text() -> str:
    return BELIEVED.format(size=2 * math.pi * 0.010 / 48 * (1 + 1e-9))


def truth_config(config: dict, cause: str, rng: np.random.Generator) -> tuple[dict, dict]:
    """The believed config with ``cause`` switched on at random parameters (and which);
    ``cause`` may join several with '+' (each switched on in turn)."""
    if "+" in cause:
        truth, params = config, {}
        for part in cause.split("+"):
            truth, more = truth_config(truth, part, rng)
            params.update(more)
        return truth, params
    truth = copy.deepcopy(config)
    if cause == "wear_coefficient":
        scale = rng.uniform(1.5, 2.0) if rng.random() < 0.5 else rng.uniform(0.5, 0.67)
        truth["wear"]["rbf"]["tail"][0] += math.log(scale)
        return truth, {"k_scale": scale}
    if cause == "flexible_link":
        stiffness = rng.uniform(0.8, 1.25)
        truth["wear_loop"]["rod_models"] = ["flexible"]
        truth["mechanism"]["rod_youngs_modulus_Pa"] *= stiffness
        return truth, {"youngs_modulus_factor": stiffness}
    if cause == "friction":
        mu = rng.uniform(0.25, 0.4)
        truth["joint"]["friction_coefficient"] = mu
        return truth, {"friction_coefficient": mu}
    if cause == "impact_wear":
        horizon = model_config(config, "rigid", 2 * PROFILE_CYCLES[-1])
        per_joule = worn_volume_per_cycle_m3(simulate_wear(horizon), config) / (
            impact_measures_per_cycle(horizon)["energy"])
        # the impacts wear 10-30 % of the sliding volume on the unworn joint; at 30-100 % (this
        # generator's first range) the impact-worn pocket drew ever more impacts and some truths
        # wore through half the wall before the last measured count: a failed joint, not data
        k_imp = rng.uniform(0.1, 0.3) * per_joule
        truth["wear"]["impact_wear_coefficient_m3_J"] = k_imp
        return truth, {"impact_wear_coefficient_m3_J": k_imp}
    if cause == "running_in":
        params = {"k_initial_over_steady": rng.uniform(3.0, 6.0),
                  "distance_scale_m": rng.uniform(10.0, 30.0)}
        truth["wear"]["extension"] = "running_in"
        truth["wear"]["extension_params"] = params
        return truth, params
    return truth, {}


def force_trace(truth: dict, run, cycles: int, start_deg: float,
                rng: np.random.Generator) -> ForceTrace:
    """The joint force of the truth's mechanism after ``cycles`` as a load cell records it: one
    crank cycle sampled at 20 kHz from the crank angle ``start_deg`` on, 1 % noise."""
    history = cycle_on_worn_bore(truth, run.angle_rad, run.nodal_depth_m(cycles))
    omega = truth["mechanism"]["crank_speed_rpm"] * 2.0 * math.pi / 60.0
    time_s = np.arange(0.0, 2.0 * math.pi / omega, 5e-5)
    crank = (math.radians(start_deg) + omega * time_s) % (2.0 * math.pi)
    simulated = history.crank_angle_rad - history.crank_angle_rad[0]
    force = [np.interp(crank, simulated, -history.reaction_force_N[:, i], period=2.0 * math.pi)
             for i in range(2)]
    scale = 0.01 * float(np.max(np.hypot(*force)))
    return ForceTrace(cycles, time_s, *(f + rng.normal(0.0, scale, f.size) for f in force))


def hidden_joint_case(config: dict, cause: str, seed: int, with_growth: bool = True,
                      force_start_deg: float | None = None,
                      profile_cycles: tuple[int, ...] = PROFILE_CYCLES):
    """(measured data, truth parameters, true angular offset in deg) for ``cause`` ('none':
    the believed model itself), profiles measured after ``profile_cycles``; with a force trace
    at the last count recorded from the crank angle ``force_start_deg`` on, if given."""
    rng = np.random.default_rng(seed)
    truth, params = truth_config(with_truth_numerics(config), cause, rng)
    rod = truth["wear_loop"]["rod_models"][0]
    last = profile_cycles[-1]
    run = simulate_wear(model_config(truth, rod, last), f"truth: {cause}")
    if run.stopped:
        raise ValueError(f"the truth of {cause} seed {seed} ({params}) stopped before "
                         f"{last:,} cycles: {run.stopped}")
    offset = rng.uniform(-20.0, 20.0)
    profiles = tuple(measure_profile(run.angle_rad, run.nodal_depth_m(c), rng, cycles=c,
                                     offset_deg=offset).profile for c in profile_cycles)
    growth = None
    if with_growth:
        cycles = np.arange(2000, last + 1, 2000)
        growth = max_wear_growth(cycles, np.array([run.nodal_depth_m(c).max() for c in cycles]),
                                 rng)
    force = None if force_start_deg is None else (
        force_trace(model_config(truth, rod, last), run, last, force_start_deg, rng),)
    data = JointMeasurements(profiles=profiles, max_wear=growth, force=force,
                             sources=(f"synthetic {cause} seed {seed}",))
    return data, params, offset
