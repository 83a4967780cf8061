"""The periodic tables of :mod:`fewear.mesh.profile` (no DOLFINx)."""

import math

import numpy as np

from fewear.mesh.profile import periodic_linear_rows


def test_many_tables_at_once_interpolate_as_numpy_interp_row_by_row():
    """Against ``numpy.interp(..., period=2 pi)`` on each table: node angles unsorted and
    outside [0, 2 pi), queries anywhere on the line and exactly at the nodes."""
    rng = np.random.default_rng(3)
    angles = np.sort(rng.uniform(0.0, 2.0 * math.pi, 40)) + 2.0 * math.pi * rng.integers(-2, 3, 40)
    rng.shuffle(angles)
    tables = rng.normal(size=(6, angles.size))
    at = rng.uniform(-20.0, 20.0, 500)
    at[:40] = angles  # the nodes themselves: their tabulated values
    rows = rng.integers(0, tables.shape[0], at.size)
    expected = np.array([np.interp(x, angles, tables[row], period=2.0 * math.pi)
                         for x, row in zip(at, rows)])
    got = periodic_linear_rows(angles, tables, at, rows)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(got[:40], tables[rows[:40], np.arange(40)])
