"""Whether a pin-on-disc table's units can be right: the Archard coefficient k = V / (F s) its
tests give, against what wear has been measured to do, and rows repeated word for word.

A k beyond 1e-9 m^2/N (1e3 mm^3/(N m), past the severest adhesive wear) or below 1e-20 m^2/N
(a million times milder than the mildest measured wear of metals and polymers) is a unit error
and refused; beyond 1e-11 or below 1e-17 m^2/N it is possible but rare, and warned, naming the
unit error it would be (Archard 1953; Rabinowicz, Friction and Wear of Materials, ch. 6).
k needs the normal force: from ``normal_load_N``, or ``pressure_Pa`` times a contact area the
caller gives (:func:`fewear.diagnose.tribometer.measured.wear_coefficient_samples`); a table with
neither is warned that its k cannot be checked and that what the diagnosis fits is k times the
unknown area (or the force)."""

from __future__ import annotations

import numpy as np

from fewear.diagnose.tribometer.measured import MeasuredWear
from fewear.errors import FewearInputError

POSSIBLE_K_M2_N = (1e-20, 1e-9)
"""k beyond this range is no wear a tribometer has measured: a unit error (refused)."""
USUAL_K_M2_N = (1e-17, 1e-11)
"""k beyond this range is rare (warned)."""


def wear_coefficients_per_test(data: MeasuredWear) -> np.ndarray | None:
    """Each test's k = sum(F s V) / sum((F s)^2) [m^2/N] over its readings with F s > 0 (tests
    without such a reading left out); None without ``normal_load_N`` (k needs the force)."""
    if data.normal_load_N is None:
        return None
    product = data.normal_load_N * data.sliding_distance_m
    k = []
    for index in data.tests():
        denominator = float(np.sum(product[index] ** 2))
        if denominator > 0.0:
            k.append(float(np.sum(product[index] * data.wear_volume_m3[index])) / denominator)
    return np.array(k)


def _likely_unit_error(data: MeasuredWear, too_large: bool) -> str:
    if too_large:
        if data.data_kind == "mass_loss":
            return "mass in grams under mass_loss_kg gives k 1000x too large (1 g = 1e-3 kg)"
        return ("a wear volume in mm^3 under wear_volume_m3 gives k 1e9x too large "
                "(1 mm^3 = 1e-9 m^3); a distance in km under sliding_distance_m 1e3x")
    if data.data_kind == "mass_loss":
        return "a load in kN under normal_load_N gives k 1e-3x too small (1 kN = 1e3 N)"
    return ("a wear volume converted to m^3 twice gives k 1e9x too small (1 mm^3 = 1e-9 m^3); "
            "a load in mN or a distance in mm gives 1e-3x")


def check_plausible(data: MeasuredWear) -> list[str]:
    """Refuse a table whose median k is beyond :data:`POSSIBLE_K_M2_N` (naming the likely unit
    error); return warnings (one line each): a median k beyond :data:`USUAL_K_M2_N`, a table
    without ``normal_load_N`` (k cannot be computed, so not checked), rows that repeat an
    earlier row exactly (a pasted row counts as a second reading)."""
    k = wear_coefficients_per_test(data)
    if k is None:
        warnings = [_without_load(data)]
    else:
        warnings = check_wear_coefficients(data, k)
    return warnings + _duplicate_rows(data)


def check_wear_coefficients(data: MeasuredWear, k_m2_N: np.ndarray) -> list[str]:
    """Refuse the tests' coefficients ``k_m2_N`` of ``data`` when their median is beyond
    :data:`POSSIBLE_K_M2_N`; a warning (or none) when it is beyond :data:`USUAL_K_M2_N`."""
    positive = k_m2_N[k_m2_N > 0.0]
    if not positive.size:
        return []
    median = float(np.median(positive))
    low, high = POSSIBLE_K_M2_N
    if not low <= median <= high:
        raise FewearInputError(
            f"{data.source}: the tests' median wear coefficient k = V / (F s) = "
            f"{median:.3g} m^2/N is outside what wear can give ({low:g} to {high:g} m^2/N): "
            f"check the units: {_likely_unit_error(data, median > high)}")
    low, high = USUAL_K_M2_N
    if not low <= median <= high:
        return [f"the tests' median wear coefficient k = V / (F s) = {median:.3g} m^2/N is "
                f"rare (usual {low:g} to {high:g} m^2/N); if it is a unit error: "
                f"{_likely_unit_error(data, median > high)}"]
    return []


def _without_load(data: MeasuredWear) -> str:
    fitted = ("k times the pins' apparent contact area A (F = p A)" if data.pressure_Pa is not None
              else "k times the normal force F")
    return (f"no normal_load_N column: the wear coefficient k = V / (F s) cannot be computed, so "
            f"its units are not checked ({POSSIBLE_K_M2_N[0]:g} to {POSSIBLE_K_M2_N[1]:g} m^2/N), "
            f"and the k(p, v) written to extended_wear.toml is {fitted}, not k in m^2/N; add "
            "normal_load_N (N) for both")


def _duplicate_rows(data: MeasuredWear) -> list[str]:
    columns = [data.test_id] + [getattr(data, name) for name in data.available]
    columns += list(data.factors.values())
    seen, repeats = {}, []
    for row in range(data.test_id.size):
        key = tuple(str(column[row]) for column in columns)
        if key in seen:
            repeats.append((row, seen[key]))
        else:
            seen[key] = row
    if not repeats:
        return []
    row, first = repeats[0]
    return [f"{len(repeats)} row(s) repeat an earlier row exactly (first {data._where(row)}, as "
            f"{data._where(first)}): kept as separate readings; delete a pasted duplicate"]
