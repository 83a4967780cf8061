"""Fit the RBF wear coefficient k(p, v) to the stand-in data; write ``fewear/defaults/wear.toml``.

The default ``[wear]`` section carries the network fitted here, so that the default config has a
real k(p, v) (seed eq. 9, Fig. 4). Rerun after changing the data set or the fitting method::

    python -m tests.data_makers.fit_default_wear_coefficient
"""

from __future__ import annotations

import textwrap

from fewear.data import STANDIN_PIN_ON_DISC_CSV
from fewear.diagnose.tribometer.measured import read_measured_wear, wear_coefficient_samples
from fewear.io.config import DEFAULTS_DIR
from fewear.wear.coefficient import RbfWearCoefficient, toml_value

OUTPUT = DEFAULTS_DIR / "wear.toml"
FIT_SEED = 0
FOLDS = 5
CONSTANT_K_m2_N = 2.0e-13


def fit_default():
    """The network fitted to the stand-in data, and its cross-validation report."""
    data = read_measured_wear(STANDIN_PIN_ON_DISC_CSV)
    pressure, velocity, k = wear_coefficient_samples(data)
    return RbfWearCoefficient.fit(pressure, velocity, k, folds=FOLDS, seed=FIT_SEED)


def wear_toml_text() -> str:
    model, report = fit_default()
    rbf = toml_value(model.to_config()["rbf"])
    summary = "\n# ".join(textwrap.wrap(report.summary() + ".", 96))
    return f"""\
# Archard's wear law (seed eq. 10): the wear coefficient k(p, v) in m^2/N (= 1/Pa).

[wear]
# "constant": k = constant_k_m2_N everywhere; "rbf": the RBF network k(p, v) below (seed eq. 9).
coefficient_model = "rbf"
# Brass on steel: dimensionless Archard K about 4e-4..6e-4 over H = 235 HB (2.3 GPa) gives
# k = K/H about 2e-13 m^2/N (REFERENCES.md).
constant_k_m2_N = {CONSTANT_K_m2_N!r}
# How the wear law departs from plain Archard (fewear.wear.extensions): "none", "running_in",
# "running_in_power_law", "running_in_cycles", "running_in_cycles_power_law", "time_transient"
# or "thermal"; extension_params
# holds that extension's fitted parameters.
extension = "none"
extension_params = {{}}
# Impact wear (fewear.wear.impact, energy wear after Fouvry et al., Wear 255 (2003)): worn volume
# in m^3 per joule dissipated by the contact law's hysteresis (Lankarani-Nikravesh damping),
# added to Archard's sliding wear: an impact's under its footprint (the contact at its peak force,
# where it strikes), the continuous contact's like the load steps' pressure. A number >= 0;
# 0 = no impact wear (the default: sliding wear only).
impact_wear_coefficient_m3_J = 0.0
# Impact wear by impulse (fewear.wear.impact): worn volume in m^3 per N s of the normal impulse of
# the impacts (contact episodes shorter than the impact duration), under their footprints. A
# number >= 0; 0 = none (the default). All three forms may act together.
impact_impulse_wear_coefficient_m3_Ns = 0.0
# Only the impacts whose peak normal force exceeds this (N) count for the impulse form; 0 = every
# impact (the default).
impact_impulse_force_threshold_N = 0.0
# Impact wear by impact speed (fewear.wear.impact): worn volume in m^3 per impact per (m/s)^n of
# its normal approach speed, n = impact_speed_exponent (0-6, default 3; 0: the same volume per
# impact, whatever its speed), under their footprints.
# A number >= 0; 0 = none (the default).
impact_speed_wear_coefficient = 0.0
impact_speed_exponent = 3.0
# The RBF network (fewear.wear.coefficient.RbfWearCoefficient): ln k = tail . (1, z_p, z_v)
# + sum_i weights_i exp(-|z - centres_i|^2 / (2 widths_i^2)), z = (ln(p/Pa), ln(v/(m/s)))
# standardised by log_input_mean and log_input_scale; p and v are clamped to pressure_range_Pa and
# velocity_range_m_s (the tested box). This default is fitted by
# tests/data_makers/fit_default_wear_coefficient.py to the SYNTHETIC stand-in data set
# fewear/data/pin_on_disc_cuzn25al6fe3mn3_42crmo.csv (the paper's tests are unpublished):
# {summary}
rbf = {rbf}
"""


def main() -> None:
    OUTPUT.write_text(wear_toml_text())
    print(f"wrote {OUTPUT}")


if __name__ == "__main__":
    main()
