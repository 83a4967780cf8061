"""Generalized-alpha for the index-3 DAE  M q'' + Phi_q^T lambda = Q(q, q', t), Phi(q, t) = 0.

Chung & Hulbert (J. Appl. Mech. 60, 1993) parameters, in the constrained form of Arnold & Brüls
(Multibody Syst. Dyn. 18, 2007) with scaled constraint rows, optional velocity projection,
modified Newton (the factorised iteration matrix reused while it contracts) and step-size control
by the clearance joints' gap error. :func:`advance` runs the step loop compiled (numba);
:class:`GeneralizedAlpha` is its Python face. Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from fewear.errors import FewearInputError
from fewear.jit import compiled
from fewear.mbd.clearance import begin_step, end_step, measure_rows, step_error
from fewear.mbd.constraints import (
    add_constraint_hessian,
    add_prescribed,
    constraint_values_and_jacobian,
)
from fewear.mbd.system import system_forces

REUSE_CONTRACTION = 0.25  # modified Newton: rebuild when |dq| shrinks by less than this
RECORD_CHUNK = 4096  # recorded steps per call of the compiled loop
# advance's status: reached t_end, the record buffer is full, the step fell below min_step_s,
# the velocity projection met dependent constraint rows
DONE, BUFFER_FULL, STEP_TOO_SMALL, SINGULAR_PROJECTION = 0, 1, 2, 3


class StepSizeCollapse(RuntimeError):
    """The step size fell below ``min_step_s`` (the time in the message); ``joints``: each
    clearance joint's state at the last accepted step, (penetration m, normal force N, contact
    direction rad in the bushing frame) (empty without clearance joints). A penetration beyond
    the elastic range of the contact law (comparable to the clearance itself) says the mechanism
    jammed its pin into the bore, not that a step was too stiff to take."""

    def __init__(self, message: str, joints: tuple):
        super().__init__(message)
        self.joints = joints


@dataclass(frozen=True)
class IntegratorSettings:
    """Generalized-alpha and step-size parameters (SI units).

    step_s: the (largest) time step; min_step_s: the smallest the controller may take;
    adaptive: step-size control around impacts (else fixed steps of step_s);
    gap_tolerance_m: allowed local error of a contact gap and the deepest allowed first penetration;
    newton_tolerance: convergence when max |dq| < it (m or rad or dimensionless slopes);
    modified_newton: reuse the factorised iteration matrix (method notes).
    """

    rho_inf: float = 0.9
    step_s: float = 2.0e-5
    min_step_s: float = 1.0e-8
    adaptive: bool = True
    gap_tolerance_m: float = 2.0e-8
    newton_tolerance: float = 1.0e-10
    max_newton_iterations: int = 12
    project_velocities: bool = True
    modified_newton: bool = True

    def __post_init__(self):
        if not (0.0 <= self.rho_inf <= 1.0):
            raise FewearInputError(f"rho_inf = {self.rho_inf!r}: expected a number in [0, 1]")
        if not (self.step_s > 0.0 and math.isfinite(self.step_s)):
            raise FewearInputError(f"time step step_s = {self.step_s!r} s: expected > 0")
        if not (0.0 < self.min_step_s <= self.step_s):
            raise FewearInputError(
                f"min_step_s = {self.min_step_s!r} s: expected 0 < min_step_s <= step_s")
        if not self.gap_tolerance_m > 0.0:
            raise FewearInputError(f"gap_tolerance_m = {self.gap_tolerance_m!r}: expected > 0")
        if not self.newton_tolerance > 0.0:
            raise FewearInputError(f"newton_tolerance = {self.newton_tolerance!r}: expected > 0")
        if self.max_newton_iterations < 1:
            raise FewearInputError(
                f"max_newton_iterations = {self.max_newton_iterations!r}: expected >= 1")

    @property
    def coefficients(self) -> tuple[float, float, float, float]:
        """(alpha_m, alpha_f, gamma, beta) of Chung & Hulbert."""
        rho = self.rho_inf
        alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
        alpha_f = rho / (rho + 1.0)
        gamma = 0.5 + alpha_f - alpha_m
        beta = 0.25 * (gamma + 0.5) ** 2
        return alpha_m, alpha_f, gamma, beta

    @property
    def kernel_data(self) -> tuple:
        """The settings as the tuple :func:`advance` takes: (alpha_m, alpha_f, gamma, beta,
        step_s, min_step_s, gap_tolerance_m, newton_tolerance, max_newton_iterations, adaptive,
        project_velocities, modified_newton)."""
        return (*self.coefficients, self.step_s, self.min_step_s, self.gap_tolerance_m,
                self.newton_tolerance, self.max_newton_iterations, self.adaptive,
                self.project_velocities, self.modified_newton)


@dataclass
class State:
    """The integrator's state at time t: positions, velocities, accelerations, a, multipliers."""

    t: float
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    a: np.ndarray
    lam: np.ndarray


@dataclass
class Trajectory:
    """The accepted steps of a run, one row each: the state after the step, the step size and the
    clearance joints' memory then (rows, J, 3) (see fewear.mbd.clearance.JointData)."""

    time_s: np.ndarray
    step_s: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    a: np.ndarray
    lam: np.ndarray
    joint_memory: np.ndarray

    def state(self, row: int) -> State:
        return State(float(self.time_s[row]), self.q[row], self.qd[row], self.qdd[row],
                     self.a[row], self.lam[row])


@dataclass
class RunStats:
    steps: int = 0
    rejected: int = 0
    newton_iterations: int = 0
    factorizations: int = 0
    wall_time_s: float = 0.0
    smallest_step_s: float = math.inf
    extra: dict = field(default_factory=dict)


class GeneralizedAlpha:
    """Time integration of a :class:`fewear.mbd.system.MultibodySystem`."""

    def __init__(self, system, settings: IntegratorSettings):
        self.system = system
        self.settings = settings
        self.stats = RunStats()
        size = system.n_coordinates + system.n_constraints
        # the LU factors of the last iteration matrix and their structure (lu_factor), the h
        # they were built for and whether they have aged (method notes); the counters of RunStats
        self._lu = np.zeros((size, size))
        self._structure = np.zeros((size, size + 3), dtype=np.int64)
        self._newton = np.array([math.nan, 1.0])
        self._counts = np.array([0.0, 0.0, 0.0, 0.0, math.inf])

    def initial_state(self, q0, qd0, t0: float = 0.0) -> State:
        """A state with consistent accelerations and multipliers (q0, qd0 must be consistent)."""
        q0 = np.asarray(q0, dtype=float).copy()
        qd0 = np.asarray(qd0, dtype=float).copy()
        joints = self.system.data.joints
        for j in range(joints.memory.shape[0]):
            begin_step(joints, j, q0, qd0)
        qdd0, lam0 = self.system.consistent_accelerations(q0, qd0, t0)
        return State(t0, q0, qd0, qdd0, qdd0.copy(), lam0)

    def run(self, state: State, t_end: float, observer=None) -> State:
        """Integrate from ``state`` to ``t_end``; call ``observer(state, h)`` after every step
        (once the run is done, in the order of the steps)."""
        if observer is None:
            return self._run(state, t_end, record=False)[0]
        state, trajectory = self._run(state, t_end, record=True)
        for row in range(trajectory.time_s.size):
            observer(trajectory.state(row), float(trajectory.step_s[row]))
        return state

    def run_recorded(self, state: State, t_end: float) -> tuple[State, Trajectory]:
        """Integrate from ``state`` to ``t_end``; return the final state and every step's."""
        return self._run(state, t_end, record=True)

    def _run(self, state: State, t_end: float, record: bool):
        sys_, st = self.system, self.settings
        n, m, joints = sys_.n_coordinates, sys_.n_constraints, sys_.data.joints.memory.shape[0]
        Y = np.array([state.q, state.qd, state.qdd, state.a])
        lam = np.array(state.lam, dtype=float)
        t, h = state.t, self.stats.extra.get("next_step_s", st.step_s)
        rows = RECORD_CHUNK if record else 0
        chunks = []
        start = time.perf_counter()
        while True:
            buffers = (np.empty(rows), np.empty(rows), np.empty((rows, 4, n)), np.empty((rows, m)),
                       np.empty((rows, joints, 3)))
            status, t, h, count = advance(sys_.data, st.kernel_data, t, Y, lam, t_end, h,
                                          self._lu, self._structure, self._newton, self._counts,
                                          *buffers)
            chunks.append([buffer[:count] for buffer in buffers])
            if status != BUFFER_FULL:
                break
        self.stats.wall_time_s += time.perf_counter() - start
        self._update_stats(h)
        if status == STEP_TOO_SMALL:
            raise _collapse(sys_.data, Y, t, st.min_step_s)
        if status == SINGULAR_PROJECTION:
            raise np.linalg.LinAlgError("velocity projection: Phi_q has dependent rows")
        final = State(t, Y[0].copy(), Y[1].copy(), Y[2].copy(), Y[3].copy(), lam.copy())
        if not record:
            return final, None
        times, steps, Ys, lams, memories = (np.concatenate(parts) for parts in zip(*chunks))
        return final, Trajectory(times, steps, Ys[:, 0], Ys[:, 1], Ys[:, 2], Ys[:, 3], lams,
                                 memories)

    def _update_stats(self, next_step_s: float) -> None:
        steps, rejected, iterations, factorizations, smallest = self._counts
        self.stats.steps, self.stats.rejected = int(steps), int(rejected)
        self.stats.newton_iterations, self.stats.factorizations = int(iterations), int(
            factorizations)
        self.stats.smallest_step_s = float(smallest)
        self.stats.extra["next_step_s"] = next_step_s


def _collapse(data, Y, t: float, min_step_s: float) -> StepSizeCollapse:
    """The :class:`StepSizeCollapse` at ``t``, with the clearance joints' state in ``Y`` (the
    last accepted step) in its message."""
    joints = []
    for j in range(data.joints.memory.shape[0]):
        row = measure_rows(data.joints, j, Y[0][None], Y[1][None], data.joints.memory[None])[0]
        joints.append((float(row[2]), float(row[3]), math.atan2(row[1], row[0])))
    where = "".join(
        f"; clearance joint {j}: penetration {delta * 1e6:.3g} um at "
        f"{math.degrees(direction) % 360.0:.1f} deg, normal force {force:.3g} N"
        for j, (delta, force, direction) in enumerate(joints))
    return StepSizeCollapse(f"generalized-alpha: step size fell below min_step_s = "
                            f"{min_step_s:g} s at t = {t:.6g} s{where}", tuple(joints))


# -- compiled -------------------------------------------------------------------------------------
@compiled
def lu_factor(A, structure):
    """LU factors of A with partial pivoting, in place (Golub & Van Loan, Matrix Computations,
    alg. 3.4.1: row k swapped with ``structure[k, 0]``); False if A is singular.

    Each elimination step visits only the rows whose entry in the pivot column is not zero and
    the columns where the pivot row is not: the other entries would change by an exact zero, so
    the factors are those of the dense elimination, in a fraction of its work on the sparse
    iteration matrix. ``structure`` (size, size + 3) keeps for :func:`lu_solve` each row k's
    (pivot row, count of non-zeros in U, count in L, the columns of those of U, then of L)."""
    size = A.shape[0]
    rows = np.empty(size, dtype=np.int64)
    for k in range(size):
        pivot, n_rows = k, 0
        for i in range(k + 1, size):
            if A[i, k] != 0.0:
                rows[n_rows] = i
                n_rows += 1
                if abs(A[i, k]) > abs(A[pivot, k]):
                    pivot = i
        structure[k, 0] = pivot
        if A[pivot, k] == 0.0:
            return False
        if pivot != k:  # row pivot, in the list, takes row k's entry (zero: a zero multiplier)
            for c in range(size):
                A[k, c], A[pivot, c] = A[pivot, c], A[k, c]
        n_columns = 0  # row k of U is final from here on
        for c in range(k + 1, size):
            if A[k, c] != 0.0:
                structure[k, 3 + n_columns] = c
                n_columns += 1
        structure[k, 1] = n_columns
        inverse = 1.0 / A[k, k]
        for r in range(n_rows):
            i = rows[r]
            A[i, k] *= inverse
            factor = A[i, k]
            if factor != 0.0:
                for j in range(3, 3 + n_columns):
                    A[i, structure[k, j]] -= factor * A[k, structure[k, j]]
    for i in range(size):  # the rows of L, final once the last swap is done
        start, n_lower = 3 + structure[i, 1], 0
        for c in range(i):
            if A[i, c] != 0.0:
                structure[i, start + n_lower] = c
                n_lower += 1
        structure[i, 2] = n_lower
    return True


@compiled
def lu_solve(LU, structure, b):
    """Solve A x = b in place of b with the factors and ``structure`` of :func:`lu_factor`
    (forward and back substitution over the non-zero entries, in the order of the dense
    loops)."""
    size = LU.shape[0]
    for k in range(size):
        p = structure[k, 0]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(size):
        start = 3 + structure[i, 1]
        for j in range(start, start + structure[i, 2]):
            b[i] -= LU[i, structure[i, j]] * b[structure[i, j]]
    for i in range(size - 1, -1, -1):
        for j in range(3, 3 + structure[i, 1]):
            b[i] -= LU[i, structure[i, j]] * b[structure[i, j]]
        b[i] /= LU[i, i]


@compiled
def _predictor_and_update(settings, h):
    """(P, w): the rows (q, q', q'', a)_{n+1} of the predictor are P @ (q, q', q'', a)_n
    (q''_{n+1} = q''_n, a_{n+1} from it); a Newton correction dq adds w dq to them."""
    alpha_m, alpha_f, gamma, beta = settings[0], settings[1], settings[2], settings[3]
    a_qdd, a_a = 1.0 / (1.0 - alpha_m), -alpha_m / (1.0 - alpha_m)  # a_{n+1} predicted
    predictor = np.array([
        [1.0, h, h * h * beta * a_qdd, h * h * (0.5 - beta + beta * a_a)],
        [0.0, 1.0, h * gamma * a_qdd, h * (1.0 - gamma + gamma * a_a)],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, a_qdd, a_a],
    ])
    beta_p = (1.0 - alpha_m) / ((1.0 - alpha_f) * beta * h * h)
    update = np.array([1.0, gamma / (beta * h), beta_p, beta_p * (1.0 - alpha_f) * a_qdd])
    return predictor, update


@compiled
def _factorize(data, settings, q, lam, jac, K, C, h, lu, structure):
    """LU of [[beta h^2 S_t, Phi_q^T], [Phi_q, 0]] (method notes) into ``lu``; False if
    singular."""
    alpha_m, alpha_f, gamma, beta = settings[0], settings[1], settings[2], settings[3]
    n, m = q.size, jac.shape[0]
    bh2 = beta * h * h
    mass_factor = (1.0 - alpha_m) / (1.0 - alpha_f)
    lu[n:, n:] = 0.0
    for r in range(n):
        for c in range(n):
            lu[r, c] = mass_factor * data.mass[r, c] - (gamma * h) * C[r, c] - bh2 * K[r, c]
    hessian = np.zeros(n)
    add_constraint_hessian(data.offset_rows, data.offset_columns, data.offset_u, q, lam, bh2,
                           hessian)
    for r in range(n):
        lu[r, r] += hessian[r]
        for c in range(m):
            lu[r, n + c] = jac[c, r]
            lu[n + c, r] = jac[c, r]
    return lu_factor(lu, structure)


@compiled
def _project_velocities(data, jac, qd, t):
    """The M-orthogonal projection of q' onto Phi_q q' + Phi_t = 0 through the Schur complement
    of the KKT system [[M, Phi_q^T], [Phi_q, 0]]: (Phi_q M^-1 Phi_q^T) mu = Phi_q q' + Phi_t,
    q' <- q' - M^-1 Phi_q^T mu; False if Phi_q has dependent rows."""
    weighted = jac @ data.inverse_mass
    schur = weighted @ jac.T
    mu = jac @ qd + data.c1
    add_prescribed(data.drives, t, 1, mu)
    structure = np.zeros((mu.size, mu.size + 3), dtype=np.int64)
    if not lu_factor(schur, structure):
        return False
    lu_solve(schur, structure, mu)
    qd -= mu @ weighted
    return True


@compiled
def _scaled_residual(data, qdd, jac, lam, Q, scale, out):
    """out[:n] = beta h^2 (M q'' + Phi_q^T lambda - Q) (``scale`` = beta h^2); M q'' over the
    non-zero entries of M (``data.mass_row_start``, ``mass_columns``), in the order of the dense
    product."""
    n = qdd.size
    for r in range(n):
        total = -Q[r]
        for k in range(data.mass_row_start[r], data.mass_row_start[r + 1]):
            c = data.mass_columns[k]
            total += data.mass[r, c] * qdd[c]
        for c in range(lam.size):
            total += jac[c, r] * lam[c]
        out[r] = scale * total


@compiled
def _correct(Y1, lam1, update, bh2, x):
    """Apply the Newton correction x = (dq, beta h^2 dlambda): (q, q', q'', a) -= w dq,
    lambda -= dlambda; return max |dq| (NaN if dq is not finite)."""
    n = Y1.shape[1]
    size, finite = 0.0, True
    for c in range(n):
        for row in range(4):
            Y1[row, c] -= update[row] * x[c]
        size = max(size, abs(x[c]))
        finite = finite and math.isfinite(x[c])
    for c in range(lam1.size):
        lam1[c] -= x[n + c] / bh2
    return size if finite else math.nan


@compiled
def _newton_arrays(n, m):
    """The arrays :func:`_newton` fills: (Q, dQ/dq, dQ/dq', Phi, Phi_q, the Newton right-hand
    side), made once per :func:`advance`."""
    return (np.zeros(n), np.zeros((n, n)), np.zeros((n, n)), np.zeros(m), np.zeros((m, n)),
            np.empty(n + m))


@compiled
def _newton(data, settings, t1, Y1, lam1, update, h, lu, structure, newton, counts, arrays):
    """Newton on (q, lambda) at t1 from the predicted Y1 (4, n), lam1 (in place), in the
    ``arrays`` of :func:`_newton_arrays`: (converged, the last Phi_q) (method notes: modified
    Newton)."""
    beta, tolerance = settings[3], settings[7]
    max_iterations, modified = settings[8], settings[11]
    n = Y1.shape[1]
    bh2 = beta * h * h
    full = not modified
    rebuild = full or newton[1] != 0.0 or h != newton[0]
    previous, first_full = math.inf, 1
    Q, K, C, phi, jac, x = arrays
    for iteration in range(1, max_iterations + 1):
        system_forces(data, Y1[0], Y1[1], t1, rebuild, Q, K, C)
        constraint_values_and_jacobian(data.D, data.c0, data.c1, data.offset_rows,
                                       data.offset_columns, data.offset_u, Y1[0], t1, phi, jac)
        add_prescribed(data.drives, t1, 0, phi)
        _scaled_residual(data, Y1[2], jac, lam1, Q, bh2, x)
        if rebuild:
            if not _factorize(data, settings, Y1[0], lam1, jac, K, C, h, lu, structure):
                return False, jac
            newton[0] = h
            counts[3] += 1
        x[n:] = phi
        lu_solve(lu, structure, x)
        size = _correct(Y1, lam1, update, bh2, x)
        counts[2] += 1
        if not math.isfinite(size):
            return False, jac
        if size < tolerance:
            newton[1] = 1.0 if iteration > 2 else 0.0
            return True, jac
        if not full and size > REUSE_CONTRACTION * previous:
            full, first_full = True, iteration + 1  # the reused matrix is too far off
        elif full and iteration >= first_full + 2 and size > 0.5 * previous:
            return False, jac  # not contracting (e.g. cycling in and out of contact): shorter step
        previous = size
        rebuild = full
    return False, jac


@compiled
def _control(data, settings, Y, Y1, h):
    """(accept, factor): the next step (if accepted) or the retry (if not) is factor * h.

    Rejects a step that enters contact deeper than the gap tolerance (retry aimed, by the
    secant on the gap, at half the tolerance) or whose local error estimate exceeds it; the
    next step grows with the error like h^3, by at most 2x."""
    tol = settings[6]
    factor = 2.0
    for j in range(data.joints.memory.shape[0]):
        error_m, gap_old, gap_new = step_error(data.joints, j, Y[0], Y[2], Y1[0], Y1[2], h)
        if gap_old <= 0.0 and gap_new > tol:
            secant = (0.5 * tol - gap_old) / (gap_new - gap_old)
            return False, min(0.9, max(0.02, secant))
        if max(gap_old, gap_new) <= 0.0:
            continue  # free flight: the steps are limited by step_s and the onset rule
        if error_m > tol:
            return False, max(0.1, 0.8 * (tol / error_m) ** (1.0 / 3.0))
        if error_m > 0.0:
            factor = min(factor, 0.9 * (tol / error_m) ** (1.0 / 3.0))
    return True, max(0.2, min(2.0, factor))


@compiled
def advance(data, settings, t, Y, lam, t_end, h, lu, structure, newton, counts, times, steps,
            rows_Y, rows_lam, rows_memory):
    """Step from (t, Y = (q, q', q'', a), lambda) (updated in place) towards t_end; record each
    accepted step in the row buffers while they last. Returns (status, t, next h, rows recorded).

    ``newton`` = (h of the factors in ``lu``, aged); ``counts`` = (steps, rejected, Newton
    iterations, factorizations, smallest step). A failed Newton retries with h / 4, a step the
    control rejects with its factor; the next step after an accepted one is factor * h (fixed
    steps of step_s without control or clearance joints)."""
    step_s, min_step_s, adaptive, project = settings[4], settings[5], settings[9], settings[10]
    controlled = adaptive and data.joints.memory.shape[0] > 0
    arrays = _newton_arrays(Y.shape[1], lam.size)
    recorded = 0
    while t < t_end - 1e-14:
        if recorded == times.size and times.size > 0:
            return BUFFER_FULL, t, h, recorded
        h = min(h, step_s, t_end - t)
        if t_end - t - h < 1e-6 * h:  # end on t_end: no sliver step of rounding's size left
            h = t_end - t
        predictor, update = _predictor_and_update(settings, h)
        Y1, lam1 = predictor @ Y, lam.copy()
        accept, jac = _newton(data, settings, t + h, Y1, lam1, update, h, lu, structure, newton,
                              counts, arrays)
        factor = 0.25
        if accept and controlled:
            accept, factor = _control(data, settings, Y, Y1, h)
        if not accept:
            h *= factor
            counts[1] += 1
            if h < min_step_s:
                return STEP_TOO_SMALL, t, h, recorded
            continue
        if project and lam.size and not _project_velocities(data, jac, Y1[1], t + h):
            return SINGULAR_PROJECTION, t, h, recorded
        for j in range(data.joints.memory.shape[0]):
            end_step(data.joints, j, Y1[0], Y1[1])
        t += h
        Y[:] = Y1
        lam[:] = lam1
        counts[0] += 1
        counts[4] = min(counts[4], h)
        if times.size > 0:
            times[recorded], steps[recorded] = t, h
            rows_Y[recorded], rows_lam[recorded] = Y, lam
            rows_memory[recorded] = data.joints.memory
            recorded += 1
        h = max(h * factor if controlled else step_s, min_step_s)
    return DONE, t, h, recorded
