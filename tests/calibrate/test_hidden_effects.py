"""Data with a hidden departure from Archard's law, handed to the diagnosis without the answer.

Each data set comes from a forward model (fewear.calibrate.forward) with one cause switched on, its
parameters drawn across a physical range, lognormal scatter (25 % per interval between readings,
about 12 % on the cumulative readings, 2 % per weighing, 10 % test to test), 9 tests at
3 pressures x 3 speeds with 10 readings each. The diagnosis must name the cause and cut the
held-out error substantially; plain-Archard data must give ``none``; a single-speed campaign must
report running_in and time_transient as confounded, with the evidence for each.
"""

import dataclasses

import numpy as np
import pytest

from fewear.calibrate.diagnose import DiagnoseSettings, diagnose, readings_from_measured
from fewear.calibrate.forward import grid_campaign, hidden_case
from fewear.calibrate.measured import MeasuredWear

CAUSES = ("running_in", "time_transient", "thermal")
SEEDS = (11, 12, 13)
MIN_GAIN = 0.30


def measured(columns, drop=()) -> MeasuredWear:
    """The columns as W1's MeasuredWear (the reader's data class), without the ``drop`` columns."""
    kept = {name: values for name, values in columns.items() if name not in drop}
    return MeasuredWear(source="synthetic", data_kind="cumulative_volume", **kept)


def run(columns, drop=(), **settings):
    chosen = dataclasses.replace(DiagnoseSettings.default(), **settings)
    return diagnose(readings_from_measured(measured(columns, drop)), chosen)


def growth_to_double_distance(extension, readings) -> np.ndarray:
    """Per test: wear after twice the test's final distance over wear after it, S_eff(2 s) /
    S_eff(s) at the test's own speed and frictional power (plain Archard: 2)."""
    s = readings.final_per_test(readings.distance_m)
    v = readings.per_test(readings.velocity_m_s)
    q = readings.per_test(readings.power_W_m2)
    return (extension.effective_distance_m(2 * s, 2 * s / v, q)
            / extension.effective_distance_m(s, s / v, q))


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("cause", CAUSES)
def test_hidden_cause_is_named_with_a_substantial_gain(cause, seed):
    columns, hidden, _ = hidden_case(cause, seed)
    result = run(columns)
    summary = result.summary
    assert summary["cause"] == cause, summary["candidates"]
    assert summary["gain"] > MIN_GAIN
    assert summary["extended_config"]["extension"] == cause
    if cause == "thermal":
        return  # heating is over by the end of a test: wear then doubles with s (truth ~ 2)
    # how the wear grows from the test's own distance to twice it: the extended model is closer
    # to the hidden truth than plain Archard's doubling
    truth = growth_to_double_distance(hidden, result.readings)
    extended = growth_to_double_distance(result.extended_fit.extension, result.readings)
    assert np.mean(np.abs(np.log(extended / truth))) < 0.5 * np.mean(np.abs(np.log(2.0 / truth)))


@pytest.mark.parametrize("seed", range(21, 27))
def test_plain_archard_gives_none(seed):
    columns, _, _ = hidden_case("none", seed)
    summary = run(columns).summary
    assert summary["cause"] == "none", summary["candidates"]
    assert summary["gain"] == 0.0
    assert summary["extended_config"]["extension"] == "none"


def test_single_speed_confounds_running_in_and_time_transient():
    rng = np.random.default_rng(5)
    campaign = grid_campaign(pressures_Pa=(0.5e6, 1e6, 2e6, 3e6, 4e6, 6e6), velocities_m_s=(0.5,),
                             rng=rng)
    columns, _, _ = hidden_case("running_in", 5, campaign)
    summary = run(columns).summary
    assert summary["cause"] in ("running_in", "time_transient")
    assert len(summary["confounded"]) == 1
    group = summary["confounded"][0]
    assert set(group["causes"]) == {"running_in", "time_transient"}
    assert "one speed" in group["reason"]
    evidence = group["evidence"]
    assert set(evidence) == {"running_in", "time_transient"}
    for entry in evidence.values():
        assert entry["gain"] > MIN_GAIN and entry["params"]
    # the two fits are the same curve: s0 = v tau
    assert evidence["running_in"]["params"]["distance_scale_m"] == pytest.approx(
        0.5 * evidence["time_transient"]["params"]["time_scale_s"], rel=0.05)


def test_missing_time_and_speed_leave_time_driven_causes_untested():
    columns, _, _ = hidden_case("running_in", 31)
    summary = run(columns, drop=("time_s", "velocity_m_s")).summary
    assert summary["cause"] == "running_in"
    untested = {entry["name"]: entry["message"] for entry in summary["untestable"]}
    assert set(untested) == {"time_transient", "thermal"}
    assert "needs time_s" in untested["time_transient"]
    assert {c["name"] for c in summary["candidates"]} == {"running_in"}
    assert "velocity_m_s" in summary["residual_structure"]["not_measured"]


def test_missing_friction_leaves_thermal_untested():
    columns, _, _ = hidden_case("thermal", 32)
    summary = run(columns, drop=("friction_coefficient",)).summary
    untested = {entry["name"]: entry["message"] for entry in summary["untestable"]}
    assert untested == {"thermal": "could not be tested: needs friction_coefficient"}
    assert summary["cause"] != "thermal"


def test_time_derived_from_speed_when_not_measured():
    columns, _, _ = hidden_case("time_transient", 33)
    result = run(columns, drop=("time_s",))
    assert result.summary["cause"] == "time_transient"
    assert any("t = s / v" in note for note in result.summary["notes"])


def test_one_reading_per_test_holds_out_whole_tests():
    """A table of final readings only (one per test, 16 tests at one distance): the later-reading
    hold-out is impossible, whole tests are held out and plain Archard data give none."""
    rng = np.random.default_rng(40)
    campaign = grid_campaign((0.5e6, 1e6, 2e6, 4e6), (0.1, 0.3, 0.9, 2.0), rng=rng,
                             readings_per_test=1, first_reading_fraction=1.0)
    columns, _, _ = hidden_case("none", 40, campaign)
    summary = run(columns).summary
    assert summary["holdout"]["strategy"] == "tests"
    assert summary["baseline"]["coefficient_model"] == "rbf"
    assert summary["cause"] == "none"
    assert np.isfinite(summary["baseline"]["held_out_error"])
    assert {entry["name"] for entry in summary["untestable"]} == {
        "running_in", "time_transient", "thermal"}
    assert all("readings along a test" in entry["message"] for entry in summary["untestable"])


def test_few_readings_per_test_hold_out_whole_tests_and_still_find_running_in():
    """Three readings per test (fewer than min_readings_per_test): whole tests are held out, with
    their k from the network of the other tests, and the running-in is still found."""
    rng = np.random.default_rng(42)
    campaign = grid_campaign((0.5e6, 1e6, 2e6, 4e6), (0.2, 0.5, 1.2), rng=rng,
                             readings_per_test=3, first_reading_fraction=0.05)
    columns, _, _ = hidden_case("running_in", 42, campaign)
    summary = run(columns).summary
    assert summary["holdout"]["strategy"] == "tests"
    assert summary["cause"] in ("running_in", "time_transient")
    assert summary["gain"] > 0.3


def test_few_conditions_fall_back_to_constant_k():
    rng = np.random.default_rng(41)
    campaign = grid_campaign((1e6, 2e6), (0.5,), rng=rng)
    columns, _, _ = hidden_case("running_in", 41, campaign)
    summary = run(columns).summary
    assert summary["baseline"]["coefficient_model"] == "constant"
    assert "2 distinct" in summary["baseline"]["coefficient_reason"]
    assert summary["extended_config"]["coefficient_model"] == "constant"
