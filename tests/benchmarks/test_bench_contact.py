"""Benchmark: full DOLFINx Newton vs the condensed fast path on the reference mesh.

The reference mesh is the default config's (144 x 13 = 1872 quadrilaterals, bore 10 mm, outer
15 mm, STACK.md). The loads are 20 steps of a joint-force cycle shaped like a slider-crank's:
magnitude from 10 N to 5 kN and back, direction swinging +-20 degrees about the rod line and
reversing at half cycle (tension/compression), with the pin's rotation for slip and friction.
Both paths solve the same sequence (warm-started), timed side by side; prints the ratio and the
largest differences. Run with ``make bench`` (``pytest -m benchmark -s``).
"""

import math
import time

import numpy as np
import pytest

STEPS = 20


def joint_force_cycle(steps=STEPS):
    """(force N (2,), rotation increment rad) for each step of one cycle."""
    loads = []
    for k in range(steps):
        φ = 2 * math.pi * k / steps
        magnitude = 10.0 * 500.0 ** (0.5 * (1.0 - math.cos(φ)))
        direction = math.radians(20.0) * math.sin(φ) + (math.pi if φ < math.pi else 0.0)
        force = magnitude * np.array([math.cos(direction), math.sin(direction)])
        loads.append((force, 0.02 * math.cos(φ)))
    return loads


@pytest.mark.benchmark
def test_fast_path_speed_up_on_the_reference_mesh():
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.contact.solver import BushingContactSolver
    from fewear.io.config import load_config

    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    start = time.perf_counter()
    full = BushingContactSolver(problem)
    set_up_full = time.perf_counter() - start
    start = time.perf_counter()
    fast = CondensedBushingContact(full)
    condensation = time.perf_counter() - start
    full.solve((0.0, -1.0))          # JIT and first factorisation out of the timing
    fast.solve((0.0, -1.0))
    print(f"\nreference mesh: {full.mesh.topology.index_map(2).size_global} quads, "
          f"{full.V.dofmap.index_map.size_global * 2} dofs, {fast.points.shape[0]} bore nodes")
    print(f"set-up: full solver {set_up_full:.2f} s, condensation G {condensation:.2f} s")
    print(f"{'step':>4} {'|F| N':>8} {'full s':>8} {'fast ms':>8} {'ratio':>6} {'it':>7} "
          f"{'dp/pmax':>9} {'dc/|c|':>9}")
    times_full, times_fast, worst_p, worst_c = [], [], 0.0, 0.0
    for step, (force, rotation) in enumerate(joint_force_cycle()):
        start = time.perf_counter()
        reference = full.solve(force, rotation, friction=True)
        times_full.append(time.perf_counter() - start)
        start = time.perf_counter()
        result = fast.solve(force, rotation, friction=True)
        times_fast.append(time.perf_counter() - start)
        dp = np.abs(result.pressure_Pa - reference.pressure_Pa).max() / reference.max_pressure_Pa
        dc = np.linalg.norm(result.pin_centre_m - reference.pin_centre_m) / np.linalg.norm(
            reference.pin_centre_m)
        worst_p, worst_c = max(worst_p, dp), max(worst_c, dc)
        print(f"{step:4d} {np.linalg.norm(force):8.1f} {times_full[-1]:8.3f} "
              f"{1e3 * times_fast[-1]:8.2f} {times_full[-1] / times_fast[-1]:6.0f} "
              f"{reference.newton_iterations:3d}/{result.newton_iterations:<3d} "
              f"{dp:9.1e} {dc:9.1e}")
    mean_full, mean_fast = np.mean(times_full), np.mean(times_fast)
    print(f"mean per load step: full {mean_full:.3f} s, fast {1e3 * mean_fast:.2f} ms, "
          f"ratio {mean_full / mean_fast:.0f}x (sum over the cycle: "
          f"{np.sum(times_full) / np.sum(times_fast):.0f}x)")
    print(f"max relative difference: nodal pressure {worst_p:.1e} (of the peak), "
          f"pin centre {worst_c:.1e}")
    print(f"break-even after {condensation / (mean_full - mean_fast):.0f} load steps")
    assert worst_p < 1e-6 and worst_c < 1e-6
