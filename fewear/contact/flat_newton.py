"""The flat's contact on its top nodes, compiled (numba, :mod:`fewear.jit`): the penalty contact
of the rigid cylinder with Coulomb's law by return mapping, its linearisation, the Newton step of
the flat condensed onto its top (:mod:`fewear.contact.flat`'s method) and the
:class:`fewear.contact.newton.NewtonOperations` on its state, with the coupled Newton and the
solve on the cylinder's ray of :mod:`fewear.contact.newton` compiled on them.

The state (:func:`new_state`) is a tuple of arrays: the top's nodal compliance G (2n, 2n) on the
covered nodes (their rows and columns; zero elsewhere), the nodal forces on the flat g (2n,), the
nodal displacements U = G g (2n,), the cylinder's centre c (2,), the top nodes X lowered by the
cylinder's wear (n, 2), their weights w (n,), the constants (``CONSTANTS``), the history of the
frictional step (``history_parts``: tau_0 (n,), U_0 (2n,), c_0 (2,), the frozen pressure (n,))
and the covered nodes (n,), 1 or 0. The operations update it
in place. This module does not import DOLFINx.
"""

from __future__ import annotations

import math
import sys
import types

import numpy as np
from numba.extending import register_jitable

from fewear.contact.condensed_newton import (  # noqa: F401 (operations on the nodal state)
    deformed_points,
    node_weights,
    pin_position,
    place_pin,
    try_step,
    update_sizes,
    zero_displacement,
)
from fewear.contact.newton import specialised
from fewear.contact.newton_kernels import LineData, NewtonSettings, pairwise_sum
from fewear.jit import compiled

# The constants' positions: the penalty k (Pa/m, the series one in a wear step), the cylinder's
# radius R (m), mu (0: frictionless), the tangential penalty k_t (Pa/m), 1 where the pressure is
# frozen (else 0), the prescribed x of the centre (m; NaN: none), the largest |x| (m) of a node
# the contact reached outside the covered ones (0: none), the stick tolerance.
PENALTY, RADIUS, FRICTION, TANGENTIAL, FROZEN, TARGET_X, OUTGROWN_X, STICK = range(8)
CONSTANTS = 8


@register_jitable
def history_parts(history: np.ndarray, n: int):
    """tau_0 (n,), U_0 (2n,), c_0 (2,) and the frozen pressure (n,): views of ``history``."""
    return history[:n], history[n:3 * n], history[3 * n:3 * n + 2], history[3 * n + 2:]


@compiled
def tractions(points: np.ndarray, U: np.ndarray, centre: np.ndarray, weights_m: np.ndarray,
              constants: np.ndarray, history: np.ndarray):
    """The contact at the top nodes (Wriggers, *Computational Contact Mechanics*, 2006,
    sec. 5.2.2: the return mapping of a tangential penalty k_t and Coulomb's law): with
    d = X + U - c (X lowered by the cylinder's wear), n = d/|d|, t = (-n_y, n_x), the penalty
    pressure p_k = k <R - |d|>_+, the pressure p = p_k + frozen (p_frozen - p_k),
    the trial shear tau_trial = tau_0 - k_t t . ((U - U_0) - (c - c_0)) and the shear tau =
    tau_trial where mu p > 0 and |tau_trial| <= mu p (1 + stick tolerance), else
    mu p sign(tau_trial): a node out of contact does not stick (at a step's start, where
    tau_trial = 0 = mu p, it would hold the flat by k_t, the whole top in the Newton's first
    system, where the field's interpolated history had it slip by rounding). Returns
    the nodal forces on the flat f = w (p n + tau t) (n, 2), their derivatives df/dd (n, 2, 2)
    (d moves with U and against c), the distances |d| (n,), p_k, p, tau (n,) and whether each
    node sticks with mu p > 0 (n,)."""
    n = points.shape[0]
    k, radius, mu, k_t = constants[PENALTY], constants[RADIUS], constants[FRICTION], \
        constants[TANGENTIAL]
    frozen, tolerance = constants[FROZEN], constants[STICK]
    shear0, U0, c0, frozen_pressure = history_parts(history, n)
    f, jacobian = np.zeros((n, 2)), np.zeros((n, 2, 2))
    distance, penalty_pressure = np.empty(n), np.empty(n)
    pressure, shear, sticking = np.empty(n), np.empty(n), np.zeros(n, dtype=np.bool_)
    for q in range(n):
        d_x, d_y = points[q, 0] + U[q, 0] - centre[0], points[q, 1] + U[q, 1] - centre[1]
        rho = math.sqrt(d_x * d_x + d_y * d_y)
        distance[q] = rho
        n_x, n_y = d_x / rho, d_y / rho
        t_x, t_y = -n_y, n_x
        penetration = radius - rho
        penalty_pressure[q] = k * (penetration if penetration > 0.0 else 0.0)
        slope = -k if penetration > 0.0 else 0.0  # dp_k/dd = slope n^T
        p = penalty_pressure[q] + frozen * (frozen_pressure[q] - penalty_pressure[q])
        slope *= 1.0 - frozen
        m_x = U[q, 0] - U0[2 * q] - (centre[0] - c0[0])
        m_y = U[q, 1] - U0[2 * q + 1] - (centre[1] - c0[1])
        trial = shear0[q] - k_t * (t_x * m_x + t_y * m_y)
        trial_slope = -k_t * (1.0 - (m_x * n_x + m_y * n_y) / rho)  # dtrial/dd = this t^T
        bound = mu * p
        if bound > 0.0 and abs(trial) <= bound * (1.0 + tolerance):
            tau = trial
            dtau_n, dtau_t = 0.0, trial_slope  # dtau/dd = dtau_n n^T + dtau_t t^T
            sticking[q] = True
        else:
            sign = 1.0 if trial > 0.0 else -1.0
            tau = sign * bound
            dtau_n, dtau_t = sign * mu * slope, 0.0
        pressure[q], shear[q] = p, tau
        w = weights_m[q]
        f[q, 0] = w * (p * n_x + tau * t_x)
        f[q, 1] = w * (p * n_y + tau * t_y)
        # df/dd = w [n (slope n^T - tau/rho t^T) + t (dtau_n n^T + (p/rho + dtau_t) t^T)]
        # (dn/dd = t t^T / rho, dt/dd = -n t^T / rho)
        along_n_x, along_n_y = slope * n_x - tau / rho * t_x, slope * n_y - tau / rho * t_y
        along_t_x = dtau_n * n_x + (p / rho + dtau_t) * t_x
        along_t_y = dtau_n * n_y + (p / rho + dtau_t) * t_y
        jacobian[q, 0, 0] = w * (n_x * along_n_x + t_x * along_t_x)
        jacobian[q, 0, 1] = w * (n_x * along_n_y + t_x * along_t_y)
        jacobian[q, 1, 0] = w * (n_y * along_n_x + t_y * along_t_x)
        jacobian[q, 1, 1] = w * (n_y * along_n_y + t_y * along_t_y)
    return f, jacobian, distance, penalty_pressure, pressure, shear, sticking


@compiled
def linearised_tractions(points: np.ndarray, U: np.ndarray, centre: np.ndarray,
                         weights_m: np.ndarray, constants: np.ndarray, history: np.ndarray,
                         load: np.ndarray):
    """:func:`tractions` and the active nodes A (a force or a derivative not zero), the
    cylinder's residual sum f - F/L (N/m) and the active length (m): the weights of the nodes
    with p_k > 0, and in a frictional step those of the sticking nodes once more, so that the
    Newton's step cap (:func:`fewear.contact.newton_kernels.step_cap`) halves when the stick
    set alternates as it does when the contact set does: a node flipping between stick
    (tangential stiffness k_t) and slip (none) made the full steps overshoot in a growing cycle
    (h = a/16)."""
    f, jacobian, distance, penalty_pressure, pressure, shear, sticking = tractions(
        points, U, centre, weights_m, constants, history)
    n = points.shape[0]
    coupled = np.zeros(n, dtype=np.bool_)
    residual = np.zeros(2)
    for q in range(n):
        residual[0] += f[q, 0]
        residual[1] += f[q, 1]
        for i in range(2):
            coupled[q] |= f[q, i] != 0.0 or jacobian[q, i, 0] != 0.0 or jacobian[q, i, 1] != 0.0
    length = pairwise_sum(weights_m[penalty_pressure > 0.0])
    if constants[FRICTION] != 0.0:
        length += pairwise_sum(weights_m[sticking])
    return residual - load, length, (f, jacobian, distance, np.flatnonzero(coupled))


@compiled
def newton_step(G: np.ndarray, g: np.ndarray, U: np.ndarray, f: np.ndarray,
                jacobian: np.ndarray, active: np.ndarray, basis: np.ndarray, load: np.ndarray,
                prescribed: np.ndarray):
    """One Newton step on the active nodes A with the centre's update dc = p + basis z
    (p: ``prescribed``): the new forces g'_A and z from the linearised forces at the new state,

        g'_a - J_a sum_b G_ab g'_b + J_a basis z = f_a - J_a (U_a + p),
        basis^T sum_a g'_a = basis^T F/L,

    J_a = df_a/dd (:func:`tractions`); the elastic flat's equations condensed onto the top, the
    step of the whole field's Newton (K_el + J) du = -(K_el u + r) to rounding. Returns
    dg = g' - g (g' zero off A), dU = G dg (G symmetric: its rows on the support) and dc."""
    m, k = active.size, basis.shape[1]
    system = np.zeros((2 * m + k, 2 * m + k))
    rhs = np.empty(2 * m + k)
    for a in range(m):
        q = active[a]
        for i in range(2):
            row = 2 * a + i
            system[row, row] += 1.0
            for b in range(m):
                for j in range(2):
                    column = 2 * active[b] + j
                    system[row, 2 * b + j] -= (jacobian[q, i, 0] * G[column, 2 * q]
                                               + jacobian[q, i, 1] * G[column, 2 * q + 1])
            for c in range(k):
                system[row, 2 * m + c] = (jacobian[q, i, 0] * basis[0, c]
                                          + jacobian[q, i, 1] * basis[1, c])
                system[2 * m + c, row] = basis[i, c]
            rhs[row] = f[q, i] - (jacobian[q, i, 0] * (U[q, 0] + prescribed[0])
                                  + jacobian[q, i, 1] * (U[q, 1] + prescribed[1]))
    for c in range(k):
        rhs[2 * m + c] = basis[0, c] * load[0] + basis[1, c] * load[1]
    solution = np.linalg.solve(system, rhs)
    dg = -g
    for a in range(m):
        for i in range(2):
            dg[2 * active[a] + i] += solution[2 * a + i]
    dU = np.zeros(dg.size)
    for row in np.flatnonzero(dg):
        dU += dg[row] * G[row]
    dc = prescribed.copy()
    for c in range(k):
        dc += basis[:, c] * solution[2 * m + c]
    return dg, dU, dc


def new_state(nodes: int) -> tuple:
    """The state of the module docstring for ``nodes`` top nodes: no compliance, forces or
    displacement, the centre at 0, no points, weights, history or covered nodes yet."""
    size = 2 * nodes
    constants = np.zeros(CONSTANTS)
    constants[TARGET_X] = math.nan
    return (np.zeros((size, size)), np.zeros(size), np.zeros(size), np.zeros(2),
            np.zeros((nodes, 2)), np.zeros(nodes), constants, np.zeros(4 * nodes + 2),
            np.zeros(nodes))


# -- the operations of the contact Newton (fewear.contact.newton.NewtonOperations) ---------------
# as in fewear.contact.condensed_newton: NumPy code from Python, compiled into the solves; the
# nodal ones (try_step, update_sizes, ...) are that module's.
@register_jitable
def linearise(state, load):
    """The tractions at the state (``linear``: f, df/dd, |d|, A); the cylinder's residual
    (N/m) and the active length (m)."""
    G, g, U, centre, points, weights, constants, history, covered = state
    return linearised_tractions(points, U.reshape(-1, 2), centre, weights, constants, history,
                                load)


@register_jitable
def newton_direction(state, linear, pin_residual, load, basis):
    """One Newton step (:func:`newton_step`), the centre's x moved to the prescribed one where
    there is one. An active node outside the covered ones (its part of G not computed) sets
    the state's ``OUTGROWN_X`` to its |x|: the caller computes those columns and solves again."""
    G, g, U, centre, points, weights, constants, history, covered = state
    f, jacobian, distance, active = linear
    for q in active:
        if covered[q] == 0.0:
            constants[OUTGROWN_X] = max(constants[OUTGROWN_X], abs(points[q, 0]))
    prescribed = np.zeros(2)
    if not math.isnan(constants[TARGET_X]):
        prescribed[0] = constants[TARGET_X] - centre[0]
    dg, dU, dc = newton_step(G, g, U.reshape(-1, 2), f, jacobian, active, basis, load,
                             prescribed)
    return (dg, dU), dc


@register_jitable
def begin_line_search(state, linear, update, dc, pin_residual):
    """Slope of Pi along (dg, dU, dc), (g - f) . dU + (sum f - F/L) . dc (J/m); the elastic
    energy 1/2 g.G g along the line, 1/2 g.U + s g.dU + s^2/2 dg.dU; the base (g, U)."""
    G, g, U, centre, points, weights, constants, history, covered = state
    dg, dU = update
    slope = np.dot(g - linear[0].reshape(-1), dU) + np.dot(pin_residual, dc)
    elastic = np.array([0.5 * np.dot(g, U), np.dot(g, dU), 0.5 * np.dot(dg, dU)])
    line = LineData(slope, points, U.reshape(-1, 2), dU.reshape(-1, 2), elastic,
                    linear[2] - constants[RADIUS])
    return line, (g.copy(), U.copy())


@register_jitable
def frictionless(state):
    return state[6][FRICTION] == 0.0


@register_jitable
def can_turn_state(state):
    return False


@register_jitable
def turn_state(state, angle_rad):
    return False


# The algorithm of fewear.contact.newton on these operations, compiled into the two solves below.
algorithm = specialised(sys.modules[__name__], register_jitable)
coupled_newton_on_state = algorithm.coupled_newton
solve_on_ray_on_state = algorithm.solve_on_ray


@compiled
def run_coupled_newton(G, g, U, centre, points, weights, constants, history, covered, settings,
                       load, direction, basis, max_iterations):
    """:func:`fewear.contact.newton.coupled_newton` on the state of these arrays, compiled
    (the arrays apart: :func:`fewear.contact.condensed_newton.run_load_steps`)."""
    return coupled_newton_on_state((G, g, U, centre, points, weights, constants, history,
                                    covered), NewtonSettings(*settings), load, direction, basis,
                                   max_iterations)


@compiled
def run_solve_on_ray(G, g, U, centre, points, weights, constants, history, covered, settings,
                     load, a, max_iterations):
    """:func:`fewear.contact.newton.solve_on_ray` on the state of these arrays, compiled."""
    return solve_on_ray_on_state((G, g, U, centre, points, weights, constants, history,
                                  covered), NewtonSettings(*settings), load, a, max_iterations)


def coupled_newton(state, settings, load, direction, basis, max_iterations) -> int:
    """:func:`run_coupled_newton` on ``state``; ``settings`` a :class:`NewtonSettings`."""
    return run_coupled_newton(*state, tuple(settings), load, direction,
                              np.ascontiguousarray(basis, dtype=float), max_iterations)


def solve_on_ray(state, settings, load, a, max_iterations) -> int:
    """:func:`run_solve_on_ray` on ``state``."""
    return run_solve_on_ray(*state, tuple(settings), np.asarray(load, dtype=float),
                            np.asarray(a, dtype=float), max_iterations)


# the flat's algorithm: its two solves compiled, the rest as Python on the operations
newton_algorithm = types.SimpleNamespace(**{**vars(algorithm), "coupled_newton": coupled_newton,
                                            "solve_on_ray": solve_on_ray})


def compile_flat() -> None:
    """Compile, or load from numba's cache (:mod:`fewear.jit`), the flat's two solves: each
    called once on a small top (33 nodes 6 um below a cylinder of radius 6 mm centred at the
    origin, as the flat's solver places them), pressed and then pulled sideways with friction,
    with the argument types of a solve, so that a scar run after the set-up loads them instead
    of compiling them (about 20 s) without a word."""
    from fewear.contact.newton_kernels import compile_shared_kernels

    settings = compile_shared_kernels()[-1]
    nodes = 33
    state = new_state(nodes)
    G, _, _, _, points, weights, constants, _, covered = state
    constants[RADIUS], constants[FRICTION], constants[STICK] = 6e-3, 0.1, 1e-9
    constants[PENALTY] = constants[TANGENTIAL] = 1e18
    points[:, 0] = np.linspace(-5e-4, 5e-4, nodes)
    points[:, 1] = -(constants[RADIUS] + 6e-6)
    weights[:], covered[:] = 1e-3 / (nodes - 1), 1.0
    G[:] = 1e-12 * np.eye(2 * nodes)
    down = np.array([0.0, -1.0])  # the cylinder's ray and the normal force's direction
    solve_on_ray(state, settings, 1e5 * down, down, 2)
    coupled_newton(state, settings, np.array([1e3, -1e5]), down, np.eye(2), 2)
