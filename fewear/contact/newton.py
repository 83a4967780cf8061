"""The contact Newton: one algorithm for both discretisations of the pin-in-bushing problem.

The unknowns are the bore's displacement and the pin centre c; the equations the bushing's elastic
equilibrium under the penalty tractions and the pin's force balance sum_q f_q = F / L. Each
discretisation (:mod:`fewear.contact.solver`, :mod:`fewear.contact.condensed`) provides its linear
algebra as :class:`NewtonOperations`; this module holds the algorithm, written once in numba's
subset of Python: start, semi-smooth (active-set) Newton steps, step rules, stopping test, retry
and the contact-angle fallback. Method notes: docs/contact.md.
"""

from __future__ import annotations

import math
import types
from typing import Any, Protocol

import numpy as np

from fewear.contact.newton_kernels import (
    ENERGY_ROUNDING,
    NewtonSettings,
    converged,
    corner_centre,
    gaps,
    line_search,
    new_control,
    norm,
    projected,
    ray_centre,
    step_cap,
    unit,
)

# Newton starts from the previous solution when the force turned by less than this (rad).
WARM_START_MAX_ANGLE_RAD = math.radians(20.0)

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

# At most this many nodes in contact is a light load: the next solve starts at a corner.
LIGHT_CONTACT_NODES = 3
# ... unless the load grows by more than this factor.
LIGHT_LOAD_GROWTH = 1.5

# The algorithm's counts below zero: why it found no equilibrium.
NOT_CONVERGED = -1
NOT_CONVERGED_ON_RAY = -2
NO_CONTACT_ANGLE = -3
NOT_CONVERGED_ON_ANGLE = -4
FAILURES = {NOT_CONVERGED: "did not converge",
            NOT_CONVERGED_ON_RAY: "did not converge with the pin on a fixed ray",
            NO_CONTACT_ANGLE: "found no contact angle in equilibrium",
            NOT_CONVERGED_ON_ANGLE: "did not converge on the contact angle"}


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
                          pin_residual: np.ndarray) -> tuple[Any, Any]:
        """What :func:`line_search` needs (:class:`fewear.contact.newton_kernels.LineData`) along
        (update, dc), and the
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

    def can_turn_state(self, state) -> bool:
        """Whether the discretisation can turn its state with the load (:meth:`turn_state`)."""

    def turn_state(self, state, angle_rad: float) -> bool:
        """Turn the state (pin centre and displacement) about the bushing centre by the whole
        number of bore elements nearest to ``angle_rad`` (only called if ``can_turn_state``) and
        return True, or, where the bore is not invariant under that turn (worn), leave the state
        as it is and return False."""


class ContactDiscretisation(Protocol):
    """What a discretisation provides to :class:`ContactNewton`: ``problem`` (the
    :class:`fewear.contact.params.ContactProblem`), its ``operations`` (:class:`NewtonOperations`)
    and their ``newton_state``, and its ``newton_algorithm`` (the algorithm on its operations,
    :func:`specialised`, compiled or not)."""

    problem: Any
    operations: Any
    newton_state: Any
    newton_algorithm: types.SimpleNamespace


def newton_settings(problem) -> NewtonSettings:
    """The :class:`NewtonSettings` of a :class:`fewear.contact.params.ContactProblem` (or
    ``FlatContactProblem``)."""
    surface = problem.contact_surface()
    return NewtonSettings(problem.contact.newton_tolerance,
                          float(np.finfo(float).eps * problem.indenter_radius_m),
                          problem.penalty_stiffness_Pa_per_m(), problem.indenter_radius_m,
                          surface.radius_m, surface.element_size_m, surface.node_spacing_rad)


# -- the algorithm, written once (templates bound to a discretisation by specialised()) ----------
discretisation: Any = None  # the operations the templates run on: bound by specialised()


def free_pin() -> np.ndarray:
    """The basis of the pin's moves when it is free (not held on a ray): the identity (2, 2)."""
    return np.eye(2)


def coupled_newton(state, settings: NewtonSettings, load: np.ndarray, direction: np.ndarray,
                   basis: np.ndarray, max_iterations: int) -> int:
    """Semi-smooth Newton on (displacement, c) from the present state, c moving in the span of
    ``basis`` (2, k), with the step rules and the stopping test of the method notes, on the
    ``discretisation`` bound by :func:`specialised` (its :class:`NewtonOperations`, ``state``
    theirs). Returns the number of steps taken to the state that passes the stopping test, or
    ``NOT_CONVERGED`` when not converged within ``max_iterations`` steps or, for the free pin
    (k = 2), as soon as the active set alternates persistently (the step cap below
    ``CYCLE_CAP``). A state without contact restarts: at the corner start, or on the ray if the
    pin is held on one."""
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
            return NOT_CONVERGED
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
            line.points, line.displacement, line.update, line.gaps, centre, dc,
            operations.node_weights(state), load, load_size, settings.penalty,
            settings.pin_radius_m, settings.node_spacing_rad, settings.element_size_m,
            settings.bore_radius_m, cap, line.slope, descent, line.elastic)
        operations.try_step(state, base, update, step, trial_centre)
        displacement_step, displacement = operations.update_sizes(state, update)
        pin_step, penetration = norm(dc), max(-trial_gaps.min(), 0.0)
        stepped = True
    return NOT_CONVERGED


def newton_solve(state, memory: np.ndarray, settings: NewtonSettings, load: np.ndarray,
                 direction: np.ndarray, max_iterations: int) -> int:
    """One solve for the load F/L (N/m) with the expected contact direction: the start
    (:func:`start`), the coupled Newton, the retry from the corner start and the fallback on the
    contact angle of the method notes. ``memory`` (:func:`new_memory`) holds what the solves
    before left: the last contact direction (NaN: none, a cold start), the last solution's nodes
    in contact, |F/L| and the pin angle after the last fallback (NaN: none); updated after a
    solve that converged. Returns the Newton iterations (all inner ones of the fallback
    included), or a negative code of ``FAILURES``."""
    operations = discretisation
    untouched = start(state, memory, settings, direction, load)
    iterations = coupled_newton(state, settings, load, direction, free_pin(), COUPLED_ITERATIONS)
    spent = COUPLED_ITERATIONS
    if iterations < 0 and untouched:
        # the last solution, not turned on a worn bore, can lead astray (the pin slides
        # along a pocket's flank, held by one node): once more from the corner start
        corner_start(state, settings, direction, load)
        iterations = coupled_newton(state, settings, load, direction, free_pin(),
                                    COUPLED_ITERATIONS)
        if iterations >= 0:
            iterations += spent
        spent += COUPLED_ITERATIONS
    if iterations < 0:
        inner = solve_by_contact_angle(state, settings, load, direction, max_iterations,
                                       memory[4])
        if inner < 0:
            return inner
        iterations = spent + inner
        centre = operations.pin_position(state)
        memory[4] = math.atan2(centre[1], centre[0])
    memory[0], memory[1] = direction[0], direction[1]
    memory[2] = np.count_nonzero(gaps(operations.deformed_points(state),
                                      operations.pin_position(state), settings.pin_radius_m)
                                 < 0.0)
    memory[3] = norm(load)
    return iterations


def start(state, memory: np.ndarray, settings: NewtonSettings, direction: np.ndarray,
          load: np.ndarray) -> bool:
    """Without a previous solution: the corner start (:func:`corner_start`). Else, if the
    discretisation can turn its state and the bore is invariant under the turn: the last
    solution turned by the whole number of bore elements nearest to the turn of the contact
    direction (pin and indentation together: turning the pin alone against the old indentation
    would start far from equilibrium), and at a light load (the last solution had at most
    ``LIGHT_CONTACT_NODES`` nodes in contact and the load grew by at most
    ``LIGHT_LOAD_GROWTH``) the pin moved to :func:`corner` of that turned bore. If it cannot (or
    the bore is worn: a turned state would put the pin into a pocket's flank): the last solution
    as it is when the load is not light and the direction turned by at most
    ``WARM_START_MAX_ANGLE_RAD``, else the corner start. Returns whether the start is the last
    solution left as it is by a discretisation that could not turn it (a worn bore), which
    :func:`newton_solve` retries from the corner start should it not settle."""
    operations = discretisation
    last = memory[:2].copy()
    known = not math.isnan(last[0])
    size = norm(load)
    untouched = known and operations.can_turn_state(state)
    light = memory[2] <= LIGHT_CONTACT_NODES and size <= LIGHT_LOAD_GROWTH * memory[3]
    if known and operations.can_turn_state(state):
        turn = math.atan2(last[0] * direction[1] - last[1] * direction[0],
                          np.dot(last, direction))
        if operations.turn_state(state, turn):
            if light:
                operations.place_pin(state, corner(state, settings, direction, load))
            return False
    if known and not light:
        turn = math.atan2(last[0] * direction[1] - last[1] * direction[0],
                          np.dot(last, direction))
        if abs(turn) <= WARM_START_MAX_ANGLE_RAD:
            return untouched
    corner_start(state, settings, direction, load)
    return False


def corner_start(state, settings: NewtonSettings, direction: np.ndarray,
                 load: np.ndarray) -> None:
    """No displacement, the pin at :func:`corner` of the undeformed bore."""
    discretisation.zero_displacement(state)
    discretisation.place_pin(state, corner(state, settings, direction, load))


def corner(state, settings: NewtonSettings, direction: np.ndarray,
           load: np.ndarray) -> np.ndarray:
    """The light-load solution for the present bore displacement (:func:`corner_centre`)."""
    operations = discretisation
    return corner_centre(operations.deformed_points(state), operations.node_weights(state),
                         direction, norm(load), settings.penalty, settings.pin_radius_m)


def solve_on_ray(state, settings: NewtonSettings, load: np.ndarray, a: np.ndarray,
                 max_iterations: int) -> int:
    """Solve with the pin centre held on the ray c = e a through the origin (the unit vector
    ``a``), from the present state: the pin put on the ray (:func:`ray_centre`: as deep as it
    is now, or as two nodes need to carry the load), then the coupled Newton with the pin's
    moves along ``a`` alone, i.e. force control of the component a . F/L of the load (N/m;
    the component across the ray is left unbalanced). Returns the Newton iterations or
    ``NOT_CONVERGED``. The contact-angle fallback's inner problem, and the cylinder on a flat
    with its x held (:mod:`fewear.contact.flat`)."""
    operations = discretisation
    operations.place_pin(state, ray_centre(
        operations.deformed_points(state), operations.pin_position(state),
        operations.node_weights(state), a, norm(load), settings.penalty, settings.pin_radius_m))
    basis = np.empty((2, 1))
    basis[0, 0], basis[1, 0] = a[0], a[1]
    return coupled_newton(state, settings, load, a, basis, max_iterations)


def tangential_residual(state, settings: NewtonSettings, load: np.ndarray, angle_rad: float,
                        max_iterations: int) -> tuple[float, int]:
    """tau(psi) = (R - F/L) . a_perp (N/m) of the solve on the ray a = (cos psi, sin psi)
    (:func:`solve_on_ray`) and its Newton iterations (negative: not converged, tau NaN)."""
    count = solve_on_ray(state, settings, load, unit(angle_rad), max_iterations)
    if count < 0:
        return math.nan, count
    pin_residual = discretisation.linearise(state, load)[0]
    return np.dot(pin_residual, unit(angle_rad + 0.5 * math.pi)), count


def solve_by_contact_angle(state, settings: NewtonSettings, load: np.ndarray,
                           direction: np.ndarray, max_iterations: int,
                           first_angle_rad: float) -> int:
    """The fallback when the coupled Newton cycles: the pin angle psi as an outer unknown.

    Each inner problem solves the contact with the pin centre on the ray c = e a (force control
    of the component a . F only: a Newton problem without the pin's nearly free sliding mode,
    :func:`tangential_residual`). The tangential residual tau(psi) = (R - F/L) . a_perp is
    continuous and grows with psi overall (slope about |F|/L for a rigid pin), though only
    piecewise between the angles where nodes enter contact. So: step against tau, doubling the
    step until tau changes sign (the first step is the rigid estimate -tau L/|F|, at least
    1e-4 rad), on the rays a with a . F > 0 only (beyond, the load pulls the pin off the bore
    and the inner problem has no solution): a step that would pass the ray ``RAY_MARGIN_RAD``
    short of perpendicular to F goes half way to it, and a step whose inner problem fails is
    halved. Then the Illinois variant of regula falsi on the bracket until it is 1e-12 rad wide
    (the pin centre to ~1e-15 m) or |tau| <= 1e-9 |F|/L (about the rounding level of the
    penalty forces), bisecting where the inner problem at the regula falsi's angle fails. The
    search starts on the ray of ``direction``, or at ``first_angle_rad`` where it is not NaN
    (the pin angle of the last load step that needed this fallback: at a pocket's end the pin
    stays put while the load turns by several degrees) if that ray presses the pin into the
    bore. The state is left at the last angle evaluated (inside the final bracket). Returns the
    inner iterations, or a negative code of ``FAILURES``."""
    tolerance = 1e-9 * norm(load)
    # the rays that press the pin into the bore: a . F > 0, with a margin
    φ = math.atan2(load[1], load[0])
    reach = 0.5 * math.pi - RAY_MARGIN_RAD
    ψ0 = math.atan2(direction[1], direction[0])
    if not math.isnan(first_angle_rad) and abs(wrapped(first_angle_rad - φ)) < reach:
        ψ0 = φ + wrapped(first_angle_rad - φ)
    τ0, total = tangential_residual(state, settings, load, ψ0, max_iterations)
    if total < 0:
        return NOT_CONVERGED_ON_RAY
    step = -math.copysign(max(abs(τ0) / norm(load), 1e-4), τ0)
    bound = φ + math.copysign(reach, step) + 2.0 * math.pi * round((ψ0 - φ) / (2.0 * math.pi))
    iterations = 0
    ψ1, τ1 = ψ0, τ0
    bracketed = False
    while abs(τ0) > tolerance:
        if abs(step) >= abs(bound - ψ0):
            step = 0.5 * (bound - ψ0)  # half way to the last ray that presses the pin in
        ψ1 = ψ0 + step
        iterations += 1
        if iterations > max_iterations or abs(step) < ANGLE_TOLERANCE_RAD:
            return NO_CONTACT_ANGLE
        τ1, count = tangential_residual(state, settings, load, ψ1, max_iterations)
        if count < 0:
            step *= 0.5  # no equilibrium on that ray: a shorter step
            continue
        total += count
        if (τ1 > 0.0) != (τ0 > 0.0) or abs(τ1) <= tolerance:
            bracketed = True
            break
        ψ0, τ0, step = ψ1, τ1, 2.0 * step
    if not bracketed:
        return total
    ψ, τ, side = ψ1, τ1, 0
    while abs(τ) > tolerance and abs(ψ1 - ψ0) > ANGLE_TOLERANCE_RAD:
        iterations += 1
        if iterations > max_iterations:
            return NOT_CONVERGED_ON_ANGLE
        ψ = (ψ0 * τ1 - ψ1 * τ0) / (τ1 - τ0)
        τ, count = tangential_residual(state, settings, load, ψ, max_iterations)
        if count < 0:
            ψ = 0.5 * (ψ0 + ψ1)  # bisect instead
            τ, count = tangential_residual(state, settings, load, ψ, max_iterations)
            if count < 0:
                return NOT_CONVERGED_ON_RAY
        total += count
        if (τ > 0.0) == (τ1 > 0.0):
            ψ1, τ1 = ψ, τ
            τ0 = 0.5 * τ0 if side == 1 else τ0
            side = 1
        else:
            ψ0, τ0 = ψ, τ
            τ1 = 0.5 * τ1 if side == -1 else τ1
            side = -1
    return total


def wrapped(angle_rad: float) -> float:
    """The angle in [-pi, pi)."""
    return (angle_rad + math.pi) % (2.0 * math.pi) - math.pi


TEMPLATES = (free_pin, coupled_newton, newton_solve, start, corner_start, corner, solve_on_ray,
             tangential_residual, solve_by_contact_angle, wrapped)


def specialised(operations, wrap=None) -> types.SimpleNamespace:
    """The algorithm on ``operations`` (:class:`NewtonOperations`: a module of compiled
    functions, to be compiled with it, or a class whose methods take the state as ``self``):
    each function of ``TEMPLATES``, the same code with ``discretisation`` bound to them and its
    calls of the others bound to their copies, as the attributes of the namespace returned. So
    the algorithm is written once and numba can compile it whole for the condensed path (numba
    resolves a module's functions at compile time and caches the result; it caches no
    closures); ``wrap`` (e.g. numba's ``register_jitable``) is applied to each copy."""
    namespace = dict(globals(), discretisation=operations)
    for template in TEMPLATES:
        copy = types.FunctionType(template.__code__, namespace, template.__name__)
        namespace[template.__name__] = copy if wrap is None else wrap(copy)
    return types.SimpleNamespace(**{t.__name__: namespace[t.__name__] for t in TEMPLATES})


def new_memory() -> np.ndarray:
    """The memory of :func:`newton_solve` before the first solve: no last direction, no nodes in
    contact, no load, no fallback angle."""
    return np.array([math.nan, math.nan, 0.0, 0.0, math.nan])


class ContactNewton:
    """The algorithm of the method notes on a :class:`ContactDiscretisation`, with the
    memory the solves leave (:func:`new_memory`).

    ``solve(load, direction)`` with the load F/L (N/m) and the expected contact direction
    (:func:`contact_direction`) leaves the discretisation at the solution and returns the number
    of Newton iterations (all inner ones of the fallback included); :meth:`forget` makes the
    next solve start cold (after a zero force or a geometry change). Each solve depends only on
    the geometry and the solves since the last geometry change (a resumed run repeats them).
    """

    def __init__(self, path: ContactDiscretisation):
        self.path = path
        self.operations = path.operations
        self.algorithm = path.newton_algorithm
        self.memory = new_memory()
        self.settings = newton_settings(path.problem)

    @property
    def fallback_angle_rad(self) -> float | None:
        """The pin's angle (rad) after the last fallback on the contact angle, or None."""
        angle = self.memory[4]
        return None if math.isnan(angle) else float(angle)

    def forget(self) -> None:
        """Start the next solve cold. The fallback's starting angle (the pin's after the last
        fallback) stays: between load steps of no force the pin returns to the same end of a
        pocket."""
        self.memory[:2] = math.nan

    def geometry_changed(self) -> None:
        """Forget the fallback's starting angle too (the bore moved)."""
        self.memory[4] = math.nan

    def reset(self) -> None:
        """No displacement, the pin centred; the next solve starts cold (after a zero force or
        a refused load)."""
        state = self.path.newton_state
        self.operations.zero_displacement(state)
        self.operations.place_pin(state, np.zeros(2))
        self.forget()

    def solve(self, load: np.ndarray, direction: np.ndarray) -> int:
        """:func:`newton_solve`; raises :class:`ContactNotConverged` where it finds none."""
        return self._checked(load, self.algorithm.newton_solve(
            self.path.newton_state, self.memory, self.settings, load, direction,
            self.path.problem.contact.newton_max_iterations))

    def solve_on_ray(self, load: np.ndarray, a: np.ndarray) -> int:
        """:func:`solve_on_ray` within ``newton_max_iterations``; raises
        :class:`ContactNotConverged` if it does not converge."""
        return self._checked(load, self.algorithm.solve_on_ray(
            self.path.newton_state, self.settings, load, a,
            self.path.problem.contact.newton_max_iterations), "with the pin on a fixed ray")

    def solve_from_here(self, load: np.ndarray, direction: np.ndarray, basis: np.ndarray,
                        setting: str = "from the present state") -> int:
        """The coupled Newton from the present state as it is (no start, no retry, no
        fallback), the pin moving in the span of ``basis`` (2, k): force control of the
        components basis^T F/L of the load (N/m), the pin's position across them held.
        Returns the Newton iterations; raises :class:`ContactNotConverged` (naming the
        ``setting``) if it does not converge within ``newton_max_iterations``."""
        return self._checked(load, self.algorithm.coupled_newton(
            self.path.newton_state, self.settings, load, direction, basis,
            self.path.problem.contact.newton_max_iterations), setting)

    @staticmethod
    def _checked(load: np.ndarray, count: int, setting: str = "") -> int:
        if count < 0:
            reason = FAILURES[count] + (f" {setting}" if count == NOT_CONVERGED else "")
            raise ContactNotConverged(load, reason)
        return count

    def _corner(self, direction: np.ndarray, load: np.ndarray) -> np.ndarray:
        """The light-load solution for the present bore displacement (:func:`corner`)."""
        return self.algorithm.corner(self.path.newton_state, self.settings, direction, load)
