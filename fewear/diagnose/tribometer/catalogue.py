"""The catalogue of candidate causes of the tribometer diagnosis: departures from Archard's law
V = k F s, each a law of one to three parameters in one or more forms, acting on ln V along
sliding (shape laws) or across tests (level laws). The laws and their sources:
docs/diagnosis-method-notes.md."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy import special

from fewear.diagnose.core.cause import Cause
from fewear.wear.extensions import (
    RunningIn,
    RunningInPowerLaw,
    Thermal,
    TimeTransient,
    WearExtension,
)


@dataclass(frozen=True)
class Context:
    """Per row (a reading, or a test in the across-test stage) what the laws read, SI units.

    ``distance_m``, ``time_s``: sliding distance and time (None for test-level rows);
    ``power_W_m2``: frictional power mu p v; ``load``: pressure [Pa] or normal load [N] (which one
    says ``load_name``); ``load_speed``: load times speed; each None when not measured.
    ``scales``: the campaign's median final distance [m] and time [s], largest mu p v.
    """

    distance_m: np.ndarray | None
    time_s: np.ndarray | None
    power_W_m2: np.ndarray | None
    load: np.ndarray | None
    load_name: str
    load_speed: np.ndarray | None
    scale_distance_m: float
    scale_time_s: float | None
    scale_power_W_m2: float | None


@dataclass(frozen=True)
class ShapeLaw:
    """A shape law: the extension whose effective distance bends the wear curve."""

    extension: WearExtension

    def log_multiplier(self, context: Context) -> np.ndarray:
        s = context.distance_m
        return np.log(self.extension.effective_distance_m(s, context.time_s,
                                                          context.power_W_m2) / s)

    def params(self) -> dict[str, float]:
        return self.extension.params()


@dataclass(frozen=True)
class LoadExponent:
    """m = (x / reference)^(exponent - 1): wear grows as x^exponent (x: ``variable``)."""

    exponent: float
    reference: float
    variable: str

    def log_multiplier(self, context: Context) -> np.ndarray:
        return (self.exponent - 1.0) * np.log(context.load / self.reference)

    def params(self) -> dict[str, float]:
        return {"exponent": float(self.exponent)}


@dataclass(frozen=True)
class MildToSevere:
    """m = 1 + (jump - 1) / (1 + exp(-(ln x - ln threshold) / width)): k rises by ``jump`` across
    ``threshold`` of x (``variable``, the load or load x speed), over a ``width`` in ln x (a step
    as the width goes to 0, a smooth transition otherwise)."""

    jump: float
    threshold: float
    width: float
    variable: str

    def log_multiplier(self, context: Context) -> np.ndarray:
        x = context.load if self.variable in ("pressure", "normal load") else context.load_speed
        rise = special.expit((np.log(x) - np.log(self.threshold)) / self.width)
        return np.log1p((self.jump - 1.0) * rise)

    def params(self) -> dict[str, float]:
        unit = {"pressure": "Pa", "normal load": "N", "p v": "W_m2", "F v": "W"}[self.variable]
        return {"k_severe_over_mild": float(self.jump),
                f"threshold_{self.variable.replace(' ', '_')}_{unit}": float(self.threshold),
                "width_in_ln_x": float(self.width)}


@dataclass(frozen=True)
class SteadyHeating:
    """ln m = activation x q / (q + power_scale): an Arrhenius wear rate k ~ exp(-Q / (R T)) at
    the steady temperature T = T0 (1 + q / power_scale) of a test, the rise proportional to its
    frictional power q (mu p v, or p v / F v without a friction coefficient: ``variable``;
    Archard 1959 for the rise, Quinn 1983 for the Arrhenius rate); activation = Q / (R T0),
    power_scale the power that doubles the absolute temperature. k rises with q and levels off
    (a broad transition in ln q)."""

    activation: float
    power_scale: float
    variable: str

    def log_multiplier(self, context: Context) -> np.ndarray:
        q = _power(context)[0]
        return self.activation * q / (q + self.power_scale)

    def params(self) -> dict[str, float]:
        return {"activation_Q_over_RT0": float(self.activation),
                f"power_scale_{self.variable.replace(' ', '_')}": float(self.power_scale)}


def _power(context: Context) -> tuple[np.ndarray, str]:
    """The frictional power mu p v when the friction is known, else p v (or F v)."""
    if context.power_W_m2 is not None:
        return context.power_W_m2, "mu p v"
    return context.load_speed, "p v" if context.load_name == "pressure" else "F v"


Law = ShapeLaw | LoadExponent | MildToSevere | SteadyHeating


@dataclass(frozen=True)
class Form:
    """One form of a cause.

    ``kind``: "shape" (along sliding) or "level" (across tests); ``needs``: what the data must
    hold (``time``, ``friction``, ``pressure``, ``load``: a load or pressure that varies between
    tests, ``power``: a load or pressure and a speed whose product varies); ``law(x, context)``: the
    law for the search vector x; ``bounds``: (lower, upper) per entry of x; ``starts(context)``:
    start points of x.
    """

    cause: str
    name: str
    kind: str
    needs: tuple[str, ...]
    law: Callable[[np.ndarray, Context], Law]
    bounds: tuple[tuple[float, float], ...]
    starts: Callable[[Context], list[tuple[float, ...]]]

    @property
    def all_needs(self) -> set[str]:
        """``needs``, with "distance" for a shape law (the wear curve along sliding)."""
        return set(self.needs) | ({"distance"} if self.kind == "shape" else set())


# amplitude: ln(r - 1) or ln(beta q_max) in [ln 1e-3, ln 1e3]; scale: ln(s0/S) or ln(tau/T) in
# [ln 1e-4, ln 10] (a transient much longer than the tests is a curvature, much shorter an offset).
_SHAPE_BOUNDS = ((np.log(1e-3), np.log(1e3)), (np.log(1e-4), np.log(10.0)))
_SHAPE_STARTS = [(a, b) for a in np.log([0.3, 1.0, 3.0])
                 for b in np.log([0.003, 0.01, 0.03, 0.1, 0.3, 1.0])]


def _shape_starts(context: Context) -> list[tuple[float, ...]]:
    return _SHAPE_STARTS


def _running_in(x, c: Context) -> Law:
    return ShapeLaw(RunningIn(1.0 + float(np.exp(x[0])), float(np.exp(x[1])) * c.scale_distance_m))


def _running_in_power(x, c: Context) -> Law:
    return ShapeLaw(RunningInPowerLaw(1.0 + float(np.exp(x[0])),
                                      float(np.exp(x[1])) * c.scale_distance_m))


def _time_transient(x, c: Context) -> Law:
    return ShapeLaw(TimeTransient(1.0 + float(np.exp(x[0])), float(np.exp(x[1])) * c.scale_time_s))


def _thermal(x, c: Context) -> Law:
    return ShapeLaw(Thermal(float(np.exp(x[0])) / c.scale_power_W_m2,
                            float(np.exp(x[1])) * c.scale_time_s))


def _reference(values: np.ndarray) -> float:
    return float(np.exp(np.mean(np.log(values))))


def _load_exponent(x, c: Context) -> Law:
    return LoadExponent(1.0 + float(x[0]), _reference(c.load), c.load_name)


def _threshold_law(variable_of: Callable[[Context], tuple[np.ndarray, str]]):
    def law(x, c: Context) -> Law:
        values, name = variable_of(c)
        return MildToSevere(float(np.exp(x[0])), _reference(values) * float(np.exp(x[1])),
                            float(np.exp(x[2])), name)
    return law


def _threshold_starts(variable_of: Callable[[Context], tuple[np.ndarray, str]]):
    """Thresholds midway (in log) between neighbouring distinct values, as a step (width 0.01)
    and as smooth transitions (widths 0.3 and 1 in ln x)."""
    def starts(c: Context) -> list[tuple[float, ...]]:
        values, _ = variable_of(c)
        levels = np.unique(np.round(np.log(values / _reference(values)), 9))
        middles = 0.5 * (levels[1:] + levels[:-1])
        return [(np.log(2.0), float(m), np.log(w)) for m in middles for w in (0.01, 0.3, 1.0)]
    return starts


def _by_load(c: Context) -> tuple[np.ndarray, str]:
    return c.load, c.load_name


def _by_load_speed(c: Context) -> tuple[np.ndarray, str]:
    return c.load_speed, "p v" if c.load_name == "pressure" else "F v"


def _steady_heating(x, c: Context) -> Law:
    power, name = _power(c)
    return SteadyHeating(float(np.exp(x[0])), float(np.exp(x[1])) * float(np.max(power)), name)


_THRESHOLD_BOUNDS = ((0.0, np.log(1e3)), (np.log(1e-6), np.log(1e6)),
                     (np.log(0.01), np.log(3.0)))

FORMS: tuple[Form, ...] = (
    Form("running_in", "exponential", "shape", (), _running_in, _SHAPE_BOUNDS, _shape_starts),
    Form("running_in", "power_law", "shape", (), _running_in_power, _SHAPE_BOUNDS,
         _shape_starts),
    Form("time_transient", "exponential", "shape", ("time",), _time_transient, _SHAPE_BOUNDS,
         _shape_starts),
    Form("thermal", "lagged_power", "shape", ("time", "friction", "pressure"), _thermal,
         _SHAPE_BOUNDS, _shape_starts),
    Form("thermal", "steady_power", "level", ("power",), _steady_heating,
         ((np.log(1e-3), np.log(50.0)), (np.log(1e-3), np.log(1e3))),
         lambda c: [(a, b) for a in np.log([0.5, 2.0]) for b in np.log([0.1, 1.0, 10.0])]),
    Form("load_exponent", "power_law", "level", ("load",), _load_exponent, ((-0.95, 2.0),),
         lambda c: [(0.0,)]),
    Form("mild_to_severe", "load_threshold", "level", ("load",), _threshold_law(_by_load),
         _THRESHOLD_BOUNDS, _threshold_starts(_by_load)),
    Form("mild_to_severe", "load_speed_threshold", "level", ("power",),
         _threshold_law(_by_load_speed), _THRESHOLD_BOUNDS, _threshold_starts(_by_load_speed)),
)

NEEDS_TEXT = {"time": "time_s (or velocity_m_s, from which t = s / v)",
              "friction": "friction_coefficient", "pressure": "pressure_Pa",
              "load": "normal_load_N or pressure_Pa that varies between tests",
              "power": "normal_load_N or pressure_Pa, and velocity_m_s, whose product varies "
                       "between tests",
              "distance": "tests or readings at different sliding distances under one material"}
"""What each of the forms' needs asks of the data's columns."""


def forms_of(cause: str) -> tuple[Form, ...]:
    return tuple(form for form in FORMS if form.cause == cause)


def missing_needs(cause: str, have: set[str]) -> list[str]:
    """What data holding ``have`` lack for ``cause``: the fewest needs any of its forms misses
    ([] where a form can be fitted)."""
    missing_per_form = [sorted(form.all_needs - have) for form in forms_of(cause)]
    return min(missing_per_form, key=len) if all(missing_per_form) else []


def _lacking(cause: str, have: set[str]) -> str | None:
    missing = missing_needs(cause, have)
    if not missing:
        return None
    return "could not be tested: needs " + " and ".join(NEEDS_TEXT[need] for need in missing)


_MEANINGS = {
    "running_in": "k falls from an initial to a steady value over sliding distance (running-in, "
                  "Blau 2005; exponential or power-law approach)",
    "time_transient": "k falls from an initial to a steady value over time (oxide or tribofilm "
                      "growth, Quinn 1983)",
    "thermal": "k rises with the frictional power mu p v of the test, at once or through the "
               "pin's heating lag (frictional heating, Archard 1959; Quinn 1983; Lim & Ashby "
               "1987)",
    "load_exponent": "wear grows as a power of the load (or pressure) other than 1 "
                     "(Rhee 1970)",
    "mild_to_severe": "k jumps to a higher (severe) value above a load, pressure or p v threshold "
                      "(Welsh 1965; Lim & Ashby 1987)",
}
CAUSES = {name: Cause(name, meaning, tuple(form.name for form in forms_of(name)),
                      partial(_lacking, name)) for name, meaning in _MEANINGS.items()}
"""The causes of the catalogue, by name, in the order they are listed; each untestable by the
measured quantities (:func:`missing_needs`)."""
