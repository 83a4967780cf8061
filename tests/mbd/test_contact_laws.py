"""Contact laws, friction regularisation, clearance profiles and the joint's force derivatives."""

import math

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.mbd.clearance import ClearanceJoint
from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction, lankarani_nikravesh_stiffness
from fewear.mbd.points import RigidPoint

K_N_M15 = 4.0e10
DELTA_M, RATE_M_S, V_IMPACT_M_S = 1.0e-5, 0.3, 0.5


def test_lankarani_nikravesh_stiffness_of_the_paper_joint():
    """K from the seed's Table 1 by hand: h = (1 - nu^2)/(pi E), K = 4/(3 pi (h_i + h_j))
    sqrt(R_i R_j / (R_j - R_i)) with R_i = 9.5 mm, R_j = 10 mm."""
    h_pin = (1 - 0.27**2) / (math.pi * 207e9)
    h_bushing = (1 - 0.32**2) / (math.pi * 90e9)
    expected = 4 / (3 * math.pi * (h_pin + h_bushing)) * math.sqrt(0.0095 * 0.010 / 0.0005)
    assert lankarani_nikravesh_stiffness(0.0095, 0.010, 207e9, 0.27, 90e9, 0.32) == \
        pytest.approx(expected, rel=1e-12)
    assert 3.9e10 < expected < 4.1e10


@pytest.mark.parametrize("law", ["lankarani-nikravesh", "hunt-crossley", "flores"])
def test_power_laws_are_hertz_when_elastic(law):
    contact = ContactLaw(law, K_N_M15, restitution=1.0)
    force, stiffness, damping = contact.normal_force(DELTA_M, RATE_M_S, V_IMPACT_M_S)
    assert force == pytest.approx(K_N_M15 * DELTA_M**1.5, rel=1e-12)
    assert stiffness == pytest.approx(1.5 * K_N_M15 * DELTA_M**0.5, rel=1e-12)
    assert damping == 0.0


@pytest.mark.parametrize("law, chi", [
    ("lankarani-nikravesh", 0.75 * (1 - 0.8**2)),
    ("hunt-crossley", 1.5 * (1 - 0.8)),
    ("flores", 8 * (1 - 0.8) / (5 * 0.8)),
])
def test_hysteresis_damping_factors(law, chi):
    contact = ContactLaw(law, K_N_M15, restitution=0.8)
    force = contact.normal_force(DELTA_M, RATE_M_S, V_IMPACT_M_S)[0]
    assert force == pytest.approx(K_N_M15 * DELTA_M**1.5 * (1 + chi * RATE_M_S / V_IMPACT_M_S))


def test_tabulated_law_interpolates_a_sampled_hertz_law():
    penetration = np.linspace(0.0, 4e-5, 401)
    contact = ContactLaw("tabulated", restitution=1.0, penetration_m=penetration,
                         force_N=K_N_M15 * penetration**1.5)
    force = contact.normal_force(DELTA_M + 3e-8, 0.0, 1.0)[0]
    assert force == pytest.approx(K_N_M15 * (DELTA_M + 3e-8) ** 1.5, rel=1e-3)
    lnd = ContactLaw("lankarani-nikravesh", K_N_M15, restitution=0.7)
    tab = ContactLaw("tabulated", restitution=0.7, penetration_m=penetration,
                     force_N=K_N_M15 * penetration**1.5)
    ratio = tab.normal_force(DELTA_M, RATE_M_S, V_IMPACT_M_S)[0] / \
        lnd.normal_force(DELTA_M, RATE_M_S, V_IMPACT_M_S)[0]
    assert ratio == pytest.approx(1.0, rel=1e-3)


def test_tabulated_law_rejects_bad_tables():
    with pytest.raises(FewearInputError, match="increasing"):
        ContactLaw("tabulated", penetration_m=np.array([0.0, 2e-5, 1e-5]),
                   force_N=np.array([0.0, 1.0, 2.0]))


def test_damping_never_pulls():
    contact = ContactLaw("lankarani-nikravesh", K_N_M15, restitution=0.5)
    assert contact.normal_force(DELTA_M, -100.0, 0.1) == (0.0, 0.0, 0.0)


def test_friction_regularisation_is_continuous_and_odd():
    friction = Friction(0.1, 1e-4, 1e-2)
    speeds = np.linspace(-0.03, 0.03, 60001)
    psi = np.array([friction.factor(v)[0] for v in speeds])
    assert np.max(np.abs(np.diff(psi))) < 1.01 * (speeds[1] - speeds[0]) / (1e-2 - 1e-4)
    np.testing.assert_allclose(psi, -psi[::-1], atol=1e-12)
    assert friction.factor(0.5e-4) == (0.0, 0.0)
    assert friction.factor(-0.02)[0] == -1.0
    assert friction.factor(0.5 * (1e-4 + 1e-2))[0] == pytest.approx(0.5)


def test_clearance_profile_is_a_periodic_c2_spline_through_the_given_clearances():
    angles = np.radians([0.0, 90.0, 180.0, 270.0])
    values = np.array([5e-4, 6e-4, 5e-4, 4e-4])
    profile = ClearanceProfile(angles, values)
    for angle, value in zip(angles, values):
        assert profile(angle)[0] == pytest.approx(value, rel=1e-12)
        assert profile(angle + 2 * math.pi)[0] == pytest.approx(value, rel=1e-12)
        assert profile(angle - 2 * math.pi)[0] == pytest.approx(value, rel=1e-12)
    eps = 1e-9  # value, slope and curvature continuous across every node, the wrap included
    for angle in angles:
        left, right = profile(angle - eps), profile(angle + eps)
        np.testing.assert_allclose(left, right, rtol=1e-6, atol=1e-12)
    # c' and c'' are the derivatives of c (central differences)
    theta, h = 2.0, 1e-5
    assert profile(theta)[1] == pytest.approx(
        (profile(theta + h)[0] - profile(theta - h)[0]) / (2 * h), rel=1e-6)
    assert profile(theta)[2] == pytest.approx(
        (profile(theta + h)[1] - profile(theta - h)[1]) / (2 * h), rel=1e-6)
    # symmetric data about 90 deg give a symmetric curve; a sinusoid is followed closely
    assert profile(math.radians(45.0))[0] == pytest.approx(profile(math.radians(135.0))[0])
    fine = np.radians(np.arange(0.0, 360.0, 10.0))
    sinusoid = ClearanceProfile(fine, 5e-4 + 1e-4 * np.sin(fine))
    assert sinusoid(1.234)[0] == pytest.approx(5e-4 + 1e-4 * math.sin(1.234), abs=1e-8)
    assert ClearanceProfile.constant(5e-4)(1.234) == (5e-4, 0.0, 0.0)


@pytest.mark.parametrize("values", [[5e-4, -1e-5], [5e-4, 0.0]])
def test_clearance_profile_rejects_non_positive_clearance(values):
    with pytest.raises(FewearInputError, match="clearance"):
        ClearanceProfile(np.array([0.0, 1.0]), np.array(values))


def _joint(profile):
    law = ContactLaw("lankarani-nikravesh", K_N_M15, restitution=0.8)
    return ClearanceJoint(RigidPoint(0, (0.05, 0.01)), RigidPoint(3), 0.0095, 0.010, profile, law,
                          Friction(0.1, 1e-4, 1e-2))


@pytest.mark.parametrize("profile", [
    ClearanceProfile.constant(5e-4),
    ClearanceProfile(np.radians([0.0, 120.0, 240.0]), np.array([5e-4, 5.3e-4, 4.8e-4])),
])
def test_local_force_derivatives_match_finite_differences(profile):
    joint = _joint(profile)
    angle = math.radians(40.0)
    # in contact everywhere on the profile (|e| > max c), all velocities non-zero
    z = np.array([5.4e-4 * math.cos(angle), 5.4e-4 * math.sin(angle), 0.2, -0.1, 3.0, 0.5, 0.1])
    _, _, _, D = joint.local_forces(z, 0.4)
    steps = np.array([1e-10, 1e-10, 1e-7, 1e-7, 1e-6, 1e-6, 1e-7])
    for k, step in enumerate(steps):
        plus, minus = z.copy(), z.copy()
        plus[k] += step
        minus[k] -= step
        fp, _, ftp, _ = joint.local_forces(plus, 0.4)
        fm, _, ftm, _ = joint.local_forces(minus, 0.4)
        numeric = (np.append(fp, ftp) - np.append(fm, ftm)) / (2 * step)
        np.testing.assert_allclose(D[:, k], numeric, rtol=1e-4, atol=1e-6 * np.abs(D).max())


def test_generalized_force_jacobian_matches_finite_differences():
    """dQ/dq' exactly, dQ/dq up to the neglected velocity terms (zero velocities here)."""
    joint = _joint(ClearanceProfile.constant(5e-4))
    q = np.array([0.0, 0.0, 0.3, 0.0, 0.0, 0.0])
    pin = RigidPoint(0, (0.05, 0.01)).position(q[:3])
    q[3:5] = pin - 5.05e-4 * np.array([math.cos(0.7), math.sin(0.7)])
    qd = np.zeros(6)
    joint.begin_step(q, qd)
    joint.data.memory[0, 2] = 0.5  # the approach velocity: the impact velocity of the contact
    Q, K, C = joint.evaluate(q, qd, 0.0)
    for k in range(6):
        step = 1e-10
        plus, minus = q.copy(), q.copy()
        plus[k] += step
        minus[k] -= step
        numeric = (joint.evaluate(plus, qd, 0.0)[0]
                   - joint.evaluate(minus, qd, 0.0)[0]) / (2 * step)
        np.testing.assert_allclose(K[:, k], numeric, rtol=1e-4, atol=1e-6 * np.abs(K).max())
    qd_step = np.zeros(6)
    for k in range(6):
        step = 1e-6
        qd_step[:] = 0.0
        qd_step[k] = step
        numeric = (joint.evaluate(q, qd_step, 0.0)[0]
                   - joint.evaluate(q, -qd_step, 0.0)[0]) / (2 * step)
        np.testing.assert_allclose(C[:, k], numeric, rtol=1e-4, atol=1e-6 * np.abs(C).max())


def test_contact_normal_is_the_gradient_of_the_penetration_on_a_worn_profile():
    """On a clearance that varies with the angle the force direction m is grad delta / |grad
    delta|, delta = |e| - c(theta(e)) (finite differences), not the radial n; m = n on a circle."""
    from fewear.mbd.clearance import contact_normal

    profile = ClearanceProfile(np.array([0.0, 0.5, 3.0]), np.array([5e-4, 8e-4, 6e-4]))

    def delta(e):
        return math.hypot(*e) - profile(math.atan2(e[1], e[0]))[0]

    e = np.array([7.0e-4 * math.cos(0.3), 7.0e-4 * math.sin(0.3)])
    h = 1e-10
    gradient = np.array([(delta(e + h * k) - delta(e - h * k)) / (2 * h) for k in np.eye(2)])
    d = math.hypot(*e)
    m = contact_normal(e[0] / d, e[1] / d, profile(0.3)[1] / d)
    np.testing.assert_allclose(m, gradient / np.linalg.norm(gradient), atol=1e-6)
    assert contact_normal(0.6, 0.8, 0.0) == pytest.approx((0.6, 0.8))
