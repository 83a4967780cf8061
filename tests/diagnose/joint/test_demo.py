"""demos/diagnose_joint.py runs as a test: the rigid-rod model against a flexible mechanism's
measured wear names link flexibility.

Slow (`make slow`): the demo's diagnosis is the full catalogue on the full campaign (nine
flexible-rod runs among some twenty forward runs; 5-10 minutes). The default suite diagnoses a
hidden cause end to end, `fewear diagnose` included, on a short campaign
(tests/diagnose/joint/test_diagnose.py)."""

import runpy
from pathlib import Path

import pytest

DEMO = Path(__file__).resolve().parents[3] / "demos" / "diagnose_joint.py"


@pytest.mark.slow
def test_demo_names_link_flexibility(tmp_path, monkeypatch):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    runpy.run_path(str(DEMO), run_name="__main__")
    assert (tmp_path / "diagnosis" / "joint_fits.png").stat().st_size > 0
