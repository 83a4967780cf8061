"""The stages the readings make (which rows, which intercepts, which causes can be tested on
them), and predictions of the wear volume under a stage's fit."""

from __future__ import annotations

from typing import Any

import numpy as np

from fewear.diagnose.tribometer.catalogue import (
    CAUSES,
    Context,
    Form,
    ShapeLaw,
    forms_of,
    missing_needs,
)
from fewear.diagnose.tribometer.fitting import Stage, StageFit, StageResult, scatter_weights
from fewear.diagnose.tribometer.readings import Readings
from fewear.diagnose.tribometer.settings import DiagnoseSettings


def data_form(readings: Readings, settings: DiagnoseSettings) -> str:
    """"histories" when every test has ``min_readings_along_test`` readings at distinct sliding
    distances, else "table" (a design of experiments)."""
    pairs = np.unique(np.column_stack([readings.test_index, readings.distance_m]), axis=0)
    distinct = np.bincount(pairs[:, 0].astype(int), minlength=readings.n_tests)
    return "histories" if distinct.min() >= settings.min_readings_along_test else "table"


def available_needs(readings: Readings) -> set[str]:
    """What the data hold of the forms' needs (catalogue.Form.needs, plus "distance")."""
    have = set()
    if readings.time_s is not None and np.ptp(np.log(readings.time_s)) > 0:
        have.add("time")
    if readings.friction is not None:
        have.add("friction")
    if readings.pressure_Pa is not None:
        have.add("pressure")
    load, _ = readings.load_variable
    if load is not None and np.ptp(np.log(readings.per_test(load))) > 0:
        have.add("load")
    if load is not None and readings.velocity_m_s is not None:
        power = readings.per_test(load * readings.velocity_m_s)
        if np.ptp(np.log(power)) > 0:
            have.add("power")
    groups = readings.group_labels
    if any(np.ptp(np.log(readings.distance_m[groups == g])) > 0 for g in np.unique(groups)):
        have.add("distance")
    return have


def reading_context(readings: Readings, distance_m=None, time_s=None, rows=None) -> Context:
    """The laws' view of the readings (or of the readings ``rows`` at other distances/times)."""
    rows = np.arange(readings.test_index.size) if rows is None else rows
    load, name = readings.load_variable
    speed = readings.velocity_m_s
    power = readings.power_W_m2

    def pick(values):
        return None if values is None else values[rows]

    return Context(
        distance_m=readings.distance_m[rows] if distance_m is None else distance_m,
        time_s=pick(readings.time_s) if time_s is None else time_s,
        power_W_m2=pick(power), load=pick(load), load_name=name,
        load_speed=None if load is None or speed is None else (load * speed)[rows],
        **readings.campaign_scales)


def _test_context(readings: Readings) -> Context:
    load, name = readings.load_variable
    speed = readings.velocity_m_s
    per_test = None if load is None else readings.per_test(load)
    load_speed = None if load is None or speed is None else readings.per_test(load * speed)
    return Context(None, None, None, per_test, name, load_speed, **readings.campaign_scales)


def _log_force(readings: Readings) -> np.ndarray:
    """ln F per reading (ln p without a load: F = p A, the constant A joins k; 0 without both)."""
    if readings.load_N is not None:
        return np.log(readings.load_N)
    if readings.pressure_Pa is not None:
        return np.log(readings.pressure_Pa)
    return np.zeros(readings.test_index.size)


def _testable(kind: str | None, have: set[str], causes) -> tuple[Form, ...]:
    forms = []
    for cause in causes:
        for form in forms_of(cause):
            if (kind is None or form.kind == kind) and form.all_needs <= have:
                forms.append(form)
    return tuple(forms)


def reading_stage(readings: Readings, settings: DiagnoseSettings) -> Stage:
    """The stage whose rows are the readings: "along tests" (histories, each test its own level,
    the shape causes) or "all readings" (tables, one level per material group, every cause)."""
    have = available_needs(readings)
    causes = settings.candidates
    test_group, _ = readings.test_groups()
    y = np.log(readings.volume_m3) - np.log(readings.distance_m)
    if data_form(readings, settings) == "table":
        return Stage("all readings", y - _log_force(readings), test_group[readings.test_index],
                     readings.test_index, reading_context(readings),
                     _testable(None, have, causes))
    return Stage("along tests", y, readings.test_index, readings.test_index,
                 reading_context(readings), _testable("shape", have, causes))


def test_levels(readings: Readings, along: StageResult) -> np.ndarray:
    """Each test's level under the along-test model (its ln V - ln s - ln S_eff/s), the mean
    of its readings weighted by their precision (:func:`scatter_weights` on the final model's
    residuals): an early reading, or one near the instrument's resolution, says little about the
    test's level. Equally weighted, the scatter of those small readings moved the levels of the
    tests of small wear (a load exponent named on plain-Archard data: blind floor benchmark,
    tests/benchmarks/test_bench_tribometer_floor.py)."""
    final, test = along.final, readings.test_index
    log_volume = along.stage.y - final.residuals + np.log(readings.distance_m)
    weight = scatter_weights(final.residuals, log_volume, test)
    shape_free = final.residuals + final.intercepts[along.stage.group]
    return (np.bincount(test, weight * shape_free, readings.n_tests)
            / np.bincount(test, weight, readings.n_tests))


def across_stage(readings: Readings, along: StageResult, settings: DiagnoseSettings) -> Stage:
    """Histories: one row per test, its level under the along-test model (:func:`test_levels`)
    minus ln F, one level per material group, the level causes."""
    test_group, _ = readings.test_groups()
    levels = test_levels(readings, along) - readings.per_test(_log_force(readings))
    return Stage("across tests", levels, test_group, np.arange(readings.n_tests),
                 _test_context(readings),
                 _testable("level", available_needs(readings), settings.candidates))


def untestable_causes(readings: Readings, settings: DiagnoseSettings) -> list[dict[str, Any]]:
    """The candidates the data cannot test, each with the needs it lacks and why (the summary's
    ``untestable``)."""
    have = available_needs(readings)
    return [{"cause": cause, "needs": missing_needs(cause, have), "untestable_reason": reason}
            for cause in settings.candidates
            if (reason := CAUSES[cause].why_untestable(have)) is not None]


def log_k_per_test(readings: Readings, stage: Stage, fit: StageFit) -> np.ndarray:
    """Each test's ln k [m^2/N] under a reading-stage fit's shape law (ln V - ln F - ln S_eff
    averaged over the test's readings)."""
    shape = [law for law in fit.laws if isinstance(law, ShapeLaw)]
    log_shape = shape[0].log_multiplier(stage.context) if shape else 0.0
    z = (np.log(readings.volume_m3) - np.log(readings.distance_m) - _log_force(readings)
         - log_shape)
    return readings.per_test(z)


def predict_log_volume(readings: Readings, stage: Stage, fit: StageFit, test: int,
                       distance_m) -> np.ndarray:
    """ln V [m^3] of test ``test`` after sliding ``distance_m`` under a fit of the reading stage
    (at the test's speed, power and load; time s / v)."""
    rows = np.flatnonzero(readings.test_index == test)
    s = np.atleast_1d(np.asarray(distance_m, float))
    pick = np.full(s.size, rows[0])
    time = None
    if readings.time_s is not None:
        time = s * readings.time_s[rows[0]] / readings.distance_m[rows[0]]
    context = reading_context(readings, distance_m=s, time_s=time, rows=pick)
    total = np.log(s) + _log_force(readings)[pick] + fit.intercepts[stage.group[pick]]
    for law in fit.laws:
        total = total + law.log_multiplier(context)
    return total
