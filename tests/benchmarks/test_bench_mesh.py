"""Benchmark: ALE moves and a re-mesh of the reference bushing mesh under a 0.5 mm worn profile.

The reference mesh is the default config's (144 x 13 quadrilaterals, 288 bore nodes). The wear is
two Gaussian lobes at 0 and 180 deg (1/e^2 at +-30 deg), 0.5 mm deep, applied in five equal ALE
moves; then the bushing is re-meshed on that profile. Prints the time of each step and the mesh
quality (fewear.mesh.quality) after it. Run with ``make bench`` (``pytest -m benchmark -s``).
"""

import time

import numpy as np
import pytest

from tests.mesh.cases import two_lobes

MOVES = 5


@pytest.mark.benchmark
def test_ale_and_remesh_on_the_reference_mesh():
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.io.config import load_config
    from fewear.mesh.ale import BoreMotion
    from fewear.mesh.bushing import bushing_mesh
    from fewear.mesh.profile import periodic_linear
    from fewear.mesh.quality import QualityMeter, RemeshLimits

    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    geometry, settings = problem.geometry, problem.mesh
    n_theta = settings.circumferential_element_count(geometry.inner_radius_m)
    angles = np.arange(2 * n_theta) * (np.pi / n_theta)
    start = time.perf_counter()
    msh, _, facet_tags = bushing_mesh(geometry, settings)
    meshing = time.perf_counter() - start
    start = time.perf_counter()
    motion = BoreMotion(msh, facet_tags)
    set_up = time.perf_counter() - start
    print(f"\nreference mesh {msh.topology.index_map(2).size_global} quads: gmsh {meshing:.3f} s, "
          f"BoreMotion set-up {set_up:.3f} s; as meshed {motion.quality_meter.measure()}")
    limits = RemeshLimits()
    for move in range(1, MOVES + 1):
        start = time.perf_counter()
        report = motion.move(periodic_linear(angles, two_lobes(angles) / MOVES))
        elapsed = time.perf_counter() - start
        print(f"ALE move {move} ({move * 0.5 / MOVES:.1f} mm): {elapsed:.3f} s, {report.quality}, "
              f"re-mesh {limits.needs_remesh(report.quality)}")
        assert report.quality.min_scaled_jacobian > 0.9
    start = time.perf_counter()
    worn, _, worn_tags = bushing_mesh(geometry, settings,
                                      bore_profile=(angles, geometry.inner_radius_m
                                                    + two_lobes(angles)))
    remeshing = time.perf_counter() - start
    start = time.perf_counter()
    BoreMotion(worn, worn_tags)
    set_up = time.perf_counter() - start
    quality = QualityMeter(worn, worn_tags).measure()
    print(f"re-mesh on the 0.5 mm profile: gmsh + distribution {remeshing:.3f} s, BoreMotion "
          f"set-up {set_up:.3f} s; {quality}")
    assert quality.min_scaled_jacobian > 0.9
