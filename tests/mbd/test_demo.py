"""The slider-crank demo (the paper's Fig. 6) runs and its numbers hang together.

By default the demo runs without its sensitivity study (`FEWEAR_DEMO_QUICK=1`: five more runs of
three crank cycles, printed, not checked); the slow variant (`make slow`) runs the demo whole and
checks that the study reports a peak force for each of its five cases."""

import json
import runpy
from pathlib import Path

import pytest

from fewear.mbd.slider_crank import SliderCrank

DEMO = Path(__file__).resolve().parents[2] / "demos" / "slider_crank_dynamics.py"


@pytest.mark.parametrize("quick", ["1", pytest.param("0", marks=pytest.mark.slow)],
                         ids=["quick", "whole"])
def test_demo_reproduces_figure_6(tmp_path, monkeypatch, quick):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("FEWEAR_DEMO_QUICK", quick)
    runpy.run_path(str(DEMO), run_name="__main__")
    results = json.loads((tmp_path / "results.json").read_text())
    sensitivity = results["sensitivity_peak_N"]
    assert len(sensitivity) == (0 if quick == "1" else 5)
    assert all(peak > 0.0 for peak in sensitivity.values())
    peaks = results["peak_force_N"]
    crank = SliderCrank()
    # ideal joint: the largest force is the slider's inertia at the outer dead centre
    dead_centre_N = crank.slider_mass_kg * crank.crank_length_m * crank.omega_rad_s**2 * (
        1 + crank.crank_length_m / crank.rod_length_m)
    assert peaks["rigid_ideal"] == pytest.approx(dead_centre_N, rel=2e-3)
    # the clearance's impacts raise the peak above the ideal joint's
    assert peaks["rigid_clearance"] > 1.5 * peaks["rigid_ideal"]
    assert peaks["flexible_clearance"] > peaks["rigid_ideal"]
    assert results["peak_force_ratio_flexible_over_rigid"] == pytest.approx(
        peaks["flexible_clearance"] / peaks["rigid_clearance"])
    assert sum(results["fcr_mode_fractions"].values()) == pytest.approx(1.0)
    for name in ("fig6a_reaction_forces.png", "fig6b_pin_path_fcr.png"):
        assert (tmp_path / name).stat().st_size > 10_000
