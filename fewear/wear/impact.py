"""Impact wear: bore material removed by the impacts of the clearance joint, in two forms that
may act together: by the energy the contact law's hysteresis dissipates, and by the impacts'
normal impulse.

Energy wear (Fouvry, Liskiewicz, Kapsa & Hannel, Wear 255 (2003) 287-298: the worn volume is
proportional to the dissipated energy) applied to the impacts of the clearance joint:

    V_imp = k_imp W_hyst,   W_hyst = integral of (F_n - F_el(delta)) d(delta)/dt dt,

k_imp (m^3/J): the ``[wear]`` key ``impact_wear_coefficient_m3_J`` (0 = no impact wear);
F_n: the normal force of the clearance joint's contact law, F_el(delta) its elastic part, so
F_n - F_el is the hysteresis damping force of Lankarani & Nikravesh (J. Mech. Des. 112 (1990)
369-376), F_el chi delta_dot / v_imp, or -F_el where the law clips F_n at 0 while delta > 0
(the surfaces separate faster than the damping allows: the elastic energy left is not given
back). Both parts dissipate: the power (F_n - F_el) delta_dot is >= 0 at every instant, and over
a contact episode (delta from 0 back to 0) W_hyst = integral of F_n d(delta), the kinetic energy
the impact takes away.

Per load step i of a cycle the step's work W_i is spread over the bore in proportion to the
step's FE contact pressure p_{i,a}:

    dh_imp,a = sum_i k_imp W_i p_{i,a} / |F_i|,

since the integral of p over the bore is about |F_i| (exactly the integral of p n is F_i for a
frictionless contact; the scalar integral exceeds |F_i| by the mean 1/cos over the contact arc,
the same factor that Archard's k p s carries), the step removes a volume of about k_imp W_i.

Impulse form: V_imp = c_J J, J = integral of F_n dt over the impact episodes (``mode`` impact of
:class:`fewear.mbd.history.JointHistory`: contact episodes shorter than the impact duration,
a collision and rebound; the continuous contact's impulse is left out). c_J (m^3/(N s)): the
``[wear]`` key ``impact_impulse_wear_coefficient_m3_Ns``. The momentum an impact reverses, rather
than the energy it takes away, sets the damage when the restitution is high and little is
dissipated (impact wear grows with the number and the severity of the blows, Engel, Impact Wear
of Materials, Elsevier 1976). A step's impulse J_i is spread over the bore like its work.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import cumulative_trapezoid

from fewear.errors import FewearInputError

CONFIG_KEY = "impact_wear_coefficient_m3_J"
IMPULSE_CONFIG_KEY = "impact_impulse_wear_coefficient_m3_Ns"


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


def impact_impulse_N_s(time_s, normal_force_N, mode) -> np.ndarray:
    """The normal impulse of the impact episodes from the first sample to each sample (N s,
    (n,)): the trapezoid rule on F_n, counted on the intervals between two impact-mode samples
    (``mode`` 1, :data:`fewear.mbd.history.MODES`) and on those that enter or leave an episode
    (its force rises from or falls to zero there)."""
    force = np.where(np.asarray(mode) == 1, np.asarray(normal_force_N, dtype=float), 0.0)
    return cumulative_trapezoid(force, np.asarray(time_s, dtype=float), initial=0.0)


def impact_wear_depth_m(coefficient: float, measure, force_N, pressure_Pa) -> np.ndarray:
    """dh_imp,a = sum_i c M_i p_{i,a} / |F_i| (m, (n_nodes,)) over the load steps i.

    ``measure`` (n_steps,): what a step's impacts wear by, M_i (the hysteresis work W_i in J for
    k_imp in m^3/J, or the impact impulse J_i in N s for c_J in m^3/(N s)); ``force_N``
    (n_steps, 2): the steps' joint forces; ``pressure_Pa`` (n_steps, n_nodes): their FE contact
    pressures. Steps without force carry no pressure and add nothing.
    """
    magnitude = np.linalg.norm(np.asarray(force_N, dtype=float), axis=1)
    share = np.divide(coefficient * np.asarray(measure, dtype=float), magnitude,
                      out=np.zeros_like(magnitude), where=magnitude > 0.0)
    return share @ np.asarray(pressure_Pa, dtype=float)


def impact_wear_coefficient_from_config(section: dict) -> float:
    """k_imp (m^3/J) of a ``[wear]`` section: a finite number >= 0 (default 0, no impact wear)."""
    return _coefficient(section, CONFIG_KEY, "m^3/J (worn volume per joule dissipated by the "
                        "contact law's hysteresis")


def impact_impulse_wear_coefficient_from_config(section: dict) -> float:
    """c_J (m^3/(N s)) of a ``[wear]`` section: a finite number >= 0 (default 0, none)."""
    return _coefficient(section, IMPULSE_CONFIG_KEY, "m^3/(N s) (worn volume per newton second "
                        "of the impacts' normal impulse")


def _coefficient(section: dict, key: str, meaning: str) -> float:
    value = section.get(key, 0.0)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and value >= 0.0):
        raise FewearInputError(f"[wear] {key} = {value!r}: expected a finite number >= 0 in "
                               f"{meaning}; 0 = no impact wear)")
    return float(value)
