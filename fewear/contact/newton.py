"""The contact Newton: one algorithm for both discretisations of the pin-in-bushing problem.

The unknowns are the bore displacement (the DOLFINx field u in :mod:`fewear.contact.solver`, the
nodal forces g with U = G g in :mod:`fewear.contact.condensed`) and the pin centre c (m, per unit
thickness); the equations are the elastic equilibrium of the bushing under the penalty tractions
and the pin's force balance sum_q f_q = F / L. Each discretisation provides the linear algebra
as its operations (:class:`NewtonOperations`, on its state; :class:`ContactDiscretisation`);
this module holds the algorithm:

- **Start.** The *corner start* for the first solve: on a convex (circular) bore the region of
  pin centres free of contact with the bore nodes is a polygon whose corners c_j touch two
  neighbouring nodes; a light load presses the pin into the corner furthest along the contact
  direction, which is taken with no displacement and the penetration |F/L| / (k (w_j + w_j+1))
  of two nodes carrying the load. On a worn bore with pockets that corner can lie beyond other
  nodes (the bottom of a pocket narrower than the pin's curvature: the pin rests on its flanks);
  then the vertex of the free region furthest along the direction is found by a walk along its
  boundary (:func:`support_vertex`; two nodes, not necessarily neighbours). Where these two
  nodes' normals are far apart (the pin bridging a pocket rests on both rims: a wedge), the pin
  is pressed in so that both carry the load together (the load split onto the two normals);
  pressed along the direction alone it would leave one rim, and the Newton would slide it along
  the other (a single contact on a convex rim is no stable equilibrium) instead of into the
  wedge: on a bore worn 1 mm deep it did not settle within the iterations allowed.
  Afterwards the *warm start*: the last solution, turned with the load by whole bore elements
  where the discretisation can turn its state (the condensed path on a bore invariant under the
  turn, i.e. not worn; pin and indentation together), with the pin moved to the corner of the
  turned bore at a light load (the last solution had at most ``LIGHT_CONTACT_NODES`` nodes in
  contact and the load grew by at most ``LIGHT_LOAD_GROWTH``). Where it cannot (the full path,
  a worn bore), the last solution as it is if the load is not light and the direction turned by
  at most ``WARM_START_MAX_ANGLE_RAD``, else the corner start.
- **Step.** Semi-smooth (active-set) Newton: the active set is the set of bore nodes in contact
  at the current iterate; each step solves the bordered system of that active set for the
  displacement update and the pin update dc.
- **Step rules.** The pin moves by :func:`pin_update` (a move along the bore by more than one
  node spacing as a turn about the bushing centre, a smaller one straight) plus a second-order
  correction that keeps the nodes in contact as deep as the linearisation predicts (gaps curve
  with 1/R_p); by at most one bore element per step (:func:`slide_limit`) and not past the
  step at which the next node entering contact could carry the load alone (the pin's sliding
  mode is soft against the active set); a step never loses all contact; without friction, Armijo
  backtracking on the penalty potential, which with friction is no potential of the equations;
  a step cap that halves when the active set alternates (:func:`step_cap`).
- **Stopping test** (:func:`converged`), on the state returned: last updates at the Newton
  tolerance or rounding level, and the pin in force balance to ``FORCE_TOLERANCE`` or, at light
  loads, to the rounding level of the penalty forces.
- **Retry and contact-angle fallback.** Should the coupled iteration not settle within
  ``COUPLED_ITERATIONS`` (or alternate persistently) from the last solution that a
  discretisation able to turn its state left as it is (a worn bore), it starts once more from
  the corner start (the untouched last solution can send the pin sliding along a pocket's
  flank, held by one node; from the corner it converges in a handful of iterations; on the full
  path and from a turned state the retry does not pay: measured on the crank cycle). Should
  that not settle either, :func:`solve_by_contact_angle` takes over:
  the pin angle becomes an outer unknown found by bracketing, each inner problem (pin on a fixed
  ray) being a well-posed Newton problem. On a deeply worn bore the pin's angle can lie 60
  degrees and more from the load's (the pin at the end of a pocket); the bracketing stays on
  rays along which the load presses the pin into the bore. It starts on the ray where the last
  fallback since the bore last moved left the pin: at a pocket's end the pin stays put over
  several load steps while the load turns, and the tangential residual is steep there, so the
  search from the load's ray walks tens of degrees (a late block of the default rigid run: 28 %
  fewer Newton iterations).

At light loads the discrete problem can have more than one stable equilibrium (the pin resting
in either corner next to a node whose normal is nearly along the load). Both discretisations
start in the corner furthest along the contact direction; only where two corners tie to within
the bore displacement could they settle in different ones (not seen in the tests and benchmark).

A load the Newton cannot balance raises :class:`ContactNotConverged`.

The coupled Newton iteration (:func:`coupled_newton`: linearise, step, line search, stopping
test, step cap) is written once, in the subset of Python that numba compiles, on a
discretisation's *operations* (:class:`NewtonOperations`: functions of the discretisation's state,
bound into the algorithm by :func:`specialised`). The condensed path compiles it (its state is a
tuple of arrays, its operations compiled kernels: a whole solve runs without the interpreter, which
had cost 80-110 us per iteration beside 30-40 us of arithmetic); the full path runs the same code
as Python on its DOLFINx linear algebra. The rest (start, retry, fallback) stays in Python around
it. The kernels on the bore nodes are compiled (numba, :mod:`fewear.jit`) for both
discretisations: the corners and vertices of the free region (:func:`free_corner`,
:func:`support_vertex`, :func:`wedge_press`), gaps, and the whole line search
(:func:`line_search`: it needs of a discretisation only the bore nodes' displacements and
updates and the elastic energy along the line, :class:`LineData`, since the displacement at the
nodes is linear in the step). The kernels
repeat NumPy's order of operations (:func:`pairwise_sum`; 2-vectors' lengths as sqrt(v . v)):
the penalty forces amplify a rounding difference of the pin centre by ~1e5, to 1e-10 of the
pressures and at times one iteration more or less. They use the C library's trigonometric
functions, as Python's ``math`` does; NumPy's vectorised ones (``np.arctan2``, ``np.arccos``)
differ from those in the last bit on CPUs where NumPy dispatches to its SIMD versions (AVX-512).
"""

from __future__ import annotations

import math
import types
from typing import Any, NamedTuple, Protocol

import numpy as np

from fewear.jit import compiled

# Newton starts from the previous solution when the force turned by less than this (rad).
WARM_START_MAX_ANGLE_RAD = math.radians(20.0)

# Relative force residual of the pin at which Newton may stop (see converged).
FORCE_TOLERANCE = 1e-10

# Force residuals within this many times the rounding level of the penalty forces are noise.
ROUNDING_FACTOR = 0.5

# Iterations of the coupled Newton on (u, c) before the fallback on the pin angle takes over.
# A conformal contact in a worn pocket started from a corner (two nodes) grows its active set by
# a few nodes per step (the entering limit of the line search) and settles in 12-18 steps at
# 60-80 nodes; with 12 such solves went to the fallback, 30 times dearer (a default rigid run:
# 3.9 % of the solves, 66 % of the contact Newton's time).
COUPLED_ITERATIONS = 20
# ... or as soon as its step cap against active-set alternation has fallen below this.
CYCLE_CAP = 0.2

# The fallback on the pin angle keeps the pin's ray this far from perpendicular to the load
# (beyond, the load pulls the pin off the bore: no equilibrium on the ray), and stops on a
# bracket of the angle this narrow (rad).
RAY_MARGIN_RAD = math.radians(1.0)
ANGLE_TOLERANCE_RAD = 1e-12

# A corner closer than R_p (1 - this) to a node other than its two lies beyond the bore.
CORNER_TOLERANCE = 1e-9

# A vertex whose two normals are closer to parallel than this sine is pressed in along d.
WEDGE_MIN_SINE = 0.05

# Nodes within R_p (1 + this) of the pin centre touch it in the vertex walk (support_vertex).
VERTEX_TOLERANCE = 1e-11

# At most this many nodes in contact is a light load: the next solve starts at a corner.
LIGHT_CONTACT_NODES = 3
# ... unless the load grows by more than this factor.
LIGHT_LOAD_GROWTH = 1.5

# Line search: smallest step tried, Armijo constant, and how far below the first
# contact-keeping step the Armijo backtracking may go.
SMALLEST_STEP = 2.0**-10
ARMIJO = 1e-4
BACKTRACK_RANGE = 2.0**-6
ENERGY_ROUNDING = 1024.0 * np.finfo(float).eps


class ContactNotConverged(RuntimeError):
    """The contact Newton found no equilibrium for the load (N/m, per unit thickness)."""

    def __init__(self, load: np.ndarray, reason: str):
        self.load = np.array(load, dtype=float)
        super().__init__(f"contact Newton {reason} (load {self.load} N/m)")


class NewtonOperations(Protocol):
    """What a discretisation provides to the Newton: functions of its ``state`` (the displacement
    and the pin centre c (2,), m; whatever else its linear algebra needs). The condensed path's are
    functions of a tuple of arrays (:mod:`fewear.contact.condensed_newton`; compiled into the
    coupled Newton, NumPy when called from Python), the full path's the methods of
    :class:`fewear.contact.solver.BushingContactSolver`, called on the solver.
    ``linear`` is what ``linearise`` returns for the step (None where the discretisation keeps
    it), ``base`` what ``begin_line_search`` returns for ``try_step``."""

    def linearise(self, state, load: np.ndarray) -> tuple[np.ndarray, float, Any]:
        """Evaluate the contact at the current state; return the pin residual R - F/L (N/m), the
        active length (m, the sum of the weights of the nodes in contact) and ``linear``."""

    def newton_direction(self, state, linear, pin_residual: np.ndarray, load: np.ndarray,
                         basis: np.ndarray) -> tuple[Any, np.ndarray]:
        """The Newton update (displacement part, dc) of the linearisation ``linear``, with the pin
        update dc = basis z restricted to the span of ``basis`` (2, k)."""

    def begin_line_search(self, state, linear, update: Any, dc: np.ndarray,
                          pin_residual: np.ndarray) -> tuple[LineData, Any]:
        """What :func:`line_search` needs (:class:`LineData`) along (update, dc), and the
        current state as the ``base`` of the line search."""

    def try_step(self, state, base, update: Any, step: float, pin_centre: np.ndarray) -> None:
        """Set the state to base + step * update, with the pin at ``pin_centre``."""

    def update_sizes(self, state, update: Any) -> tuple[float, float]:
        """Largest displacement update and largest displacement (m), max norms."""

    def zero_displacement(self, state) -> None:
        """Set the displacement to zero."""

    def deformed_points(self, state) -> np.ndarray:
        """The bore nodes' current positions X + U (n, 2), m."""

    def node_weights(self, state) -> np.ndarray:
        """The Gauss-Lobatto weights w_q (n,) of the bore nodes (m), angle-sorted."""

    def pin_position(self, state) -> np.ndarray:
        """The pin centre c (2,), m."""

    def place_pin(self, state, centre: np.ndarray) -> None:
        """Put the pin centre at ``centre``."""

    def frictionless(self, state) -> bool:
        """Whether the present solve is without friction (then Pi is the potential of the
        equations)."""


class ContactDiscretisation(Protocol):
    """What a discretisation provides to :class:`ContactNewton`: ``problem`` (the
    :class:`fewear.contact.params.ContactProblem`), its ``operations`` (:class:`NewtonOperations`)
    and their ``newton_state``, its ``coupled_newton`` (:func:`coupled_newton` on its operations,
    by :func:`specialised`, compiled or not), and whether it ``can_turn_state``."""

    problem: Any
    operations: Any
    newton_state: Any
    coupled_newton: Any
    can_turn_state: bool

    def turn_state(self, angle_rad: float) -> bool:
        """Turn the state (pin centre and displacement) about the bushing centre by the whole
        number of bore elements nearest to ``angle_rad`` (only called if ``can_turn_state``) and
        return True, or, where the bore is not invariant under that turn (worn), leave the state
        as it is and return False."""


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


def newton_settings(problem) -> NewtonSettings:
    """The :class:`NewtonSettings` of a :class:`fewear.contact.params.ContactProblem` (or
    ``FlatContactProblem``)."""
    surface = problem.contact_surface()
    return NewtonSettings(problem.contact.newton_tolerance,
                          float(np.finfo(float).eps * problem.indenter_radius_m),
                          problem.penalty_stiffness_Pa_per_m(), problem.indenter_radius_m,
                          surface.radius_m, surface.element_size_m, surface.node_spacing_rad)


@compiled
def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


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
        result[q] = math.hypot(points[q, 0] - centre[0], points[q, 1] - centre[1]) - pin_radius
    return result


def contact_direction(force: np.ndarray, friction_value: float) -> np.ndarray:
    """Expected direction of the contact arc's centre: F turned by -atan(mu s), since the
    traction p (n + mu s t) of a narrow arc around n has the direction of n turned by
    atan(mu s)."""
    return unit(math.atan2(force[1], force[0]) - math.atan(friction_value))


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
        for q in range(points.shape[0]):
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
    line_search(points, np.zeros((16, 2)), np.zeros((16, 2)), centre, dc, weights, load, 10.0,
                penalty, pin_radius, 0.2, 0.4, 1.0, 1.0, -1.0, True, np.zeros(3))
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


discretisation: Any = None  # the operations coupled_newton runs on: bound by specialised()
# (coupled_newton itself is the template: only its specialised copies can run)


def coupled_newton(state, settings: NewtonSettings, load: np.ndarray, direction: np.ndarray,
                   basis: np.ndarray, max_iterations: int) -> int:
    """Semi-smooth Newton on (displacement, c) from the present state, c moving in the span of
    ``basis`` (2, k), with the step rules and the stopping test of the module docstring, on the
    ``discretisation`` bound by :func:`specialised` (its :class:`NewtonOperations`, ``state``
    theirs). Returns the number of steps taken to the state that passes the stopping test, or -1
    when not converged within ``max_iterations`` steps or, for the free pin (k = 2), as soon as
    the active set alternates persistently (the step cap below ``CYCLE_CAP``). A state without
    contact restarts: at the corner start, or on the ray if the pin is held on one."""
    operations = discretisation
    control = new_control()
    load_size = norm(load)
    pin_step = displacement_step = penetration = displacement = 0.0
    stepped = False
    for iteration in range(max_iterations + 1):
        pin_residual, active, linear = operations.linearise(state, load)
        if active == 0.0:
            operations.zero_displacement(state)
            points, weights = operations.deformed_points(state), operations.node_weights(state)
            if basis.shape[1] == 2:
                centre = corner_centre(points, weights, direction, load_size, settings.penalty,
                                       settings.pin_radius_m)
            else:
                centre = ray_centre(points, operations.pin_position(state), weights, direction,
                                    load_size, settings.penalty, settings.pin_radius_m)
            operations.place_pin(state, centre)
            control = new_control()
            stepped = False
            continue
        residual = norm(projected(basis, pin_residual))
        if stepped and converged(control, settings, pin_step, displacement_step, penetration,
                                 displacement, residual, load_size, active):
            return iteration
        cap = step_cap(control, active)
        if iteration == max_iterations or (cap < CYCLE_CAP and basis.shape[1] == 2):
            return -1
        update, dc = operations.newton_direction(state, linear, pin_residual, load, basis)
        # the line search on the bore nodes; the Armijo test (a descent direction without
        # friction) only where the decrease of Pi it asks for is above the rounding level: Pi is
        # a sum of terms of size |F/L| |c|, and a decrease below ENERGY_ROUNDING of that is
        # noise; with friction Pi is no potential of the equations
        line, base = operations.begin_line_search(state, linear, update, dc, pin_residual)
        centre = operations.pin_position(state)
        descent = operations.frictionless(state) and -line.slope > ENERGY_ROUNDING * (
            load_size * norm(centre))
        step, trial_centre, trial_gaps = line_search(
            line.points, line.displacement, line.update, centre, dc,
            operations.node_weights(state), load, load_size, settings.penalty,
            settings.pin_radius_m, settings.node_spacing_rad, settings.element_size_m,
            settings.bore_radius_m, cap, line.slope, descent, line.elastic)
        operations.try_step(state, base, update, step, trial_centre)
        displacement_step, displacement = operations.update_sizes(state, update)
        pin_step, penetration = norm(dc), max(-trial_gaps.min(), 0.0)
        stepped = True
    return -1


def specialised(operations) -> types.FunctionType:
    """:func:`coupled_newton` on ``operations`` (:class:`NewtonOperations`: a module of compiled
    functions, to be compiled with it, or a class whose methods take the state as ``self``): the
    same code with ``discretisation`` bound to them, so that the algorithm is written once and
    numba can compile it whole for the condensed path (numba resolves a module's functions at
    compile time and caches the result; it caches no closures)."""
    namespace = dict(globals(), discretisation=operations)
    return types.FunctionType(coupled_newton.__code__, namespace, coupled_newton.__name__)


def solve_by_contact_angle(inner, pin_residual, direction: np.ndarray, load: np.ndarray,
                           max_iterations: int, first_angle_rad: float | None = None) -> int:
    """The fallback when the coupled Newton cycles: the pin angle psi as an outer unknown.

    ``inner(a)`` solves the contact with the pin centre on the ray c = e a (force control of
    the component a . F only: a Newton problem without the pin's nearly free sliding mode) and
    returns its Newton iterations; ``pin_residual()`` then gives R - F/L (N/m) for the last inner
    solution. The tangential residual tau(psi) = (R - F/L) . a_perp is continuous and grows with
    psi overall (slope about |F|/L for a rigid pin), though only piecewise between the angles
    where nodes enter contact. So: step against tau, doubling the step until tau changes sign
    (the first step is the rigid estimate -tau L/|F|, at least 1e-4 rad), on the rays a with
    a . F > 0 only (beyond, the load pulls the pin off the bore and the inner problem has no
    solution): a step that would pass the ray ``RAY_MARGIN_RAD`` short of perpendicular to F
    goes half way to it, and a step whose inner problem fails is halved. Then the Illinois
    variant of regula falsi on the bracket until it is 1e-12 rad wide (the pin centre to
    ~1e-15 m) or |tau| <= 1e-9 |F|/L (about the rounding level of the penalty forces), bisecting
    where the inner problem at the regula falsi's angle fails. The search starts on the ray of
    ``direction``, or at ``first_angle_rad`` where given (the pin angle of the last load step
    that needed this fallback: at a pocket's end the pin stays put while the load turns by
    several degrees) if that ray presses the pin into the bore. The
    state is left at the last angle evaluated (inside the final bracket). Returns the inner
    iterations.
    """
    total = 0
    tolerance = 1e-9 * norm(load)

    def tangential_residual(ψ: float) -> float:
        nonlocal total
        total += inner(unit(ψ))
        return float(pin_residual() @ unit(ψ + 0.5 * math.pi))

    # the rays that press the pin into the bore: a . F > 0, with a margin
    φ = math.atan2(load[1], load[0])
    reach = 0.5 * math.pi - RAY_MARGIN_RAD
    ψ0 = math.atan2(direction[1], direction[0])
    if first_angle_rad is not None and abs(_wrapped(first_angle_rad - φ)) < reach:
        ψ0 = φ + _wrapped(first_angle_rad - φ)
    τ0 = tangential_residual(ψ0)
    step = -math.copysign(max(abs(τ0) / norm(load), 1e-4), τ0)
    bound = φ + math.copysign(reach, step) + 2.0 * math.pi * round((ψ0 - φ) / (2.0 * math.pi))
    iterations = 0
    while abs(τ0) > tolerance:
        if abs(step) >= abs(bound - ψ0):
            step = 0.5 * (bound - ψ0)  # half way to the last ray that presses the pin in
        ψ1 = ψ0 + step
        iterations += 1
        if iterations > max_iterations or abs(step) < ANGLE_TOLERANCE_RAD:
            raise ContactNotConverged(load, "found no contact angle in equilibrium")
        try:
            τ1 = tangential_residual(ψ1)
        except ContactNotConverged:
            step *= 0.5  # no equilibrium on that ray: a shorter step
            continue
        if (τ1 > 0.0) != (τ0 > 0.0) or abs(τ1) <= tolerance:
            break
        ψ0, τ0, step = ψ1, τ1, 2.0 * step
    else:
        return total
    ψ, τ, side = ψ1, τ1, 0
    while abs(τ) > tolerance and abs(ψ1 - ψ0) > ANGLE_TOLERANCE_RAD:
        iterations += 1
        if iterations > max_iterations:
            raise ContactNotConverged(load, "did not converge on the contact angle")
        ψ = (ψ0 * τ1 - ψ1 * τ0) / (τ1 - τ0)
        try:
            τ = tangential_residual(ψ)
        except ContactNotConverged:
            ψ = 0.5 * (ψ0 + ψ1)  # bisect instead
            τ = tangential_residual(ψ)
        if (τ > 0.0) == (τ1 > 0.0):
            ψ1, τ1 = ψ, τ
            τ0 = 0.5 * τ0 if side == 1 else τ0
            side = 1
        else:
            ψ0, τ0 = ψ, τ
            τ1 = 0.5 * τ1 if side == -1 else τ1
            side = -1
    return total


def _wrapped(angle_rad: float) -> float:
    """The angle in [-pi, pi)."""
    return (angle_rad + math.pi) % (2.0 * math.pi) - math.pi


class ContactNewton:
    """The algorithm of the module docstring on a :class:`ContactDiscretisation`.

    ``solve(load, direction)`` with the load F/L (N/m) and the expected contact direction
    (:func:`contact_direction`) leaves the discretisation at the solution and returns the number
    of Newton iterations (all inner ones of the fallback included); :meth:`forget` makes the
    next solve start cold (after a zero force or a geometry change). Each solve depends only on
    the geometry and the solves since the last geometry change (a resumed run repeats them).
    """

    def __init__(self, path: ContactDiscretisation):
        self.path = path
        self.operations = path.operations
        self.last_direction: np.ndarray | None = None
        self.last_contact_nodes = 0
        self.last_load = 0.0
        self.fallback_angle_rad: float | None = None  # the pin's after the last fallback
        self.settings = newton_settings(path.problem)

    def forget(self) -> None:
        """Start the next solve cold. The fallback's starting angle (the pin's after the last
        fallback) stays: between load steps of no force the pin returns to the same end of a
        pocket."""
        self.last_direction = None

    def geometry_changed(self) -> None:
        """Forget the fallback's starting angle too (the bore moved)."""
        self.fallback_angle_rad = None

    def reset(self) -> None:
        """No displacement, the pin centred; the next solve starts cold (after a zero force or
        a refused load)."""
        state = self.path.newton_state
        self.operations.zero_displacement(state)
        self.operations.place_pin(state, np.zeros(2))
        self.forget()

    def solve(self, load: np.ndarray, direction: np.ndarray) -> int:
        untouched = self._start(direction, load)
        iterations = self._coupled_newton(load, direction, FREE_PIN, COUPLED_ITERATIONS)
        spent = COUPLED_ITERATIONS
        if iterations is None and untouched:
            # the last solution, not turned on a worn bore, can lead astray (the pin slides
            # along a pocket's flank, held by one node): once more from the corner start
            self._corner_start(direction, load)
            iterations = self._coupled_newton(load, direction, FREE_PIN, COUPLED_ITERATIONS)
            if iterations is not None:
                iterations += spent
            spent += COUPLED_ITERATIONS
        if iterations is None:
            iterations = spent + self._solve_by_contact_angle(load, direction,
                                                              self.fallback_angle_rad)
            centre = self._pin()
            self.fallback_angle_rad = math.atan2(centre[1], centre[0])
        self.last_direction = direction
        self.last_contact_nodes = int(np.count_nonzero(self._gaps() < 0.0))
        self.last_load = norm(load)
        return iterations

    def _solve_by_contact_angle(self, load: np.ndarray, direction: np.ndarray,
                                first_angle_rad: float | None) -> int:
        operations, state = self.operations, self.path.newton_state
        return solve_by_contact_angle(lambda a: self.solve_on_ray(load, a),
                                      lambda: operations.linearise(state, load)[0], direction,
                                      load, self.path.problem.contact.newton_max_iterations,
                                      first_angle_rad)

    def solve_on_ray(self, load: np.ndarray, a: np.ndarray) -> int:
        """Solve with the pin centre held on the ray c = e a through the origin (the unit vector
        ``a``), from the present state: the pin put on the ray (:meth:`_onto_ray`), then the
        coupled Newton with the pin's moves along ``a`` alone, i.e. force control of the
        component a . F/L of the load (N/m; the component across the ray is left unbalanced).
        Returns the Newton iterations; raises :class:`ContactNotConverged` if it does not
        converge within ``newton_max_iterations``. The contact-angle fallback's inner problem,
        and the cylinder on a flat with its x held (:mod:`fewear.contact.flat`)."""
        self._onto_ray(a, load)
        return self.solve_from_here(load, a, np.ascontiguousarray(a[:, None]),
                                    "with the pin on a fixed ray")

    def solve_from_here(self, load: np.ndarray, direction: np.ndarray, basis: np.ndarray,
                        setting: str = "from the present state") -> int:
        """The coupled Newton from the present state as it is (no start, no retry, no
        fallback), the pin moving in the span of ``basis`` (2, k): force control of the
        components basis^T F/L of the load (N/m), the pin's position across them held.
        Returns the Newton iterations; raises :class:`ContactNotConverged` (naming the
        ``setting``) if it does not converge within ``newton_max_iterations``."""
        count = self._coupled_newton(load, direction, basis,
                                     self.path.problem.contact.newton_max_iterations)
        if count is None:
            raise ContactNotConverged(load, f"did not converge {setting}")
        return count

    def _coupled_newton(self, load, direction, basis, max_iterations) -> int | None:
        """:func:`coupled_newton` of the discretisation on its state; None if not converged."""
        iterations = self.path.coupled_newton(self.path.newton_state, self.settings, load,
                                              direction, basis, max_iterations)
        return None if iterations < 0 else iterations

    def _pin(self) -> np.ndarray:
        return self.operations.pin_position(self.path.newton_state)

    def _place_pin(self, centre: np.ndarray) -> None:
        self.operations.place_pin(self.path.newton_state, centre)

    def _onto_ray(self, a: np.ndarray, load: np.ndarray) -> None:
        """Put the pin on the ray c = e a (:func:`ray_centre`)."""
        operations, state, settings = self.operations, self.path.newton_state, self.settings
        self._place_pin(ray_centre(operations.deformed_points(state), self._pin(),
                                   operations.node_weights(state), a, norm(load),
                                   settings.penalty, settings.pin_radius_m))

    def _start(self, direction: np.ndarray, load: np.ndarray) -> bool:
        """Without a previous solution: the corner start (:meth:`_corner_start`). Else, if the
        discretisation can turn its state and the bore is invariant under the turn: the last
        solution turned by the whole number of bore elements nearest to the turn of the contact
        direction (pin and indentation together: turning the pin alone against the old
        indentation would start far from equilibrium), and at a light load (the last solution
        had at most ``LIGHT_CONTACT_NODES`` nodes in contact and the load grew by at most
        ``LIGHT_LOAD_GROWTH``) the pin moved to :meth:`_corner` of that turned bore. If it
        cannot (or the bore is worn: a turned state would put the pin into a pocket's flank):
        the last solution as it is when the load is not light and the direction turned by at
        most ``WARM_START_MAX_ANGLE_RAD``, else the corner start. Returns whether the start
        is the last solution left as it is by a discretisation that could not turn it (a worn
        bore), which :meth:`solve` retries from the corner start should it not settle."""
        last, path = self.last_direction, self.path
        size = norm(load)
        untouched = last is not None and path.can_turn_state
        light = (self.last_contact_nodes <= LIGHT_CONTACT_NODES
                 and size <= LIGHT_LOAD_GROWTH * self.last_load)
        if last is not None and path.can_turn_state:
            turn = math.atan2(last[0] * direction[1] - last[1] * direction[0], last @ direction)
            if path.turn_state(turn):
                if light:
                    self._place_pin(self._corner(direction, load))
                return False
        if last is not None and not light:
            turn = math.atan2(last[0] * direction[1] - last[1] * direction[0], last @ direction)
            if abs(turn) <= WARM_START_MAX_ANGLE_RAD:
                return untouched
        self._corner_start(direction, load)
        return False

    def _corner_start(self, direction: np.ndarray, load: np.ndarray) -> None:
        """No displacement, the pin at :meth:`_corner` of the undeformed bore."""
        self.operations.zero_displacement(self.path.newton_state)
        self._place_pin(self._corner(direction, load))

    def _corner(self, direction: np.ndarray, load: np.ndarray) -> np.ndarray:
        """The light-load solution for the present bore displacement (:func:`corner_centre`)."""
        operations, state, settings = self.operations, self.path.newton_state, self.settings
        return corner_centre(operations.deformed_points(state), operations.node_weights(state),
                             direction, norm(load), settings.penalty, settings.pin_radius_m)

    def _gaps(self) -> np.ndarray:
        """Gaps |X + U - c| - R_p at the bore nodes (m), negative in contact."""
        return gaps(self.operations.deformed_points(self.path.newton_state), self._pin(),
                    self.settings.pin_radius_m)


FREE_PIN = np.eye(2)  # the basis of the pin's moves when it is free (not held on a ray)


class LineData(NamedTuple):
    """What :func:`line_search` needs of a discretisation at the start of a line search along
    (displacement update, dc): the slope dPi/dstep at step 0 (J/m); the bore nodes' reference
    positions X, displacements U and displacement updates dU (n, 2), m (the trial step s puts
    the nodes at X + (U + s dU)); and the elastic energy along the line as the coefficients
    (e0, e1, e2) of e0 + e1 s + e2 s^2 (J/m)."""

    slope: float
    points: np.ndarray
    displacement: np.ndarray
    update: np.ndarray
    elastic: np.ndarray


@compiled
def _trial(step, points, displacement, update, centre0, dc, contact, base_points, normals,
           base_gaps, pin_radius, node_spacing_rad):
    """The pin centre and the nodes' gaps at the trial ``step``: the pin by :func:`pin_update`
    plus the second-order correction of :func:`following_centre` (the nodes in contact at the
    base move off the pin by more than their linearised gaps predict: gaps curve with 1/R_p,
    which at light loads is more than the penetrations)."""
    centre = pin_update(centre0, step * dc, node_spacing_rad)
    deformed = points + (displacement + step * update)
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
def line_search(points, displacement, update, centre0, dc, weights_m, load, load_size, penalty,
                pin_radius, node_spacing_rad, element_size_m, bore_radius_m, cap, slope, descent,
                elastic):
    """The step length along a Newton direction, on the bore nodes (:class:`LineData`): the
    step, the pin centre there and the nodes' gaps there.

    Starts from the smaller of ``cap``, :func:`slide_limit` and the step at which the first
    node entering contact could carry the load alone (:func:`entering_limit`). Then halves the
    step while the trial loses all contact, and, for a ``descent`` direction, backtracks
    (Armijo, at most ``BACKTRACK_RANGE`` below the first contact-keeping step) on the penalty
    potential (:func:`_line_energy`); else the first contact-keeping step is taken. Should every
    trial lose contact, a step below the smallest tried."""
    base = points + displacement
    gaps0 = gaps(base, centre0, pin_radius)
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
