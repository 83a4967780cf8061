"""Benchmark: full DOLFINx Newton vs the condensed fast path on the reference mesh.

The reference mesh is the default config's (144 x 13 = 1872 quadrilaterals, 288 bore nodes, bore
10 mm, outer 15 mm, STACK.md). The loads are the 200 load steps of one joint-force cycle shaped
like a slider-crank's (the wear loop's n = 200): magnitude from 10 N to 5 kN and back, direction
swinging +-20 degrees about the rod line and reversing at half cycle (tension/compression), the
pin's rotation for slip and friction; friction is on except at every 7th step, so the sequence
also switches friction on and off. Both paths solve the same sequence (each warm-started from its
previous step), timed side by side; the benchmark prints the time per load step, the Newton
iterations (mean, max), the largest differences in nodal pressure and pin centre, and the time
to rebuild the bore compliance G after the mesh moved (``update_geometry``). Run with
``make bench`` (``pytest -m benchmark -s``).
"""

import math
import time

import numpy as np
import pytest

STEPS = 200


def joint_force_cycle(steps=STEPS):
    """(force N (2,), rotation increment rad, friction) for each step of one cycle."""
    loads = []
    for k in range(steps):
        φ = 2 * math.pi * k / steps
        magnitude = 10.0 * 500.0 ** (0.5 * (1.0 - math.cos(φ)))
        direction = math.radians(20.0) * math.sin(φ) + (math.pi if φ < math.pi else 0.0)
        force = magnitude * np.array([math.cos(direction), math.sin(direction)])
        loads.append((force, 0.02 * math.cos(φ), k % 7 != 3))
    return loads


def relative_differences(result, reference):
    dp = np.abs(result.pressure_Pa - reference.pressure_Pa).max() / reference.max_pressure_Pa
    dc = np.linalg.norm(result.pin_centre_m - reference.pin_centre_m) / np.linalg.norm(
        reference.pin_centre_m)
    return dp, dc


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
    print(f"set-up: full solver {set_up_full:.2f} s, condensation (N and G) {condensation:.2f} s")
    print(f"{'step':>4} {'|F| N':>8} {'fr':>2} {'full s':>7} {'fast ms':>8} {'it full/fast':>12} "
          f"{'dp/pmax':>9} {'dc/|c|':>9}")
    times = {"full": [], "fast": []}
    iterations = {"full": [], "fast": []}
    worst_p, worst_c = 0.0, 0.0
    for step, (force, rotation, friction) in enumerate(joint_force_cycle()):
        results = {}
        for name, path in (("full", full), ("fast", fast)):
            start = time.perf_counter()
            results[name] = path.solve(force, rotation, friction)
            times[name].append(time.perf_counter() - start)
            iterations[name].append(results[name].newton_iterations)
        dp, dc = relative_differences(results["fast"], results["full"])
        worst_p, worst_c = max(worst_p, dp), max(worst_c, dc)
        if step % 10 == 0:
            print(f"{step:4d} {np.linalg.norm(force):8.1f} {int(friction):2d} "
                  f"{times['full'][-1]:7.3f} {1e3 * times['fast'][-1]:8.2f} "
                  f"{iterations['full'][-1]:6d}/{iterations['fast'][-1]:<5d} {dp:9.1e} {dc:9.1e}")
    for name in ("full", "fast"):
        print(f"{name}: {1e3 * np.mean(times[name]):.2f} ms per load step (max "
              f"{1e3 * np.max(times[name]):.2f}), Newton iterations mean "
              f"{np.mean(iterations[name]):.2f}, max {np.max(iterations[name])}")
    print(f"speed-up {np.sum(times['full']) / np.sum(times['fast']):.0f}x over the cycle")
    print(f"max relative difference over {STEPS} steps: nodal pressure {worst_p:.1e} (of the "
          f"peak), pin centre {worst_c:.1e}")
    start = time.perf_counter()
    fast.update_geometry()
    print(f"rebuild after the mesh moved (update_geometry: stiffness, bore nodes, G): "
          f"{time.perf_counter() - start:.2f} s")
    assert worst_p < 1e-6 and worst_c < 1e-6
