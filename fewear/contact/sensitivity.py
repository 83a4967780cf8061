"""How the nodal contact pressures of a solved load step change when the bore wears.

Wear recedes the bore node q by dh_q along its normal n_q, which opens its gap by dh_q. With the
load on the pin fixed (force control), the linearised penalty contact on the active set A gives
the change of the nodal normal forces df (N/m, f_q = w_q p_q) and of the pin centre dc:

    df = -D (dh + G_n df - N dc),      N^T df = 0,

D = diag(w_q k) (the penalty per node), G_n = [n_a . G_ab n_b] the normal part of the bore
compliance G of :mod:`fewear.contact.condensed`, N the (|A|, 2) matrix of the normals: the gap
g_q = |x_q + U_q - c| - R_p opens by dh_q, by the normal displacement n_q . dU_q = (G_n df)_q and
closes by the pin's motion n_q . dc, and the pin stays in balance. Solved for dh = the unit
vectors, it gives the sensitivity J = dp/dh = diag(1/w) df/dh (Pa/m, |A| x |A|): a node that
wears sheds load to its neighbours, which is what keeps wear from roughening the bore. Friction
is left out of the linearisation (it tilts the normals by at most atan(mu) in the force balance).

With K = D^-1 + G_n, symmetric positive definite (G is), the first equation is K df = N dc - dh;
the balance N^T df = 0 eliminates dc:

    df/dh = -P,   P = K^-1 - B (N^T B)^-1 B^T,   B = K^-1 N,

one inverse of |A| rows and a rank-2 correction, in place of a bordered system of |A| + 2 rows
solved for |A| right-hand sides (a run's sensitivities 1.4-1.7 times faster, the same J to
rounding).
"""

from __future__ import annotations

import math

import numpy as np

from fewear.contact.newton_kernels import pairwise_sum
from fewear.jit import compiled

EPSILON = float(np.finfo(float).eps)  # machine epsilon: NumPy's rcond=None is eps max(M, N)


@compiled
def compliance_blocks(G_xx: np.ndarray, G_xy: np.ndarray, G_yx: np.ndarray, G_yy: np.ndarray,
                      compliance: np.ndarray, node: int, active: np.ndarray) -> None:
    """The 2x2 blocks G_ab (m per N/m) of the bore node ``node`` (a) and the nodes ``active``
    (b) of the compliance G (2n, 2n), as four arrays over b: contiguous arrays for the
    vectorised loops over b (:func:`_normal_blocks`)."""
    row_x, row_y = 2 * node, 2 * node + 1
    for b in range(active.size):
        column = 2 * active[b]
        G_xx[b], G_xy[b] = compliance[row_x, column], compliance[row_x, column + 1]
        G_yx[b], G_yy[b] = compliance[row_y, column], compliance[row_y, column + 1]


@compiled
def _normal_blocks(out: np.ndarray, G_xx: np.ndarray, G_xy: np.ndarray, G_yx: np.ndarray,
                   G_yy: np.ndarray, m_x: np.ndarray, m_y: np.ndarray, n_x: float,
                   n_y: float) -> None:
    """out_b = n . G_ab m_b, summed as sum_ij n_i G_ij m_j in the order of (i, j): a loop over
    arrays passed in, which numba vectorises (the same loop over the caller's arrays it does
    not)."""
    for b in range(out.size):
        out[b] = ((((0.0 + n_x * G_xx[b] * m_x[b]) + n_x * G_xy[b] * m_y[b])
                   + n_y * G_yx[b] * m_x[b]) + n_y * G_yy[b] * m_y[b])


@compiled
def normal_compliance(compliance: np.ndarray, active: np.ndarray, normal_x: np.ndarray,
                      normal_y: np.ndarray) -> np.ndarray:
    """G_n = [n_a . G_ab n_b] (m per N/m, |A| x |A|) on the nodes ``active`` of the compliance
    G (2n, 2n) with their normals (``normal_x``, ``normal_y``)."""
    m = active.size
    G_n = np.empty((m, m))
    G_xx, G_xy, G_yx, G_yy = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    row = np.empty(m)
    for a in range(m):
        compliance_blocks(G_xx, G_xy, G_yx, G_yy, compliance, active[a], active)
        _normal_blocks(row, G_xx, G_xy, G_yx, G_yy, normal_x, normal_y, normal_x[a],
                       normal_y[a])
        G_n[a] = row
    return G_n


@compiled
def pressure_sensitivity(compliance: np.ndarray, weights_m: np.ndarray, points_m: np.ndarray,
                         pin_centre_m: np.ndarray, active: np.ndarray,
                         penalty_Pa_per_m: float) -> np.ndarray:
    """J = dp_A/dh_A (Pa/m) on the active nodes ``active`` (indices) of a solved load step.

    ``compliance``: G (2n, 2n), rows and columns (node, direction), m per N/m; ``weights_m`` (n,);
    ``points_m`` (n, 2) the bore nodes (their normal is taken from the pin centre, the nodal
    displacements being microns against a radius of millimetres). Compiled (numba): it runs for
    every load step with slip of every wear step.
    """
    m = active.size
    normal_x, normal_y = np.empty(m), np.empty(m)
    for a in range(m):
        d_x = points_m[active[a], 0] - pin_centre_m[0]
        d_y = points_m[active[a], 1] - pin_centre_m[1]
        length = math.sqrt(d_x * d_x + d_y * d_y)
        normal_x[a], normal_y[a] = d_x / length, d_y / length
    penalty = weights_m[active] * penalty_Pa_per_m
    if m < 3:
        return _few_nodes_sensitivity(compliance, weights_m, active, penalty, normal_x,
                                      normal_y)
    stiffness = normal_compliance(compliance, active, normal_x, normal_y)  # K = D^-1 + G_n
    for a in range(m):
        stiffness[a, a] += 1.0 / penalty[a]
    inverse = np.linalg.inv(stiffness)
    B_x, B_y = inverse @ normal_x, inverse @ normal_y  # B = K^-1 N
    C_xx, C_xy, C_yy = normal_x @ B_x, normal_x @ B_y, normal_y @ B_y  # N^T B (symmetric)
    determinant = C_xx * C_yy - C_xy * C_xy
    sensitivity = np.empty((m, m))
    for a in range(m):
        # row a of B (N^T B)^-1
        u_x = (B_x[a] * C_yy - B_y[a] * C_xy) / determinant
        u_y = (B_y[a] * C_xx - B_x[a] * C_xy) / determinant
        scale = -1.0 / weights_m[active[a]]
        for b in range(m):
            sensitivity[a, b] = scale * (inverse[a, b] - u_x * B_x[b] - u_y * B_y[b])
    return sensitivity


@compiled
def _few_nodes_sensitivity(compliance: np.ndarray, weights_m: np.ndarray, active: np.ndarray,
                           penalty: np.ndarray, normal_x: np.ndarray,
                           normal_y: np.ndarray) -> np.ndarray:
    """J with one or two nodes in contact: the pin's sliding mode is free (N^T K^-1 N is
    singular), so the bordered system of the module docstring is solved by least squares,
    whose minimum-norm solution keeps the pin still."""
    m = active.size
    mean_penalty = pairwise_sum(penalty) / m  # the constraint rows scaled like the others
    system = np.zeros((m + 2, m + 2))
    rhs = np.zeros((m + 2, m))
    G_n = normal_compliance(compliance, active, normal_x, normal_y)
    for a in range(m):
        for b in range(m):
            system[a, b] = (1.0 if a == b else 0.0) + penalty[a] * G_n[a, b]
        system[a, m], system[a, m + 1] = -penalty[a] * normal_x[a], -penalty[a] * normal_y[a]
        system[m, a] = normal_x[a] * mean_penalty
        system[m + 1, a] = normal_y[a] * mean_penalty
        rhs[a, a] = -penalty[a]
    force_change = np.linalg.lstsq(system, rhs, rcond=(m + 2) * EPSILON)[0][:m]
    return force_change / weights_m[active].reshape(-1, 1)


@compiled
def summed_sensitivity(compliance: np.ndarray, weights_m: np.ndarray, points_m: np.ndarray,
                       penalty_Pa_per_m: float, node_order: np.ndarray, pressure_Pa: np.ndarray,
                       slip_m: np.ndarray, k_m2_N: np.ndarray,
                       pin_centre_m: np.ndarray) -> np.ndarray:
    """sum_s k_s s_s dp_s/dh (m/m per cycle's steps, (n, n)) over the load steps s of
    ``pressure_Pa``, ``slip_m``, ``k_m2_N`` (steps, n) and ``pin_centre_m`` (steps, 2) that
    slide in contact: row a, column b the change of node a's Archard depth with node b's wear,
    J (:func:`pressure_sensitivity`) on each step's active nodes. The step arrays' nodes are the
    bore nodes ``node_order`` of ``compliance``, ``weights_m`` and ``points_m``. One call for
    all the steps of a block (the per-step NumPy indexing cost more than J)."""
    n = pressure_Pa.shape[1]
    total = np.zeros((n, n))
    for s in range(pressure_Pa.shape[0]):
        if not (np.any(slip_m[s] > 0.0) and np.any(pressure_Pa[s] > 0.0)):
            continue
        active = np.flatnonzero(pressure_Pa[s] > 0.0)
        J = pressure_sensitivity(compliance, weights_m, points_m, pin_centre_m[s],
                                 node_order[active], penalty_Pa_per_m)
        for a in range(active.size):
            scale = k_m2_N[s, active[a]] * slip_m[s, active[a]]
            for b in range(active.size):
                total[active[a], active[b]] += scale * J[a, b]
    return total
