"""The wear demo (the paper's Fig. 7 with the runs' spread) on a short, coarse case: its numbers
hang together with the run folders it made."""

import json
import runpy
from pathlib import Path

import numpy as np
import pytest

DEMO = Path(__file__).resolve().parents[1] / "demos" / "slider_crank_wear.py"
CYCLES = 4000


def test_demo_runs_members_of_both_rods_and_reports_their_spread(tmp_path, monkeypatch):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    monkeypatch.setenv("FEWEAR_DEMO_TOTAL_CYCLES", str(CYCLES))
    monkeypatch.setenv("FEWEAR_DEMO_MEMBERS", "2")
    monkeypatch.setenv("FEWEAR_DEMO_QUICK", "1")
    monkeypatch.setenv("FEWEAR_DEMO_COARSE", "1")
    runpy.run_path(str(DEMO), run_name="__main__")
    results = json.loads((tmp_path / "results.json").read_text())
    assert results["reported_cycles"] == [CYCLES]
    (label, comparison), = results["comparison"].items()
    folders = [Path(f) for f in results["runs"][label]]
    assert len(folders) == 2
    # each member's maximum depth read back from its own run, and the spread recomputed
    depth = {}
    for rod in ("rigid", "flexible"):
        depth[rod] = []
        for folder in folders:
            summary = json.loads((folder / "summary.json").read_text())["cases"][rod][
                "joints"]["rod_slider"]
            assert summary["cycles"] == CYCLES
            depth[rod].append(summary["max_wear_depth_m"])
        assert comparison[f"{rod}_max_depth_m"]["mean"] == pytest.approx([np.mean(depth[rod])])
        assert comparison[f"{rod}_max_depth_m"]["sd"] == pytest.approx(
            [np.std(depth[rod], ddof=1)])
        assert results["axis_share"][rod] > 0.8  # the paper: wear left and right of the bore
    ratios = np.array(depth["rigid"]) / np.array(depth["flexible"])
    assert comparison["rigid_over_flexible"]["mean"] == pytest.approx([ratios.mean()])
    # the members start at other crank angles and so differ (the spread is not zero by accident)
    assert comparison["rigid_max_depth_m"]["sd"][0] > 0.0
    for values in results["mechanics"][label].values():
        assert 0.0 < values["contact_share"] <= 1.0
        assert values["peak_force_N"] > values["mean_force_N"] > 0.0
        assert values["load_slip_J"] > 0.0
    assert (tmp_path / "max_wear_members.png").stat().st_size > 10_000
    for name in ("wear_profiles.png", "max_wear.png", "rigid-rod_slider.xdmf",
                 "flexible-rod_slider.xdmf"):
        assert (folders[0] / name).stat().st_size > 0
