"""The contact Newton's compiled kernels on the bore nodes (numba, :mod:`fewear.jit`), shared by
the discretisations (:mod:`fewear.contact.newton` holds the algorithm that calls them).

The corners and vertices of the region of pin centres free of contact (:func:`free_corner`,
:func:`support_vertex`, :func:`wedge_press`), the starts on them (:func:`corner_centre`,
:func:`ray_centre`), gaps, the pin's update rules (:func:`pin_update`, :func:`slide_limit`), the
stopping test and step cap (:func:`converged`, :func:`step_cap`) and the whole line search
(:func:`line_search`: it needs of a discretisation only the bore nodes' displacements and
updates and the elastic energy along the line, :class:`LineData`, since the displacement at the
nodes is linear in the step).

The kernels repeat NumPy's order of operations (:func:`pairwise_sum`; 2-vectors' lengths as
sqrt(v . v)): the penalty forces amplify a rounding difference of the pin centre by ~1e5, to
1e-10 of the pressures and at times one iteration more or less. They use the C library's
trigonometric functions, as Python's ``math`` does; NumPy's vectorised ones (``np.arctan2``,
``np.arccos``) differ from those in the last bit on CPUs where NumPy dispatches to its SIMD
versions (AVX-512).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from fewear.jit import compiled

# Relative force residual of the pin at which Newton may stop (see converged): about twice the
# rounding level of the penalty forces at the paper's loads (residuals 2e-10 to 4e-9 of |F/L|
# one step after the updates have become small), so that a state one step past a small update
# is accepted without a further step that only confirms it.
FORCE_TOLERANCE = 1e-8

# Force residuals within this many times the rounding level of the penalty forces are noise.
ROUNDING_FACTOR = 0.5

# A corner closer than R_p (1 - this) to a node other than its two lies beyond the bore.
CORNER_TOLERANCE = 1e-9

# A vertex whose two normals are closer to parallel than this sine is pressed in along d.
WEDGE_MIN_SINE = 0.05

# Nodes within R_p (1 + this) of the pin centre touch it in the vertex walk (support_vertex).
VERTEX_TOLERANCE = 1e-11
# ... which passes over the nodes whose circle misses the arc to the nearest intersection found
# by more than this angle (rad): above the rounding of the intersections' angles (acos loses
# up to sqrt(eps) ~ 1.5e-8 rad for circles that just touch) and of the pin's distance to its
# node (VERTEX_TOLERANCE).
ARC_MARGIN_RAD = 1e-6

# Line search: smallest step tried, Armijo constant, and how far below the first
# contact-keeping step the Armijo backtracking may go.
SMALLEST_STEP = 2.0**-10
ARMIJO = 1e-4
BACKTRACK_RANGE = 2.0**-6
ENERGY_ROUNDING = 1024.0 * np.finfo(float).eps


class NewtonSettings(NamedTuple):
    """The constants of the coupled Newton for one problem: ``tolerance`` ([contact]
    newton_tolerance), ``rounding_m`` = eps R_p (the level at which gaps are computed), the
    penalty stiffness k (Pa/m), R_p, R_b and the bore element size h (m), and the angle between
    neighbouring bore nodes (rad); for another contact surface than the bore, its
    :class:`fewear.contact.params.ContactSurface` in place of the last three."""

    tolerance: float
    rounding_m: float
    penalty: float
    pin_radius_m: float
    bore_radius_m: float
    element_size_m: float
    node_spacing_rad: float


@compiled
def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


@compiled
def contact_direction(force: np.ndarray, friction_value: float) -> np.ndarray:
    """Expected direction of the contact arc's centre: F turned by -atan(mu s), since the
    traction p (n + mu s t) of a narrow arc around n has the direction of n turned by
    atan(mu s)."""
    return unit(math.atan2(force[1], force[0]) - math.atan(friction_value))


@compiled
def norm(vector: np.ndarray) -> float:
    """The Euclidean length sqrt(v . v) of a short vector: ``np.linalg.norm`` without its
    overhead (and so, unlike ``math.hypot``, to the same bits)."""
    return math.sqrt(np.dot(vector, vector))


@compiled
def projected(basis: np.ndarray, vector: np.ndarray) -> np.ndarray:
    """basis^T v for a basis (2, k) of the pin's moves and a 2-vector v."""
    result = np.empty(basis.shape[1])
    for column in range(basis.shape[1]):
        result[column] = basis[0, column] * vector[0] + basis[1, column] * vector[1]
    return result


@compiled
def _block_sum(values: np.ndarray, start: int, size: int) -> float:
    """NumPy's sum of a block of at most 128 values: sequential below 8, else 8 partial sums
    over blocks of 8, added pairwise, then the rest sequentially."""
    if size < 8:
        result = 0.0
        for i in range(start, start + size):
            result += values[i]
        return result
    partial = values[start:start + 8].copy()
    tail = size - size % 8
    for block in range(start + 8, start + tail, 8):
        for j in range(8):
            partial[j] += values[block + j]
    result = (((partial[0] + partial[1]) + (partial[2] + partial[3]))
              + ((partial[4] + partial[5]) + (partial[6] + partial[7])))
    for i in range(start + tail, start + size):
        result += values[i]
    return result


@compiled
def _halving_sum(values: np.ndarray, begin: int, count: int) -> float:
    """NumPy's pairwise sum of ``values[begin:begin + count]``: blocks of at most 128 values
    (:func:`_block_sum`), larger ones split at the multiple of 8 nearest below half and the
    halves' sums added; the halving walked with a stack (numba's cache does not load recursive
    functions reliably)."""
    if count <= 128:
        return _block_sum(values, begin, count)
    starts, sizes = np.full(64, begin), np.full(64, count)
    split = np.zeros(64, np.bool_)
    sums = np.empty(64)
    top, done = 0, 0
    while top >= 0:
        start, size = starts[top], sizes[top]
        if size <= 128:
            sums[done] = _block_sum(values, start, size)
            done += 1
            top -= 1
        elif split[top]:  # both halves summed: left, right
            sums[done - 2] += sums[done - 1]
            done -= 1
            top -= 1
        else:
            split[top] = True
            half = size // 2 - (size // 2) % 8
            starts[top + 1], sizes[top + 1], split[top + 1] = start + half, size - half, False
            starts[top + 2], sizes[top + 2], split[top + 2] = start, half, False
            top += 2
    return sums[0]


@compiled
def pairwise_sum(values: np.ndarray) -> float:
    """The sum of the contiguous array ``values`` in NumPy's order (``np.add.reduce``: the
    pairwise sums (:func:`_halving_sum`) of buffers of 8192 values, added in turn), so that the
    compiled kernels give the NumPy formulas' results to the bit: the contact's penalty forces
    amplify a rounding difference of the pin centre by ~1e5, so sums in another order would
    change the iterates at 1e-10 and, at times, the number of iterations."""
    total = 0.0
    for begin in range(0, values.size, 8192):
        total += _halving_sum(values, begin, min(8192, values.size - begin))
    return total


@compiled
def load_penetration(load_size: float, penalty: float, weight_m: float) -> float:
    """The penetration (m) at which nodes of total weight w carry the load |F/L| (N/m) with the
    penalty stiffness k (Pa/m): |F/L| / (k w)."""
    return load_size / (penalty * weight_m)


@compiled
def gaps(points: np.ndarray, centre: np.ndarray, pin_radius: float) -> np.ndarray:
    """Gaps |X_q - c| - R_p of the (deformed) bore nodes X (n, 2) to the pin (m), negative in
    contact."""
    result = np.empty(points.shape[0])
    for q in range(points.shape[0]):
        d_x, d_y = points[q, 0] - centre[0], points[q, 1] - centre[1]
        result[q] = math.sqrt(d_x * d_x + d_y * d_y) - pin_radius  # as nodal_forces
    return result



@compiled
def first_touch_centre(points: np.ndarray, centre: np.ndarray, direction: np.ndarray,
                       pin_radius: float) -> np.ndarray:
    """Move the pin from ``centre`` along ``direction`` until its circle first meets ``points``.

    For a point q (relative to the centre) outside the circle, |q - s d| = R_p at
    s = q.d - sqrt((q.d)^2 - |q|^2 + R_p^2); the smallest such s over the points is the touch.
    """
    nearest = np.inf
    for i in range(points.shape[0]):
        qx, qy = points[i, 0] - centre[0], points[i, 1] - centre[1]
        qd = qx * direction[0] + qy * direction[1]
        disc = qd**2 - (qx * qx + qy * qy) + pin_radius**2
        if disc >= 0.0 and 0.0 <= qd - math.sqrt(disc) < nearest:
            nearest = qd - math.sqrt(disc)
    return centre + (nearest if nearest < np.inf else 0.0) * direction


@compiled
def support_vertex(points: np.ndarray, direction: np.ndarray,
                   pin_radius: float) -> tuple[np.ndarray, tuple[int, int]]:
    """The pin centre furthest along ``direction`` d in the contact-free region of a bore that
    need not be convex (a worn bore with pockets), and two nodes it touches.

    The free region {c : |X_q - c| >= R_p for all q} (the component of the bushing centre) is
    bounded by arcs of the circles of radius R_p about the nodes, each concave toward the
    region, so c . d is largest at a vertex, the intersection of two circles (not necessarily
    of neighbouring nodes: a pin bridging a pocket rests on its rims). Walk: from the first
    touch along d (:func:`first_touch_centre`), slide along the circle of a touched node, in the
    sense that increases c . d and leads away from the other touched nodes (the one that
    increases it most), up to the first other circle it meets; repeat until no touched node
    offers such a sense. c . d grows at every vertex, so the walk ends, at the vertex sought.
    The arc from c by the angle s about the node lies within R_p s of c, so a circle about a
    node X_q with ||X_q - c| - R_p| > R_p s meets it nowhere: once an intersection at angle s
    is found, such nodes are passed over (with ``ARC_MARGIN_RAD`` for the rounding of the
    angles), their angles spared; the nearest nodes, looked at first, bound s soonest.
    """
    centre = first_touch_centre(points, np.zeros(2), direction, pin_radius)
    for _ in range(points.shape[0]):
        distance = gaps(points, centre, 0.0)
        touching = np.flatnonzero(distance <= pin_radius * (1.0 + VERTEX_TOLERANCE))
        node, sense = _steepest_slide(points, centre, touching, direction, pin_radius)
        if node < 0:
            nearest = touching[np.argsort(distance[touching])]
            return centre, (nearest[0], nearest[min(1, nearest.size - 1)])
        # the intersections of this node's circle with the others', as angles about the node
        α = math.atan2(centre[1] - points[node, 1], centre[0] - points[node, 0])
        step = np.inf
        n = points.shape[0]
        for order in range(n):  # the nodes from this one outward along the bore
            q = (node + (order + 1) // 2 * (1 if order % 2 else -1)) % n
            if abs(distance[q] - pin_radius) > pin_radius * (step + ARC_MARGIN_RAD):
                continue  # its circle misses the arc to the nearest intersection so far
            chord_x, chord_y = points[q, 0] - points[node, 0], points[q, 1] - points[node, 1]
            chord = math.hypot(chord_x, chord_y)
            if 0.0 < chord < 2.0 * pin_radius:
                base = math.atan2(chord_y, chord_x)
                half_angle = math.acos(chord / (2.0 * pin_radius))
                for sign in (1.0, -1.0):
                    travel = (sense * (base + sign * half_angle - α)) % (2.0 * math.pi)
                    if VERTEX_TOLERANCE <= travel < step:
                        step = travel
        if step == np.inf:
            break
        centre = points[node] + pin_radius * unit(α + sense * step)
    raise ValueError("no vertex of the contact-free region found along the direction")


@compiled
def _steepest_slide(points: np.ndarray, centre: np.ndarray, touching: np.ndarray,
                    direction: np.ndarray, pin_radius: float) -> tuple[int, float]:
    """The touched node q and sense s (+-1) of the slide along q's circle, tangent
    s (-r_y, r_x) with r = (c - X_q) / R_p, that increases c . d most and leads away from every
    touched node; (-1, 0) if none does (:func:`support_vertex`)."""
    best, node, sense = 0.0, -1, 0.0
    for q in touching:
        radial_x = (centre[0] - points[q, 0]) / pin_radius
        radial_y = (centre[1] - points[q, 1]) / pin_radius
        for s in (1.0, -1.0):
            tangent_x, tangent_y = -s * radial_y, s * radial_x
            rate = tangent_x * direction[0] + tangent_y * direction[1]
            if rate <= best:
                continue
            away = True
            for t in touching:
                if ((centre[0] - points[t, 0]) * tangent_x + (centre[1] - points[t, 1])
                        * tangent_y < -VERTEX_TOLERANCE * pin_radius):
                    away = False
                    break
            if away:
                best, node, sense = rate, q, s
    return node, sense


@compiled
def pin_update(centre: np.ndarray, dc: np.ndarray, node_spacing_rad: float) -> np.ndarray:
    """The pin centre after the Newton update dc.

    A move along the bore by more than one node spacing is applied as a turn about the bushing
    centre: c' = (|c| + dc.e_r) e_r turned by (dc.e_t)/|c|. The pin then slides around the bore
    (at constant depth in a conformal contact) instead of along a tangent, which would change
    its radial position by (dc.e_t)^2 / (2|c|), far more than the penetrations. A smaller move
    keeps the pin on the same nodes, whose gaps |X_q - c| - R_p curve only with 1/R_p: it is
    applied as it is, c' = c + dc (the turn would add the radial error (dc.e_t)^2 / (2|c|),
    R_p/|c| times more than the linearised gaps leave out, and lose a light contact). On a
    straight surface (``node_spacing_rad`` = inf, the flat) every move is applied as it is.
    """
    radius = math.sqrt(centre[0] * centre[0] + centre[1] * centre[1])
    if radius == 0.0:
        return centre + dc
    radial = centre / radius
    tangential = radial[0] * dc[1] - radial[1] * dc[0]
    if abs(tangential) <= radius * node_spacing_rad:
        return centre + dc
    return (radius + (radial[0] * dc[0] + radial[1] * dc[1])) * unit(
        math.atan2(radial[1], radial[0]) + tangential / radius)


@compiled
def slide_limit(centre: np.ndarray, dc: np.ndarray, element_size_m: float,
                bore_radius_m: float) -> float:
    """Step factor that lets the pin move along the surface by at most one element per step:
    turn by h / R_b about the bushing centre on a bore of radius R_b, slide by h along a
    straight surface (R_b = inf, the flat: :meth:`fewear.contact.params.FlatContactProblem.
    contact_surface`)."""
    radius = math.sqrt(centre[0] * centre[0] + centre[1] * centre[1])
    if radius == 0.0:
        return 1.0
    tangential = abs(centre[0] * dc[1] - centre[1] * dc[0]) / radius
    limit = element_size_m if math.isinf(bore_radius_m) else radius * element_size_m / bore_radius_m
    return min(1.0, limit / tangential) if tangential > 0.0 else 1.0


@compiled
def free_corner(points: np.ndarray, direction: np.ndarray,
                pin_radius: float) -> tuple[np.ndarray, tuple[int, int], bool]:
    """The corner of the contact-free region of the pin centre furthest along ``direction`` d,
    the two nodes it touches, and whether the bore is non-convex there.

    On a convex bore the region is the polygon of the corners c_j of neighbouring nodes j, j+1
    (X = ``points``, the pin centre at R_p from both): with the chord's midpoint m_j, half
    length h_j and outward normal o_j, c_j = m_j - sqrt(R_p^2 - h_j^2) o_j; the corner is the
    c_j furthest along d. Should it lie closer than R_p (1 - ``CORNER_TOLERANCE``) to another
    node (a non-convex, worn bore), it is the vertex of the free region furthest along d
    (:func:`support_vertex`) and its two nodes instead, and the flag is True.
    """
    n = points.shape[0]
    best, corner, pair = -np.inf, np.zeros(2), (-1, -1)
    for j in range(n):
        ahead = (j + 1) % n
        middle_x = 0.5 * (points[j, 0] + points[ahead, 0])
        middle_y = 0.5 * (points[j, 1] + points[ahead, 1])
        chord_x, chord_y = points[ahead, 0] - points[j, 0], points[ahead, 1] - points[j, 1]
        half = 0.5 * math.hypot(chord_x, chord_y)
        outward_x, outward_y = chord_y / (2.0 * half), -chord_x / (2.0 * half)
        side = np.sign(outward_x * middle_x + outward_y * middle_y)
        depth = math.sqrt(pin_radius**2 - half**2)
        corner_x = middle_x - depth * (side * outward_x)
        corner_y = middle_y - depth * (side * outward_y)
        along = corner_x * direction[0] + corner_y * direction[1]
        if along > best:
            best, pair = along, (j, ahead)
            corner = np.array([corner_x, corner_y])
    if gaps(points, corner, 0.0).min() < pin_radius * (1.0 - CORNER_TOLERANCE):
        vertex, nodes = support_vertex(points, direction, pin_radius)
        return vertex, nodes, True
    return corner, pair, False


@compiled
def wedge_press(points: np.ndarray, corner: np.ndarray, pair: tuple[int, int],
                direction: np.ndarray, load_size: float, penalty: float,
                weights_m: np.ndarray) -> tuple[bool, np.ndarray]:
    """The pin's move (m) from a vertex ``corner`` of the free region into its two nodes
    ``pair`` (at ``points``) that makes them carry the load |F/L| (N/m) together:
    |F/L| d = a_1 n_1 + a_2 n_2 with a_q >= 0 on their normals n_q, penetrations
    delta_q = a_q / (k w_q), and the move dc with n_q . dc = delta_q. (False, 0) where the
    normals are closer to parallel than ``WEDGE_MIN_SINE`` or d is not between them."""
    normals = np.empty((2, 2))
    weights = np.empty(2)
    for row in range(2):
        chord_x = points[pair[row], 0] - corner[0]
        chord_y = points[pair[row], 1] - corner[1]
        length = math.hypot(chord_x, chord_y)
        normals[row, 0], normals[row, 1] = chord_x / length, chord_y / length
        weights[row] = weights_m[pair[row]]
    if abs(normals[0, 0] * normals[1, 1] - normals[0, 1] * normals[1, 0]) < WEDGE_MIN_SINE:
        return False, np.zeros(2)
    shares = np.linalg.solve(normals.T.copy(), load_size * direction)
    if shares[0] < 0.0 or shares[1] < 0.0:
        return False, np.zeros(2)
    return True, np.linalg.solve(normals, shares / (penalty * weights))


@compiled
def entering_limit(gaps0: np.ndarray, gaps: np.ndarray, step: float, weights_m: np.ndarray,
                   load_size: float, penalty: float) -> float:
    """The step at which the first node that enters contact between step 0 (gaps ``gaps0``) and
    ``step`` (``gaps``) reaches the penetration at which it would carry the load |F/L| alone
    (:func:`load_penetration`), with the gaps linear in the step; ``step`` if no node enters."""
    limit, entering = np.inf, False
    for q in range(gaps.size):
        if gaps0[q] >= 0.0 and gaps[q] < 0.0:
            entering = True
            closing_rate = (gaps0[q] - gaps[q]) / step
            needed = load_penetration(load_size, penalty, weights_m[q])
            limit = min(limit, (gaps0[q] + needed) / closing_rate)
    return limit if entering else step


@compiled
def contact_normals(points: np.ndarray, centre: np.ndarray,
                    gaps: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nodes in contact (gap < 0), their positions ``points`` (m) and unit normals
    (X_q - c) / |X_q - c|."""
    contact = np.flatnonzero(gaps < 0.0)
    at = np.empty((contact.size, 2))
    normals = np.empty((contact.size, 2))
    for a, q in enumerate(contact):
        at[a] = points[q]
        distance = math.hypot(points[q, 0] - centre[0], points[q, 1] - centre[1])
        normals[a, 0] = (points[q, 0] - centre[0]) / distance
        normals[a, 1] = (points[q, 1] - centre[1]) / distance
    return contact, at, normals


@compiled
def following_centre(points: np.ndarray, centre: np.ndarray, contact: np.ndarray,
                     base_points: np.ndarray, normals: np.ndarray, base_gaps: np.ndarray,
                     base_centre: np.ndarray, pin_radius: float) -> np.ndarray:
    """The pin centre c corrected to second order: the nodes ``contact`` in contact at the base
    of the line search (positions ``base_points``, normals n_q, gaps, pin at ``base_centre``)
    are now at X_q (``points``) and move off the pin by more than their linearised gaps
    g_q + n_q . (dX_q - dc) predict (gaps curve with 1/R_p); the pin follows them by the mean
    of that excess |X_q - c| - R_p - (g_q + n_q . (dX_q - dc)) along their mean normal."""
    excess = np.empty(contact.size)
    normal_x, normal_y = 0.0, 0.0
    for a, q in enumerate(contact):
        moved = (normals[a, 0] * (points[q, 0] - base_points[a, 0] - (centre[0] - base_centre[0]))
                 + normals[a, 1] * (points[q, 1] - base_points[a, 1]
                                    - (centre[1] - base_centre[1])))
        excess[a] = math.hypot(points[q, 0] - centre[0], points[q, 1] - centre[1]) - pin_radius - (
            base_gaps[a] + moved)
        normal_x += normals[a, 0]
        normal_y += normals[a, 1]
    mean = pairwise_sum(excess) / contact.size
    length = math.sqrt(normal_x * normal_x + normal_y * normal_y)
    return np.array([centre[0] + mean * normal_x / length, centre[1] + mean * normal_y / length])


def compile_shared_kernels():
    """Call each kernel of this module that :class:`ContactNewton` calls once, on a small bore
    (16 nodes on a circle of radius 1 m, the pin of radius 0.9 m pressed into two of them),
    so that numba compiles it or loads it from the cache; return the bore for the
    discretisation's kernels (:func:`fewear.contact.condensed_newton.compile_contact`): points,
    weights, pin radius, penalty stiffness, load, the pressed pin's centre and the Newton's
    settings."""
    angles = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
    points = np.column_stack([np.cos(angles), np.sin(angles)])
    weights, pin_radius, penalty = np.full(16, 0.4), 0.9, 1e3
    direction = unit(-0.5 * math.pi)
    load = 10.0 * direction
    norm(load)
    contact_direction(load, 0.1)
    corner, pair, _ = free_corner(points, direction, pin_radius)
    wedge_press(points, corner, pair, direction, 10.0, penalty, weights)
    centre = first_touch_centre(points, np.zeros(2), direction, pin_radius) + 0.01 * direction
    base_gaps = gaps(points, centre, pin_radius)
    contact, at, normals = contact_normals(points, centre, base_gaps)
    dc = 0.001 * unit(0.0)
    trial = pin_update(centre, dc, 0.2)
    slide_limit(centre, dc, 0.4, 1.0)
    entering_limit(base_gaps, gaps(points, trial, pin_radius), 1.0, weights, 10.0, penalty)
    following_centre(points, trial, contact, at, normals, base_gaps[contact], centre,
                     pin_radius)
    line_search(points, np.zeros((16, 2)), np.zeros((16, 2)), base_gaps, centre, dc, weights,
                load, 10.0, penalty, pin_radius, 0.2, 0.4, 1.0, 1.0, -1.0, True, np.zeros(3))
    load_penetration(10.0, penalty, weights[pair[0]] + weights[pair[1]])
    corner_centre(points, weights, direction, 10.0, penalty, pin_radius)
    ray_centre(points, centre, weights, direction, 10.0, penalty, pin_radius)
    projected(FREE_PIN, load)
    control = new_control()
    step_cap(control, 0.8)
    settings = NewtonSettings(1e-10, 1e-16, penalty, pin_radius, 1.0, 0.4, 0.2)
    converged(control, settings, 0.0, 0.0, 0.01, 0.0, 1.0, 10.0, 0.8)
    return points, weights, pin_radius, penalty, load, centre, settings


# The stopping test and the step cap against active-set cycling (compiled; their memory, the
# ``control`` array of :func:`new_control`: the step cap, the last force residual, the active
# lengths of the last two iterations and the number of iterations counted).
#
# Converged when the last Newton update of the pin centre is below ``newton_tolerance`` times
# the largest penetration or 64 rounding units of R_p (the level at which gaps are computed),
# the largest displacement update below 1000 ``newton_tolerance`` times the largest
# displacement (the LU solves of the penalty-stiffened system are not more accurate) or the
# same rounding level, and the pin is in force balance at the present state: its force
# residual below ``FORCE_TOLERANCE`` |F/L|, or, stagnating (not halved by the last step),
# below ``ROUNDING_FACTOR`` times the rounding level of the penalty forces on the active nodes,
# k eps R_p sum_A w_q (a gap |X + u - c| - R_p is computed to about eps R_p; at light loads
# on fine meshes this is the larger bound), or the last pin update was at 8 rounding units
# (the residual is the noise of the LU solves of the penalty-stiffened full system).
# Semi-smooth Newton can alternate between two active sets around a node that is just entering
# contact; when the active set (measured by its length) returns to the one of two iterations
# before, the step cap is halved, which turns the alternation into a converging bisection; it
# is lifted again as soon as the active set stays the same (full Newton steps converge then).


@compiled
def new_control() -> np.ndarray:
    """The memory of :func:`step_cap` and :func:`converged` for a new iteration."""
    return np.array([1.0, math.inf, math.nan, math.nan, 0.0])


@compiled
def step_cap(control: np.ndarray, active: float) -> float:
    """The cap on the next step for the active length ``active`` (m): halved when the active set
    returns to the one of two iterations before, lifted when it stays the same."""
    before, last, count = control[2], control[3], control[4]
    if count >= 2.0 and active == before and before != last:
        control[0] *= 0.5
    elif count >= 1.0 and active == last:
        control[0] = 1.0
    control[2], control[3], control[4] = last, active, count + 1.0
    return control[0]


@compiled
def converged(control: np.ndarray, settings: NewtonSettings, pin_update: float,
              displacement_update: float, penetration: float, displacement: float,
              force_residual: float, load: float, active_length: float) -> bool:
    """The stopping test: the last step's updates, the present penetration and displacement
    (m); the pin's force residual |R - F/L| at the present state and |F/L| (N/m); the active
    length (m)."""
    floor = 64.0 * settings.rounding_m
    small = (pin_update <= max(settings.tolerance * penetration, floor)
             and displacement_update <= max(1e3 * settings.tolerance * displacement, floor))
    rounding = ROUNDING_FACTOR * settings.penalty * settings.rounding_m * active_length
    stagnating = 2.0 * force_residual >= control[1]
    control[1] = force_residual
    return small and (force_residual <= FORCE_TOLERANCE * load
                      or (stagnating and force_residual <= rounding)
                      or pin_update <= floor / 8.0)


@compiled
def corner_centre(points: np.ndarray, weights_m: np.ndarray, direction: np.ndarray,
                  load_size: float, penalty: float, pin_radius: float) -> np.ndarray:
    """The light-load solution for the bore nodes at ``points`` (deformed): the pin rests on the
    two neighbouring bore nodes j, j+1 whose corner c_j (the pin centre touching both, at R_p
    from each) lies furthest along ``direction`` d (on a convex bore the contact-free region of
    the pin centre is the polygon of these corners), pressed in along d by the penetration
    |F/L| / (k (w_j + w_j+1)) that two nodes of weight w need to carry the load. Should c_j lie
    closer than R_p to another node (a non-convex, worn bore), the vertex of the free region
    furthest along d (:func:`support_vertex`) and its two nodes instead (:func:`free_corner`),
    pressed into both where their normals are far apart (:func:`wedge_press`: a pin bridging a
    pocket rests on rims whose normals are far apart, a wedge; pressed along d alone, it would
    leave one rim and start on the other alone, whence the Newton slides it along that rim, a
    single contact on a convex rim being no stable equilibrium, instead of into the wedge)."""
    corner, pair, vertex = free_corner(points, direction, pin_radius)
    if vertex:
        pressed, press = wedge_press(points, corner, pair, direction, load_size, penalty,
                                     weights_m)
        if pressed:
            return corner + press
    weight = weights_m[pair[0]] + weights_m[pair[1]]
    return corner + load_penetration(load_size, penalty, weight) * direction


@compiled
def ray_centre(points: np.ndarray, centre: np.ndarray, weights_m: np.ndarray, a: np.ndarray,
               load_size: float, penalty: float, pin_radius: float) -> np.ndarray:
    """The pin on the ray c = e a, as deep in the bore (nodes at ``points``, deformed) as it is
    now at ``centre`` or at least as deep as two nodes need to carry the load: first touch along
    a plus that penetration, so that it is in contact."""
    penetration = max(-gaps(points, centre, pin_radius).min(),
                      load_penetration(load_size, penalty, 2.0 * weights_m.max()))
    return first_touch_centre(points, np.zeros(2), a, pin_radius) + penetration * a


FREE_PIN = np.eye(2)  # the basis of the pin's moves when it is free (not held on a ray)


class LineData(NamedTuple):
    """What :func:`line_search` needs of a discretisation at the start of a line search along
    (displacement update, dc): the slope dPi/dstep at step 0 (J/m); the bore nodes' reference
    positions X, displacements U and displacement updates dU (n, 2), m (the trial step s puts
    the nodes at X + (U + s dU)); the elastic energy along the line as the coefficients
    (e0, e1, e2) of e0 + e1 s + e2 s^2 (J/m); and the nodes' gaps at step 0 (n,), m
    (:func:`gaps` of X + U: the condensed path has them from its linearisation)."""

    slope: float
    points: np.ndarray
    displacement: np.ndarray
    update: np.ndarray
    elastic: np.ndarray
    gaps: np.ndarray


@compiled
def _trial(step, points, displacement, update, centre0, dc, contact, base_points, normals,
           base_gaps, pin_radius, node_spacing_rad):
    """The pin centre and the nodes' gaps at the trial ``step``: the pin by :func:`pin_update`
    plus the second-order correction of :func:`following_centre` (the nodes in contact at the
    base move off the pin by more than their linearised gaps predict: gaps curve with 1/R_p,
    which at light loads is more than the penetrations)."""
    centre = pin_update(centre0, step * dc, node_spacing_rad)
    deformed = np.empty_like(points)
    for q in range(points.shape[0]):
        for i in range(2):
            deformed[q, i] = points[q, i] + (displacement[q, i] + step * update[q, i])
    if contact.size:
        centre = following_centre(deformed, centre, contact, base_points, normals, base_gaps,
                                  centre0, pin_radius)
    return centre, gaps(deformed, centre, pin_radius)


@compiled
def _line_energy(step, elastic, trial_gaps, centre, weights_m, load, penalty):
    """Pi = e(step) + sum_q w_q k/2 <-gap_q>^2 - F/L . c (J/m) at a trial state."""
    penetration = np.maximum(-trial_gaps, 0.0)
    return (elastic[0] + step * (elastic[1] + step * elastic[2])
            + 0.5 * penalty * np.dot(weights_m, penetration**2)
            - (load[0] * centre[0] + load[1] * centre[1]))


@compiled
def line_search(points, displacement, update, gaps0, centre0, dc, weights_m, load, load_size,
                penalty, pin_radius, node_spacing_rad, element_size_m, bore_radius_m, cap, slope,
                descent, elastic):
    """The step length along a Newton direction, on the bore nodes (:class:`LineData`; ``gaps0``
    its gaps at step 0): the step, the pin centre there and the nodes' gaps there.

    Starts from the smaller of ``cap``, :func:`slide_limit` and the step at which the first
    node entering contact could carry the load alone (:func:`entering_limit`). Then halves the
    step while the trial loses all contact, and, for a ``descent`` direction, backtracks
    (Armijo, at most ``BACKTRACK_RANGE`` below the first contact-keeping step) on the penalty
    potential (:func:`_line_energy`); else the first contact-keeping step is taken. Should every
    trial lose contact, a step below the smallest tried."""
    base = points + displacement
    contact, base_points, normals = contact_normals(base, centre0, gaps0)
    base_gaps = gaps0[contact]
    energy0 = _line_energy(0.0, elastic, gaps0, centre0, weights_m, load, penalty) if descent \
        else math.nan
    step = min(cap, slide_limit(centre0, dc, element_size_m, bore_radius_m))
    keeps_contact = -1.0
    while step >= SMALLEST_STEP:
        centre, trial_gaps = _trial(step, points, displacement, update, centre0, dc, contact,
                                    base_points, normals, base_gaps, pin_radius,
                                    node_spacing_rad)
        limit = entering_limit(gaps0, trial_gaps, step, weights_m, load_size, penalty)
        if step > limit:
            step = limit
            centre, trial_gaps = _trial(step, points, displacement, update, centre0, dc, contact,
                                        base_points, normals, base_gaps, pin_radius,
                                        node_spacing_rad)
        if trial_gaps.min() >= 0.0:
            step *= 0.5
            continue
        if keeps_contact < 0.0:
            keeps_contact = step
            if not descent:
                return step, centre, trial_gaps
        if step < keeps_contact * BACKTRACK_RANGE:
            break
        if _line_energy(step, elastic, trial_gaps, centre, weights_m, load,
                        penalty) <= energy0 + ARMIJO * step * slope:
            return step, centre, trial_gaps
        step *= 0.5
    if keeps_contact < 0.0:
        keeps_contact = step
    centre, trial_gaps = _trial(keeps_contact, points, displacement, update, centre0, dc,
                                contact, base_points, normals, base_gaps, pin_radius,
                                node_spacing_rad)
    return keeps_contact, centre, trial_gaps
