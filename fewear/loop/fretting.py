"""Fretting of a flat under a rigid cylinder: the stroke cycle and the wear blocks (DOLFINx).

The cylinder of :mod:`fewear.contact.flat`, pressed by P, follows a triangular stroke under
displacement control (McColl, Ding & Leen, Wear 256 (2004) 1114-1127); one solved cycle stands
for a block of N cycles, each increment wearing flat (and optionally cylinder) implicitly by
Archard's law, the blocks alternating the stroke's sense. Method notes: docs/scar.md.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mpi4py import MPI

from fewear.contact.flat import FlatContactSolver
from fewear.contact.params import FlatContactProblem
from fewear.errors import FewearInputError, require_finite_positive
from fewear.loop.settings import FrettingWearSettings
from fewear.mesh.flat import worn_node_y_m
from fewear.parallel import release_petsc_garbage
from fewear.wear.state import FlatWearState


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
class CycleWear:
    """The wear during a stroke cycle that stands for ``cycles`` cycles: Archard's k of the flat
    (``coefficient_m2_N``, m^2/N) and of the cylinder (``cylinder_coefficient_m2_N``; 0: the
    cylinder does not wear), and ``wear``, called after each increment with the flat's depth
    increment per top node, the cylinder's under each top node (m) and the centre's x (m), to
    move the worn surfaces (module docstring)."""

    coefficient_m2_N: float
    cylinder_coefficient_m2_N: float
    cycles: int
    wear: Callable[[np.ndarray, np.ndarray, float], None]

    def compliance_m_per_Pa(self, move_m: float) -> float:
        """The increment's wear compliance c = (k + k_c) N |dx| (m/Pa): in gross slip every node
        in contact slides by the centre's move dx (less the change of its elastic shear), and
        flat and cylinder recede under the same pressure, so their compliances add."""
        return (self.coefficient_m2_N + self.cylinder_coefficient_m2_N) * self.cycles * abs(
            move_m)

    def worn(self, pressure_Pa: np.ndarray, slip_m: np.ndarray, centre_x_m: float) -> None:
        """Wear flat and cylinder by the increment's Archard depths k N p s and k_c N p s."""
        sliding = self.cycles * pressure_Pa * slip_m
        self.wear(self.coefficient_m2_N * sliding, self.cylinder_coefficient_m2_N * sliding,
                  centre_x_m)


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
    max_pressure_Pa: float = 0.0

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
                 increments: int, wear: CycleWear | None = None,
                 sense: float = 1.0) -> StrokeCycle:
    """One stroke cycle of amplitude d = ``amplitude_m`` (m) in ``increments`` frictional steps
    under the normal force P = ``normal_force_N`` (N) from the solver's present state (module
    docstring); the solver is left at the cycle's end (centre back at x = 0, the shear it
    locked in kept as the next step's history).

    ``wear``: the flat worn in every increment as it goes (:class:`CycleWear`); None: no wear.
    ``sense``: +1, the stroke towards +x first; -1, towards -x first."""
    positions = math.copysign(1.0, sense) * stroke_positions_m(amplitude_m, increments)
    previous = 0.0
    nodes = solver.bore.points.shape[0]
    slip, pressure_slip, work = np.zeros(nodes), np.zeros(nodes), np.zeros(nodes)
    forces, iterations = np.empty(increments), np.empty(increments, dtype=int)
    peak = 0.0
    for j, centre_x in enumerate(positions):
        compliance = 0.0 if wear is None else wear.compliance_m_per_Pa(centre_x - previous)
        step = solver.solve_tangential_shift(centre_x, normal_force_N, compliance)
        if wear is not None:
            wear.worn(step.contact.pressure_Pa, step.contact.slip_m, centre_x)
        previous = centre_x
        slip += step.contact.slip_m
        pressure_slip += step.contact.pressure_Pa * step.contact.slip_m
        work += np.abs(step.shear_Pa) * step.contact.slip_m
        forces[j], iterations[j] = step.tangential_force_N, step.contact.newton_iterations
        peak = max(peak, step.contact.max_pressure_Pa)
    return StrokeCycle(positions, forces, iterations, solver.bore.points[:, 0].copy(), slip,
                       pressure_slip, work, solver.weights_m.copy(),
                       solver.problem.out_of_plane_length_m, peak)


@dataclass(frozen=True)
class FrettingBlock:
    """One wear block: the cycles done at its end, its stroke cycle's largest nodal pressure
    (Pa, over the increments), |Q| at the stroke's first end (N) and the largest depth at its
    end (m)."""

    cycles: int
    max_pressure_Pa: float
    tangential_force_N: float
    max_depth_m: float


@dataclass(frozen=True)
class FrettingRun:
    """The worn flat after the run: ``state`` (its ``steps`` count the increments that wore it;
    its ``sliding_distance_m`` is not kept, 0: the slip differs from node to node);
    ``cylinder``: the cylinder's wear alike, its x_m the position s along the cylinder's bottom
    from below its centre (m), its depth_m h_c into the cylinder (zero when its k is 0);
    ``blocks`` (a :class:`FrettingBlock` each); ``first_cycle``: the first block's stroke cycle
    (from the unworn flat, which it wears as it goes); ``wall_time_s``."""

    state: FlatWearState
    cylinder: FlatWearState
    blocks: tuple[FrettingBlock, ...]
    first_cycle: StrokeCycle
    wall_time_s: float


def run_fretting_wear(problem: FlatContactProblem, settings: FrettingWearSettings,
                      comm=MPI.COMM_WORLD,
                      report: Callable[[FrettingBlock], None] | None = None) -> FrettingRun:
    """Wear the flat of ``problem`` by ``settings`` (module docstring); ``report`` is called
    with every block (e.g. a progress line)."""
    start = time.perf_counter()
    solver = FlatContactSolver(problem, comm)
    made_xy = solver.mesh.geometry.x[:, :2].copy()
    state = FlatWearState.unworn(solver.bore.points[:, 0])
    k, per_block = settings.wear_coefficient_m2_N, settings.cycles_per_block
    blocks, first = [], None
    zone = np.abs(state.x_m) <= problem.mesh.contact_zone_half_width_m
    worn = [state, FlatWearState.unworn(state.x_m[zone])]  # the flat; the cylinder (s, h_c)

    def move_top(increment_m: np.ndarray, cylinder_m: np.ndarray, centre_x_m: float) -> None:
        worn[0] = worn[0].worn_by(increment_m, 0.0)
        solver.mesh.geometry.x[:, 1] = worn_node_y_m(made_xy, problem.geometry,
                                                     worn[0].depth_at)
        solver.update_geometry()
        release_petsc_garbage(solver.mesh.comm)  # the stiffness the move replaced
        if settings.cylinder_wear_coefficient_m2_N > 0.0:
            cylinder = worn[1]
            worn[1] = cylinder.worn_by(np.interp(cylinder.x_m, state.x_m - centre_x_m,
                                                 cylinder_m), 0.0)
            solver.set_cylinder_wear(worn[1].x_m, worn[1].depth_m)

    wear = CycleWear(k, settings.cylinder_wear_coefficient_m2_N, per_block, move_top)
    solver.solve(settings.normal_force_N)
    for block in range(settings.blocks):
        cycle = stroke_cycle(solver, settings.normal_force_N, settings.stroke_amplitude_m,
                             settings.increments_per_cycle, wear, sense=(-1.0) ** block)
        first = first or cycle
        blocks.append(FrettingBlock((block + 1) * per_block, cycle.max_pressure_Pa,
                                    float(abs(cycle.tangential_force_N[
                                        settings.increments_per_cycle // 4 - 1])),
                                    float(worn[0].depth_m.max())))
        if report is not None:
            report(blocks[-1])
    return FrettingRun(worn[0], worn[1], tuple(blocks), first, time.perf_counter() - start)
