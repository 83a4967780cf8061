"""Resolution first (fewear.diagnose.joint.resolution): the believed model's wear steps halved
until its own noise is at most the instrument's scatter, on runs made up with a known noise.

The made-up model at depth-increment fraction f: the bore of a run is D (1 + 4 f) plus a
constant +-a f for the runs started 1 and 2 deg later (0 for the first), so its runs' spread (the
sample RMS about their mean) is exactly a f and halving f moves their mean by 2 f D."""

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

from fewear.diagnose.joint import resolution
from fewear.diagnose.joint.forward import WearHistory

D_M, SPREAD_PER_F_M, SCATTER_M, LAST = 4e-6, 6e-6, 0.5e-6, 4000
NODES = 12
SCALE = LAST / (LAST + 1)  # the runs go one cycle past the last count; depth linear in cycles


def _key(config: dict) -> str:
    return json.dumps(config, sort_keys=True)


OFFSETS = {0.0: 0.0, 1.0: 1.0, 2.0: -1.0}
"""A run's offset (in a f) by how many degrees later its crank starts."""


def _made_up_run(config: dict) -> WearHistory:
    f = config["wear_loop"]["max_depth_increment_fraction"]
    later = config["mechanism"]["initial_crank_angle_deg"]
    offset = OFFSETS[later] * SPREAD_PER_F_M * f
    if config["wear_loop"]["recorded_cycles_per_block"] > 1:
        offset += 0.1e-6  # recording twice the cycles moves the bore by 0.1 um
    depth = np.full(NODES, D_M * (1.0 + 4.0 * f) + offset)
    return WearHistory(np.linspace(0.0, 2 * math.pi, NODES, endpoint=False),
                       np.array([0.0, config["wear_loop"]["total_cycles"]]),
                       np.vstack([np.zeros(NODES), depth]), np.ones(NODES))


@pytest.fixture
def made_up(monkeypatch):
    """The made-up runs in place of the wear loop, the scatter set to :data:`SCATTER_M`."""
    made, memo = [], {}

    def runs(requests):  # memoised by config, as the wear loop's runs are
        for config, _ in requests:
            if _key(config) not in memo:
                made.append(config["wear_loop"]["max_depth_increment_fraction"])
                memo[_key(config)] = _made_up_run(config)
        return [memo[_key(config)] for config, _ in requests]

    monkeypatch.setattr(resolution, "simulate_wears", runs)
    monkeypatch.setattr(resolution, "baseline_fit",
                        lambda name, run, obs, offset: SimpleNamespace(residuals_m=None))
    monkeypatch.setattr(resolution.structure, "scatter_estimate_m", lambda *args: SCATTER_M)
    return made


CONFIG = {"wear_loop": {"rod_models": ["rigid"], "extrapolation": "adaptive",
                        "max_extrapolation_factor": 50000.0, "max_depth_increment_fraction": 0.25,
                        "recorded_cycles_per_block": 1, "wear_steps_per_block": 1,
                        "total_cycles": 100},
          "mechanism": {"initial_crank_angle_deg": 0.0}}
OBS = SimpleNamespace(cycles=np.array([LAST / 2, LAST]), angle_rad=None)


def test_the_coarsest_blocks_whose_noise_is_within_the_scatter_are_chosen(made_up):
    """f = 0.25: runs 1.5 um apart; 0.125: 0.75 um; 0.0625: 0.375 um, and halving it moves the
    mean by 0.5 um (each times the RMS over the two counts, 0.79): the first within the 0.5 um
    scatter on both counts."""
    config, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=6, max_offset_deg=30)
    fractions = [level["blocks"]["max_depth_increment_fraction"]
                 for level in found["wear_step_levels"]]
    assert fractions == [0.25, 0.125, 0.0625, 0.03125]  # the last only to judge the one before
    assert found["resolved"] and not found["out_of_reach"]
    assert found["wear_step"] == {"max_depth_increment_fraction": 0.0625,
                                  "max_extrapolation_factor": 12500.0, "wear_steps_per_block": 4}
    assert config["wear_loop"]["max_depth_increment_fraction"] == 0.0625
    assert config["wear_loop"]["wear_steps_per_block"] == 4
    assert config["wear_loop"]["total_cycles"] == 100  # the config's own, not the runs'
    assert CONFIG["wear_loop"]["max_depth_increment_fraction"] == 0.25  # not changed in place
    # at the two counts (half and all of the last one's depth) the RMS of a f and of 2 f D
    rms_of_counts = SCALE * math.sqrt((0.25 + 1.0) / 2)
    spreads = [level["spread_rms_m"] for level in found["wear_step_levels"]]
    assert spreads[:3] == pytest.approx([SPREAD_PER_F_M * f * rms_of_counts
                                         for f in fractions[:3]])
    # the last level's run from the config's angle deviates 0 from its level's mean here, so
    # its distance from the coarser mean, the upper estimate, is the move itself
    assert spreads[3] is None
    assert found["halved_blocks_rms_m"] == pytest.approx(2 * 0.0625 * D_M * rms_of_counts)
    assert found["start_angle_spread_rms_m"] == spreads[2]
    assert found["doubled_recorded_cycles_rms_m"] == pytest.approx(0.1e-6 * rms_of_counts)
    assert resolution.model_noise_m(found) == pytest.approx(max(spreads[2],
                                                                found["halved_blocks_rms_m"]))
    # three runs per level, and beside each level the doubled recorded cycles of the level
    # before (needed if that one is chosen): the chosen one's is not run again; the level
    # after the first within the scatter only its run from the config's angle
    assert made_up == ([0.25] * 3 + [0.125] * 3 + [0.25] + [0.0625] * 3 + [0.125]
                       + [0.03125] + [0.0625])


def test_a_level_whose_one_run_strays_beyond_the_scatter_is_measured_in_full(made_up,
                                                                            monkeypatch):
    """The run from the config's angle a f below its level's mean (the others a f above and on
    it: the same spread, the means unmoved) and the scatter 0.41 um: at f = 0.03125 the mean
    moves 0.395 um (shallower) but that run lies 0.395 + 0.148 = 0.543 um from the coarser mean,
    beyond the scatter; so the level's other two runs are made, and the true move resolves
    f = 0.0625."""
    monkeypatch.setattr(resolution.structure, "scatter_estimate_m", lambda *args: 0.41e-6)
    monkeypatch.setitem(OFFSETS, 0.0, -1.0)
    monkeypatch.setitem(OFFSETS, 1.0, 1.0)
    monkeypatch.setitem(OFFSETS, 2.0, 0.0)
    _, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=6, max_offset_deg=30)
    rms_of_counts = SCALE * math.sqrt((0.25 + 1.0) / 2)
    levels = found["wear_step_levels"]
    assert [level["blocks"]["max_depth_increment_fraction"] for level in levels] == [
        0.25, 0.125, 0.0625, 0.03125]
    assert levels[3]["spread_rms_m"] == pytest.approx(SPREAD_PER_F_M * 0.03125 * rms_of_counts)
    assert found["halved_blocks_rms_m"] == pytest.approx(2 * 0.0625 * D_M * rms_of_counts)
    assert found["resolved"] and found["wear_step"]["max_depth_increment_fraction"] == 0.0625
    assert made_up == ([0.25] * 3 + [0.125] * 3 + [0.25] + [0.0625] * 3 + [0.125]
                       + [0.03125] + [0.0625] + [0.03125] * 2)


def test_the_ladder_stops_where_the_halvings_left_cannot_reach_the_scatter(made_up, monkeypatch,
                                                                         capsys):
    """One halving allowed: f = 0.25's runs part by 1.19 um, more than twice the 0.5 um scatter,
    so not even a halved spread would come within it: the config's level is taken at once (not
    resolved, its move not measured: three runs and its doubled recorded cycles). So it is too
    when the data are far more precise than the model (a model's own output: 1 nm) with all six
    halvings allowed, where the ladder would have run six levels, each twice as dear."""
    config, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=1, max_offset_deg=30)
    assert len(found["wear_step_levels"]) == 1 and found["out_of_reach"]
    assert not found["resolved"] and math.isnan(found["halved_blocks_rms_m"])
    assert config["wear_loop"]["max_depth_increment_fraction"] == 0.25
    assert made_up == [0.25] * 4
    monkeypatch.setattr(resolution.structure, "scatter_estimate_m", lambda *args: 1e-9)
    _, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=6, max_offset_deg=30)
    assert len(found["wear_step_levels"]) == 1 and found["out_of_reach"]
    assert "resolution stops at level 1: its runs part by more than the 6 halvings left" in (
        capsys.readouterr().err)


def test_the_config_s_blocks_with_no_halving_allowed_or_no_profiles(made_up, monkeypatch):
    config, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=0, max_offset_deg=30)
    assert found["wear_step"]["max_depth_increment_fraction"] == 0.25 and not found["resolved"]
    assert len(found["wear_step_levels"]) == 2  # the halved level measures the move
    monkeypatch.setattr(resolution.structure, "scatter_estimate_m", lambda *args: None)
    config, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=6, max_offset_deg=30)
    assert len(found["wear_step_levels"]) == 1 and math.isnan(found["halved_blocks_rms_m"])
    assert config["wear_loop"]["max_depth_increment_fraction"] == 0.25


def test_each_level_reports_its_noise_against_the_scatter_when_measured(made_up, capsys):
    """A line per level on stderr, as it is measured: a user whose model is dear sees each
    level's noise against the scatter and what its runs cost before the next runs."""
    _, found = resolution.resolve_wear_step(CONFIG, OBS, max_halvings=6, max_offset_deg=30)
    lines = [line for line in capsys.readouterr().err.splitlines() if "resolution, level" in line]
    assert len(lines) == len(found["wear_step_levels"]) == 4
    for number, line in enumerate(lines, start=1):
        assert f"level {number} of at most 8" in line
        assert "the instrument's scatter 0.5 um" in line
    for line, level in zip(lines[:3], found["wear_step_levels"]):
        assert f"part by {level['spread_rms_m'] * 1e6:.3g} um" in line
    assert "moved" not in lines[0]
    assert (f"lies {found['halved_blocks_rms_m'] * 1e6:.3g} um from the level before's mean"
            in lines[3]) and "other runs are not made" in lines[3]
