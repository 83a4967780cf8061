"""Make the SYNTHETIC pin-on-disc data set ``pin_on_disc_running_in_synthetic.csv`` (a demo of
``fewear diagnose``: a campaign with a running-in hidden in it). It is no measurement. Regenerate
it bit for bit with::

    python -m tests.data_makers.make_running_in_pin_on_disc

Made by the forward model :func:`tests.diagnose.tribometer.campaign_generator.simulate_campaign`:
CuZn25Al6Fe3Mn3 pin (diameter 6 mm) on a 42CrMo disc, 3 pressures x 3 speeds (one test each,
shuffled order), 10 cumulative readings per test every 200 m to 2000 m, k = 2e-13 m^2/N times a
running-in k(s) = k [1 + (R - 1) exp(-s / S0)] with R = K_INITIAL_OVER_STEADY,
S0 = DISTANCE_SCALE_m; 3 % relative noise per reading (readings that dip are kept), lognormal
scatter 0.10 per test on k; friction coefficient 0.3 x lognormal(0.1) per test.
"""

from __future__ import annotations

import numpy as np

from fewear.data import RUNNING_IN_SYNTHETIC_CSV
from fewear.wear.extensions import RunningIn
from tests.diagnose.tribometer.campaign_generator import (
    grid_campaign,
    simulate_campaign,
    write_measured_csv,
)

SEED = 20240611
K_INITIAL_OVER_STEADY = 5.0
DISTANCE_SCALE_m = 150.0
OUTPUT = RUNNING_IN_SYNTHETIC_CSV
HEADER = (
    "SYNTHETIC pin-on-disc data with a HIDDEN departure from Archard's law: not a measurement.\n"
    "CuZn25Al6Fe3Mn3 pin (6 mm) on 42CrMo disc; 3 pressures x 3 speeds, 10 cumulative readings\n"
    "every 200 m.\n"
    f"Made by tests/data_makers/make_running_in_pin_on_disc.py (numpy default_rng({SEED}))\n"
    "with the forward model tests/diagnose/tribometer/campaign_generator.py:\n"
    "k(s) = k [1 + (R - 1) exp(-s / S0)],\n"
    f"R = {K_INITIAL_OVER_STEADY:g}, S0 = {DISTANCE_SCALE_m:g} m (running-in); 3 % noise per "
    "reading (dips kept),\nlognormal scatter 0.10 per test. Used by demos/diagnose_tribometer.py; "
    "SI units in the\ncolumn names."
)


def make() -> dict[str, np.ndarray]:
    rng = np.random.default_rng(SEED)
    campaign = grid_campaign(rng=rng)
    return simulate_campaign(RunningIn(K_INITIAL_OVER_STEADY, DISTANCE_SCALE_m), campaign, rng)


if __name__ == "__main__":
    write_measured_csv(OUTPUT, make(), HEADER)
    print(f"wrote {OUTPUT}")
