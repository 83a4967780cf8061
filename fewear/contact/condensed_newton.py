"""The condensed path's arithmetic on the bore nodes, compiled (numba, :mod:`fewear.jit`): the
nodal forces and their linearisation, the bordered Newton step of
:mod:`fewear.contact.condensed` (whose module docstring gives the equations), and the path's
:class:`fewear.contact.newton.NewtonOperations` on its state, with the whole solve of
:mod:`fewear.contact.newton` compiled on them for a run of load steps (:func:`run_load_steps`).

The state (:func:`new_state`) is a tuple of arrays: the bore compliance G (2n, 2n), the nodal
forces g (2n,), the nodal displacements U = G g (2n,), the pin centre c (2,), the bore nodes
X (n, 2), their weights w (n,), and the constants (k, R_p, mu s) with mu s the signed friction
coefficient of the present solve. The operations update it in place, so the class that owns it
(:class:`fewear.contact.condensed.CondensedBushingContact`) sees every step. This module does
not import DOLFINx.
"""

from __future__ import annotations

import math
import sys

import numpy as np
from numba.extending import register_jitable

from fewear.contact.newton import new_memory, specialised
from fewear.contact.newton_kernels import (
    FREE_PIN,
    LineData,
    NewtonSettings,
    compile_shared_kernels,
    contact_direction,
    gaps,
    pairwise_sum,
)
from fewear.contact.sensitivity import (
    compliance_blocks,
    pressure_sensitivity,
    summed_sensitivity,
)
from fewear.jit import compiled

# The state is turned with the load only where the bore nodes that carry the turned forces lie
# where the turned nodes did to this fraction of the last solution's penetration or largest
# displacement (whichever is larger: an error of the start the Newton corrects in a few steps).
TURN_TOLERANCE = 0.1


@compiled
def nodal_forces(points: np.ndarray, U: np.ndarray, centre: np.ndarray, pin_radius: float,
                 penalty: float, friction_value: float, weights_m: np.ndarray):
    """Nodal forces f = w p (n + mu s t) (n, 2), pressures p = k <R_p - r>_+ (n,), normals
    n = d / r (n, 2) and distances r = |d| (n,) of the bore nodes X (``points``) with nodal
    displacements U and the pin centre c, d = X + U - c, t = (-n_y, n_x)."""
    size = points.shape[0]
    f, p = np.empty((size, 2)), np.empty(size)
    normal, r = np.empty((size, 2)), np.empty(size)
    for q in range(size):
        d_x = points[q, 0] + U[q, 0] - centre[0]
        d_y = points[q, 1] + U[q, 1] - centre[1]
        r[q] = math.sqrt(d_x * d_x + d_y * d_y)  # the C library's hypot: twice the time
        normal[q, 0], normal[q, 1] = d_x / r[q], d_y / r[q]
        p[q] = penalty * max(pin_radius - r[q], 0.0)
        wp = weights_m[q] * p[q]
        f[q, 0] = wp * (normal[q, 0] + friction_value * -normal[q, 1])
        f[q, 1] = wp * (normal[q, 1] + friction_value * normal[q, 0])
    return f, p, normal, r


@compiled
def equilibrium_fields(points: np.ndarray, U: np.ndarray, centre: np.ndarray, pin_radius: float,
                       penalty: float, friction_value: float, weights_m: np.ndarray,
                       slip_m: float, order: np.ndarray, limit_m: float):
    """What a solved load step reports, in one pass over the bore nodes: the nodal fields
    (5, n) x, y (m), pressure p = k <-g>_+ (Pa), gap g = |X + U - c| - R_p (m) and slip
    (``slip_m`` where p > 0, else 0), node i of them the node ``order[i]`` of the state; the
    sums of the nodal forces f and of their pressure part w p n (:func:`nodal_forces`, N/m);
    the largest |U_q| (m) where it may reach ``limit_m``, else 0 (the components' largest
    bounds it by a factor sqrt 2: the C library's hypot, the dearest part, is then spared).
    Each value is the one of the NumPy formulas of :func:`fewear.contact.solver.nodal_result`
    to the bit: the sums over the nodes in turn (as NumPy's sum over an array's first axis),
    p = 0 (not -0) where g = 0 (as ``np.maximum``)."""
    f, p, normal, r = nodal_forces(points, U, centre, pin_radius, penalty, friction_value,
                                   weights_m)
    size = points.shape[0]
    force_sum, normal_sum = np.zeros(2), np.zeros(2)
    component = 0.0
    for q in range(size):
        wp = weights_m[q] * p[q]
        for i in range(2):
            force_sum[i] += f[q, i]
            normal_sum[i] += wp * normal[q, i]
            component = max(component, abs(U[q, i]))
            if math.isnan(U[q, i]):
                component = math.inf  # then the largest |U_q| is NaN, as NumPy's
    largest = 0.0
    if not 1.5 * component < limit_m:
        largest = -math.inf
        for q in range(size):
            largest = max(largest, math.hypot(U[q, 0], U[q, 1]))
    fields = np.empty((5, size))
    for i in range(size):
        q = order[i]
        gap = r[q] - pin_radius
        penetration = -gap
        if not (penetration > 0.0 or math.isnan(penetration)):
            penetration = 0.0
        fields[0, i], fields[1, i] = points[q, 0], points[q, 1]
        fields[2, i] = penalty * penetration
        fields[3, i] = gap
        fields[4, i] = slip_m if fields[2, i] > 0.0 else 0.0
    return fields, force_sum, normal_sum, largest


@compiled
def penetrations(points: np.ndarray, U: np.ndarray, centre: np.ndarray,
                 pin_radius: float) -> np.ndarray:
    """<R_p - |X + U - c|>_+ at the bore nodes (m): the negative part of the deformed bore's
    :func:`fewear.contact.newton.gaps`."""
    return np.maximum(-gaps(points + U, centre, pin_radius), 0.0)


@compiled
def turned_forces(g: np.ndarray, points: np.ndarray, U: np.ndarray, centre: np.ndarray,
                  pin_radius: float, nodes_turned: int, angle: float, tolerance: float):
    """The nodal forces g (2n,) moved ``nodes_turned`` nodes along the angle-sorted bore nodes
    (``points``, (n, 2)) and turned by ``angle`` (rad), and whether the bore is invariant on
    the nodes that carry them: each lies within ``tolerance`` times the larger of the state's
    penetration and largest displacement (U (n, 2), pin at ``centre``) of where the node its
    force came from lands when turned."""
    n = points.shape[0]
    cosine, sine = math.cos(angle), math.sin(angle)
    turned = np.zeros_like(g)
    mismatch = 0.0
    for q in range(n):
        source = (q - nodes_turned) % n
        g_x, g_y = g[2 * source], g[2 * source + 1]
        if g_x == 0.0 and g_y == 0.0:
            continue
        turned[2 * q] = cosine * g_x - sine * g_y
        turned[2 * q + 1] = sine * g_x + cosine * g_y
        landed_x = cosine * points[source, 0] - sine * points[source, 1]
        landed_y = sine * points[source, 0] + cosine * points[source, 1]
        mismatch = max(mismatch, math.hypot(landed_x - points[q, 0], landed_y - points[q, 1]))
    scale = max(penetrations(points, U, centre, pin_radius).max(), np.abs(U).max())
    return mismatch <= tolerance * scale, turned


@compiled
def linearised_forces(points: np.ndarray, U: np.ndarray, centre: np.ndarray, pin_radius: float,
                      penalty: float, friction_value: float, weights_m: np.ndarray,
                      load: np.ndarray):
    """The nodal forces f, normals n and distances r (:func:`nodal_forces`), the active nodes A
    (p > 0), the pin residual sum f - F/L (N/m) and the active length sum_A w (m)."""
    f, p, normal, r = nodal_forces(points, U, centre, pin_radius, penalty, friction_value,
                                   weights_m)
    active = np.flatnonzero(p > 0.0)
    residual = np.zeros(2)
    for q in range(f.shape[0]):
        residual[0] += f[q, 0]
        residual[1] += f[q, 1]
    return f, normal, r, active, residual - load, pairwise_sum(weights_m[active])


@compiled
def _projected_blocks(out: np.ndarray, G_xx: np.ndarray, G_xy: np.ndarray, G_yx: np.ndarray,
                      G_yy: np.ndarray, d_x: np.ndarray, d_y: np.ndarray, n_x: float, n_y: float,
                      stiffness: float) -> None:
    """out_b = s n . (G_b d_b) for the 2x2 blocks G_b = [[G_xx, G_xy], [G_yx, G_yy]]_b and the
    directions d_b: a loop over arrays passed in, which numba vectorises (the same loop over
    arrays of the caller's is not)."""
    for b in range(out.size):
        out[b] = stiffness * (n_x * (G_xx[b] * d_x[b] + G_xy[b] * d_y[b])
                              + n_y * (G_yx[b] * d_x[b] + G_yy[b] * d_y[b]))


@compiled
def _subtract_scaled(total: np.ndarray, scale: float, values: np.ndarray) -> None:
    """total -= values * scale, elementwise (vectorised: see :func:`_projected_blocks`)."""
    for i in range(total.size):
        total[i] = total[i] - values[i] * scale


@compiled
def _add_scaled(total: np.ndarray, scale: float, values: np.ndarray) -> None:
    """total += scale * values, elementwise (vectorised: see :func:`_projected_blocks`)."""
    for i in range(total.size):
        total[i] = total[i] + scale * values[i]


@compiled
def _add_scaled_rows(total: np.ndarray, s0: float, g0: np.ndarray, s1: float, g1: np.ndarray,
                     s2: float, g2: np.ndarray, s3: float, g3: np.ndarray) -> None:
    """total += s0 g0 + s1 g1 + s2 g2 + s3 g3, added one after the other to each entry (the
    sums of four passes of ``total += s g``, in one pass; vectorised)."""
    for j in range(total.size):
        total[j] = (((total[j] + s0 * g0[j]) + s1 * g1[j]) + s2 * g2[j]) + s3 * g3[j]


@compiled
def support_product(dg: np.ndarray, compliance: np.ndarray) -> np.ndarray:
    """G dg from the rows of G on the support of dg (G symmetric): the sum of dg_r G_r over the
    rows r with dg_r != 0 in increasing r, each entry summed in that order; four rows per pass
    over the result (a pass per row reads and writes the result as often as the rows)."""
    rows = np.flatnonzero(dg)
    total = np.zeros(dg.size)
    first = 0
    while first + 4 <= rows.size:
        r0, r1, r2, r3 = rows[first], rows[first + 1], rows[first + 2], rows[first + 3]
        _add_scaled_rows(total, dg[r0], compliance[r0], dg[r1], compliance[r1], dg[r2],
                         compliance[r2], dg[r3], compliance[r3])
        first += 4
    for row in rows[first:]:
        _add_scaled(total, dg[row], compliance[row])
    return total


@compiled
def newton_step(compliance: np.ndarray, g: np.ndarray, U: np.ndarray, f: np.ndarray,
                normal: np.ndarray, distance: np.ndarray, active: np.ndarray,
                weights_m: np.ndarray, penalty: float, friction_value: float, basis: np.ndarray,
                load: np.ndarray):
    """One Newton step (:mod:`fewear.contact.condensed`'s docstring) on the active nodes A with
    the pin update dc = basis dz, on one unknown lambda_a per node.

    The Jacobian block of the nodal force, w dT/dd = -s e n^T + h v t^T (s = w k, h = w p / r,
    e = n + mu s t the traction's direction, v = t - mu s n; the second term is the turn of the
    normal as the node slides along the pin), linearises the new force as
    g'_a = lambda_a e_a + h_a v_a t_a . (dU_a - dc). Its sliding term is 1e-7 of the penalty
    term (p / (k r), the penetration over the pin radius) and matters only for the pin's soft
    sliding mode, so it is kept for dc alone: g'_a = lambda_a e_a - h_a v_a (t_a . dc), and

        lambda_a + s_a n_a . (sum_b G_ab g'_b - U_a - dc) = f_a . n_a,
        basis^T sum_a g'_a = basis^T F/L,

    a system of |A| + k unknowns in place of the 2|A| + k of the full blocks, whose dense solve
    is the step's dearest part. It converges to the same solution (at a linear rate where the
    full step converges quadratically: a few more, far cheaper steps). Returns the updates
    dg = g' - g of the nodal forces (g' zero off A), dU = G dg (:func:`support_product`) and
    dc."""
    m, k = active.size, basis.shape[1]
    traction_x, traction_y = np.empty(m), np.empty(m)
    sliding_x, sliding_y = np.empty(m), np.empty(m)
    slide = np.empty((k, m))  # h_a t_a . basis_c
    for a in range(m):
        q = active[a]
        n_x, n_y = normal[q, 0], normal[q, 1]
        traction_x[a], traction_y[a] = n_x - friction_value * n_y, n_y + friction_value * n_x
        sliding_x[a], sliding_y[a] = -n_y - friction_value * n_x, n_x - friction_value * n_y
        h = (f[q, 0] * n_x + f[q, 1] * n_y) / distance[q]
        for c in range(k):
            slide[c, a] = h * (-n_y * basis[0, c] + n_x * basis[1, c])
    system = np.zeros((m + k, m + k))
    rhs = np.empty(m + k)
    coupling = np.empty(m)  # s_a n_a . G_ab e_b of row a
    turned = np.empty((m, m))  # [b, a]: s_a n_a . G_ab v_b
    turned_row = np.empty(m)
    G_xx, G_xy, G_yx, G_yy = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    for a in range(m):
        q = active[a]
        n_x, n_y = normal[q, 0], normal[q, 1]
        stiffness = weights_m[q] * penalty
        compliance_blocks(G_xx, G_xy, G_yx, G_yy, compliance, q, active)
        _projected_blocks(coupling, G_xx, G_xy, G_yx, G_yy, traction_x, traction_y, n_x, n_y,
                          stiffness)
        _projected_blocks(turned_row, G_xx, G_xy, G_yx, G_yy, sliding_x, sliding_y, n_x, n_y,
                          stiffness)
        for b in range(m):
            system[a, b] = (1.0 if a == b else 0.0) + coupling[b]
            turned[b, a] = turned_row[b]
        rhs[a] = f[q, 0] * n_x + f[q, 1] * n_y + stiffness * (n_x * U[q, 0] + n_y * U[q, 1])
    border = np.empty(m)  # - sum_b s_a n_a . G_ab v_b slide_bc, summed over b in turn
    for c in range(k):
        border[:] = 0.0
        for b in range(m):
            _subtract_scaled(border, slide[c, b], turned[b])
        for a in range(m):
            q = active[a]
            stiffness = weights_m[q] * penalty
            system[a, m + c] = border[a] - stiffness * (normal[q, 0] * basis[0, c]
                                                        + normal[q, 1] * basis[1, c])
            system[m + c, a] = traction_x[a] * basis[0, c] + traction_y[a] * basis[1, c]
            for d in range(k):
                system[m + c, m + d] -= (sliding_x[a] * basis[0, c]
                                         + sliding_y[a] * basis[1, c]) * slide[d, a]
    for c in range(k):
        rhs[m + c] = basis[0, c] * load[0] + basis[1, c] * load[1]
    solution = np.linalg.solve(system, rhs)
    dg = -g
    for a in range(m):
        turn = 0.0
        for c in range(k):
            turn += slide[c, a] * solution[m + c]
        dg[2 * active[a]] += solution[a] * traction_x[a] - turn * sliding_x[a]
        dg[2 * active[a] + 1] += solution[a] * traction_y[a] - turn * sliding_y[a]
    dU = support_product(dg, compliance)
    dc = np.zeros(2)
    for c in range(k):
        dc += basis[:, c] * solution[m + c]
    return dg, dU, dc


def new_state(compliance: np.ndarray, points: np.ndarray, weights_m: np.ndarray,
              penalty: float, pin_radius: float) -> tuple:
    """The state of module docstring for G, X and w (m) with no displacement, the pin centred
    and no friction; arrays C-contiguous (the kernels' signatures)."""
    size = 2 * points.shape[0]
    return (np.ascontiguousarray(compliance, dtype=float), np.zeros(size), np.zeros(size),
            np.zeros(2), np.ascontiguousarray(points, dtype=float),
            np.ascontiguousarray(weights_m, dtype=float), np.array([penalty, pin_radius, 0.0]))


# -- the operations of the contact Newton (fewear.contact.newton.NewtonOperations) ---------------
# register_jitable: NumPy code when ContactNewton calls them from Python (numba would type the
# state tuple at every call, slowly: see run_load_steps), compiled into the solve.
@register_jitable
def linearise(state, load):
    """Nodal forces, normals and distances at the state (``linear``: f, n, r, A); the pin
    residual sum f - F/L (N/m) and the active length (m)."""
    compliance, g, U, centre, points, weights, constants = state
    f, normal, distance, active, residual, length = linearised_forces(
        points, U.reshape(-1, 2), centre, constants[1], constants[0], constants[2], weights, load)
    return residual, length, (f, normal, distance, active)


@register_jitable
def newton_direction(state, linear, pin_residual, load, basis):
    """One Newton step (:func:`newton_step`): the update (dg, dU = G dg) of the nodal forces and
    displacements, and dc. Only the rows of G on the old and new support are used."""
    compliance, g, U, centre, points, weights, constants = state
    f, normal, distance, active = linear
    dg, dU, dc = newton_step(compliance, g, U.reshape(-1, 2), f, normal, distance, active,
                             weights, constants[0], constants[2], basis, load)
    return (dg, dU), dc


@register_jitable
def begin_line_search(state, linear, update, dc, pin_residual):
    """Slope of Pi along (dg, dU, dc): (g - f) . dU + (sum f - F/L) . dc (J/m); the elastic
    energy 1/2 g.G g along the line, 1/2 g.U + s g.dU + s^2/2 dg.dU (G symmetric); the base
    (g, U) of the line search."""
    compliance, g, U, centre, points, weights, constants = state
    dg, dU = update
    slope = np.dot(g - linear[0].reshape(-1), dU) + np.dot(pin_residual, dc)
    elastic = np.array([0.5 * np.dot(g, U), np.dot(g, dU), 0.5 * np.dot(dg, dU)])
    distance = linear[2]  # |X + U - c| at this state
    line = LineData(slope, points, U.reshape(-1, 2), dU.reshape(-1, 2), elastic,
                    distance - constants[1])
    return line, (g.copy(), U.copy())


@register_jitable
def try_step(state, base, update, step, pin_centre):
    g, U, centre = state[1], state[2], state[3]
    g0, U0 = base
    dg, dU = update
    for i in range(g.size):
        g[i] = g0[i] + step * dg[i]
        U[i] = U0[i] + step * dU[i]
    centre[:] = pin_centre


@register_jitable
def update_sizes(state, update):
    return np.abs(update[1]).max(), np.abs(state[2]).max()


@register_jitable
def zero_displacement(state):
    state[1][:] = 0.0
    state[2][:] = 0.0


@register_jitable
def deformed_points(state):
    return state[4] + state[2].reshape(-1, 2)


@register_jitable
def node_weights(state):
    return state[5]


@register_jitable
def pin_position(state):
    return state[3].copy()


@register_jitable
def place_pin(state, centre):
    state[3][:] = centre


@register_jitable
def frictionless(state):
    return state[6][2] == 0.0


@register_jitable
def can_turn_state(state):
    return True


@register_jitable
def turn_state(state, angle_rad):
    """Turn nodal forces and pin centre by the whole number of bore elements (2 nodes each, at
    uniform angles, sorted by angle) nearest to ``angle_rad``, U = G g; on the circular O-grid,
    whose compliance is invariant under such turns, the turned state is the turned solution. On
    a worn bore it is not: the nodes carrying the turned forces sit elsewhere than the turned
    nodes did, by as much as the wear depth changes over the turn, and the turned pin can stand
    deep in a pocket's flank (hundreds of nodes in contact, a start the Newton does not recover
    from). So the state is turned only where the bore is invariant on the nodes that carry the
    turned forces, to ``TURN_TOLERANCE`` times the penetration or the largest displacement of
    the last solution; else it is left as it is and False returned."""
    compliance, g, U, centre, points, weights, constants = state
    elements_around = points.shape[0] // 2
    element_rad = 2.0 * math.pi / elements_around
    elements = round(angle_rad / element_rad)
    if elements % elements_around == 0:
        return True
    angle = elements * element_rad
    invariant, turned = turned_forces(g, points, U.reshape(-1, 2), centre, constants[1],
                                      2 * elements, angle, TURN_TOLERANCE)
    if not invariant:
        return False
    g[:] = turned
    support = np.flatnonzero(turned)  # the nodes in contact
    U[:] = np.dot(turned[support], compliance[support])  # G symmetric: its rows, contiguous
    rotation = np.array([[math.cos(angle), -math.sin(angle)],
                         [math.sin(angle), math.cos(angle)]])
    centre[:] = np.dot(rotation, centre.copy())
    return True


# The algorithm of fewear.contact.newton on these operations, each function compiled into its
# callers (register_jitable); Python's when called from Python.
algorithm = specialised(sys.modules[__name__], register_jitable)
newton_solve_on_state = algorithm.newton_solve


@compiled
def run_load_steps(compliance, g, U, centre, points, weights, constants, memory, settings,
                   forces_N, width_m, friction_values, slips_m, order, limit_m, max_iterations,
                   first, fields, centres, sums, iterations):
    """The load steps ``first``, ``first`` + 1, ... of ``forces_N`` (steps, 2) in turn
    (:meth:`fewear.contact.condensed.CondensedBushingContact.solve_run`), with the step's
    signed friction coefficient ``friction_values`` and slip ``slips_m`` (m), in one compiled
    call (the Python around a solve cost a fifth of its time; the state's arrays apart: numba
    0.56 types a tuple of more than four arrays, or a named tuple, in Python at every call, its
    type cache keying them on more bytes than it keeps: 20-60 us, as much as a Newton
    iteration): a zero force resets the state
    (no displacement, the pin centred, the next solve cold); else the whole solve of
    :mod:`fewear.contact.newton` for F/L (L = ``width_m``) and :func:`equilibrium_fields`.
    Step s writes ``fields[s]`` (5, n), ``centres[s]`` (2,), ``sums[s]`` (the sums of the
    nodal forces and of their pressure part, (2, 2), N/m) and ``iterations[s]``. Stops at the
    first step whose solve fails (its count, negative, in ``iterations``) or whose largest
    displacement reaches ``limit_m``, with the state reset as after a refused step, and returns
    (that step, its largest displacement (m; 0 for a failed solve)); (steps, 0) when all are
    solved."""
    state = (compliance, g, U, centre, points, weights, constants)
    newton_settings = NewtonSettings(*settings)
    for s in range(first, forces_N.shape[0]):
        force = forces_N[s]
        constants[2] = friction_values[s]
        count = 0
        if force[0] == 0.0 and force[1] == 0.0:
            _reset(state, memory)
        else:
            count = newton_solve_on_state(state, memory, newton_settings, force / width_m,
                                          contact_direction(force, friction_values[s]),
                                          max_iterations)
            if count < 0:
                iterations[s] = count
                _reset(state, memory)
                return s, 0.0
        nodal, force_sum, normal_sum, largest = equilibrium_fields(
            points, U.reshape(-1, 2), centre, constants[1], constants[0], constants[2], weights,
            slips_m[s], order, limit_m)
        fields[s], sums[s, 0], sums[s, 1] = nodal, force_sum, normal_sum
        if not largest < limit_m:
            _reset(state, memory)
            return s, largest
        centres[s] = centre
        iterations[s] = count
    return forces_N.shape[0], 0.0


@register_jitable
def _reset(state, memory):
    """No displacement, the pin centred, the next solve cold (``ContactNewton.reset``)."""
    zero_displacement(state)
    place_pin(state, np.zeros(2))
    memory[0], memory[1] = math.nan, math.nan


def compile_contact() -> None:
    """Compile, or load from numba's cache (:mod:`fewear.jit`), the contact Newton's kernels:
    each called once on a small bore (16 nodes on a circle, the pin pressed into two) with the
    argument types of a solve, so that worker processes started afterwards load them instead
    of each compiling them (tests/contact/test_newton.py checks that a solve adds no
    signature); and :func:`fewear.contact.sensitivity.pressure_sensitivity` and
    :func:`~fewear.contact.sensitivity.summed_sensitivity`."""
    points, weights, pin_radius, penalty, load, centre, settings = compile_shared_kernels()
    size = points.shape[0]
    U, g = np.zeros((size, 2)), np.zeros(2 * size)
    f, normal, distance, active, _, _ = linearised_forces(points, U, centre, pin_radius,
                                                          penalty, 0.1, weights, load)
    newton_step(np.eye(2 * size), g, U, f, normal, distance, active, weights, penalty, 0.1,
                FREE_PIN, load)
    nodal_forces(points, U, centre, pin_radius, penalty, 0.0, weights)
    equilibrium_fields(points, U, centre, pin_radius, penalty, 0.0, weights, 0.0,
                       np.arange(size), 1.0)
    turned_forces(g, points, U, centre, pin_radius, 2, 0.1, 0.1)
    state = new_state(np.eye(2 * size), points, weights, penalty, pin_radius)
    steps = np.array([[0.0, 0.0], load])
    run_load_steps(*state, new_memory(), tuple(settings), steps, 1.0, np.zeros(2), np.zeros(2),
                   np.arange(size), 1.0, 2, 0, np.empty((2, 5, size)), np.empty((2, 2)),
                   np.empty((2, 2, 2)), np.empty(2, dtype=np.int64))
    pressure_sensitivity(np.eye(2 * size), weights, points, centre, np.arange(3), penalty)
    steps = np.ones((2, size))
    summed_sensitivity(np.eye(2 * size), weights, points, penalty, np.arange(size), steps, steps,
                       steps, np.zeros((2, 2)))
