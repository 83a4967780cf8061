"""Fretting of a flat under a rigid cylinder: the stroke cycle (DOLFINx).

The cylinder of :mod:`fewear.contact.flat`, pressed by the normal force P, is moved back and
forth under displacement control: its centre's x follows the triangular stroke 0 -> +d -> 0 ->
-d -> 0 in n equal increments (McColl, Ding & Leen, Wear 256 (2004) 1114-1127, as LevelSetWear
models it: d = 25 um, n = 40). Each increment is one frictional step
(:meth:`fewear.contact.flat.FlatContactSolver.solve_tangential_shift`, P by force control, Q the
reaction), the shear history carried from step to step; the cycle starts from the state the
solver is in (after a plain ``solve(P)``: no shear).

Per top node the cycle accumulates the Coulomb slip sum_j s_j (each step's slip is the relative
tangential motion less the tangential penalty's elastic part), the Archard integral
sum_j p_j s_j (the flat's wear depth of the cycle is k times it: Archard, J. Appl. Phys. 24 (1953)
981, per node and step) and the friction work sum_j |tau_j| s_j (J/m^2, the energy the cycle
dissipates per unit area). The energy dissipated per cycle, L sum_i w_i sum_j |tau_ij| s_ij (w_i
the nodes' quadrature weights, L the out-of-plane length), is the area of the hysteresis loop
Q(x) once the loop is steady; in gross slip it is 4 mu P (d - d_stick) to the normals' tilt
(tests/loop/test_fretting_cycle.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fewear.contact.flat import FlatContactSolver
from fewear.errors import FewearInputError, require_finite_positive


def stroke_positions_m(amplitude_m: float, increments: int) -> np.ndarray:
    """The centre's x (m) at the end of each of the cycle's ``increments`` (a whole multiple of
    4, so that +d and -d are increment ends): the triangle 0 -> +d -> 0 -> -d -> 0 in equal
    steps of 4 d / n."""
    require_finite_positive("stroke amplitude_m", amplitude_m)
    if not (isinstance(increments, int) and not isinstance(increments, bool)
            and 4 <= increments <= 10000 and increments % 4 == 0):
        raise FewearInputError(f"increments per cycle = {increments!r}: must be a whole multiple "
                               "of 4 in [4, 10000] (the stroke's ends and middle at increments)")
    phase = 4.0 * np.arange(1, increments + 1) / increments  # 0..4 over the cycle
    return amplitude_m * np.where(phase <= 1.0, phase,
                                  np.where(phase <= 3.0, 2.0 - phase, phase - 4.0))


@dataclass(frozen=True)
class StrokeCycle:
    """One stroke cycle of the cylinder on the flat (module docstring).

    Per increment: ``centre_x_m`` (n,), the prescribed centre x at its end (m);
    ``tangential_force_N`` (n,), the reaction Q (N, x component of the contact resultant);
    ``newton_iterations`` (n,). Per top node (in the order of x, ``x_m``): ``slip_m``, the
    cycle's accumulated Coulomb slip (m); ``pressure_slip_Pa_m``, sum_j p_j s_j (Pa m: the
    flat's wear depth of the cycle divided by Archard's k); ``friction_work_J_m2``,
    sum_j |tau_j| s_j (J/m^2). ``weights_m``: the top nodes' quadrature weights (m), so that
    integrals along the top are sums of weight times value; ``length_m``: the out-of-plane
    length L (m)."""

    centre_x_m: np.ndarray
    tangential_force_N: np.ndarray
    newton_iterations: np.ndarray
    x_m: np.ndarray
    slip_m: np.ndarray
    pressure_slip_Pa_m: np.ndarray
    friction_work_J_m2: np.ndarray
    weights_m: np.ndarray
    length_m: float

    @property
    def dissipated_energy_J(self) -> float:
        """The energy friction dissipates in the cycle, L sum_i w_i sum_j |tau_ij| s_ij (J)."""
        return float(self.length_m * np.sum(self.weights_m * self.friction_work_J_m2))

    def loop_area_J(self, start_x_m: float = 0.0, start_force_N: float = 0.0) -> float:
        """The work of Q along the centre's path, the integral of Q dx by the trapezoid rule
        over the increments, from the cycle's start (``start_x_m``, ``start_force_N``): the
        hysteresis loop's area when the loop is steady (J). The trapezoid is exact only where Q
        is linear in x over an increment: not over a gross-slip reversal shorter than an
        increment (use :attr:`dissipated_energy_J` there)."""
        x = np.concatenate([[start_x_m], self.centre_x_m])
        force = np.concatenate([[start_force_N], self.tangential_force_N])
        return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(x)))


def stroke_cycle(solver: FlatContactSolver, normal_force_N: float, amplitude_m: float,
                 increments: int) -> StrokeCycle:
    """One stroke cycle of amplitude d = ``amplitude_m`` (m) in ``increments`` frictional steps
    under the normal force P = ``normal_force_N`` (N) from the solver's present state (module
    docstring); the solver is left at the cycle's end (centre back at x = 0, the shear it
    locked in kept as the next step's history)."""
    positions = stroke_positions_m(amplitude_m, increments)
    nodes = solver.bore.points.shape[0]
    slip, pressure_slip, work = np.zeros(nodes), np.zeros(nodes), np.zeros(nodes)
    forces, iterations = np.empty(increments), np.empty(increments, dtype=int)
    for j, centre_x in enumerate(positions):
        step = solver.solve_tangential_shift(centre_x, normal_force_N)
        slip += step.contact.slip_m
        pressure_slip += step.contact.pressure_Pa * step.contact.slip_m
        work += np.abs(step.shear_Pa) * step.contact.slip_m
        forces[j], iterations[j] = step.tangential_force_N, step.contact.newton_iterations
    return StrokeCycle(positions, forces, iterations, solver.bore.points[:, 0].copy(), slip,
                       pressure_slip, work, solver.weights_m.copy(),
                       solver.problem.out_of_plane_length_m)
