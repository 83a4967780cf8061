"""The wear demo (the paper's Fig. 7) runs on a short, coarse case and its numbers hang together."""

import json
import runpy
from pathlib import Path

import numpy as np

DEMO = Path(__file__).resolve().parents[1] / "demos" / "slider_crank_wear.py"


def test_demo_runs_both_rods_and_reports_fig_7(tmp_path, monkeypatch):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    monkeypatch.setenv("FEWEAR_DEMO_TOTAL_CYCLES", "4000")
    monkeypatch.setenv("FEWEAR_DEMO_COARSE", "1")
    runpy.run_path(str(DEMO), run_name="__main__")
    results = json.loads((tmp_path / "results.json").read_text())
    assert set(results["cases"]) == {"rigid", "flexible"}
    for rod, case in results["cases"].items():
        assert case["cycles"] == 4000
        assert results["axis_share"][rod] > 0.8  # the paper: wear left and right of the bore
    maxima = np.genfromtxt(tmp_path / "run" / "max_wear.csv", delimiter=",", names=True,
                           dtype=None, encoding=None)
    last = {rod: maxima["max_wear_depth_m"][maxima["case"] == rod][-1] for rod in ("rigid",
                                                                                 "flexible")}
    ratio = dict(results["rigid_over_flexible"])[4000.0]
    assert ratio == last["rigid"] / last["flexible"]
    for name in ("wear_profiles.png", "max_wear.png", "rigid.xdmf", "flexible.xdmf"):
        assert (tmp_path / "run" / name).stat().st_size > 0
