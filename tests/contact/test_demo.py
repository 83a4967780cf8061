"""demos/hertz_contact.py runs and produces what it promises: a convergence table whose finest
errors against Hertz are small, a positive fitted rate, and the plot. (The demo's run is the
session fixture ``hertz_demo`` of tests/contact/conftest.py, shared with tests/contact/
test_hertz.py.)"""

import csv

import numpy as np


def test_hertz_demo(hertz_demo):
    tmp_path, _ = hertz_demo

    with open(tmp_path / "convergence.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) >= 3
    sizes = np.array([float(row["bore_element_size_m"]) for row in rows])
    assert np.all(np.diff(sizes) < 0)
    finest = rows[-1]
    assert abs(float(finest["peak_pressure_rel_error"])) < 0.03
    assert abs(float(finest["moment_half_width_rel_error"])) < 0.03
    assert all(float(row["force_balance_rel_error"]) < 1e-8 for row in rows)

    with open(tmp_path / "rates.csv", newline="") as handle:
        rates = {row["quantity"]: float(row["rate"]) for row in csv.DictReader(handle)}
    errors = np.abs([float(row["peak_pressure_rel_error"]) for row in rows])
    assert np.isclose(rates["peak_pressure_rel_error"],
                      np.polyfit(np.log(sizes), np.log(errors), 1)[0])
    assert rates["peak_pressure_rel_error"] > 0.0
    assert (tmp_path / "hertz_pressure.png").read_bytes()[:4] == b"\x89PNG"
