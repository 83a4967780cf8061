"""Two causes fitted together (fewear.diagnose.joint.pairs): running-in on a grid cause's runs.

Constructed world: two runs of a friction grid (mu 0.1, the believed, and 0.3) that wear at
constant but differently shaped rates, so a run's depth is rate x N at each node. The data of
friction mu = 0.18 with a running-in by crank cycles, k falling from r k to k with N0, are
written out here with the closed form N_eff(N) = N + (r - 1) N0 (1 - exp(-N / N0)) of that
running-in (not the diagnosis's time map), plus 0.2 um of noise.
"""

import math
from dataclasses import fields

import numpy as np
import pytest

from fewear.diagnose.joint.candidates import RUNNING_IN_FORMS
from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.fitting import Observations, fit_candidate
from fewear.diagnose.joint.forward import WearHistory
from fewear.diagnose.joint.pairs import causes_of, pair_config, pair_name
from fewear.diagnose.joint.resolution import baseline_fit
from fewear.diagnose.joint.selection import select_pairs
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.io.config import default_config

ANGLE = np.linspace(0.0, 2.0 * math.pi, 96, endpoint=False)
GRID = (0.1, 0.3)
RATES = (1e-9 * (1.2 + np.cos(ANGLE)),                      # m per cycle at mu = 0.1
         1.6e-9 * (1.2 + np.cos(ANGLE) + 0.6 * np.cos(2.0 * ANGLE)))  # at mu = 0.3
COUNTS = (2000.0, 3000.0, 4500.0, 6000.0, 8000.0, 10000.0, 14000.0, 20000.0)
SETTINGS = JointDiagnoseSettings.default()


def _run(rate: np.ndarray) -> WearHistory:
    cycles = np.linspace(0.0, 1e6, 11)
    return WearHistory(ANGLE, cycles, cycles[:, None] * rate[None, :], np.full(ANGLE.size, 0.01))


def _data(mu: float, r: float, n0: float, k_scale: float, offset_deg: float = 6.0,
          noise_m: float = 0.2e-6) -> Observations:
    w = (mu - GRID[0]) / (GRID[1] - GRID[0])
    rate = (1.0 - w) * RATES[0] + w * RATES[1]
    measured = np.radians(np.arange(0.0, 360.0, 6.0))
    noise = np.random.default_rng(7)
    cycles, angle, depth = [], [], []
    for count in COUNTS:
        effective = count + (r - 1.0) * n0 * (1.0 - math.exp(-count / n0))
        nodal = k_scale * rate * effective
        cycles.append(np.full(measured.size, count))
        angle.append(measured)
        depth.append(np.interp(measured + math.radians(offset_deg), ANGLE, nodal, period=2 * np.pi)
                     + noise.normal(0.0, noise_m, measured.size))
    cycles = np.concatenate(cycles)
    return Observations(cycles, np.concatenate(angle), np.concatenate(depth), cycles < 12000.0)


def _diagnosis_inputs(obs: Observations):
    """The round's inputs on ``obs``: the candidates of friction and running-in (forms), each
    cause fitted alone, and the believed model's fit."""
    runs = [_run(rate) for rate in RATES]
    running_in = CAUSES["running_in"]  # two of its forms (every node slides alike here)
    candidates = {"friction": (CAUSES["friction"].candidate(runs, GRID),),
                  "running_in": tuple(running_in.candidate(runs[0], form)
                                      for form in ("exponential", "power_law"))}
    baseline = baseline_fit("baseline", runs[0], obs, SETTINGS.max_offset_deg)
    fits = {name: fit_candidate(forms, obs, float(baseline.x[0]), SETTINGS)
            for name, forms in candidates.items()}
    return candidates, fits, baseline


@pytest.fixture(scope="module")
def friction_and_running_in():
    obs = _data(mu=0.18, r=3.0, n0=2500.0, k_scale=1.2)
    return obs, *_diagnosis_inputs(obs)


def test_friction_and_running_in_together_are_fitted_and_accepted(friction_and_running_in):
    obs, candidates, fits, baseline = friction_and_running_in
    accepted, verdicts, pair_fits = select_pairs(candidates, fits, obs, baseline, SETTINGS,
                                                  None)
    assert accepted == [pair_name("friction")] == [v.cause for v in verdicts]
    pair = pair_fits[pair_name("friction")]
    # every node slides 0.01 m per cycle: running-in by distance over s0 = 0.01 N0
    assert pair.running_in_form == "exponential"
    assert pair.params["k_initial_over_steady"] == pytest.approx(3.0, rel=0.05)
    assert pair.params["distance_scale_m"] == pytest.approx(0.01 * 2500.0, rel=0.1)
    assert pair.params["friction_coefficient"] == pytest.approx(0.18, abs=0.005)
    assert pair.params["k_scale"] == pytest.approx(1.2, rel=0.03)
    assert pair.params["angle_offset_deg"] == pytest.approx(6.0, abs=0.2)
    assert pair.held_out_rms_m < 0.5e-6  # the noise is 0.2 um
    assert pair.held_out_rms_m < 0.2 * min(f.held_out_rms_m for f in fits.values())
    assert verdicts[0].evidence.gain > 0.5


@pytest.fixture(scope="module")
def friction_alone():
    obs = _data(mu=0.18, r=1.0, n0=2500.0, k_scale=1.0)  # no running-in
    return obs, *_diagnosis_inputs(obs)


def test_no_pair_is_tried_without_a_running_in_that_fits_better_than_the_believed_model(
        friction_alone):
    obs, candidates, fits, baseline = friction_alone
    fits = {**fits, "running_in": baseline}  # running-in no better than the believed model
    assert select_pairs(candidates, fits, obs, baseline, SETTINGS, None) == ([], [], {})


def test_a_pair_no_better_than_its_cause_alone_is_not_accepted(friction_alone):
    obs, candidates, fits, baseline = friction_alone
    accepted, verdicts, _ = select_pairs(candidates, fits, obs, baseline, SETTINGS, None)
    assert accepted == [] and len(verdicts) == 1
    assert verdicts[0].evidence.gain > 0.5  # as good as friction alone, which it must beat


def test_the_extended_config_of_a_pair_has_both_causes_and_the_level_once(
        friction_and_running_in):
    _, _, fits, baseline = friction_and_running_in
    obs, candidates = friction_and_running_in[0], friction_and_running_in[1]
    _, _, pair_fits = select_pairs(candidates, fits, obs, baseline, SETTINGS, None)
    pair = pair_fits[pair_name("friction")]
    config = default_config()
    config["wear"]["coefficient_model"] = "constant"
    extended = pair_config(config, pair)
    assert extended["joint"]["friction_coefficient"] == pair.params["friction_coefficient"]
    assert extended["wear"]["constant_k_m2_N"] == pytest.approx(
        pair.params["k_scale"] * config["wear"]["constant_k_m2_N"], rel=1e-12)
    assert extended["wear"]["extension"] == RUNNING_IN_FORMS[pair.running_in_form].name
    law = {field.name for field in fields(RUNNING_IN_FORMS[pair.running_in_form])}
    assert extended["wear"]["extension_params"] == pytest.approx(
        {key: value for key, value in pair.params.items() if key in law})
    assert causes_of(pair.name) == ("friction", "running_in")
