"""Wall time per crank cycle of the slider-crank (issue 3, item 9): prints, never asserts times.

One settling and one recorded cycle for each case with the default config, side by side in one
run: rigid rod + ideal joint (the reference: fixed steps of step_s), rigid rod + clearance and
flexible rod (4 ANCF elements) + clearance (adaptive steps). Goals: < 1 s per cycle (rigid,
clearance) and < 3 s (flexible, clearance) on an unloaded core; the printed ratios to the ideal
case are the machine-independent figures.
"""

import pytest

from fewear.mbd.slider_crank import simulate_slider_crank

CASES = (("rigid", "ideal"), ("rigid", "clearance"), ("flexible", "clearance"))


@pytest.mark.benchmark
def test_time_per_crank_cycle():
    rows = {}
    for rod, joint in CASES:
        history, summary = simulate_slider_crank(rod=rod, joint=joint, cycles=1,
                                                 settling_cycles=1)
        rows[(rod, joint)] = (summary, history)
    reference = rows[("rigid", "ideal")][0].wall_time_per_cycle_s
    print("\ncase                   s/cycle  x ideal  steps/cycle  rejected  Newton/step"
          "  peak |F| N")
    for (rod, joint), (summary, history) in rows.items():
        print(f"{rod:8s} {joint:10s}  {summary.wall_time_per_cycle_s:8.2f}  "
              f"{summary.wall_time_per_cycle_s / reference:7.1f}  "
              f"{summary.steps / summary.cycles:11.0f}  {summary.rejected_steps:8d}  "
              f"{summary.newton_iterations / summary.steps:11.2f}  "
              f"{history.peak_contact_force_N:10.1f}")
        assert history.n_steps > 0
