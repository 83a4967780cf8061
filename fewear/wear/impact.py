"""Impact wear: bore material removed by the impacts of the clearance joint.

Three forms that may act together: by the hysteresis energy of the contact law (Fouvry et al.,
Wear 255 (2003) 287-298; Lankarani & Nikravesh damping), by the impacts' normal impulse
(optionally above a force threshold), and by a power of the impact speed (Engel 1976). Each
impact is spread under its own FE footprint. :class:`ImpactWearLaw` holds the coefficients
parsed from ``[wear]``. Method notes: docs/run.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid

from fewear.errors import FewearInputError
from fewear.mbd.history import impact_episodes

CONFIG_KEY = "impact_wear_coefficient_m3_J"
IMPULSE_CONFIG_KEY = "impact_impulse_wear_coefficient_m3_Ns"
THRESHOLD_CONFIG_KEY = "impact_impulse_force_threshold_N"
SPEED_CONFIG_KEY = "impact_speed_wear_coefficient"
EXPONENT_CONFIG_KEY = "impact_speed_exponent"
FORM_CONFIG_KEYS = {"energy": CONFIG_KEY, "impulse": IMPULSE_CONFIG_KEY,
                    "speed": SPEED_CONFIG_KEY}
"""The forms of impact wear, each by the ``[wear]`` key of its coefficient."""
MAX_SPEED_EXPONENT = 6.0
"""The largest ``impact_speed_exponent`` accepted (the forms of the literature lie in 1-3)."""


@dataclass(frozen=True)
class ImpactWearLaw:
    """The impact wear of a run (method notes): k_imp (m^3/J) on the hysteresis work, c_J
    (m^3/(N s)) on the impulse of the impacts whose peak normal force exceeds
    ``impulse_threshold_N``, c_v (m^3/(m/s)^n) on the n-th power of the impact speeds. All zero:
    sliding wear only (the default)."""

    energy_m3_J: float = 0.0
    impulse_m3_Ns: float = 0.0
    impulse_threshold_N: float = 0.0
    speed_coefficient: float = 0.0
    speed_exponent: float = 3.0

    @classmethod
    def from_config(cls, section: dict) -> ImpactWearLaw:
        """The law of a ``[wear]`` section; each value checked (:class:`FewearInputError`
        naming the key, the value and what is allowed)."""
        return cls(impact_wear_coefficient_from_config(section),
                   impact_impulse_wear_coefficient_from_config(section),
                   _coefficient(section, THRESHOLD_CONFIG_KEY, "N (the peak normal force an "
                                "impact must exceed for its impulse to wear; 0 = every impact)"),
                   _coefficient(section, SPEED_CONFIG_KEY, "m^3 per (m/s)^n (worn volume per "
                                "impact and n-th power of its approach speed; 0 = none)"),
                   _coefficient(section, EXPONENT_CONFIG_KEY, "(the power n of the impact "
                                "speed that impact wear grows with)", default=3.0,
                                upper=MAX_SPEED_EXPONENT))

    @property
    def wears_by_impacts(self) -> bool:
        """Whether any form removes material (then each impact's footprint is needed)."""
        return self.energy_m3_J > 0.0 or self.impulse_m3_Ns > 0.0 or self.speed_coefficient > 0.0

    def volume_m3(self, work_J, impulse_N_s, speed_power) -> np.ndarray:
        """The volume of each impact (m^3): k_imp W_k + c_J J_k + c_v v_k^n from its hysteresis
        work, impulse (0 below the threshold) and v^n."""
        return (self.energy_m3_J * np.asarray(work_J) + self.impulse_m3_Ns * np.asarray(impulse_N_s)
                + self.speed_coefficient * np.asarray(speed_power))


NO_IMPACT_WEAR = ImpactWearLaw()
"""Sliding wear only (every coefficient zero), the default."""


def hysteresis_work_J(law, penetration_m, normal_force_N) -> np.ndarray:
    """The hysteresis work done from the first sample to each sample of a history (J, (n,)).

    W(t_k) = integral of (F_n - F_el(delta)) d(delta) over [t_0, t_k] (delta_dot dt = d(delta)),
    by the trapezoid rule in delta between the samples (a Stieltjes sum: no rate needed, second
    order in the sampling step on variable steps). ``law``: the
    :class:`fewear.mbd.contact.ContactLaw` that produced ``normal_force_N``; ``penetration_m``:
    delta (<= 0 is no contact, F_el = 0).
    """
    delta = np.maximum(np.asarray(penetration_m, dtype=float), 0.0)
    elastic = np.array([law.elastic(d)[0] if d > 0.0 else 0.0 for d in delta])
    damping = np.asarray(normal_force_N, dtype=float) - elastic
    return cumulative_trapezoid(damping, delta, initial=0.0)


def impact_impulse_N_s(time_s, normal_force_N, mode, threshold_N: float = 0.0) -> np.ndarray:
    """The normal impulse of the impact episodes from the first sample to each sample (N s,
    (n,)): the trapezoid rule on F_n, counted on the intervals between two impact-mode samples
    (``mode`` 1, :data:`fewear.mbd.history.MODES`) and on those that enter or leave an episode
    (its force rises from or falls to zero there); only the episodes whose peak normal force
    exceeds ``threshold_N``."""
    force = np.where(np.asarray(mode) == 1, np.asarray(normal_force_N, dtype=float), 0.0)
    if threshold_N > 0.0:
        for first, last in impact_episodes(mode):
            if force[first:last + 1].max() <= threshold_N:
                force[first:last + 1] = 0.0
    return cumulative_trapezoid(force, np.asarray(time_s, dtype=float), initial=0.0)


def impact_speed_power(time_s, eccentricity_m, mode, exponent: float) -> np.ndarray:
    """v_k^n of each impact k at its episode's first sample, 0 at the others ((n_samples,),
    (m/s)^n): v_k the rate at which the pin centre's
    distance from the bushing's, |e| (``eccentricity_m`` (n, 2)), grew over the step into the
    episode (from the sample before it, in free flight). The recorded penetration cannot give
    it: it is clipped at 0 out of contact, and the step into contact ends a few tens of
    nanometres in. The bore's own slope along the pin's path is left out (on a worn bore
    |e| grows by dc/dtheta dtheta over the step without a normal approach); an episode that
    begins at the first sample has no step into it and is not counted."""
    time = np.asarray(time_s, dtype=float)
    distance = np.hypot(*np.asarray(eccentricity_m, dtype=float).T)
    onset = np.zeros(time.size)
    for first, _ in impact_episodes(mode):
        if first > 0:
            speed = (distance[first] - distance[first - 1]) / (time[first] - time[first - 1])
            onset[first] = max(speed, 0.0) ** exponent
    return onset


def impact_wear_depth_m(coefficient: float, measure, force_N, pressure_Pa) -> np.ndarray:
    """dh_imp,a = sum_i c M_i p_{i,a} / |F_i| (m, (n_nodes,)) over the rows i (load steps or
    impacts).

    ``measure`` (n,): what a row wears by, M_i (the hysteresis work W_i in J for k_imp in
    m^3/J, the impact impulse J_i in N s for c_J in m^3/(N s), a volume in m^3 for c = 1);
    ``force_N`` (n, 2): the rows' forces; ``pressure_Pa`` (n, n_nodes): the FE contact
    pressures under them. Rows without force carry no pressure and add nothing.
    """
    magnitude = np.linalg.norm(np.asarray(force_N, dtype=float), axis=1)
    share = np.divide(coefficient * np.asarray(measure, dtype=float), magnitude,
                      out=np.zeros_like(magnitude), where=magnitude > 0.0)
    return share @ np.asarray(pressure_Pa, dtype=float)


def impact_wear_coefficient_from_config(section: dict) -> float:
    """k_imp (m^3/J) of a ``[wear]`` section: a finite number >= 0 (default 0, no impact wear)."""
    return _coefficient(section, CONFIG_KEY, "m^3/J (worn volume per joule dissipated by the "
                        "contact law's hysteresis; 0 = no impact wear)")


def impact_impulse_wear_coefficient_from_config(section: dict) -> float:
    """c_J (m^3/(N s)) of a ``[wear]`` section: a finite number >= 0 (default 0, none)."""
    return _coefficient(section, IMPULSE_CONFIG_KEY, "m^3/(N s) (worn volume per newton second "
                        "of the impacts' normal impulse; 0 = none)")


def _coefficient(section: dict, key: str, meaning: str, default: float = 0.0,
                 upper: float = math.inf) -> float:
    """A number of ``section`` in [0, ``upper``], finite (``default`` if absent); ``meaning``:
    its unit and what it is, for the message."""
    value = section.get(key, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and 0.0 <= value <= upper):
        allowed = ("a finite number >= 0 in" if upper == math.inf
                   else f"a number between 0 and {upper:g}")
        raise FewearInputError(f"[wear] {key} = {value!r}: expected {allowed} {meaning}")
    return float(value)
