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
"""

from __future__ import annotations

import numpy as np


def pressure_sensitivity(compliance: np.ndarray, weights_m: np.ndarray, points_m: np.ndarray,
                         pin_centre_m: np.ndarray, active: np.ndarray,
                         penalty_Pa_per_m: float) -> np.ndarray:
    """J = dp_A/dh_A (Pa/m) on the active nodes ``active`` (indices) of a solved load step.

    ``compliance``: G (2n, 2n), rows and columns (node, direction), m per N/m; ``weights_m`` (n,);
    ``points_m`` (n, 2) the bore nodes (their normal is taken from the pin centre, the nodal
    displacements being microns against a radius of millimetres).
    """
    m = active.size
    normal = points_m[active] - pin_centre_m
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    rows = (2 * active[:, None] + np.arange(2)[None, :]).reshape(-1)
    G = compliance[np.ix_(rows, rows)].reshape(m, 2, m, 2)
    normal_compliance = np.einsum("ai,aibj,bj->ab", normal, G, normal)
    penalty = weights_m[active] * penalty_Pa_per_m
    system = np.zeros((m + 2, m + 2))
    system[:m, :m] = np.eye(m) + penalty[:, None] * normal_compliance
    system[:m, m:] = -penalty[:, None] * normal
    system[m:, :m] = normal.T * penalty.mean()  # scaled like the rows above (N^T df = 0)
    rhs = np.zeros((m + 2, m))
    rhs[:m] = -np.diag(penalty)
    # with one or two nodes in contact the pin's sliding mode is free (the system is singular):
    # least squares, whose minimum-norm solution keeps it still; else an LU solve (the SVD of
    # least squares cost 3 times as much over a run)
    if m >= 3:
        force_change = np.linalg.solve(system, rhs)[:m]
    else:
        force_change = np.linalg.lstsq(system, rhs, rcond=None)[0][:m]
    return force_change / weights_m[active][:, None]
