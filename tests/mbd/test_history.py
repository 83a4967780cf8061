"""Where a joint history's pin slides under load (JointHistory.load_slip_by_direction,
loaded_sectors), against sums worked by hand."""

import math

import numpy as np
import pytest

from fewear.mbd.history import JointHistory, loaded_sectors


def steady_history(angle_deg: float, normal_N: float, omega_rad_s: float, steps: int,
                   dt_s: float) -> JointHistory:
    """The pin pressed at ``angle_deg`` by ``normal_N``, turning at ``omega_rad_s``."""
    n = steps + 1
    direction = np.array([math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))])
    zeros = np.zeros(n)
    return JointHistory(np.arange(n) * dt_s, zeros, zeros, zeros, np.tile(1e-5 * direction, (n, 1)),
                        zeros, np.full(n, normal_N), zeros, np.tile(-normal_N * direction, (n, 1)),
                        np.full(n, omega_rad_s), np.full(n, 2))


def test_the_load_slip_lands_in_the_sector_of_the_eccentricity():
    # 100 steps of 0.01 s at 10 N, 2 rad/s (either sense), pin radius 10 mm: 10 * 0.01 * 2 = 0.2 W
    # of load-slip rate, 1 s of it: 0.2 J, all in the 90-105 deg sector
    history = steady_history(100.0, 10.0, -2.0, 100, 0.01)
    by_sector, edges = history.load_slip_by_direction(0.01, 15.0)
    assert by_sector.shape == (24,) and edges[0] == 0.0 and edges[-1] == 360.0
    assert by_sector[6] == pytest.approx(0.2, rel=1e-12)
    assert np.count_nonzero(by_sector) == 1


def test_the_loaded_arc_is_the_fullest_sectors_holding_the_share():
    load_slip = np.array([2.0, 5.0, 3.0, 0.0])  # shares 0.2, 0.5, 0.3, 0
    assert loaded_sectors(load_slip, 0.5) == [1]
    assert loaded_sectors(load_slip, 0.6) == [1, 2]
    assert loaded_sectors(load_slip, 0.85) == [0, 1, 2]
    assert loaded_sectors(load_slip, 1.0) == [0, 1, 2]  # the empty sector is no load
