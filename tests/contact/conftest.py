"""Fixtures of the contact tests."""

import runpy
from pathlib import Path

import pytest

HERTZ_DEMO = Path(__file__).resolve().parents[2] / "demos" / "hertz_contact.py"


@pytest.fixture(scope="session")
def hertz_demo(tmp_path_factory):
    """demos/hertz_contact.py run once, in this process, on its full meshes: its output folder and
    its namespace (the refinement study's constants, table rows and FE results). Shared by the
    demo's test and the FE-against-Hertz tests (both in tests/contact/test_hertz.py, one file:
    the test run gives each file to one worker), which solve the same three meshes."""
    out = tmp_path_factory.mktemp("hertz_demo")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("FEWEAR_DEMO_OUT", str(out))
        patch.setenv("MPLBACKEND", "Agg")
        patch.delenv("FEWEAR_DEMO_COARSE", raising=False)
        namespace = runpy.run_path(str(HERTZ_DEMO), run_name="__main__")
    return out, namespace
