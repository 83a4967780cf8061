"""The worn bore as a periodic function of angle (no DOLFINx).

The wear state knows the wear depth h at the bore nodes' angles; the worn bore is the radial
profile r(theta) = R_b + h(theta), 2 pi periodic, linear in theta between the tabulated angles.
:func:`periodic_linear` turns such a table into the function the ALE motion
(:class:`fewear.mesh.ale.BoreMotion`) and the re-mesh (``bushing_mesh(..., bore_profile=...)``)
evaluate at their nodes' angles; at a tabulated angle it returns the tabulated value exactly.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from fewear.errors import FewearInputError

TWO_PI = 2.0 * math.pi


def polar_angle(xy: np.ndarray) -> np.ndarray:
    """Angle (rad) in [0, 2 pi) of points ``xy`` (n, 2) seen from the bushing centre (origin)."""
    return np.mod(np.arctan2(xy[:, 1], xy[:, 0]), TWO_PI)


def checked_periodic_table(angle_rad, values, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The table ``(angle_rad, values)`` as float arrays, after checking it can be interpolated.

    Angles must be finite, distinct modulo 2 pi, at least 3 of them; values finite, one per angle.
    Raises :class:`FewearInputError` naming ``name``.
    """
    angles = np.asarray(angle_rad, dtype=float)
    table = np.asarray(values, dtype=float)
    if angles.ndim != 1 or table.shape != angles.shape or angles.size < 3:
        raise FewearInputError(f"{name}: needs two 1-D arrays of equal length >= 3 (angle, value), "
                               f"got shapes {angles.shape} and {table.shape}")
    if not (np.all(np.isfinite(angles)) and np.all(np.isfinite(table))):
        raise FewearInputError(f"{name}: angles and values must be finite numbers")
    if np.unique(np.mod(angles, TWO_PI)).size != angles.size:
        raise FewearInputError(f"{name}: angles must be distinct modulo 2 pi")
    return angles, table


def periodic_linear(angle_rad, values) -> Callable[[np.ndarray], np.ndarray]:
    """The 2 pi periodic, piecewise linear interpolant of the table ``(angle_rad, values)``.

    Returns ``f(angle_rad: ndarray) -> ndarray`` (``numpy.interp`` with ``period=2 pi``): exact at
    the tabulated angles, linear in angle between neighbours, wrapping from the last to the first.
    """
    angles, table = checked_periodic_table(angle_rad, values, "periodic table")

    def interpolant(at_angle_rad: np.ndarray) -> np.ndarray:
        return np.interp(at_angle_rad, angles, table, period=TWO_PI)

    return interpolant


def periodic_linear_rows(angle_rad: np.ndarray, tables: np.ndarray, at_angle_rad: np.ndarray,
                         rows: np.ndarray) -> np.ndarray:
    """Many periodic tables on the same angles at once: the value of the interpolant of
    :func:`periodic_linear` of ``(angle_rad, tables[rows[i]])`` at ``at_angle_rad[i]``
    (``tables`` (m, n) finite, ``angle_rad`` (n,) distinct modulo 2 pi; unchecked: for inner
    loops, where ``numpy.interp``'s periodic set-up, a sort per call, costs more than the
    interpolation)."""
    angles = np.mod(angle_rad, TWO_PI)
    order = np.argsort(angles)
    angles = angles[order]
    xp = np.concatenate([angles[-1:] - TWO_PI, angles, angles[:1] + TWO_PI])
    fp = tables[:, np.concatenate([order[-1:], order, order[:1]])]
    x = np.mod(at_angle_rad, TWO_PI)
    j = np.minimum(np.searchsorted(xp, x, side="right") - 1, xp.size - 2)
    left, right = fp[rows, j], fp[rows, j + 1]
    return left + (right - left) * ((x - xp[j]) / (xp[j + 1] - xp[j]))
