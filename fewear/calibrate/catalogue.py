"""The catalogue of candidate causes: physical extensions of Archard's law with two parameters each.

Each entry says which measured variables it needs, how its two parameters are mapped to an
unconstrained search vector x (logarithms, scaled by the campaign's own distances, times and
frictional powers so that one start grid serves every data set) and where the search starts.
The physics (formulas and citations) is in :mod:`fewear.wear.extensions`; ``none`` (plain Archard)
is the baseline itself and has no entry here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fewear.wear.extensions import RunningIn, Thermal, TimeTransient, WearExtension


@dataclass(frozen=True)
class Scales:
    """Characteristic sizes of a data set: median final distance [m] and time [s] of the tests,
    and the largest frictional power mu p v [W/m^2] (None when not measured)."""

    distance_m: float
    time_s: float | None
    power_W_m2: float | None


@dataclass(frozen=True)
class Candidate:
    """A cause of the catalogue.

    ``needs``: measured variables (names of the CSV schema) without which it cannot be tested;
    ``build(x, scales)``: the extension for the search vector x (2 numbers);
    ``bounds``: lower and upper bounds of x; ``starts``: start points of x;
    ``meaning``: what the cause is, in a sentence for the report.
    """

    name: str
    needs: tuple[str, ...]
    build: Callable[[np.ndarray, Scales], WearExtension]
    bounds: tuple[tuple[float, float], tuple[float, float]]
    starts: tuple[tuple[float, float], ...]
    meaning: str


# amplitude: ln(r - 1) or ln(beta q_max) in [ln 1e-3, ln 1e3]; scale: ln(s0/S) or ln(tau/T) in
# [ln 1e-3, ln 10] (a transient much longer than the tests is a curvature, much shorter an offset).
_BOUNDS = ((np.log(1e-3), np.log(1e3)), (np.log(1e-3), np.log(10.0)))
_STARTS = tuple((a, b) for a in np.log([0.3, 1.0, 3.0])
                for b in np.log([0.01, 0.03, 0.1, 0.3, 1.0]))


def _running_in(x, scales: Scales) -> WearExtension:
    return RunningIn(1.0 + float(np.exp(x[0])), float(np.exp(x[1])) * scales.distance_m)


def _time_transient(x, scales: Scales) -> WearExtension:
    return TimeTransient(1.0 + float(np.exp(x[0])), float(np.exp(x[1])) * scales.time_s)


def _thermal(x, scales: Scales) -> WearExtension:
    return Thermal(float(np.exp(x[0])) / scales.power_W_m2, float(np.exp(x[1])) * scales.time_s)


CATALOGUE: dict[str, Candidate] = {
    "running_in": Candidate(
        "running_in", ("sliding_distance_m",), _running_in, _BOUNDS, _STARTS,
        "k falls from an initial to a steady value over sliding distance (running-in, Blau 2005)",
    ),
    "time_transient": Candidate(
        "time_transient", ("time_s",), _time_transient, _BOUNDS, _STARTS,
        "k falls from an initial to a steady value over time (oxide or tribofilm growth, Quinn)",
    ),
    "thermal": Candidate(
        "thermal", ("time_s", "friction_coefficient", "pressure_Pa"), _thermal, _BOUNDS, _STARTS,
        "k rises with the lagged frictional power mu p v of the test (frictional heating, "
        "Archard 1959; Lim & Ashby 1987)",
    ),
}
CAUSE_NAMES = ("none", *CATALOGUE)
