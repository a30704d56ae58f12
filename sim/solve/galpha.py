"""Generalized-α: one implicit step of the constrained equations of motion.

The index-3 form of Arnold & Brüls (Multibody Syst. Dyn. 18, 2007) of the
generalized-α method of Chung & Hulbert (J. Appl. Mech. 60, 1993): at
t_{n+1} = t_n + h it solves

    M q̈ + Φ_qᵀ λ = Q(q, q̇, t)        (Q: gravity, contact, −elastic, −damping)
    Φ(q, t) = 0                       (position level: no drift, no Baumgarte)

with Newmark's relations through the pseudo-acceleration a,
    (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) q̈_{n+1} + α_f q̈_n,
    q_{n+1} = q_n + h q̇_n + h² ((½ − β) a_n + β a_{n+1}),
    q̇_{n+1} = q̇_n + h ((1 − γ) a_n + γ a_{n+1}),
and the parameters from the spectral radius at infinity ρ∞ ∈ [0, 1]
(`solver.rho_inf`): α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1),
γ = ½ − α_m + α_f, β = ¼ (1 − α_m + α_f)². Second order; modes with ω h ≫ 1
(the axial modes of short stiff beam elements) are damped by the factor ρ∞
per step, the motion of interest (ω h ≪ 1) is not.

Newton on (q_{n+1}, λ_{n+1}) with the iteration matrix, scaled by β h² so
that its blocks are of one order (Arnold & Brüls, sec. 4):

    [ M (1 − α_m)/(1 − α_f) + γ h C_t + β h² K_t   Φ_qᵀ ] [ Δq       ]   [ −β h² r ]
    [ Φ_q                                           0    ] [ β h² Δλ ] = [ −Φ      ]

with r = M q̈ + Φ_qᵀ λ − Q, K_t = −∂Q/∂q and C_t = −∂Q/∂q̇ (`sim.solve.tangent`):
simplified Newton, the factors kept from step to step while Newton converges
with them (Hairer & Wanner, Solving ODEs II, IV.8), convergence judged on the
residual, or on the residual the last contraction foresees (FORESEEN_TOL).
What is reported (accelerations, torque, contact outputs) comes from the
equations of motion solved at each step's end, not from the method's own q̈ and
λ, with the step's velocities first projected onto Φ_q q̇ = ν: in the index-3
form they satisfy it only to the position tolerance times γ/(β h), which the
very short steps after a contact event turn into m/s.

Step control: the local error of q is estimated as (β − 1/6) h² (q̈_{n+1} − q̈_n)
(Zienkiewicz & Xie, Earthquake Eng. Struct. Dyn. 20, 1991; Géradin & Cardona,
Flexible Multibody Dynamics, 2001, ch. 11), of order h³. The continuous
extension over the step is the cubic Hermite interpolant of (q, q̇) and (q̇, q̈).
The drive work is integrated by the trapezoidal rule, the dissipated energy by
Simpson's, whose difference from the trapezoid is a third error estimate.
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel, kernel_inline, spliced
from sim.model.clearance import gap
from sim.model.constraints import constraint_terms
from sim.model.gaps import MEM_GRAZED, MEM_IN_CONTACT
from sim.solve.control import ERR_MIN
from sim.solve.dae import (
    block_times,
    dissipated_power,
    factor_schur,
    factored_accelerations,
    generalized_forces,
    kinetic_energy,
    no_rotations,
    project_velocities,
)
from sim.solve.dense import hermite_coefficients, interpolate
from sim.solve.linalg import (
    lu_in_place,
    lu_solve_in_place,
    pattern_lu_in_place,
    pattern_lu_solve_in_place,
)
from sim.solve.means import next_window_end
from sim.solve.record import write_row
from sim.solve.state import next_sample
from sim.solve.status import OK, SINGULAR
from sim.solve.tangent import iteration_matrix

MAX_NEWTON = 20
"""Newton iterations per step before the step is retried shorter."""
NEWTON_TOL = 0.1
"""Newton stops when the residual is below this share of the tolerance (the κ of
Hairer & Wanner, 0.01–0.1). The residual, not the correction of q, is tested:
q̈ and λ follow from q with a factor 1/(β h²), so a q converged to a share of
atol can leave forces and accelerations wrong by tens of newtons."""
FORESEEN_TOL = 0.01
"""Newton also stops, without evaluating the residual at the new iterate, when the residual
that iterate will have, foreseen from the contraction θ of the last iteration as
θ/(1 − θ) times the last residual (Hairer & Wanner, Solving ODEs II, IV.8, eq. 8.10), is
below this share of the tolerance: a tenth of NEWTON_TOL, because the contraction slows as the
residual nears the beams' round-off floor. On the flexible flagship it saves 0.6 of the 3.8
residuals a step, and of the iterates it accepts 1 % would have missed NEWTON_TOL
(by 6 × at most), none the tolerance."""
ROUNDOFF = 1e-14
"""Relative size of a Newton correction of q that is round-off (float64 ε ≈ 2e-16
times the condition of the iteration matrix's scaled q block)."""
STALL = 1e-10
"""Relative correction below which a residual that stops falling is taken as
stalled at its round-off floor, not as diverging: iterate on to ROUNDOFF."""
SLOW = 0.3
"""Contraction of the residual per iteration above which the iteration matrix is
re-formed at the current iterate: a matrix formed before a contact closed lacks
the contact's stiffness and damping, and simplified Newton then crawls (measured
0.85 per iteration on the 30 rpm six-bar) or diverges."""
MAX_REFRESH = 8
"""Iteration matrices re-formed within one Newton solve before the step is retried shorter."""
SLOW_ITERATIONS = 3
"""Newton iterations of an accepted step beyond which the iteration matrix is re-formed at
the next step: the kept matrix no longer describes the forces well."""
SAFE = 0.9
"""Safety factor of the step-size ratio: aim below the tolerance so that the next step is
rarely rejected."""
ERROR_ORDER = 3.0
"""Order in h of the local error estimate of q (the step-size ratio is err^(−1/ERROR_ORDER))."""
GROWTH = 2.0
"""The only growth of the step: by this factor, when the error allows it (`step_factor`)."""
PLAN_ROUNDOFF = 1e-9
"""Relative round-off in the number of equal steps to the next sample: a ratio a hair above
a whole number must not add a step."""
GRAZE_PROBES = (0.25, 0.5, 0.75)
"""Fractions of a step at which the continuous extension is probed for a graze."""


class Carry(NamedTuple):
    """What a step hands to the next besides the trajectory: the start data, valid while
    clock.started, and the Newton factors, kept while it_fresh; and the method's own
    scratch: the step's end values (made the start data by `accept`) and Newton's
    right-hand side."""

    derivative: np.ndarray  # (2n + 2,) ẏ at (t, y): k0 of the energy quadratures
    acc: np.ndarray  # (n,) pseudo-acceleration a_n
    xdd: np.ndarray  # (n,) the method's own q̈_n
    lam: np.ndarray  # (m,) multipliers λ_n
    it_mat: np.ndarray  # (n + m, n + m) Newton iteration matrix, then its LU factors
    it_piv: np.ndarray  # (n + m,) their row exchanges, when pivoted
    it_pivoted: np.ndarray  # (1,) 1 when the factors are partial pivoting's, else 0
    it_fresh: np.ndarray  # (1,) 1 while the factors are usable, else 0
    acc_new: np.ndarray  # (n,) scratch: a_{n+1} at the step's end
    xdd_new: np.ndarray  # (n,) scratch: the method's own q̈_{n+1}
    lam_new: np.ndarray  # (m,) scratch: λ_{n+1}
    newton_rhs: np.ndarray  # (n + m,) scratch: Newton's right-hand side, then the correction


def make_carry(n: int, m: int) -> Carry:
    """The carry of a system of n coordinates and m constraints, its factors not yet formed."""
    return Carry(
        derivative=np.zeros(2 * n + 2),
        acc=np.zeros(n),
        xdd=np.zeros(n),
        lam=np.zeros(m),
        it_mat=np.zeros((n + m, n + m)),
        it_piv=np.zeros(n + m, dtype=np.int64),
        it_pivoted=np.zeros(1),
        it_fresh=np.zeros(1),
        acc_new=np.zeros(n),
        xdd_new=np.zeros(n),
        lam_new=np.zeros(m),
        newton_rhs=np.zeros(n + m),
    )


@kernel_inline
def coefficients(rho_inf: float) -> tuple[float, float, float, float]:
    """(α_m, α_f, β, γ) of Chung & Hulbert for the spectral radius ρ∞."""
    am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
    af = rho_inf / (rho_inf + 1.0)
    gamma = 0.5 - am + af
    beta = 0.25 * (1.0 - am + af) ** 2
    return am, af, beta, gamma


@kernel_inline
def start(sys, work, carry) -> None:
    """Start from the evaluation at (t, y) (ẏ in carry.derivative, λ in work.rhs):
    a_0 = q̈_0."""
    n = sys.n
    for i in range(n):
        carry.acc[i] = carry.derivative[n + i]
        carry.xdd[i] = carry.derivative[n + i]
    for r in range(sys.m):
        carry.lam[r] = work.rhs[r]


@kernel_inline
def accept(sys, work, carry) -> None:
    """Make the step just computed the start of the next: a_n, q̈_n, λ_n."""
    for i in range(carry.acc.shape[0]):
        carry.acc[i] = carry.acc_new[i]
        carry.xdd[i] = carry.xdd_new[i]
    for r in range(carry.lam.shape[0]):
        carry.lam[r] = carry.lam_new[r]


@kernel_inline
def plan(t: float, h: float, t_end: float, buffers, tally) -> float:
    """The step to take from t given the step size h the controller wants: equal steps
    to the next sample, window end or t_end, none longer than h. Samples record the step's
    own state (`sample`), so steps end on them; an interval mean takes the velocities at its
    window's ends (`sim.solve.means`), so steps end there too: the method's continuous
    extension, a cubic through the step's ends, carries vibration the steps do not resolve."""
    boundary = min(next_sample(t, buffers, tally), next_window_end(t, buffers.means, buffers.out_t))
    left = min(t_end, boundary) - t
    return left / np.ceil(left / h * (1.0 - PLAN_ROUNDOFF))


@kernel_inline
def mark_grazes(sys, work, mem) -> None:
    """Mark MEM_GRAZED every open gap that the step's continuous extension penetrates
    at GRAZE_PROBES. The Newton iterates are not points of the motion (an iterate that
    overshoots into a wall says nothing about the motion), so the marks they left are
    cleared first."""
    n = sys.n
    for g in range(mem.shape[0]):
        mem[g, MEM_GRAZED] = 0.0
    for theta in GRAZE_PROBES:
        interpolate(work, theta, 2 * n, work.yint)
        for g in range(mem.shape[0]):
            if (
                mem[g, MEM_IN_CONTACT] == 0.0
                and gap(sys, g, work.yint[:n], work.yint[n : 2 * n])[0] > 0.0
            ):
                mem[g, MEM_GRAZED] = 1.0


@kernel
def sample(sys, work, mem, t0: float, h: float, time: float, row: np.ndarray) -> int:
    """Record the sample at `time`, the step's end (`plan`), from the step's own state,
    accelerations and multipliers: accelerations evaluated afresh at an interpolated state
    would carry its interpolation error times the beams' axial stiffness."""
    write_row(sys, work, work.ynew, row)
    return OK


@kernel_inline
def _scaled_rms(x: np.ndarray, ref0: np.ndarray, ref1: np.ndarray, rtol: float, atol: float):
    """RMS of x_i / (atol + rtol max(|ref0_i|, |ref1_i|))."""
    total = 0.0
    for i in range(x.shape[0]):
        sc = atol + rtol * max(abs(ref0[i]), abs(ref1[i]))
        total += (x[i] / sc) ** 2
    return np.sqrt(total / x.shape[0])


@spliced
def _residual(sys, work, carry, mem, t, q, v, xdd, lam, bh2, rtol, atol) -> float:
    """The scaled Newton right-hand side into carry.newton_rhs, −β h² r and −Φ, with
    r = M q̈ + Φ_qᵀ λ − Q, from a fresh evaluation at (t, q, v); returns the size
    of the residual against the tolerance: force rows against rtol times the
    size of the terms they balance (a floor of 1e-3 of the largest keeps rows
    that balance nothing from demanding round-off; the beams' round-off is a
    floor too), constraint rows against atol."""
    n = sys.n
    m = sys.m
    x = carry.newton_rhs
    generalized_forces(sys, work, t, q, v, mem, no_rotations(work))
    constraint_terms(sys, t, q, v, work.phi, work.jac, work.gamma, work.nu)
    block_times(sys, sys.mass, xdd, work.scratch)
    largest = 0.0
    for i in range(n):
        inertia = work.scratch[i]
        reaction = 0.0
        for r in range(m):
            reaction += work.jac[r, i] * lam[r]
        x[i] = -bh2 * (inertia + reaction - work.gen[i])
        scale = abs(inertia) + abs(reaction) + abs(work.gen[i])
        work.scratch[i] = scale
        largest = max(largest, scale)
    # Round-off floor of the elastic forces: EA ε with ε = (r'·r' − 1)/2 is known
    # to about 1e-16 (with a margin of 100), whatever the tolerance asks.
    floor = 0.0
    for b in range(sys.beam_off.shape[0]):
        floor = max(floor, 1e-14 * sys.beam[b].ea)
    total = 0.0
    for i in range(n):
        total += (x[i] / (bh2 * (rtol * (work.scratch[i] + 1e-3 * largest) + floor) + 1e-300)) ** 2
    for r in range(m):
        x[n + r] = -work.phi[r]
        total += (work.phi[r] / atol) ** 2
    return np.sqrt(total / (n + m))


@spliced
def _factor(sys, work, carry, mem, t, q, v, am, af, beta, gamma, h) -> bool:
    """The iteration matrix at (t, q, v) into carry.it_mat and its LU factors: over its
    pattern of nonzeros without row exchanges (work.newton_lu), or, where a pivot fails
    there, by partial pivoting of the matrix assembled again (carry.it_pivoted then 1).
    False when the matrix is singular."""
    c_m, c_c, c_k = (1.0 - am) / (1.0 - af), gamma * h, beta * h * h
    iteration_matrix(sys, work, carry.it_mat, mem, t, q, v, c_m, c_c, c_k)
    carry.it_pivoted[0] = 0.0
    if pattern_lu_in_place(carry.it_mat, work.newton_lu):
        return True
    iteration_matrix(sys, work, carry.it_mat, mem, t, q, v, c_m, c_c, c_k)
    carry.it_pivoted[0] = 1.0
    return lu_in_place(carry.it_mat, carry.it_piv)


@kernel
def _newton(sys, work, carry, mem, t, h, y, rtol, atol, rho_inf, factor: bool):
    """Predict the state at t + h, then correct it by simplified Newton with the
    factors in carry.it_mat, refreshed first when `factor` and again at the
    current iterate whenever the residual contracts by less than SLOW (at most
    MAX_REFRESH matrices), until the residual of the equations of motion and
    constraints is within NEWTON_TOL of the tolerance, or foreseen within FORESEEN_TOL.
    Returns (status, converged, force evaluations, iteration matrices, solves, evaluated):
    evaluated when work holds the evaluation at the new state, which a foreseen
    convergence does not make."""
    n = sys.n
    m = sys.m
    am, af, beta, gamma = coefficients(rho_inf)
    q = work.ynew[:n]
    v = work.ynew[n : 2 * n]
    xdd = carry.xdd_new
    x_old = carry.xdd
    lam = carry.lam_new
    # Predictor: the acceleration carried over.
    for i in range(n):
        a_old = carry.acc[i]
        xdd[i] = x_old[i]
        a_new = ((1.0 - af) * xdd[i] + af * x_old[i] - am * a_old) / (1.0 - am)
        v[i] = y[n + i] + h * ((1.0 - gamma) * a_old + gamma * a_new)
        q[i] = y[i] + h * y[n + i] + h * h * ((0.5 - beta) * a_old + beta * a_new)
    for r in range(m):
        lam[r] = carry.lam[r]
    tn = t + h
    bh2 = beta * h * h
    v_per_q = gamma / (beta * h)
    a_per_q = (1.0 - am) / (bh2 * (1.0 - af))
    x = carry.newton_rhs
    matrices = 0
    previous = np.inf
    largest = np.inf
    roundoff = False
    for it in range(MAX_NEWTON + 1):
        size = _residual(sys, work, carry, mem, tn, q, v, xdd, lam, bh2, rtol, atol)
        if size <= NEWTON_TOL or roundoff:
            return OK, True, it + 1, matrices, it, True
        if it == MAX_NEWTON or not np.isfinite(size):
            break
        refresh = factor and it == 0
        if size > SLOW * previous and not largest < STALL:
            # Crawling or diverging, and not merely stalled at round-off: the matrix
            # no longer describes the forces (a contact closed or opened since).
            if matrices >= MAX_REFRESH:
                break
            refresh = True
        # θ of the last iteration, a guide to this one's only with the same matrix
        theta = size / previous if it > 0 and not refresh else 1.0
        previous = size
        if refresh:
            matrices += 1
            carry.it_fresh[0] = 1.0
            if not _factor(sys, work, carry, mem, tn, q, v, am, af, beta, gamma, h):
                carry.it_fresh[0] = 0.0
                return SINGULAR, False, it + 1, matrices, it, True
        if carry.it_pivoted[0] > 0.0:
            lu_solve_in_place(carry.it_mat, carry.it_piv, x)
        else:
            pattern_lu_solve_in_place(carry.it_mat, work.newton_lu, x)
        for i in range(n):
            q[i] += x[i]
            v[i] += v_per_q * x[i]
            xdd[i] += a_per_q * x[i]
        largest = 0.0
        for i in range(n):
            largest = max(largest, abs(x[i]) / (abs(q[i]) + atol))
        for r in range(m):
            lam[r] += x[n + r] / bh2
        if theta < 1.0 and theta / (1.0 - theta) * size <= FORESEEN_TOL:
            return OK, True, it + 1, matrices, it + 1, False
        # A correction at the round-off of q ends the iteration: the residual of
        # very stiff beams (EA ε with ε near 1e-16) cannot fall further.
        roundoff = largest < ROUNDOFF
    return OK, False, it + 1, matrices, it, True


@kernel
def step(sys, work, carry, mem, t: float, h: float, y: np.ndarray, options, tally):
    """`_step`, its force evaluations, iteration matrices and Newton failures counted in
    tally. Returns (status, error estimate scaled to the tolerance)."""
    s, err, evaluations, jacobians = _step(
        sys, work, carry, mem, t, h, y, options.rtol, options.atol, options.method.rho_inf
    )
    tally.evaluations += evaluations
    tally.jacobians += jacobians
    if s == OK and not np.isfinite(err):
        tally.newton_failures += 1
    return s, err


@spliced
def _step(sys, work, carry, mem, t: float, h: float, y: np.ndarray, rtol, atol, rho_inf):
    """One step from (t, y), ẏ in carry.derivative, a_n, q̈_n and λ_n in carry: the new
    state into work.ynew, its derivative into work.ydot_end, the Hermite
    extension into work.dense. Returns (status, error scaled to the tolerance,
    force evaluations, iteration matrices); an error of ∞ when Newton fails.

    The iteration matrix is kept from step to step while Newton converges with
    it (its h-dependent terms are small at the short steps contacts force), and
    refreshed when it does not: a stale matrix slows convergence, it never
    changes the converged solution. A Newton that fails with a kept matrix is
    tried once more at the same h from a matrix formed at the predictor, before
    the step is rejected. That retry is not redundant with the refreshes inside
    Newton: measured without it on the rigid six-bar (A and B at 0.5 mm, 20/30/40
    rpm, 400/1000/3000 samples per revolution, rtol 1e-7 and 1e-8, a quarter
    revolution), 9 of 18 runs ended with an energy audit 4 to 1250 times worse
    (up to 2.5e-2, against at most 2.0e-5 with it): after a contact, steps grown
    long in free flight carried a kinetic energy error alternating from step to
    step (the index-3 method's decaying (−ρ∞)ⁿ mode) that the error estimate of
    q does not see. On the flexible flagship the retry costs 4 % of the run."""
    n = sys.n
    fresh = carry.it_fresh[0] > 0.0
    s, converged, evaluations, jacobians, iterations, evaluated = _newton(
        sys, work, carry, mem, t, h, y, rtol, atol, rho_inf, not fresh
    )
    if s == OK and not converged and fresh:
        # factor = fresh, which is True here: a literal True would compile a second _newton
        s, converged, more, more_jacobians, iterations, evaluated = _newton(
            sys, work, carry, mem, t, h, y, rtol, atol, rho_inf, fresh
        )
        evaluations += more
        jacobians += more_jacobians
    if s != OK or not converged:
        return s, np.inf, evaluations, jacobians
    if iterations > SLOW_ITERATIONS:
        carry.it_fresh[0] = 0.0  # converging slowly: refresh at the next step
    am, af, beta, _ = coefficients(rho_inf)
    for i in range(n):
        a_old = carry.acc[i]
        carry.acc_new[i] = ((1.0 - af) * carry.xdd_new[i] + af * carry.xdd[i] - am * a_old) / (
            1.0 - am
        )
    # What is reported and carried on (accelerations, drive torque, powers, the
    # derivative for the continuous extension) comes from the equations of
    # motion solved at the new state, not from the method's q̈ and λ: in the
    # index-3 form those carry a spurious oscillation that the position-level
    # constraints hide from q and q̇ (Arnold & Brüls 2007, sec. 4).
    # Newton's last evaluation, when `evaluated`, was at the new state: its forces and
    # constraint terms are in work. Its velocities satisfy Φ_q q̇ = ν only as far as the
    # position-level constraints were converged, times γ/(β h): after a contact
    # event, at h of 1e-9 s, that is an error of 0.1-1 m/s, a kinetic energy
    # tripled for a few steps and a lasting error in the energy audit. They are
    # projected onto the velocity constraints, and the velocity-dependent
    # forces (contact damping, friction, beam damping, the γ of Φ_q q̈) are
    # evaluated again with them.
    k0 = carry.derivative
    k6 = work.ydot_end
    yn = work.ynew
    if sys.m > 0:
        if not evaluated:  # the projection's Φ_q and ν at the new state
            constraint_terms(
                sys, t + h, yn[:n], yn[n : 2 * n], work.phi, work.jac, work.gamma, work.nu
            )
        if factor_schur(sys, work) != OK:
            return SINGULAR, np.inf, evaluations, jacobians
        project_velocities(sys, work, yn[n : 2 * n])
        generalized_forces(sys, work, t + h, yn[:n], yn[n : 2 * n], mem, no_rotations(work))
        constraint_terms(sys, t + h, yn[:n], yn[n : 2 * n], work.phi, work.jac, work.gamma, work.nu)
        evaluations += 1
    elif not evaluated:
        generalized_forces(sys, work, t + h, yn[:n], yn[n : 2 * n], mem, no_rotations(work))
        evaluations += 1
    s = factored_accelerations(sys, work, yn[n : 2 * n], k6)
    if s != OK:
        return s, np.inf, evaluations, jacobians
    hermite_coefficients(work, y, k0, h)
    err_energy = _energy_quadratures(sys, work, mem, h, y, k0, rtol, atol)
    evaluations += 1  # the midpoint's dissipated power, a partial evaluation
    # Local error of q: (β − 1/6) h² (q̈_{n+1} − q̈_n), in work.scratch.
    for i in range(n):
        work.scratch[i] = (beta - 1.0 / 6.0) * h * h * (k6[n + i] - k0[n + i])
    err_q = _scaled_rms(work.scratch, y[:n], yn[:n], rtol, atol)
    return OK, max(err_q, err_energy), evaluations, jacobians


@spliced
def _energy_quadratures(sys, work, mem, h: float, y: np.ndarray, k0, rtol, atol) -> float:
    """The drive work (trapezoidal rule) and the dissipated energy (Simpson's rule,
    the midpoint state from the Hermite extension) over the step into work.ynew;
    returns the dissipated energy's quadrature error, |Simpson − trapezoid|,
    against atol + rtol T (J, T the kinetic energy at the step's end).

    Why: contact damping with a small onset rate is a very stiff damper. The
    motion passes it stably in a long implicit step, but its power can peak at
    a step's end, and a trapezoid over such a step books a large, false energy.
    The estimate rejects such steps. Only the dissipative forces are evaluated
    at the midpoint, aside, so work keeps the evaluation at the step's end
    (forces, contact outputs)."""
    n = sys.n
    k6 = work.ydot_end
    yn = work.ynew
    mid = work.ytmp
    interpolate(work, 0.5, 2 * n, mid)
    p_mid = dissipated_power(sys, work, mid[:n], mid[n : 2 * n], mem)
    p0 = k0[2 * n + 1]
    p1 = k6[2 * n + 1]
    yn[2 * n] = y[2 * n] + 0.5 * h * (k0[2 * n] + k6[2 * n])
    yn[2 * n + 1] = y[2 * n + 1] + h / 6.0 * (p0 + 4.0 * p_mid + p1)
    error = h / 3.0 * abs(2.0 * p_mid - p0 - p1)
    return error / (atol + rtol * kinetic_energy(sys, work, yn[n : 2 * n]))


@kernel_inline
def step_factor(err: float, err_old: float) -> float:
    """Ratio of the next step size to this one for a local error of order h³ (err_old,
    DOPRI5's, is not used),
    held at 1 unless the error allows doubling: every change of h excites the
    spurious oscillation of the index-3 method's q̈ and λ (decaying like
    (−ρ∞)ⁿ), which stiff beams turn into visible acceleration noise; a constant
    step also lets Newton keep its factored iteration matrix."""
    fac = SAFE * max(err, ERR_MIN) ** (-1.0 / ERROR_ORDER)
    if err > 1.0:
        return fac
    return GROWTH if fac >= GROWTH else 1.0
