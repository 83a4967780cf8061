"""demos/diagnose_joint.py runs as a test: the rigid-rod model against a flexible mechanism's
measured wear names link flexibility."""

import runpy
from pathlib import Path

DEMO = Path(__file__).resolve().parents[2] / "demos" / "diagnose_joint.py"


def test_demo_names_link_flexibility(tmp_path, monkeypatch):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    runpy.run_path(str(DEMO), run_name="__main__")
    assert (tmp_path / "diagnosis" / "joint_fits.png").stat().st_size > 0
