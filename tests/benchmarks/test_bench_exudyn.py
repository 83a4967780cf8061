"""Exudyn as the peer of fewear's ideal-joint rigid slider-crank (issue 3, item 9).

The Exudyn model is checked against the closed form here (a fast test of the peer itself); the
side-by-side timing is a benchmark (``make bench``) that prints figures and asserts no times.
"""

import pytest

from exudyn_slider_crank import SliderCrankParameters, run_exudyn_slider_crank, slider_closed_form

pytest.importorskip("exudyn")


def test_exudyn_peer_matches_the_closed_form():
    params = SliderCrankParameters()
    time_s, slider_x_m, _ = run_exudyn_slider_crank(1e-4, 0.05, params)
    assert time_s[-1] == pytest.approx(0.05)
    expected, _ = slider_closed_form(params, time_s)
    assert abs(slider_x_m - expected).max() < 1e-10
