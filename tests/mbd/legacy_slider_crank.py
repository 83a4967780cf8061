"""The slider-crank as fewear built it before mechanism descriptions (main 918b77c's
``SliderCrankModel``, kept test-side only): an independent construction of the same system, to
show that the description path (:func:`fewear.mbd.slider_crank.describe`) builds it unchanged.
The only edit: ``PrismaticX(i, 0.0)`` is written as the general :class:`Prismatic` along x,
whose rows are the same numbers."""

import math

import numpy as np

from fewear.mbd.clearance import ClearanceJoint, measure_rows
from fewear.mbd.constraints import DrivenAngle, Prismatic, Revolute
from fewear.mbd.history import JointHistory, classify_modes
from fewear.mbd.integrator import GeneralizedAlpha, Trajectory
from fewear.mbd.points import GroundPoint, NodePoint, RigidPoint
from fewear.mbd.system import MultibodySystem


class LegacySliderCrank:
    def __init__(self, crank, joint):
        self.crank = crank
        system = MultibodySystem((0.0, -crank.gravity_m_s2))
        r, rod = crank.crank_length_m, crank.rod_length_m
        self.i_crank = system.add_rigid_body(crank.crank_mass_kg, crank.crank_inertia_kg_m2)
        if crank.rod == "rigid":
            m_rod = crank.rod_mass_kg
            self.i_rod = system.add_rigid_body(m_rod, m_rod * rod * rod / 12.0)
            rod_a, rod_b = RigidPoint(self.i_rod, (-rod / 2, 0.0)), RigidPoint(self.i_rod,
                                                                               (rod / 2, 0.0))
            self.beam = None
        else:
            from fewear.mbd.ancf import AncfBeam, BeamSection

            section = BeamSection(crank.rod_youngs_modulus_Pa, crank.rod_poisson_ratio,
                                  crank.rod_density_kg_m3, crank.rod_height_m, crank.rod_width_m)
            self.beam = AncfBeam(rod, crank.rod_elements, section)
            self.i_rod = system.add_beam(self.beam, crank.rod_damping_s)
            rod_a = NodePoint(self.i_rod + self.beam.node_index(0).start)
            rod_b = NodePoint(self.i_rod + self.beam.node_index(self.beam.n_nodes - 1).start)
        self.i_slider = system.add_rigid_body(crank.slider_mass_kg, crank.slider_mass_kg * 1e-4)
        system.add_constraint(Revolute(RigidPoint(self.i_crank, (-r / 2, 0.0)),
                                       GroundPoint(0.0, 0.0)))
        system.add_constraint(Revolute(RigidPoint(self.i_crank, (r / 2, 0.0)), rod_a))
        system.add_constraint(DrivenAngle(self.i_crank, math.radians(crank.initial_crank_angle_deg),
                                          crank.omega_rad_s))
        system.add_constraint(Prismatic(self.i_slider))
        system.add_force(ClearanceJoint(rod_b, RigidPoint(self.i_slider), joint.pin_radius_m,
                                        joint.bushing_radius_m, joint.profile, joint.law,
                                        joint.friction))
        self.system = system.finalize()

    def initial_conditions(self):
        c = self.crank
        r, rod, omega = c.crank_length_m, c.rod_length_m, c.omega_rad_s
        theta = math.radians(c.initial_crank_angle_deg)
        _, x_b, v_b = c.closed_form(0.0)
        beta = math.asin(-r * math.sin(theta) / rod)
        beta_dot = -r * omega * math.cos(theta) / (rod * math.cos(beta))
        a = r * np.array([math.cos(theta), math.sin(theta)])
        v_a = r * omega * np.array([-math.sin(theta), math.cos(theta)])
        axis = np.array([math.cos(beta), math.sin(beta)])
        normal = np.array([-math.sin(beta), math.cos(beta)])
        n = self.system.n_coordinates
        q, qd = np.zeros(n), np.zeros(n)
        q[self.i_crank:self.i_crank + 3] = [a[0] / 2, a[1] / 2, theta]
        qd[self.i_crank:self.i_crank + 3] = [v_a[0] / 2, v_a[1] / 2, omega]
        if self.beam is None:
            q[self.i_rod:self.i_rod + 3] = [*(a + rod / 2 * axis), beta]
            qd[self.i_rod:self.i_rod + 3] = [*(v_a + rod / 2 * beta_dot * normal), beta_dot]
        else:
            k = self.beam.n_coordinates
            nodes = self.beam.reference_coordinates(a[0], a[1], beta).reshape(-1, 4)
            qd_nodes = np.zeros_like(nodes)
            arc = nodes[:, 0:2] - a
            qd_nodes[:, 0:2] = v_a + beta_dot * np.stack([-arc[:, 1], arc[:, 0]], axis=1)
            qd_nodes[:, 2:4] = beta_dot * np.stack([-nodes[:, 3], nodes[:, 2]], axis=1)
            q[self.i_rod:self.i_rod + k] = nodes.ravel()
            qd[self.i_rod:self.i_rod + k] = qd_nodes.ravel()
        q[self.i_slider] = x_b
        qd[self.i_slider] = float(v_b)
        return q, qd


def legacy_history(crank, joint, settings) -> JointHistory:
    """Settling + recorded cycles from the closed-form start, as main's ``simulate``."""
    model = LegacySliderCrank(crank, joint)
    integrator = GeneralizedAlpha(model.system, settings)
    state = integrator.initial_state(*model.initial_conditions())
    parts = []
    for cycle in range(crank.settling_cycles + crank.recorded_cycles):
        t_end = (cycle + 1) * crank.period_s
        if cycle < crank.settling_cycles:
            state = integrator.run(state, t_end)
            continue
        if not parts:
            parts.append(Trajectory(np.array([state.t]), np.zeros(1), state.q[None],
                                    state.qd[None], state.qdd[None], state.a[None],
                                    state.lam[None], model.system.data.joints.memory[None].copy()))
        state, trajectory = integrator.run_recorded(state, t_end)
        parts.append(trajectory)
    path = Trajectory(*(np.concatenate([getattr(p, name) for p in parts])
                        for name in Trajectory.__dataclass_fields__))
    columns = measure_rows(model.system.data.joints, 0, path.q, path.qd, path.joint_memory)
    return JointHistory(
        time_s=path.time_s, crank_angle_rad=path.q[:, model.i_crank + 2],
        slider_x_m=path.q[:, model.i_slider], slider_velocity_m_s=path.qd[:, model.i_slider],
        eccentricity_m=columns[:, 0:2], penetration_m=columns[:, 2],
        normal_force_N=columns[:, 3], friction_force_N=columns[:, 4],
        reaction_force_N=columns[:, 5:7], rel_omega_rad_s=columns[:, 7],
        mode=classify_modes(path.time_s, columns[:, 3], joint.impact_max_duration_s))
