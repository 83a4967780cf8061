"""Generalized-alpha for the index-3 DAE  M q'' + Phi_q^T lambda = Q(q, q', t), Phi(q, t) = 0.

Chung & Hulbert (J. Appl. Mech. 60, 1993) parameters from the spectral radius at infinity:
alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
beta = (gamma + 1/2)^2 / 4. Constrained form of Arnold & Brüls (Multibody Syst. Dyn. 18, 2007):
the equations hold at t_{n+1}; the acceleration-like variable ``a`` obeys
(1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) q''_{n+1} + alpha_f q''_n,
q_{n+1} = q_n + h q'_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
q'_{n+1} = q'_n + h (1 - gamma) a_n + h gamma a_{n+1}.
Newton on (q_{n+1}, lambda_{n+1}) with q' and q'' following from q: dq' = gamma/(beta h) dq,
dq'' = (1 - alpha_m)/((1 - alpha_f) beta h^2) dq. The iteration matrix is
[[beta h^2 S_t, Phi_q^T], [Phi_q, 0]] on (dq, beta h^2 dlambda): the equations of motion are
multiplied by beta h^2, which is the same as scaling the constraint rows by 1/(beta h^2) (Arnold &
Brüls sec. 3.3) and makes the matrix's condition independent of h. S_t = M beta' - dQ/dq' gamma'
- dQ/dq + d(Phi_q^T lambda)/dq, all analytic.

Optional velocity projection (on by default): after each step q' is projected M-orthogonally
onto Phi_q q' + Phi_t = 0. Index-3 generalized-alpha leaves an O(h^2) drift in the velocity
constraint; the projection removes it (a driven mechanism then has exact velocities) and keeps the
scheme second order.

Newton variants (``modified_newton``). Full Newton builds and factorises the iteration matrix in
every iteration. Modified Newton (the default, as in Exudyn) keeps the LU factors of the last
matrix, across iterations and across steps, and only re-evaluates the residual: what is reused
is the whole matrix, i.e. M, the force elements' dQ/dq and dQ/dq', Phi_q and the constraint
Hessian (at the q, q', lambda where it was built), and h through beta h^2 (so a change of step size
forces a rebuild). It is rebuilt at the first iteration of a step when there is none, h changed
or the previous step needed more than two iterations (the matrix has aged: one correction after
the predictor's no longer meets the tolerance); and when a correction shrinks by less than the
factor ``REUSE_CONTRACTION`` against the previous one, the rest of the step runs as full Newton.
The residual and the constraints are always evaluated exactly at the current iterate, so the
converged state solves the same equations; the test max |dq| < newton_tolerance stays meaningful
because a reused matrix is only kept while the iteration contracts by at least 1/4 per
iteration, so the error left after the last correction is below |dq| / 3. Full Newton rejects the
step when its corrections stop contracting (the step is retried shorter).

Step-size control (adaptive mode): force elements may offer ``step_error`` returning an estimate of
the local error of a contact gap (m) and whether the step entered contact too deep; the step is
rejected and retried shorter when the estimate exceeds the tolerance. See
:class:`fewear.mbd.clearance.ClearanceJoint` for the estimate used. Such elements follow the
steps: ``begin_step(q, q')`` at the initial state, ``end_step(q, q')`` after each accepted step
(which is where the next step begins).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import lapack

from fewear.errors import FewearInputError

REUSE_CONTRACTION = 0.25  # modified Newton: rebuild when |dq| shrinks by less than this


def lu_solve(factors, rhs):
    """Solve with the LU factors (lu, pivots) of LAPACK's dgetrf (in place of ``rhs`` when it is a
    contiguous float array)."""
    x, _ = lapack.dgetrs(*factors, rhs, overwrite_b=True)
    return x


@dataclass(frozen=True)
class IntegratorSettings:
    """Generalized-alpha and step-size parameters (SI units).

    step_s: the (largest) time step; min_step_s: the smallest the controller may take;
    adaptive: step-size control around impacts (else fixed steps of step_s);
    gap_tolerance_m: allowed local error of a contact gap and the deepest allowed first penetration;
    newton_tolerance: convergence when max |dq| < it (m or rad or dimensionless slopes);
    modified_newton: reuse the factorised iteration matrix (module docstring).
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
        n, m = system.n_coordinates, system.n_constraints
        self._matrix = np.zeros((n + m, n + m))
        self._diagonal = np.arange(n)
        self._controlled = [e for e in system.force_elements if hasattr(e, "step_error")]
        self._alpha_m, self._alpha_f, self._gamma, self._beta = settings.coefficients
        # the constant block of the iteration matrix, (1 - alpha_m)/(1 - alpha_f) M
        self._mass_term = ((1.0 - self._alpha_m) / (1.0 - self._alpha_f)) * system.mass
        self._factors = None  # (lu, pivots) of the last iteration matrix
        self._factors_step_s = math.nan  # the h it was built for
        self._aged = True  # rebuild at the next step's first iteration
        self._scheme = (math.nan, None, None)  # (h, predictor, update) of the last step size

    def initial_state(self, q0, qd0, t0: float = 0.0) -> State:
        """A state with consistent accelerations and multipliers (q0, qd0 must be consistent)."""
        q0 = np.asarray(q0, dtype=float).copy()
        qd0 = np.asarray(qd0, dtype=float).copy()
        for element in self._controlled:
            element.begin_step(q0, qd0)
        qdd0, lam0 = self.system.consistent_accelerations(q0, qd0, t0)
        return State(t0, q0, qd0, qdd0, qdd0.copy(), lam0)

    def _predictor_and_update(self, h: float):
        """(P, w): the rows (q, q', q'', a)_{n+1} of the predictor are P @ (q, q', q'', a)_n
        (q''_{n+1} = q''_n, a_{n+1} from it); a Newton correction dq adds w dq to them."""
        alpha_m, alpha_f, gamma, beta = self._alpha_m, self._alpha_f, self._gamma, self._beta
        a_qdd, a_a = 1.0 / (1.0 - alpha_m), -alpha_m / (1.0 - alpha_m)  # a_{n+1} predicted
        predictor = np.array([
            [1.0, h, h * h * beta * a_qdd, h * h * (0.5 - beta + beta * a_a)],
            [0.0, 1.0, h * gamma * a_qdd, h * (1.0 - gamma + gamma * a_a)],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, a_qdd, a_a],
        ])
        beta_p = (1.0 - alpha_m) / ((1.0 - alpha_f) * beta * h * h)
        update = np.array([1.0, gamma / (beta * h), beta_p, beta_p * (1.0 - alpha_f) * a_qdd])
        return predictor, update[:, None]

    def step(self, s: State, h: float) -> State | None:
        """One generalized-alpha step of size h; None if Newton does not converge."""
        sys_, st = self.system, self.settings
        n = sys_.n_coordinates
        t1 = s.t + h
        if h != self._scheme[0]:
            self._scheme = (h, *self._predictor_and_update(h))
        _, predictor, update = self._scheme
        Y = predictor @ np.array([s.q, s.qd, s.qdd, s.a])
        q1, qd1, qdd1, a1 = Y
        lam1 = s.lam.copy()
        bh2 = self._beta * h * h
        full = not st.modified_newton
        rebuild = full or self._aged or h != self._factors_step_s
        previous, first_full = math.inf, 1
        x = np.empty(n + sys_.n_constraints)  # (beta h^2 residual, Phi), solved in place
        for iteration in range(1, st.max_newton_iterations + 1):
            Q, K, C = sys_.forces(q1, qd1, t1, jacobian=rebuild)
            phi, jac = sys_.constraint_values_and_jacobian(q1, t1)
            residual = sys_.mass @ qdd1 + jac.T @ lam1 - Q
            if rebuild and not self._factorize(q1, lam1, jac, K, C, h):
                return None
            np.multiply(residual, bh2, out=x[:n])
            x[n:] = phi
            x = lu_solve(self._factors, x)
            dq = x[:n]
            Y -= update * dq
            lam1 -= x[n:] / bh2
            self.stats.newton_iterations += 1
            size = np.abs(dq).max()
            if not math.isfinite(size):
                return None
            if size < st.newton_tolerance:
                break
            if not full and size > REUSE_CONTRACTION * previous:
                full, first_full = True, iteration + 1  # the reused matrix is too far off
            elif full and iteration >= first_full + 2 and size > 0.5 * previous:
                return None  # not contracting (e.g. cycling in and out of contact): shorter step
            previous = size
            rebuild = full
        else:
            return None
        self._aged = iteration > 2
        if st.project_velocities and sys_.n_constraints:
            qd1 = sys_.project_velocities(q1, qd1, t1, jac)
        return State(t1, q1, qd1, qdd1, a1, lam1)

    def _factorize(self, q, lam, jac, K, C, h) -> bool:
        """LU of [[beta h^2 S_t, Phi_q^T], [Phi_q, 0]] (module docstring); False if singular."""
        sys_ = self.system
        n = sys_.n_coordinates
        bh2 = self._beta * h * h
        A = self._matrix
        A[:n, :n] = self._mass_term
        if C is not None:
            A[:n, :n] -= (self._gamma * h) * C
        if K is not None:
            A[:n, :n] -= bh2 * K
        A[self._diagonal, self._diagonal] += bh2 * sys_.constraint_hessian(q, lam)
        A[:n, n:] = jac.T
        A[n:, :n] = jac
        lu, pivots, info = lapack.dgetrf(A)
        if info != 0:
            return False
        self._factors, self._factors_step_s = (lu, pivots), h
        self.stats.factorizations += 1
        return True

    def run(self, state: State, t_end: float, observer=None) -> State:
        """Integrate from ``state`` to ``t_end``; call ``observer(state, h)`` after every step."""
        st = self.settings
        h = self.stats.extra.get("next_step_s", st.step_s)
        start = time.perf_counter()
        while state.t < t_end - 1e-14:
            h = min(h, st.step_s, t_end - state.t)
            new = self.step(state, h)
            if new is None:
                h = self._shrink(h, 0.25, state.t)
                self.stats.rejected += 1
                continue
            h_next = st.step_s
            if st.adaptive and self._controlled:
                accept, factor = self._control(state, new, h)
                if not accept:
                    h = self._shrink(h, factor, state.t)
                    self.stats.rejected += 1
                    continue
                h_next = h * factor
            for element in self._controlled:
                element.end_step(new.q, new.qd)
            state = new
            self.stats.steps += 1
            self.stats.smallest_step_s = min(self.stats.smallest_step_s, h)
            if observer is not None:
                observer(state, h)
            h = max(h_next, st.min_step_s)
        self.stats.extra["next_step_s"] = h
        self.stats.wall_time_s += time.perf_counter() - start
        return state

    def _shrink(self, h: float, factor: float, t: float) -> float:
        h_new = h * factor
        if h_new < self.settings.min_step_s:
            raise RuntimeError(
                f"generalized-alpha: step size fell below min_step_s = "
                f"{self.settings.min_step_s:g} s at t = {t:.6g} s")
        return h_new

    def _control(self, old: State, new: State, h: float) -> tuple[bool, float]:
        """(accept, factor): the next step (if accepted) or the retry (if not) is factor * h.

        Rejects a step that enters contact deeper than the gap tolerance (retry aimed, by the
        secant on the gap, at half the tolerance) or whose local error estimate exceeds it; the
        next step grows with the error like h^3, by at most 2x."""
        tol = self.settings.gap_tolerance_m
        factor = 2.0
        for element in self._controlled:
            error_m, gap_old, gap_new = element.step_error(old.q, old.qdd, new.q, new.qdd, h)
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
