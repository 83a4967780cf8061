"""Held-out errors of a large table in folds (issue 57: 20,000 tests took hours one test at a
time): every test is held out once, its error the mean square of its rows about the level
learnt from the tests outside its fold, computed here independently for the plain model (one
level per material group, no law)."""

import numpy as np
import pytest

from fewear.diagnose.tribometer import fitting
from fewear.diagnose.tribometer.catalogue import Context
from fewear.diagnose.tribometer.fitting import Stage, fit_stage, held_out_errors


def plain_stage(n_tests=11, per_test=3, seed=2):
    rng = np.random.default_rng(seed)
    unit = np.repeat(np.arange(n_tests), per_test)
    group = (unit % 2)  # two material groups
    y = rng.normal(size=unit.size) + 3.0 * group
    context = Context(None, None, None, None, "pressure", None, 1.0, None, None)
    return Stage("all readings", y, group, unit, context, ())


@pytest.mark.parametrize("folds", [3, 200])
def test_each_test_is_held_out_once_about_the_other_folds_level(monkeypatch, folds):
    monkeypatch.setattr(fitting, "MAX_HELD_OUT_FOLDS", folds)
    stage = plain_stage()
    errors = held_out_errors(stage, fit_stage(stage, (), []))
    n_units = stage.unit.max() + 1
    fold_of = np.arange(n_units) % min(folds, n_units)
    for u in range(n_units):
        rows = stage.unit == u
        train = fold_of[stage.unit] != fold_of[u]
        level = stage.y[train & (stage.group == stage.group[rows][0])].mean()
        assert errors[u] == pytest.approx(np.mean((stage.y[rows] - level) ** 2), rel=1e-12)
