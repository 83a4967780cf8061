"""The planar shear-deformable ANCF beam against beam theory, rigid motion and its own derivatives.

References: Timoshenko cantilever, w(L) = F L^3/(3 E I) + F L/(kappa G A) under a tip load and
w(L) = q L^4/(8 E I) + q L^2/(2 kappa G A) under a uniform line load q; a beam under an end moment M
rolls up into a circle of radius E I / M (thin beam). Loads are small in the linear checks
(w/L ~ 1e-5), so geometric nonlinearity stays below 1e-9 relative.
"""

import math

import numpy as np
import pytest
import scipy.linalg

from fewear.errors import FewearInputError
from fewear.mbd.ancf import AncfBeam, BeamSection, cowper_shear_correction

STEEL = {"youngs_modulus_Pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0}


def section(height_m: float, width_m: float = 0.01) -> BeamSection:
    return BeamSection(height_m=height_m, width_m=width_m, **STEEL)


def clamped_solve(beam: AncfBeam, external_N: np.ndarray, moment_Nm: float = 0.0,
                  load_steps: int = 1) -> np.ndarray:
    """Newton on F(q) = Q with node 0 clamped (r and r_,y fixed), optional end moment.

    The end moment is the conservative load of potential -M theta(d), theta = atan2(-d_x, d_y) the
    rotation of the tip's slope vector d = r_,y.
    """
    q = beam.reference_coordinates(0.0, 0.0, 0.0)
    free = np.arange(4, beam.n_coordinates)
    slope = slice(beam.node_index(-1).start + 2, beam.node_index(-1).stop)
    for step in range(1, load_steps + 1):
        load = step / load_steps
        for _ in range(40):
            forces, stiffness = beam.elastic_forces_and_stiffness(q)
            residual = load * external_N - forces
            d = q[slope]
            norm2 = d @ d
            residual[slope] += load * moment_Nm * np.array([-d[1], d[0]]) / norm2
            off_diagonal = d[1] ** 2 - d[0] ** 2
            stiffness[slope, slope] -= load * moment_Nm * np.array(
                [[2 * d[0] * d[1], off_diagonal], [off_diagonal, -2 * d[0] * d[1]]]
            ) / norm2**2
            dq = np.linalg.solve(stiffness[np.ix_(free, free)], residual[free])
            q[free] += dq
            if np.abs(dq).max() < 1e-14 * beam.length_m:
                break
        else:
            raise AssertionError("Newton did not converge")
    return q


@pytest.mark.parametrize("n_elements", [1, 2, 4])
@pytest.mark.parametrize("slenderness", [100.0, 5.0], ids=["thin", "thick"])
def test_cantilever_tip_load_matches_timoshenko(slenderness, n_elements):
    length = 1.0
    sec = section(length / slenderness)
    beam = AncfBeam(length, n_elements, sec)
    EI = sec.youngs_modulus_Pa * sec.second_moment_m4
    kGA = sec.kappa * sec.shear_modulus_Pa * sec.area_m2
    force = 3e-5 * EI / length**2
    load = np.zeros(beam.n_coordinates)
    load[beam.node_index(-1).start + 1] = force
    q = clamped_solve(beam, load)
    expected = force * length**3 / (3 * EI) + force * length / kGA
    error = abs(q[beam.node_index(-1).start + 1] / expected - 1.0)
    print(f"L/h = {slenderness:g}, {n_elements} elements: tip deflection error {error:.2e}")
    # The issue asks for 1 %; this element's nodal values are in fact exact in the linear limit.
    assert error < 1e-6


@pytest.mark.parametrize("slenderness", [100.0, 5.0], ids=["thin", "thick"])
def test_cantilever_uniform_load_matches_timoshenko(slenderness):
    length = 1.0
    sec = section(length / slenderness)
    beam = AncfBeam(length, 4, sec)
    EI = sec.youngs_modulus_Pa * sec.second_moment_m4
    kGA = sec.kappa * sec.shear_modulus_Pa * sec.area_m2
    line_load = 1e-4 * EI / length**3
    gravity = line_load / (sec.density_kg_m3 * sec.area_m2)
    q = clamped_solve(beam, beam.gravity_forces((0.0, -gravity)))
    expected = line_load * length**4 / (8 * EI) + line_load * length**2 / (2 * kGA)
    assert -q[beam.node_index(-1).start + 1] == pytest.approx(expected, rel=1e-6)


def test_end_moment_rolls_thin_beam_into_circle():
    """Large rotation without membrane or shear locking: a quarter circle with 4 elements."""
    length = 1.0
    sec = section(0.01)
    EI = sec.youngs_modulus_Pa * sec.second_moment_m4
    radius = length / (0.5 * math.pi)
    angle = length / radius
    exact_tip = radius * np.array([math.sin(angle), 1 - math.cos(angle)])
    errors = []
    for n_elements in (2, 4):
        beam = AncfBeam(length, n_elements, sec)
        q = clamped_solve(beam, np.zeros(beam.n_coordinates), EI / radius, load_steps=5)
        errors.append(np.linalg.norm(q[beam.node_index(-1)][:2] - exact_tip) / length)
    print(f"quarter-circle roll-up, tip error / L: 2 elements {errors[0]:.2e}, 4: {errors[1]:.2e}")
    assert errors[1] < 5e-4 and errors[1] < errors[0]


def test_clamped_free_natural_frequencies():
    """Mass and stiffness together: a thin cantilever (L/h = 100) vibrates at the Euler-Bernoulli
    frequencies (beta_n L)^2 sqrt(E I/(rho A L^4)), beta_n L = 1.87510, 4.69409, 7.85476, within
    0.1 % (shear and rotary inertia lower them by O((n h/L)^2)), and axially at pi c/(2 L)."""
    length = 1.0
    sec = section(0.01)
    beam = AncfBeam(length, 8, sec)
    free = np.arange(4, beam.n_coordinates)
    stiffness = beam.stiffness_matrix(beam.reference_coordinates(0.0, 0.0, 0.0))
    mass = beam.mass_matrix()
    eigenvalues = scipy.linalg.eigh(stiffness[np.ix_(free, free)], mass[np.ix_(free, free)],
                                    eigvals_only=True)
    omega = np.sqrt(eigenvalues)
    EI = sec.youngs_modulus_Pa * sec.second_moment_m4
    rho_A = sec.density_kg_m3 * sec.area_m2
    bending = np.array([1.875104, 4.694091, 7.854757]) ** 2 * math.sqrt(EI / (rho_A * length**4))
    assert omega[:3] == pytest.approx(bending, rel=1e-3)
    axial = 0.5 * math.pi * math.sqrt(sec.youngs_modulus_Pa / sec.density_kg_m3) / length
    assert np.min(np.abs(omega / axial - 1.0)) < 1e-4


def test_rigid_motion_has_no_strain():
    sec = section(0.005, 0.018)
    beam = AncfBeam(0.34, 4, sec)
    axial_scale_N = sec.youngs_modulus_Pa * sec.area_m2
    for angle in (0.0, 0.7, 2.5, -2.0):
        q = beam.reference_coordinates(0.3, -1.2, angle)
        assert np.abs(beam.elastic_forces(q)).max() < 1e-13 * axial_scale_N
        assert abs(beam.strain_energy(q)) < 1e-20 * axial_scale_N * beam.length_m


def test_stiffness_has_exactly_the_three_rigid_modes():
    beam = AncfBeam(0.34, 4, section(0.005, 0.018))
    stiffness = beam.stiffness_matrix(beam.reference_coordinates(0.0, 0.0, 0.4))
    singular = np.linalg.svd(stiffness, compute_uv=False)
    assert np.sum(singular < 1e-10 * singular[0]) == 3


def deformed_state(beam: AncfBeam, amplitude: float = 0.02) -> np.ndarray:
    rng = np.random.default_rng(3)
    q = beam.reference_coordinates(0.1, 0.2, 0.9)
    return q + amplitude * beam.element_length_m * rng.standard_normal(q.size)


def test_stiffness_is_the_derivative_of_the_elastic_forces():
    beam = AncfBeam(0.34, 3, section(0.005, 0.018))
    q = deformed_state(beam)
    forces, stiffness = beam.elastic_forces_and_stiffness(q)
    assert np.array_equal(forces, beam.elastic_forces(q))
    step = 1e-7
    jacobian = np.column_stack([
        (beam.elastic_forces(q + step * e) - beam.elastic_forces(q - step * e)) / (2 * step)
        for e in np.eye(q.size)
    ])
    error = np.abs(jacobian - stiffness).max() / np.abs(stiffness).max()
    print(f"stiffness vs central differences: max relative error {error:.1e}")
    assert error < 1e-7
    assert np.allclose(stiffness, stiffness.T, rtol=0.0, atol=1e-14 * np.abs(stiffness).max())


def test_elastic_forces_are_the_derivative_of_the_energy():
    beam = AncfBeam(0.34, 3, section(0.005, 0.018))
    q = deformed_state(beam)
    step = 1e-7
    gradient = np.array([
        (beam.strain_energy(q + step * e) - beam.strain_energy(q - step * e)) / (2 * step)
        for e in np.eye(q.size)
    ])
    forces = beam.elastic_forces(q)
    assert np.abs(gradient - forces).max() < 1e-7 * np.abs(forces).max()


def damped_beam(tau_s: float = 2e-5) -> AncfBeam:
    sec = BeamSection(height_m=0.005, width_m=0.018, damping_time_s=tau_s, **STEEL)
    return AncfBeam(0.34, 3, sec)


def test_kelvin_voigt_jacobians_are_the_derivatives_of_the_forces():
    beam = damped_beam()
    q = deformed_state(beam)
    rng = np.random.default_rng(5)
    qd = 50.0 * beam.element_length_m * rng.standard_normal(q.size)
    forces, d_dq, d_dqd = beam.internal_forces(q, qd)
    step = 1e-7
    for jacobian, shift in ((d_dq, lambda e: (q + step * e, qd)),
                            (d_dqd, lambda e: (q, qd + step * e))):
        columns = []
        for e in np.eye(q.size):
            plus = beam.internal_forces(*shift(e))[0]
            minus = beam.internal_forces(*shift(-e))[0]
            columns.append((plus - minus) / (2 * step))
        error = np.abs(np.column_stack(columns) - jacobian).max() / np.abs(jacobian).max()
        assert error < 1e-6
    elastic = beam.elastic_forces(q)
    tau = beam.section.damping_time_s
    strain_rate_power = (forces - elastic) @ qd
    assert strain_rate_power > 0.0
    # Dissipation tau s'^T H s' equals tau q'^T (dF/dq' / tau) q' (both quadratic in s').
    assert strain_rate_power == pytest.approx(qd @ d_dqd @ qd, rel=1e-9)
    assert np.allclose(d_dqd, d_dqd.T, atol=1e-12 * tau * np.abs(d_dqd).max())


def test_stiffness_proportional_forces_and_their_exact_jacobians():
    """F + beta K q' equals the assembled form, and d/dq, d/dq' match finite differences (the
    d(K q')/dq term included: the Newton iteration of the damped rod converges quadratically)."""
    beam = AncfBeam(0.34, 3, section(0.005, 0.018))
    q = deformed_state(beam)
    rng = np.random.default_rng(7)
    qd = 50.0 * beam.element_length_m * rng.standard_normal(q.size)
    beta = 3e-5
    forces, d_dq, d_dqd = beam.stiffness_proportional_forces(q, qd, beta)
    elastic, stiffness = beam.elastic_forces_and_stiffness(q)
    assert np.allclose(forces, elastic + beta * stiffness @ qd, rtol=0.0,
                       atol=1e-12 * np.abs(forces).max())
    assert np.allclose(d_dqd, beta * stiffness, rtol=1e-14, atol=0.0)
    step = 1e-7
    columns = [(beam.stiffness_proportional_forces(q + step * e, qd, beta, False)[0]
                - beam.stiffness_proportional_forces(q - step * e, qd, beta, False)[0]) / (2 * step)
               for e in np.eye(q.size)]
    error = np.abs(np.column_stack(columns) - d_dq).max() / np.abs(d_dq).max()
    assert error < 1e-6
    assert np.abs(d_dq - stiffness).max() > 1e3 * error * np.abs(d_dq).max()  # the rate term


def test_kelvin_voigt_damping_is_stiffness_proportional_at_rest_and_spares_rigid_motion():
    beam = damped_beam()
    tau = beam.section.damping_time_s
    q = beam.reference_coordinates(0.2, -0.1, 0.8)
    # Rigid rotation about node 0 at 40 rad/s plus a translation: no strain rate, no damping force.
    nodes = q.reshape(-1, 4)
    qd = np.empty_like(nodes)
    qd[:, 0:2] = 40.0 * np.stack([-(nodes[:, 1] - q[1]), nodes[:, 0] - q[0]], axis=1) + [1.0, 2.0]
    qd[:, 2:4] = 40.0 * np.stack([-nodes[:, 3], nodes[:, 2]], axis=1)
    forces, stiffness, damping = beam.internal_forces(q, qd.ravel())
    scale = beam.section.youngs_modulus_Pa * beam.section.area_m2
    assert np.abs(forces).max() < 1e-13 * scale
    assert np.allclose(damping, tau * beam.stiffness_matrix(q), rtol=0.0,
                       atol=1e-12 * tau * np.abs(stiffness).max())
    elastic_only = AncfBeam(0.34, 3, section(0.005, 0.018))
    q_deformed = deformed_state(elastic_only)
    forces, stiffness, damping = elastic_only.internal_forces(q_deformed, qd.ravel())
    expected_forces, expected_stiffness = elastic_only.elastic_forces_and_stiffness(q_deformed)
    assert np.array_equal(forces, expected_forces)
    assert np.allclose(stiffness, expected_stiffness, rtol=1e-14, atol=0.0)
    assert not damping.any()


def test_mass_matrix_total_mass_and_rigid_kinetic_energy():
    sec = section(0.005, 0.018)
    beam = AncfBeam(0.34, 4, sec)
    mass = sec.density_kg_m3 * sec.area_m2 * beam.length_m
    M = beam.mass_matrix()
    assert np.allclose(M, M.T)
    velocity = np.array([1.5, -0.4])
    translation = np.zeros(beam.n_coordinates)
    translation[0::4], translation[1::4] = velocity
    assert 0.5 * translation @ M @ translation == pytest.approx(0.5 * mass * velocity @ velocity)
    # Rotation about node 0 at rate omega: r' = omega e_z x (r - r_0), r_,y' = omega e_z x r_,y.
    angle, omega = 0.6, 3.0
    q = beam.reference_coordinates(0.2, 0.1, angle)
    rotated = np.array([[0.0, -1.0], [1.0, 0.0]])
    rate = q.reshape(-1, 4).copy()
    rate[:, 0:2] = omega * (rate[:, 0:2] - q[0:2]) @ rotated.T
    rate[:, 2:4] = omega * rate[:, 2:4] @ rotated.T
    rate = rate.ravel()
    inertia_about_end = mass * beam.length_m**2 / 3 + mass * sec.height_m**2 / 12
    assert 0.5 * rate @ M @ rate == pytest.approx(0.5 * inertia_about_end * omega**2, rel=1e-12)


def test_gravity_forces_sum_to_the_weight():
    sec = section(0.005, 0.018)
    beam = AncfBeam(0.34, 4, sec)
    g = (0.3, -9.81)
    forces = beam.gravity_forces(g).reshape(-1, 4)
    weight = sec.density_kg_m3 * sec.area_m2 * beam.length_m * np.array(g)
    assert np.allclose(forces[:, 0:2].sum(axis=0), weight)
    assert np.all(forces[:, 2:4] == 0.0)


def test_axial_stretch_gives_the_EA_force():
    """Uniform stretch lambda: U = E A L a^2/2 with a = (lambda^2 - 1)/2, end force E A a lambda."""
    sec = section(0.005, 0.018)
    beam = AncfBeam(0.34, 4, sec)
    stretch = 1.002
    q = beam.reference_coordinates(0.0, 0.0, 0.0).reshape(-1, 4)
    q[:, 0] *= stretch
    q = q.ravel()
    green = 0.5 * (stretch**2 - 1.0)
    end_force = sec.youngs_modulus_Pa * sec.area_m2 * green * stretch
    forces = beam.elastic_forces(q)
    expected = np.zeros_like(forces)
    expected[beam.node_index(0).start] = -end_force
    expected[beam.node_index(-1).start] = end_force
    assert np.allclose(forces, expected, rtol=0.0, atol=1e-10 * end_force)
    assert beam.strain_energy(q) == pytest.approx(
        0.5 * sec.youngs_modulus_Pa * sec.area_m2 * beam.length_m * green**2, rel=1e-12
    )


def test_position_and_shape_matrix_on_the_reference_beam():
    beam = AncfBeam(0.34, 4, section(0.005, 0.018))
    angle = 1.1
    tangent = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-math.sin(angle), math.cos(angle)])
    origin = np.array([0.05, -0.3])
    q = beam.reference_coordinates(*origin, angle)
    for s, y in [(0.0, 0.0), (0.0123, 0.002), (0.17, -0.0025), (0.34, 0.001)]:
        assert np.allclose(beam.position(q, s, y), origin + s * tangent + y * normal, atol=1e-15)
        assert beam.shape_matrix(s, y).shape == (2, beam.n_coordinates)
    assert np.array_equal(q[beam.node_index(3)][0:2], beam.position(q, 3 * beam.length_m / 8))


def test_cowper_factor_of_a_rectangle():
    assert cowper_shear_correction(0.0) == pytest.approx(10 / 12)
    assert section(0.01).kappa == pytest.approx(10 * 1.3 / (12 + 3.3))
    assert BeamSection(height_m=0.01, width_m=0.01, shear_correction=5 / 6, **STEEL).kappa == 5 / 6


@pytest.mark.parametrize("bad", [
    {"youngs_modulus_Pa": -1.0}, {"poisson_ratio": 0.5}, {"density_kg_m3": 0.0},
    {"height_m": float("nan")}, {"width_m": -0.01}, {"shear_correction": 0.0},
    {"damping_time_s": -1e-6},
])
def test_bad_section_is_rejected(bad):
    values = {"height_m": 0.01, "width_m": 0.01, **STEEL} | bad
    with pytest.raises(FewearInputError, match=next(iter(bad))):
        BeamSection(**values)


def test_bad_beam_arguments_are_rejected():
    sec = section(0.01)
    with pytest.raises(FewearInputError, match="n_elements"):
        AncfBeam(1.0, 0, sec)
    with pytest.raises(FewearInputError, match="length_m"):
        AncfBeam(0.0, 2, sec)
    beam = AncfBeam(1.0, 2, sec)
    with pytest.raises(FewearInputError, match="s_m"):
        beam.shape_matrix(1.5)
    with pytest.raises(FewearInputError, match="node"):
        beam.node_index(5)


def test_one_element_beam_uses_the_compiled_kernels_of_any_other():
    """A beam of one element hands the kernels writable arrays as a beam of four does (a
    broadcast view of one element is contiguous but read-only, and numba compiled every beam
    kernel once more for it, tens of seconds on a first run): after the set-up's compile, its
    forces and stiffness add no signature to add_beam_forces."""
    from fewear.mbd import ancf
    from fewear.mbd.slider_crank import compile_dynamics

    compile_dynamics()
    for n_elements in (1, 4):
        beam = AncfBeam(1.0, n_elements, section(0.01))
        _, B, H, _, _ = beam.kernel_data(0.0, 0.0)
        assert B.flags.writeable and H.flags.writeable
        q = beam.reference_coordinates(0.0, 0.0, 0.3)
        beam.elastic_forces_and_stiffness(q)
    assert len(ancf.add_beam_forces.signatures) == 1
