"""The joint-history CSV: what ``fewear dynamics`` writes and ``fewear run --joint-history`` wears
the bushing with (a history made elsewhere: another multibody code, a measurement).

One header line of column names, each with its unit as a suffix, then one row per sample
(``#`` comment lines and blank lines allowed). Columns, in any order:

- time (required): ``time_s`` or ``time_ms``; strictly increasing.
- the load on the pin (required): the force pressing the pin into the bore, minus the bushing's
  reaction on the pin (as ``fewear contact --force``), in the bushing body's frame,
  ``force_x_<F>`` and ``force_y_<F>``; or in the global frame, ``global_force_x_<F>`` and
  ``global_force_y_<F>`` with the bushing body's angle ``bushing_angle_<A>`` (the force is
  turned by minus that angle into the bushing's frame). F: ``N`` or ``kN``; A: ``rad`` or ``deg``.
- the rotation of the pin relative to the bushing, pin minus bushing (required, exactly one):
  the angle ``relative_angle_<A>`` (differentiated to the angular velocity, second order,
  :func:`numpy.gradient`) or the angular velocity ``relative_omega_<W>``, W: ``rad_s``,
  ``deg_s`` or ``rpm``.
- optional, for the checks and the impact wear laws (``fewear dynamics`` writes them):
  ``crank_angle_<A>`` (the driving angle: it must advance by 360 deg per cycle),
  ``eccentricity_x_<L>``, ``eccentricity_y_<L>`` and ``penetration_<L>`` (L: ``m``, ``mm`` or
  ``um``; pin centre minus bushing centre, bushing frame), ``normal_force_<F>``,
  ``friction_force_<F>`` and ``mode`` (``free``, ``impact`` or ``contact``;
  :mod:`fewear.mbd.history`). Without them the history has no impact episodes, no penetration
  (so no hysteresis work), a centred pin, the normal force |F| and no friction force: what the
  wear of the sliding contact needs, and nothing it would invent.

The file spans a whole number of cycles (the run's ``[wear_loop] recorded_cycles_per_block``):
its last load equals its first within ``PERIODIC_FORCE_TOLERANCE`` of the peak load, its net
relative rotation is a whole number of turns within ``PERIODIC_ROTATION_TOLERANCE_RAD``, and a
crank angle, when given, advances by exactly that many turns within the same tolerance.
A column whose rotation values look like the other angle unit is refused
(:func:`_check_angle_unit`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.integrate import cumulative_trapezoid

from fewear.errors import FewearInputError
from fewear.io.csv_rows import numeric_column, read_rows, require_finite_column
from fewear.mbd.history import MODES, JointHistory

PERIODIC_FORCE_TOLERANCE = 0.05
"""The largest |F(last) - F(first)| of a history, as a share of its peak |F|: a recorded cycle of
the slider-crank with its clearance joint closes within a few tenths of a per cent."""

PERIODIC_ROTATION_TOLERANCE_RAD = math.radians(2.0)
"""How far the net relative rotation (and the crank angle's advance) may miss a whole number of
turns."""

TIME_UNITS = {"s": 1.0, "ms": 1e-3}
FORCE_UNITS = {"N": 1.0, "kN": 1e3}
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
SPEED_UNITS = {"rad_s": 1.0, "deg_s": math.pi / 180.0, "rpm": 2.0 * math.pi / 60.0}
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6}

QUANTITIES = {  # column name without its unit suffix -> the units it takes
    "time": TIME_UNITS, "force_x": FORCE_UNITS, "force_y": FORCE_UNITS,
    "global_force_x": FORCE_UNITS, "global_force_y": FORCE_UNITS, "bushing_angle": ANGLE_UNITS,
    "relative_angle": ANGLE_UNITS, "relative_omega": SPEED_UNITS, "crank_angle": ANGLE_UNITS,
    "eccentricity_x": LENGTH_UNITS, "eccentricity_y": LENGTH_UNITS, "penetration": LENGTH_UNITS,
    "normal_force": FORCE_UNITS, "friction_force": FORCE_UNITS,
}

EXPORTED_COLUMNS = ("time_s", "force_x_N", "force_y_N", "relative_omega_rad_s", "crank_angle_deg",
                    "eccentricity_x_m", "eccentricity_y_m", "penetration_m", "normal_force_N",
                    "friction_force_N", "mode")
"""The columns :func:`write_joint_history` writes (the bushing frame; SI but the crank angle)."""


def write_joint_history(history: JointHistory, path) -> None:
    """``history`` as the CSV of the module docstring, every number to 17 significant digits so
    that reading it back gives the same floats."""
    load = -history.reaction_force_N
    numbers = np.column_stack([
        history.time_s, load, history.rel_omega_rad_s, np.degrees(history.crank_angle_rad),
        history.eccentricity_m, history.penetration_m, history.normal_force_N,
        history.friction_force_N])
    with open(path, "w") as handle:
        handle.write(",".join(EXPORTED_COLUMNS) + "\n")
        for row, mode in zip(numbers, history.mode):
            handle.write(",".join(f"{v:.17g}" for v in row) + f",{MODES[mode]}\n")


IMPACT_COLUMNS = ("penetration", "normal_force", "mode")
"""The optional columns an impact wear law needs (the hysteresis work and the impact episodes)."""


def read_joint_history(path, cycles: int = 1, impacts: bool = False) -> JointHistory:
    """The :class:`JointHistory` of the CSV at ``path`` spanning ``cycles`` cycles (module
    docstring; SI units, bushing frame); every fault a :class:`FewearInputError` naming the file,
    the line or column, and what is allowed. ``impacts``: the wear law wears by the contact's
    hysteresis work or the impacts, so the file must give ``IMPACT_COLUMNS``."""
    path = Path(path)
    _, header, rows = read_rows(path)
    lines = [number for number, _ in rows]

    def where(index: int) -> str:
        return f"{path} line {lines[index]}"

    columns = _columns(path, header)
    missing = [quantity for quantity in IMPACT_COLUMNS if quantity not in columns]
    if impacts and missing:
        raise FewearInputError(
            f"{path}: [wear] impact wear (impact_*) needs the impacts of the history: missing "
            f"column(s) {', '.join(missing)} (penetration_<m|mm|um>, normal_force_<N|kN>, mode); "
            "give them, or no impact wear")
    values = {}
    for quantity, (name, unit) in columns.items():
        if quantity == "mode":
            continue
        index = header.index(name)
        raw = numeric_column(name, [cells[index] for _, cells in rows], where)
        require_finite_column(name, raw, where)
        values[quantity] = raw * QUANTITIES[quantity][unit]
    if len(rows) < 3:
        raise FewearInputError(f"{path}: {len(rows)} data rows; a joint history needs at least 3 "
                               "(one cycle, sampled)")
    time = values["time"]
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0] + 1)}, column {columns['time'][0]}: time {time[bad[0] + 1]!r} after "
            f"{time[bad[0]]!r}; expected strictly increasing times")
    load = _load_in_bushing_frame(values)
    omega, rotation = _relative_rotation(path, columns, values, time)
    _check_periodic(path, columns, values, load, rotation, cycles)
    mode = _modes(path, header, rows, columns, where, load)
    normal = values.get("normal_force", np.hypot(load[:, 0], load[:, 1]))
    zeros = np.zeros(time.size)
    eccentricity = np.column_stack([values.get("eccentricity_x", zeros),
                                    values.get("eccentricity_y", zeros)])
    return JointHistory(
        time_s=time, crank_angle_rad=values.get("crank_angle", np.full(time.size, np.nan)),
        slider_x_m=np.full(time.size, np.nan), slider_velocity_m_s=np.full(time.size, np.nan),
        eccentricity_m=eccentricity, penetration_m=values.get("penetration", zeros),
        normal_force_N=normal, friction_force_N=values.get("friction_force", zeros),
        reaction_force_N=-load, rel_omega_rad_s=omega, mode=mode)


def _columns(path: Path, header: list[str]) -> dict:
    """quantity -> (column name, unit) of the header; ``mode`` -> ("mode", ""). Unknown names,
    units, repeated quantities and missing or conflicting required columns are input errors."""
    allowed = ", ".join(f"{quantity}_<{'|'.join(units)}>" for quantity, units in
                        QUANTITIES.items()) + ", mode"
    found = {}
    for name in header:
        if name == "mode":
            quantity, unit = "mode", ""
        else:
            quantity, unit = _split_unit(name)
            if quantity is None:
                raise FewearInputError(f"{path}: column {name!r} is not a known quantity with a "
                                       f"unit suffix; allowed: {allowed}")
        if quantity in found:
            raise FewearInputError(f"{path}: columns {found[quantity][0]!r} and {name!r} both "
                                   f"give {quantity}; give it once")
        found[quantity] = (name, unit)
    bushing = {"force_x", "force_y"} & set(found)
    world = {"global_force_x", "global_force_y", "bushing_angle"} & set(found)
    needs = [("time", "time_s or time_ms")]
    if bushing and world:
        raise FewearInputError(f"{path}: both bushing-frame (force_x, force_y) and global-frame "
                               "(global_force_x, global_force_y, bushing_angle) loads; give one")
    if world:
        needs += [(q, f"{q}_<{'|'.join(QUANTITIES[q])}>")
                  for q in ("global_force_x", "global_force_y", "bushing_angle")]
    else:
        needs += [(q, f"{q}_<N|kN>") for q in ("force_x", "force_y")]
    missing = [text for quantity, text in needs if quantity not in found]
    if missing:
        raise FewearInputError(f"{path}: missing column(s) {', '.join(missing)}")
    rotations = [q for q in ("relative_angle", "relative_omega") if q in found]
    if len(rotations) != 1:
        raise FewearInputError(
            f"{path}: {'both' if rotations else 'neither'} relative_angle_<rad|deg> "
            f"{'and' if rotations else 'nor'} relative_omega_<rad_s|deg_s|rpm>; give exactly one "
            "(the rotation of the pin relative to the bushing)")
    return found


def _split_unit(name: str) -> tuple[str | None, str]:
    """(quantity, unit) of a column name such as ``force_x_kN``; (None, "") if none fits."""
    for quantity, units in QUANTITIES.items():
        for unit in units:
            if name == f"{quantity}_{unit}":
                return quantity, unit
    return None, ""


def _load_in_bushing_frame(values: dict) -> np.ndarray:
    """The load on the pin (n, 2) in the bushing body's frame (N)."""
    if "force_x" in values:
        return np.column_stack([values["force_x"], values["force_y"]])
    angle = values["bushing_angle"]
    cos, sin = np.cos(angle), np.sin(angle)
    fx, fy = values["global_force_x"], values["global_force_y"]
    return np.column_stack([cos * fx + sin * fy, -sin * fx + cos * fy])


def _relative_rotation(path: Path, columns: dict, values: dict, time: np.ndarray):
    """(the relative angular velocity (n,) rad/s, the relative angle from the first row (n,)
    rad), each unit of the rotation column checked (:func:`_check_angle_unit`)."""
    if "relative_angle" in values:
        angle = values["relative_angle"]
        _check_angle_unit(path, columns["relative_angle"], angle - angle[0])
        return np.gradient(angle, time), angle - angle[0]
    omega = values["relative_omega"]
    rotation = cumulative_trapezoid(omega, time, initial=0.0)
    _check_angle_unit(path, columns["relative_omega"], rotation)
    return omega, rotation


def _check_angle_unit(path: Path, column: tuple[str, str], rotation_rad: np.ndarray) -> None:
    """Refuse a rotation column whose values look like the other unit. In degrees read as radians
    a joint would turn by more than one turn back and forth within the file (its relative angle
    spans more than 2 pi from its lowest to its highest, beyond the whole turns it makes: a
    planar linkage's joint either oscillates or turns once per cycle); in radians read as degrees
    a swinging joint would sweep less than 2 pi degrees (6.3 deg) in all: such a small swing is
    accepted in rad only."""
    name, unit = column
    full_turns = round(abs(rotation_rad[-1]) / (2.0 * math.pi))
    swing = float(np.ptp(rotation_rad)) - 2.0 * math.pi * full_turns
    if unit in ("rad", "rad_s") and swing > 2.0 * math.pi + PERIODIC_ROTATION_TOLERANCE_RAD:
        raise FewearInputError(
            f"{path}, column {name}: the pin swings {swing:.3g} rad relative to the bushing "
            "besides whole turns, more than one turn: the values look like degrees; label the "
            "column in deg")
    if unit in ("deg", "deg_s") and 0.0 < math.degrees(swing) < 2.0 * math.pi and (
            full_turns == 0):
        raise FewearInputError(
            f"{path}, column {name}: the pin swings only {math.degrees(swing):.3g} deg relative "
            "to the bushing: the values look like radians; label the column in rad (a swing "
            "this small is accepted in rad only)")


def _check_periodic(path: Path, columns: dict, values: dict, load: np.ndarray,
                    rotation_rad: np.ndarray, cycles: int) -> None:
    """The history spans ``cycles`` whole cycles (module docstring)."""
    peak = float(np.max(np.hypot(load[:, 0], load[:, 1])))
    mismatch = float(np.hypot(*(load[-1] - load[0])))
    if mismatch > PERIODIC_FORCE_TOLERANCE * peak:
        raise FewearInputError(
            f"{path}: the last load differs from the first by {mismatch:.4g} N, "
            f"{mismatch / peak:.1%} of the peak {peak:.4g} N; a joint history spans whole cycles "
            f"(first and last load within {PERIODIC_FORCE_TOLERANCE:.0%} of the peak)")
    turns = rotation_rad[-1] / (2.0 * math.pi)
    if abs(turns - round(turns)) * 2.0 * math.pi > PERIODIC_ROTATION_TOLERANCE_RAD:
        raise FewearInputError(
            f"{path}, column {columns.get('relative_angle', columns.get('relative_omega'))[0]}: "
            f"the pin turns by {math.degrees(rotation_rad[-1]):.4g} deg relative to the bushing "
            "over the history; over whole cycles it turns by whole turns (0 for an oscillating "
            "joint) within " f"{math.degrees(PERIODIC_ROTATION_TOLERANCE_RAD):g} deg")
    if "crank_angle" in values:
        advance = values["crank_angle"][-1] - values["crank_angle"][0]
        if abs(abs(advance) - 2.0 * math.pi * cycles) > PERIODIC_ROTATION_TOLERANCE_RAD:
            raise FewearInputError(
                f"{path}, column {columns['crank_angle'][0]}: the crank turns by "
                f"{math.degrees(advance):.6g} deg over the history; expected {cycles} cycle(s) "
                f"([wear_loop] recorded_cycles_per_block), {360 * cycles} deg")


def _modes(path, header, rows, columns, where, load) -> np.ndarray:
    """The ``mode`` column as codes of :data:`MODES`; without it, contact where the load is not
    zero, else free (no impact episodes)."""
    if "mode" not in columns:
        return np.where(np.hypot(load[:, 0], load[:, 1]) > 0.0, 2, 0)
    index = header.index("mode")
    codes = np.empty(len(rows), dtype=int)
    for row, (_, cells) in enumerate(rows):
        text = cells[index].strip()
        if text not in MODES:
            raise FewearInputError(f"{where(row)}, column mode: {text!r}; expected one of "
                                   f"{', '.join(MODES)}")
        codes[row] = MODES.index(text)
    return codes
