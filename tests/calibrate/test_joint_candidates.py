"""The joint diagnosis's candidate runs and resolution (fewear.calibrate.joint_diagnose), on
constructed wear histories: runs that stop before the data are left out, halving the blocks
halves what the extrapolation settings allow, and a 'none' whose misfit lies within what the
model's blocks resolve says so."""

import math

import numpy as np
import pytest

from fewear.calibrate.joint_diagnose import (
    Candidate,
    Fit,
    JointDiagnoseSettings,
    _lasting,
    _unexplained,
)
from fewear.calibrate.joint_forward import WearHistory, with_halved_blocks
from fewear.errors import FewearInputError


def _run(last_cycles: float, stopped: str = "") -> WearHistory:
    angle = np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False)
    cycles = np.array([0.0, last_cycles])
    return WearHistory(angle, cycles, np.vstack([np.zeros(8), np.full(8, 1e-5)]),
                       np.ones(8), stopped)


def test_runs_that_stop_before_the_needed_cycles_are_left_out():
    runs = (_run(20000), _run(20000), _run(3000, "worn through"), _run(12000, "worn through"))
    kept = _lasting(Candidate("impact_wear", runs, (0.0, 1.0, 2.0, 3.0)), needed_cycles=8000)
    assert kept.grid == (0.0, 1.0, 3.0)  # the one stopped at 3,000 < 8,000 cycles is out
    assert kept.runs == (runs[0], runs[1], runs[3])


def test_a_grid_cause_with_only_the_believed_run_left_is_untestable():
    runs = (_run(20000), _run(3000, "worn through"))
    assert _lasting(Candidate("friction", runs, (0.1, 0.3)), needed_cycles=8000) is None
    # a discrete choice keeps a single lasting run: it is still a different model
    assert _lasting(Candidate("flexible_link", runs, (1.0, 1.1), discrete=True), 8000).runs == (
        runs[0],)


def test_halving_the_blocks_halves_the_extrapolation_limits():
    adaptive = {"wear_loop": {"extrapolation": "adaptive", "extrapolation_factor": 5000.0,
                              "max_extrapolation_factor": 50000.0,
                              "max_depth_increment_fraction": 0.25}}
    halved = with_halved_blocks(adaptive)["wear_loop"]
    assert (halved["max_extrapolation_factor"], halved["max_depth_increment_fraction"]) == (
        25000.0, 0.125)
    assert adaptive["wear_loop"]["max_extrapolation_factor"] == 50000.0  # not changed in place
    fixed = {"wear_loop": {**adaptive["wear_loop"], "extrapolation": "fixed"}}
    assert with_halved_blocks(fixed)["wear_loop"]["extrapolation_factor"] == 2500.0


def _fit(train_rms_m: float) -> Fit:
    return Fit("baseline", np.zeros(1), 1, 0.0, 10, train_rms_m, train_rms_m, np.zeros(10))


def test_none_with_a_large_misfit_names_the_block_size_when_that_is_what_limits():
    baseline = _fit(10e-6)
    # 20 x the instrument's 0.5 um scatter, and the blocks move the bore by 8 um: not resolved
    sentence, = _unexplained(baseline, baseline, [], {"instrument_scatter_m": 0.5e-6,
                                                      "halved_blocks_rms_m": 8e-6})
    assert "20 times the instrument's scatter" in sentence and "smaller wear blocks" in sentence
    # the same misfit with well-resolved blocks: unexplained, without the block-size remark
    sentence, = _unexplained(baseline, baseline, [], {"instrument_scatter_m": 0.5e-6,
                                                      "halved_blocks_rms_m": 0.2e-6})
    assert "smaller wear blocks" not in sentence
    # within 3 x the scatter: nothing is unexplained
    assert _unexplained(_fit(1.2e-6), _fit(1.2e-6), [], {"instrument_scatter_m": 0.5e-6,
                                                         "halved_blocks_rms_m": 8e-6}) == []


def test_a_grid_with_a_non_positive_value_is_a_clear_error():
    with pytest.raises(FewearInputError, match=r"friction_grid = \[0.0, 0.3\]: expected a non"):
        JointDiagnoseSettings(friction_grid=(0.0, 0.3))
