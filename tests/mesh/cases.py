"""Shared cases of the mesh tests: the paper's bushing on coarse O-grids and a worn profile."""

import math

import numpy as np

from fewear.mesh.geometry import BushingGeometry, MeshSettings

GEOMETRY = BushingGeometry(inner_radius_m=0.010, outer_radius_m=0.015, width_m=0.018,
                           pin_radius_m=0.0095)
LOBE_DEPTH_M = 0.5e-3
LOBE_HALF_WIDTH_RAD = math.radians(30.0)


def coarse_settings(n_theta=48, radial_count=4, grading=2.0) -> MeshSettings:
    """O-grid settings giving exactly ``n_theta`` elements around the bore."""
    size = 2 * math.pi * GEOMETRY.inner_radius_m / n_theta * (1 + 1e-9)
    return MeshSettings(size, radial_count, grading)


def two_lobes(angle_rad, depth_m=LOBE_DEPTH_M):
    """Wear depth (m) of two Gaussian lobes centred at 0 and 180 deg, falling to 1/e^2 of
    ``depth_m`` at +-30 deg: the shape of a slider-crank bushing's wear."""
    angle_rad = np.asarray(angle_rad, dtype=float)
    width = LOBE_HALF_WIDTH_RAD / 2.0
    depth = np.zeros_like(angle_rad)
    for centre in (0.0, math.pi):
        offset = np.angle(np.exp(1j * (angle_rad - centre)))
        depth += depth_m * np.exp(-0.5 * (offset / width) ** 2)
    return depth


def bore_node_angles(n_theta) -> np.ndarray:
    """The 2 n_theta uniform angles (rad) of the bore nodes, vertices and edge midpoints."""
    return np.arange(2 * n_theta) * (math.pi / n_theta)
