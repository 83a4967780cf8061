"""Two independently written generators of synthetic tribometer data behind one interface, for the
tests and the benchmark of the diagnosis.

- ``fewear``: :mod:`tests.diagnose.tribometer.campaign_generator` (written with the diagnosis);
- ``independent``: ``tests/diagnose/tribometer/independent_generator.py``, written by another
  author without
  seeing the diagnosis (its own functional forms, scales, noise, column names and DOE layout).

Both data sets go through the CSV reader, as a user's file would. The sweep variables are those of
the independent generator's public interface: ``scale`` (the effect's length as a fraction of the
test: 0.01-0.5), ``noise`` (relative noise of the cumulative readings: 0.01-0.1) and ``sampling``
("histories": many readings per test; "table": one reading per test, a design of experiments).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fewear.diagnose.tribometer.measured import read_measured_wear
from fewear.diagnose.tribometer.readings import Readings, readings_from_measured
from tests.diagnose.tribometer.campaign_generator import (
    grid_campaign,
    hidden_case,
    table_campaign,
    write_measured_csv,
)
from tests.diagnose.tribometer.independent_generator import make_dataset, write_csv

GENERATORS = ("fewear", "independent")
CAUSES = ("running_in", "time_transient", "thermal", "load_exponent", "mild_to_severe")
SAMPLINGS = ("histories", "table")


def dataset(generator: str, cause: str, seed: int, folder: Path, *, scale: float = 0.1,
            noise: float = 0.03, sampling: str = "histories") -> Readings:
    """The readings of one synthetic data set with ``cause`` hidden in it (``"none"``: plain
    Archard), written to and read back from a CSV file in ``folder``."""
    path = Path(folder) / f"{generator}_{cause}_{sampling}_{seed}.csv"
    if generator == "fewear":
        rng = np.random.default_rng(seed)
        options = {"reading_scatter": noise}
        campaign = (grid_campaign(rng=rng, **options) if sampling == "histories"
                    else table_campaign(rng=rng, **options))
        columns, _, _ = hidden_case(cause, seed, campaign, effect_scale=scale)
        write_measured_csv(path, columns,
                           "SYNTHETIC (tests/diagnose/tribometer/campaign_generator.py)")
    elif generator == "independent":
        columns, _ = make_dataset(cause, seed, scale=scale, noise=noise,
                                  sampling="doe" if sampling == "table" else sampling)
        write_csv(path, columns)
    else:
        raise ValueError(f"generator {generator!r}: expected one of {GENERATORS}")
    return readings_from_measured(read_measured_wear(path))


def named(summary, cause: str) -> bool:
    """Among the causes named, or reported confounded with the first (the report then says the
    data cannot tell the two apart)."""
    confounded = {name for group in summary["confounded"] for name in group["causes"]}
    return cause in summary["causes"] or cause in confounded


def named_as_power_law(summary, cause: str) -> bool:
    """:func:`named`, or ``thermal`` hidden and ``mild_to_severe`` named with a threshold of the
    frictional power (p v or F v), or the reverse. Both generators define the two causes as k
    rising with p v (heating: smoothly; mild-to-severe: as a step or a sigmoid in ln p v), so a
    smooth p v threshold and heating are one law family that the data alone cannot name apart;
    the benchmark prints this figure next to the strict one."""
    if named(summary, cause):
        return True
    other = {"thermal": "mild_to_severe", "mild_to_severe": "thermal"}.get(cause)
    if other not in summary["causes"]:
        return False
    params = {name: value for stage in summary["stages"]
              for cause_name, values in stage["final_params"].items() if cause_name
              == "mild_to_severe" for name, value in values.items()}
    uses_power = any(key.startswith(("threshold_p_v", "threshold_F_v")) for key in params)
    return other == "thermal" or uses_power
