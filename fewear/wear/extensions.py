"""Physical extensions of Archard's law: a multiplier on the wear coefficient k(p, v).

k = k(p, v) m(state), the state being one contact point's history (sliding distance, time in
contact, lagged frictional power, crank cycles): running-in by distance, cycles or time (Blau,
Tribol. Int. 38 (2005) 1007-1012; Quinn 1983) and a thermal law (Archard 1959; Lim & Ashby 1987).
Configured by the ``[wear]`` keys ``extension`` and ``extension_params``.
Method notes: docs/run.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import check_exact_keys


@dataclass(frozen=True)
class SlidingState:
    """The history of one contact point (arrays broadcast; all start at zero).

    ``distance_m``: accumulated sliding distance; ``time_s``: time in sliding contact;
    ``lagged_power_W_m2``: frictional power mu p v through the thermal lag of :class:`Thermal`
    (zero for the other extensions); ``cycles``: the crank cycles the joint has run (the same at
    every point; :class:`RunningInCycles`).
    """

    distance_m: np.ndarray | float = 0.0
    time_s: np.ndarray | float = 0.0
    lagged_power_W_m2: np.ndarray | float = 0.0
    cycles: float = 0.0


def _check_positive(name: str, value: float, allowed: str) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise FewearInputError(f"[wear] extension_params {name} = {value!r}: expected a number")
    if not (math.isfinite(value) and value > 0.0):
        raise FewearInputError(f"[wear] extension_params {name} = {value!r}: expected {allowed}")


def _check_ratio(value: float) -> None:
    _check_positive("k_initial_over_steady", value, "a number >= 1 (k falls to its steady value)")
    if value < 1.0:
        raise FewearInputError(
            f"[wear] extension_params k_initial_over_steady = {value!r}: expected a number >= 1 "
            "(k falls from the initial to the steady value; a rising k is the thermal extension)"
        )


def _advance_common(state: SlidingState, ds_m, dt_s, cycles: float) -> SlidingState:
    return replace(state, distance_m=state.distance_m + np.asarray(ds_m),
                   time_s=state.time_s + np.asarray(dt_s), cycles=state.cycles + float(cycles))


@dataclass(frozen=True)
class NoExtension:
    """Plain Archard: m = 1."""

    name = "none"
    required_variables = ()

    def multiplier(self, state: SlidingState) -> np.ndarray:
        return np.ones_like(np.asarray(state.distance_m, dtype=float))

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        return _advance_common(state, ds_m, dt_s, cycles)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        return np.asarray(distance_m, dtype=float)

    def params(self) -> dict[str, float]:
        return {}


@dataclass(frozen=True)
class RunningIn:
    """m(s) = 1 + (r - 1) exp(-s / s0) (Blau 2005); S_eff = s + (r - 1) s0 (1 - exp(-s / s0)).

    ``k_initial_over_steady`` r >= 1; ``distance_scale_m`` s0 > 0.
    """

    k_initial_over_steady: float
    distance_scale_m: float
    name = "running_in"
    required_variables = ("sliding_distance_m",)

    def __post_init__(self):
        _check_ratio(self.k_initial_over_steady)
        _check_positive("distance_scale_m", self.distance_scale_m, "a positive distance in m")

    def multiplier(self, state: SlidingState) -> np.ndarray:
        s = np.asarray(state.distance_m, dtype=float)
        return 1.0 + (self.k_initial_over_steady - 1.0) * np.exp(-s / self.distance_scale_m)

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        return _advance_common(state, ds_m, dt_s, cycles)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        s = np.asarray(distance_m, dtype=float)
        s0 = self.distance_scale_m
        return s + (self.k_initial_over_steady - 1.0) * s0 * -np.expm1(-s / s0)

    def params(self) -> dict[str, float]:
        return {"k_initial_over_steady": float(self.k_initial_over_steady),
                "distance_scale_m": float(self.distance_scale_m)}


@dataclass(frozen=True)
class RunningInPowerLaw(RunningIn):
    """m(s) = 1 + (r - 1) / (1 + s / s0) (Blau 2005, hyperbolic break-in);
    S_eff = s + (r - 1) s0 ln(1 + s / s0).

    ``k_initial_over_steady`` r >= 1; ``distance_scale_m`` s0 > 0.
    """

    name = "running_in_power_law"

    def multiplier(self, state: SlidingState) -> np.ndarray:
        s = np.asarray(state.distance_m, dtype=float)
        return 1.0 + (self.k_initial_over_steady - 1.0) / (1.0 + s / self.distance_scale_m)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        s = np.asarray(distance_m, dtype=float)
        s0 = self.distance_scale_m
        return s + (self.k_initial_over_steady - 1.0) * s0 * np.log1p(s / s0)


@dataclass(frozen=True)
class RunningInCycles:
    """m(N) = 1 + (r - 1) exp(-N / N0), N the crank cycles run (Blau 2005), at every bore point
    alike; the wear after N cycles is that of plain Archard after the effective cycles
    N_eff = N + (r - 1) N0 (1 - exp(-N / N0)) (:meth:`effective_cycles`): the law of
    :meth:`on_cycle_axis` with the crank cycles for the sliding distance.

    ``k_initial_over_steady`` r >= 1; ``scale_cycles`` N0 > 0.
    """

    k_initial_over_steady: float
    scale_cycles: float
    name = "running_in_cycles"
    required_variables = ("cycles",)

    def __post_init__(self):
        _check_ratio(self.k_initial_over_steady)
        _check_positive("scale_cycles", self.scale_cycles, "a positive number of crank cycles")

    def on_cycle_axis(self) -> RunningIn | RunningInPowerLaw:
        """The law of the sliding distance that this one is of the crank cycles."""
        return RunningIn(self.k_initial_over_steady, self.scale_cycles)

    def multiplier(self, state: SlidingState) -> np.ndarray:
        fall = self.on_cycle_axis().multiplier(SlidingState(distance_m=state.cycles))
        return np.full(np.shape(state.distance_m), float(fall))

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        return _advance_common(state, ds_m, dt_s, cycles)

    def effective_cycles(self, cycles) -> np.ndarray:
        return self.on_cycle_axis().effective_distance_m(cycles)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        raise FewearInputError(
            f"{self.name} extension: driven by a mechanism's crank cycles; a test at one "
            "sliding speed has none (use running_in or time_transient)")

    def params(self) -> dict[str, float]:
        return {"k_initial_over_steady": float(self.k_initial_over_steady),
                "scale_cycles": float(self.scale_cycles)}


@dataclass(frozen=True)
class RunningInCyclesPowerLaw(RunningInCycles):
    """m(N) = 1 + (r - 1) / (1 + N / N0) (Blau 2005, hyperbolic break-in) over the crank cycles
    N, at every bore point alike: N_eff = N + (r - 1) N0 ln(1 + N / N0).

    ``k_initial_over_steady`` r >= 1; ``scale_cycles`` N0 > 0.
    """

    name = "running_in_cycles_power_law"

    def on_cycle_axis(self) -> RunningInPowerLaw:
        return RunningInPowerLaw(self.k_initial_over_steady, self.scale_cycles)


@dataclass(frozen=True)
class TimeTransient:
    """m(t) = 1 + (r - 1) exp(-t / tau) (oxide/tribofilm growth, Quinn 1983).

    At constant speed v = s / t: S_eff = s + (r - 1) v tau (1 - exp(-t / tau)).
    ``k_initial_over_steady`` r >= 1; ``time_scale_s`` tau > 0.
    """

    k_initial_over_steady: float
    time_scale_s: float
    name = "time_transient"
    required_variables = ("sliding_distance_m", "time_s")

    def __post_init__(self):
        _check_ratio(self.k_initial_over_steady)
        _check_positive("time_scale_s", self.time_scale_s, "a positive time in s")

    def multiplier(self, state: SlidingState) -> np.ndarray:
        t = np.asarray(state.time_s, dtype=float)
        return 1.0 + (self.k_initial_over_steady - 1.0) * np.exp(-t / self.time_scale_s)

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        return _advance_common(state, ds_m, dt_s, cycles)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        s, t = _distance_and_time(distance_m, time_s, self.name)
        tau = self.time_scale_s
        speed = _mean_speed(s, t)
        return s + (self.k_initial_over_steady - 1.0) * speed * tau * -np.expm1(-t / tau)

    def params(self) -> dict[str, float]:
        return {"k_initial_over_steady": float(self.k_initial_over_steady),
                "time_scale_s": float(self.time_scale_s)}


@dataclass(frozen=True)
class Thermal:
    """m = 1 + beta theta, d theta/dt = (mu p v - theta) / tau (Archard 1959; Quinn; Lim & Ashby).

    At constant speed v = s / t and power q = mu p v:
    S_eff = s + beta q (s - v tau (1 - exp(-t / tau))).
    ``beta_m2_W`` >= 0 per unit frictional power [m^2/W]; ``time_scale_s`` tau > 0, the thermal
    time constant of the pin.
    """

    beta_m2_W: float
    time_scale_s: float
    name = "thermal"
    required_variables = ("sliding_distance_m", "time_s", "friction_coefficient")

    def __post_init__(self):
        if isinstance(self.beta_m2_W, bool) or not isinstance(self.beta_m2_W, (int, float)) or not (
            math.isfinite(self.beta_m2_W) and self.beta_m2_W >= 0.0
        ):
            raise FewearInputError(
                f"[wear] extension_params beta_m2_W = {self.beta_m2_W!r}: expected a number >= 0 "
                "(k rises with frictional power)"
            )
        _check_positive("time_scale_s", self.time_scale_s, "a positive time in s")

    def multiplier(self, state: SlidingState) -> np.ndarray:
        return 1.0 + self.beta_m2_W * np.asarray(state.lagged_power_W_m2, dtype=float)

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        """Exact update of the lag for power held constant over the step."""
        decay = np.exp(-np.asarray(dt_s, dtype=float) / self.time_scale_s)
        power = np.asarray(power_W_m2, dtype=float)
        lagged = power + (np.asarray(state.lagged_power_W_m2) - power) * decay
        return replace(_advance_common(state, ds_m, dt_s, cycles), lagged_power_W_m2=lagged)

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        s, t = _distance_and_time(distance_m, time_s, self.name)
        if power_W_m2 is None:
            raise FewearInputError("thermal extension: needs the frictional power mu p v")
        q = np.asarray(power_W_m2, dtype=float)
        tau = self.time_scale_s
        speed = _mean_speed(s, t)
        return s + self.beta_m2_W * q * (s - speed * tau * -np.expm1(-t / tau))

    def params(self) -> dict[str, float]:
        return {"beta_m2_W": float(self.beta_m2_W), "time_scale_s": float(self.time_scale_s)}


WearExtension = (NoExtension | RunningIn | RunningInPowerLaw | RunningInCycles
                 | RunningInCyclesPowerLaw | TimeTransient
                 | Thermal)

EXTENSIONS: dict[str, type] = {
    "none": NoExtension,
    "running_in": RunningIn,
    "running_in_power_law": RunningInPowerLaw,
    "running_in_cycles": RunningInCycles,
    "running_in_cycles_power_law": RunningInCyclesPowerLaw,
    "time_transient": TimeTransient,
    "thermal": Thermal,
}


def _distance_and_time(distance_m, time_s, name: str) -> tuple[np.ndarray, np.ndarray]:
    if time_s is None:
        raise FewearInputError(f"{name} extension: needs the sliding time (time_s or a velocity)")
    s, t = np.broadcast_arrays(np.asarray(distance_m, float), np.asarray(time_s, float))
    return s, t


def _mean_speed(s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """s / t, the constant sliding speed of a test (0 where t = 0, where s is 0 too)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t > 0.0, s / np.where(t > 0.0, t, 1.0), 0.0)


def make_extension(name: str, params: dict[str, Any]) -> WearExtension:
    """The extension ``name`` with ``params`` (keys as in the classes above)."""
    if name not in EXTENSIONS:
        raise FewearInputError(
            f"[wear] extension = {name!r}: expected one of {', '.join(map(repr, EXTENSIONS))}"
        )
    cls = EXTENSIONS[name]
    allowed = [f.name for f in fields(cls)]
    if not isinstance(params, dict):
        raise FewearInputError(f"[wear] extension_params = {params!r}: expected a table")
    check_exact_keys(params, allowed, f"[wear] extension_params for extension {name!r}")
    return cls(**params)


def wear_extension_from_config(section: dict[str, Any]) -> WearExtension:
    """The extension a ``[wear]`` section selects (``extension``, ``extension_params``)."""
    return make_extension(section.get("extension", "none"), section.get("extension_params", {}))


def extension_to_config(extension: WearExtension) -> dict[str, Any]:
    """The ``[wear]`` keys ``extension`` and ``extension_params`` that rebuild ``extension``."""
    return {"extension": extension.name, "extension_params": extension.params()}


def distance_at_effective_m(extension: NoExtension | RunningIn, effective_m) -> np.ndarray:
    """The sliding distance s at which a distance-driven extension's S_eff(s) reaches
    ``effective_m`` (the inverse of :meth:`effective_distance_m`). S_eff is increasing and
    concave for these (m >= 1, non-increasing), so Newton's iteration s <- s - (S_eff(s) - y) /
    m(s) from s = y lands left of the root after one step and then rises to it monotonically."""
    target = np.asarray(effective_m, dtype=float)
    if extension.name == "none":
        return target.copy()
    s = target.copy()
    for _ in range(100):
        step = (extension.effective_distance_m(s) - target) / extension.multiplier(
            SlidingState(distance_m=s))
        s = np.maximum(s - step, 0.0)
        if np.all(np.abs(step) <= 1e-13 * np.maximum(target, 1e-300)):
            break
    return s
