r"""Adaptive fifth-order implicit Runge--Kutta steps (Radau IIA) of a stacked linear system dy/dV = A(V) y.

For Fokker--Planck coefficients that do not separate (b(p, zeta), or a drift that does not scale with the
diffusion) the collocated operator of :mod:`persson_fp.solvers.chebyshev.collocation` depends on V and is marched.
Each step is the three-stage Radau IIA method (Ehle 1969; Hairer & Wanner, *Solving Ordinary Differential
Equations II*, Sec. IV.5): order 5, L-stable and stiffly accurate, so the stiff modes of the collocated diffusion
(||A|| ~ n^4 / dp_min^2) are damped, never amplified, at any step size.  For the linear system the stage equations

.. math::  Y_i = y_n + h \sum_j a_{ij} A(V_n + c_j h)\, Y_j, \qquad y_{n+1} = Y_3,
           \qquad c = \bigl(\tfrac{4 - \sqrt6}{10}, \tfrac{4 + \sqrt6}{10}, 1\bigr),

are one dense linear system of size 3m (m ~ 40-80 collocation nodes plus the three wall and moment rows), solved by
one LU per step and load -- no matrix exponential is ever formed.

Step control by step doubling: every step is taken once with h and as two steps of h/2; the kept result is the
two half steps, its local error estimated as :math:`\|y_{h/2,h/2} - y_h\| / (2^q - 1)` with q = 4 (``EST_DIV``),
one below the classical order 5, which parabolic problems with boundary conditions reduce (Ostermann & Roche, Math.
Comp. 59 (1992) 403), so the estimate is not below the local error when the order is reduced by one, and about twice
above it when it is not.  Local errors are held to ``tol`` per unit ln V; the reported estimate of the march is the
local estimates propagated, signed, through the later steps (the march carries the error as a second right-hand
side): their sum bounds it, because the Fokker--Planck evolution is a contraction in L1 (an error made early is
carried, not amplified), and the propagation sees how much the later evolution damps it.

A march forecasts its cost after a few steps (the steps taken per unit ln V so far against the distance left, times
the time per step so far) and stops at once (``MarchTooLong``) if the forecast exceeds its time budget or its
step limit, naming a tol that would fit.
"""

from __future__ import annotations

import math
import time

import numpy as np

__all__ = [
    "radau_march",
    "radau_step",
    "one_sided",
    "MAX_STEPS",
    "MarchTooLong",
    "EST_ORDER",
    "EST_DIV",
    "EST_DIV_WALL",
    "FORECAST_AFTER_BREAK",
]

MAX_STEPS = 4000
"""Accepted plus rejected steps a march may take (a :class:`MarchTooLong`; the forecast refuses it earlier)."""
PREDICT_AFTER = 8
"""Accepted steps before the march forecasts its cost (the first steps grow from the trial step h0)."""
EST_ORDER = 4
"""q of the local estimate |two half steps - one step| / (2^q - 1) (module docstring)."""
START_SPAN = 4.0
"""Steps before V = START_SPAN x V_a take their local error as |two - full| (first order), not / (2^q - 1)."""
EST_DIV = 15.0
"""The local error of the two half steps is |two - full| / EST_DIV, i.e. order 4 assumed (2^4 - 1).  Over the 320
random cases of ``benchmarks/honesty.py --method chebyshev`` (the march: drift, shifted squared-Bessel, strip and
Ornstein--Uhlenbeck families) no result is above its estimate (true / estimate <= 0.34 on the march paths) and the
march's true error lands at a median 0.04 of tol (0.01 with / 3).  / 3 (order 2) had been needed while the march
stepped across the spectrum's roll-off, where the coefficients have a kink in V and a step is first order; it now
stops there."""
EST_DIV_WALL = 3.0
"""The divisor of the moving wall's march (:mod:`persson_fp.solvers.chebyshev.wall`): order 2 assumed, the setting
its random-problem check against fv (``benchmarks/chebyshev_wall_fuzz.py``) was measured with; / 15 is not measured
there."""
RELAX = 100.0
"""The largest relaxation of the local step target by the damping measured so far (sum of |local| / |global|)."""
FORECAST_AFTER_BREAK = 1.05
"""A march piece forecasts its cost once it is a tenth of its span in ln V on, and one that starts at a break of the
operator (the roll-off's kink) not before this times its start: the first steps are graded (from the narrow start;
from the break, where the wall value's derivative jumps and a boundary layer forms at the wall), and their pace in
ln V over-forecasts (measured 2.5x after 8 steps on the moving-wall scene W; thousands of steps from a break)."""
ORDER_TOL = 4.0
"""The exponent of ``reachable = tol (forecast / budget)^ORDER_TOL``, the tol a refused march names: the steps
of a march held to tol per unit ln V grow as tol^(-1/q), q ~ 3-4 (measured 1e-4 -> 1e-8: ~3x the steps)."""

_S6 = math.sqrt(6.0)
C = np.array([(4.0 - _S6) / 10.0, (4.0 + _S6) / 10.0, 1.0])
"""The Radau IIA nodes."""
A_RK = np.array(
    [
        [(88.0 - 7.0 * _S6) / 360.0, (296.0 - 169.0 * _S6) / 1800.0, (-2.0 + 3.0 * _S6) / 225.0],
        [(296.0 + 169.0 * _S6) / 1800.0, (88.0 + 7.0 * _S6) / 360.0, (-2.0 - 3.0 * _S6) / 225.0],
        [(16.0 - _S6) / 36.0, (16.0 + _S6) / 36.0, 1.0 / 9.0],
    ]
)
"""The Radau IIA coefficients (its last row is the weights: stiffly accurate)."""


class MarchTooLong(RuntimeError):
    """The march needs (or is forecast to need) more steps or time than allowed; ``reachable`` is a march
    tolerance that would fit (in the units of ``norm``), ``needed`` the forecast seconds of the march."""

    def __init__(self, message: str, reachable: float, needed: float = math.nan):
        super().__init__(message)
        self.reachable = reachable
        self.needed = needed


_LAM, _T = np.linalg.eig(np.linalg.inv(A_RK))
_ORDER = np.argsort(np.abs(_LAM.imag))  # the real eigenvalue first, then the pair
_LAM, _T = _LAM[_ORDER], _T[:, _ORDER]
_LAM = _LAM[:2]  # (the third is the conjugate of the second, and so are its W and eigenvector)
_TI = np.linalg.inv(_T)
_NODES = np.concatenate([[0.0], C])
_HALF_INTERP = np.array(
    [
        [np.prod([(t - _NODES[k]) / (_NODES[j] - _NODES[k]) for k in range(4) if k != j]) for j in range(1, 4)]
        for t in np.concatenate([0.5 * C, 0.5 + 0.5 * C])
    ]
)
"""(6, 3): the collocation polynomial of a step (through 0 at tau = 0 and the stage increments at c_i) at the
stages of its two half steps, tau = c_i / 2 and 1/2 + c_i / 2 (Lagrange weights; the weight of tau = 0 multiplies
0)."""
EXTRAPOLATE_MAX = 2.5
"""The longest next step, in units of the last, whose first stage guesses extrapolate the last step's collocation
polynomial (Hairer & Wanner, Sec. IV.8: starting values); longer ones start from the explicit Euler stages."""


_OTHER = np.array([[k for k in range(4) if k != i] for i in range(1, 4)])
_LAGRANGE_DEN = _NODES[1:, None] - _NODES[_OTHER]
"""(3, 3): the Lagrange basis of the nodes 0, c_1, c_2, c_3 at c_i: the other nodes' indices and N_i - N_k."""


def _extrapolation(r: float) -> np.ndarray:
    """(3, 3): the last step's collocation polynomial u (through 0 at tau = 0 and its stage increments at c_i, tau in
    units of that step) at the next step's stages tau = 1 + r c_j, less u(1): the next step's stage increments."""
    t = 1.0 + r * C
    W = np.prod((t[:, None, None] - _NODES[_OTHER][None]) / _LAGRANGE_DEN[None], axis=-1)
    W[:, 2] -= 1.0
    return W


_TI_RE, _TI_IM = np.ascontiguousarray(_TI[:2].real), np.ascontiguousarray(_TI[1].imag)
_AI = np.linalg.inv(A_RK)
_TI_MIX = np.stack([_TI_RE[0], _TI_RE[1], _TI_IM])
"""(3, 3): the rows of T^-1 G in real arithmetic: the real eigenvalue's, the pair's real and imaginary parts."""
_T_MIX = np.stack([_T[:, 0].real, 2.0 * _T[:, 1].real, -2.0 * _T[:, 1].imag], axis=1)
"""(3, 3): T W back from (W0, Re W1, Im W1): Z_i = T_i0 W0 + 2 Re(T_i1 W1)."""


def _mix(M, Z):
    """M (k, j) applied along the first axis of Z (j, ...): a tensordot without its overhead (the stage arrays are
    small, the call count large)."""
    return (M @ Z.reshape(Z.shape[0], -1)).reshape((M.shape[0],) + Z.shape[1:])


NEWTON_MAX = 12
"""Most simplified-Newton sweeps of one step (slower convergence: the step is retried at a smaller h)."""


class _NoConvergence(RuntimeError):
    """The stage iteration of a step did not converge (the operator changes too much over the step)."""


def operators(A_of, Vs):
    """The operators at the points ``Vs``, stacked (len(Vs), n_loads, m, m): one call of ``A_of`` with the array
    where it takes one (``A_of.many``: e.g. one inversion zeta(V) for all of them), else one call per point."""
    many = getattr(A_of, "many", None)
    if many is not None:
        return many(np.asarray(Vs, dtype=float))
    return np.stack([A_of(float(v)) for v in Vs])


def factor(J, h):
    """The LUs of the stage iteration for the frozen operator J (n_loads, m, m) and step h: per load, LAPACK getrf of
    the real (gamma / h - J) and of the complex ((alpha + i beta) / h - J) (:func:`radau_step`)."""
    from scipy.linalg.lapack import dgetrf, zgetrf

    m = J.shape[-1]
    idx = np.arange(m)
    Mr = -J
    Mr[:, idx, idx] += _LAM[0].real / h
    Mc = (-J).astype(complex)
    Mc[:, idx, idx] += _LAM[1] / h
    return [(dgetrf(Mr[lo], overwrite_a=True)[:2], zgetrf(Mc[lo], overwrite_a=True)[:2]) for lo in range(J.shape[0])]


def radau_step(A_of, V, h, y, As=None, frozen=None, guess=None, rel=None, stages=None):
    r"""One Radau IIA step of dy/dV = A(V) y from V over h.

    The stage system is solved by simplified Newton sweeps with the operator frozen at the mean of its stage values
    J, the Radau matrix diagonalised (Hairer & Wanner, Sec. IV.8): one real LU of (gamma / h - J) and one complex
    LU of ((alpha + i beta) / h - J), m x m each, per step and load (LAPACK getrf / getrs); the sweeps stop at
    round-off (linear convergence at a rate ~ h ||A(V + c_i h) - J|| / ||J||, the relative change of the operator
    over the step).

    Parameters
    ----------
    A_of : callable
        ``A_of(V) -> (n_loads, m, m)``.
    V, h : float
        Start and step.
    y : ndarray, shape (n_loads, m)
    As : ndarray or None, shape (3, n_loads, m, m)
        The operator at the stages V + c_i h, if the caller has it (:func:`operators`).
    frozen : (ndarray, list) or None
        (J, :func:`factor` (J, h)): the frozen operator and its LUs, shared by steps of the same h (the two half
        steps of a doubled step); default the mean of the stage operators, factorised here.
    guess : ndarray or None, shape (3, n_loads, m)
        A first guess of the stage increments Y_i - y of the first right-hand side (e.g. from the collocation
        polynomial of a step over the same interval); default the explicit Euler stages c_i h J y.
    rel : sequence of float or None
        The sweeps stop once each right-hand side's change is below this share of its size (default 1e-12 each).
    stages : list or None
        The stage increments (3, n_loads, m) of the first right-hand side are appended to it.

    Returns
    -------
    ndarray, shape (n_loads, m)

    Raises
    ------
    _NoConvergence
        (a ``RuntimeError``) the sweeps did not converge in :data:`NEWTON_MAX`.
    """
    if As is None:
        As = operators(A_of, V + C * h)
    from scipy.linalg.lapack import dgetrs, zgetrs

    single = y.ndim == 2
    # (n_loads, m, r): r right-hand sides share the operators and their LUs
    y = y[:, :, None] if single else np.swapaxes(y, 1, 2)
    J, lus = frozen if frozen is not None else (None, None)
    if J is None:
        J = As.mean(axis=0)
        lus = factor(J, h)
    nl, m, r = y.shape
    Z = (C * h)[:, None, None, None] * (J @ y)[None]  # the first guess: the explicit Euler stages y + c_i h J y
    if guess is not None:
        Z[:, :, :, 0] = guess
    scale = np.max(np.abs(y), axis=1)  # (n_loads, r)
    scale = np.where(scale > 0, scale, 1.0) * (1e-12 if rel is None else np.asarray(rel, dtype=float))
    last = np.inf
    dW0 = np.empty((nl, m, r))
    dW1 = np.empty((nl, m, r), dtype=complex)
    AI_h = _AI / h
    for _ in range(NEWTON_MAX):
        G = As @ (y[None] + Z) - _mix(AI_h, Z)
        R = _mix(_TI_MIX, G)  # (T^-1 G: real arithmetic, the pair's parts apart)
        R0, R1 = R[0], R[1] + 1j * R[2]
        for lo, ((lu_r, piv_r), (lu_c, piv_c)) in enumerate(lus):
            dW0[lo] = dgetrs(lu_r, piv_r, R0[lo])[0]
            dW1[lo] = zgetrs(lu_c, piv_c, R1[lo])[0]
        dZ = _mix(_T_MIX, np.stack([dW0, dW1.real, dW1.imag]))
        Z += dZ
        change = float(np.max(np.max(np.abs(dZ), axis=(0, 2)) / scale))  # (in units of the asked change)
        if change <= 1.0:
            break
        if change > 0.8 * last:  # (not contracting: the step is too long for the frozen J)
            raise _NoConvergence(f"stage sweeps stalled at {change:.2g} x the change asked")
        last = change
    else:
        if last > 10.0:
            raise _NoConvergence(f"stage sweeps at {last:.2g} x the change asked after {NEWTON_MAX}")
    if stages is not None:
        stages.append(Z[:, :, :, 0].copy())
    out = y + Z[2]
    return out[:, :, 0] if single else np.swapaxes(out, 1, 2)


SWEEP_SHARE = 1e-3
"""The stage sweeps of a step stop once their change is below this share of the step's local error target (in the
march's norm; never looser than 1e-7 nor tighter than 1e-12 of the state's largest entry): converging them to
round-off bought nothing the error estimates could see, at one or two sweeps a step."""


def _sweep_rel(y, unit, target):
    """The sweeps' stopping threshold relative to max |y|: ``SWEEP_SHARE`` x ``target`` over ``unit`` max |y|, where
    ``unit`` is the norm of a state of ones (a max-norm change c moves the norm by at most c x unit)."""
    big = float(np.max(np.abs(y))) * unit
    if not big > 0.0:
        return 1e-12
    return float(np.clip(SWEEP_SHARE * target / big, 1e-12, 1e-7))


def radau_march(
    A_of,
    y0,
    V_a: float,
    V_b: float,
    tol: float,
    norm,
    floor: float,
    h0: float | None = None,
    deadline=None,
    *,
    nodes=None,
    record: list | None = None,
    time_budget: float | None = None,
    forecast_from: float = 0.0,
    est_div: float = EST_DIV,
):
    """March dy/dV = A(V) y from V_a > 0 to V_b with adaptive Radau IIA steps (module docstring).

    Parameters
    ----------
    A_of : callable
        ``A_of(V) -> (n_loads, m, m)`` the operator at V (pressure^-2; any augmented rows included).
    y0 : ndarray, shape (n_loads, m)
        The state at V_a.
    V_a, V_b : float, pressure^2
        The span, 0 < V_a < V_b.
    tol : float
        The error asked for the march, in the units of ``norm``: local estimates are held to tol per unit
        ln(V) / ln(V_b / V_a), so that their sum -- the reported estimate -- is at most tol.
    norm : callable
        ``norm(dy) -> (n_loads,)``, the error measure of a state difference (an L1 with quadrature weights).
    floor : float
        Local errors below this are round-off: such a step is accepted whatever its size, and one whose error does
        not fall at least 2x on a smaller try is taken as round-off if it is below 100 x floor.
    h0 : float or None
        First trial step; default V_a (a narrow start changes on the scale V_a).
    deadline : float or None
        A ``time.perf_counter()`` value: past it the march stops with a ``TimeoutError`` (the caller's max_time).
    nodes : sequence of float or None
        Replay: take exactly these steps (each as two half steps, as the controlled march keeps them; the points
        beyond V_a), no control and no estimate -- a partner run on the steps of a main run then differs from it
        by its own changes alone.
    record : list or None
        The accepted points (V_a first) are appended to it (the ``nodes`` of a replay).
    time_budget : float or None
        Seconds this march may take: after :data:`PREDICT_AFTER` accepted steps, a forecast above it (or above
        :data:`MAX_STEPS` steps) stops the march at once with :class:`MarchTooLong`.
    forecast_from : float
        No forecast before V reaches this (pressure^2): a march that starts at a jump of the operator (a break
        point, not a narrow start) takes graded steps from there whose pace in ln V says nothing of the rest.
    est_div : float
        The local error of the two half steps is |two - full| / est_div (``EST_DIV``; the moving wall's
        ``EST_DIV_WALL``).

    Returns
    -------
    (ndarray, ndarray, dict)
        y(V_b) (n_loads, m); the estimate of its error (n_loads,), the sum of the local estimates (0 on a replay);
        the statistics ``{"steps", "rejected", "solves"}``.
    """
    t_start = time.perf_counter()
    V, y = float(V_a), np.array(y0, dtype=float)
    log_span = math.log(V_b / V_a)
    unit = float(np.max(norm(np.ones_like(y))))  # (the norm of a unit max-norm change: the sweeps' scale)
    if nodes is not None:
        steps, prev = 0, []  # (prev: the last half step's (h, stage increments), the next one's first guess)
        for Vn in [v for v in nodes if v > V_a * (1.0 + 1e-12)] + (
            [V_b] if max(nodes, default=0) < V_b * (1 - 1e-13) else []
        ):
            if deadline is not None and time.perf_counter() > deadline:
                raise TimeoutError(f"the replayed march stopped at V = {V:.6g} of {V_b:.6g} after {steps} steps")
            rel = _sweep_rel(y, unit, tol * math.log1p((Vn - V) / V) / log_span)
            y = _replay_step(A_of, V, Vn - V, y, rel=rel, prev=prev)
            V, steps = Vn, steps + 1
        return y, np.zeros(y.shape[0]), {"steps": steps, "rejected": 0, "solves": 2 * steps}
    div = est_div
    if record is not None:
        record.append(V)
    h = min(V_b - V_a, h0 if h0 is not None else V_a)
    h_cap = math.inf  # (below a step whose stage sweeps did not converge, growing again 1.2x a step)
    steps = rejected = 0
    e = np.zeros_like(y)  # the global error, propagated: e <- (two half steps) e + d
    local_sum = np.zeros(y.shape[0])
    last_reject = math.inf
    noise_level = floor
    prev = None  # (h, stage increments) of the last accepted full step
    while V < V_b:
        if deadline is not None and time.perf_counter() > deadline:
            raise TimeoutError(f"the march stopped at V = {V:.6g} of {V_b:.6g} after {steps} steps")
        if steps + rejected >= MAX_STEPS:
            raise MarchTooLong(
                f"{MAX_STEPS} Radau steps did not reach V = {V_b:.6g} (at {V:.6g}, h = {h:.3g})",
                tol * (1.0 + math.log(V_b / V) / (math.log1p(h / V) * MAX_STEPS)) ** ORDER_TOL,
            )
        h = min(h, h_cap)
        last = V + h >= V_b * (1.0 - 1e-13)
        if last:
            h = V_b - V
        try:
            ops = operators(A_of, np.concatenate([V + C * h, V + 0.5 * C * h, V + 0.5 * h + 0.5 * C[:2] * h]))
            st: list = []
            rel = _sweep_rel(y, unit, tol * math.log1p(h / V) / log_span)  # (the local target, relax = 1)
            g = _guess([] if prev is None else [prev], h)
            full = radau_step(A_of, V, h, y, ops[:3], (ops[5], factor(ops[5], h)), g, (rel,), stages=st)
            frozen = (ops[5], factor(ops[5], 0.5 * h))  # (the half steps share the operator at V + h/2, its LUs)
            # first guesses of the half steps' stages: the full step's collocation polynomial (its error is the
            # local error, so a sweep or two reach round-off); the propagated error needs 1e-4 of itself only
            u = _mix(_HALF_INTERP, st[0])  # (6, n_loads, m): u(c_i / 2) - y, u(1/2 + c_i / 2) - y
            half = radau_step(A_of, V, 0.5 * h, np.stack([y, e], axis=1), ops[3:6], frozen, u[:3], (rel, 1e-4))
            u_mid = u[2]  # (u(1/2) - y: the second half's guesses are the polynomial's increments from there)
            two = radau_step(
                A_of, V + 0.5 * h, 0.5 * h, half, np.concatenate([ops[6:], ops[2:3]]), frozen, u[3:] - u_mid,
                (rel, 1e-4),
            )  # fmt: skip
        except _NoConvergence:
            rejected += 1
            h_cap = h = 0.5 * h
            continue
        # the local error of the two half steps, signed: |two - full| / (2^q - 1) once the march is past its start,
        # whose undamped high modes leave the first steps below their asymptotic order (there 1 / (2^1 - 1))
        d = (two[:, 0] - full) / (div if V >= START_SPAN * V_a else 1.0)
        err_l = norm(d)
        worst = float(np.max(err_l))
        # errors made early are damped by the later evolution (an L1 contraction, strongly for the high modes of a
        # narrow start): the local target is relaxed by the damping seen so far, sum |d| / |e| (at most RELAX)
        e_now = float(np.max(norm(e)))
        relax = float(np.clip(float(np.max(local_sum)) / e_now, 1.0, RELAX)) if e_now > 0 else 1.0
        allowed = relax * tol * math.log1p(h / V) / log_span
        if worst >= 0.5 * last_reject and worst <= 100.0 * floor:  # a smaller step did not help: round-off
            noise_level = max(noise_level, 2.0 * worst)
        target = max(allowed, noise_level)
        if worst <= target:
            last_reject = math.inf
            prev = (h, st[0])  # (the full step's stages: the next full step's first guess)
            y, e, V = two[:, 0], two[:, 1] + d, (V_b if last else V + h)
            local_sum += err_l
            steps += 1
            h_cap *= 1.2
            if record is not None:
                record.append(V)
            h *= 5.0 if worst == 0.0 else float(np.clip(0.9 * (target / worst) ** (1.0 / (EST_ORDER + 1)), 0.2, 5.0))
            if steps == PREDICT_AFTER // 2:  # (the time per try from here: the first tries carry first-call costs)
                t_mark, tries_mark = time.perf_counter(), steps + rejected
            if steps >= PREDICT_AFTER and forecast_from <= V < V_b:
                pace = (time.perf_counter() - t_mark) / max(steps + rejected - tries_mark, 1)
                left = None if time_budget is None else time_budget - (time.perf_counter() - t_start)
                _forecast(V, V_a, V_b, h, steps, rejected, pace, tol, left)
        else:
            rejected += 1
            last_reject = worst
            h *= float(np.clip(0.9 * (target / worst) ** (1.0 / (EST_ORDER + 1)), 0.05, 0.5))
    return y, norm(e), {"steps": steps, "rejected": rejected, "solves": 3 * (steps + rejected)}


def _guess(prev, h):
    """The first stage guesses of a step of h from the last step's (h, stages) in ``prev`` (a list, [] at first)."""
    if not prev or h > EXTRAPOLATE_MAX * prev[-1][0]:
        return None
    return _mix(_extrapolation(h / prev[-1][0]), prev[-1][1])


def _replay_step(A_of, V, h, y, depth=0, rel=None, prev=None):
    """A replayed step (two half steps sharing the operator at V + h/2 and its LUs); where their stage sweeps do not
    converge (a partner's grid, stiffer than the main run's), each half with its own operator, then in halves again
    (at most 3 times) -- the replay's steps are fixed, so it cannot shorten them otherwise."""
    ops = operators(A_of, np.concatenate([V + 0.5 * C * h, V + 0.5 * h + 0.5 * C * h]))
    try:
        frozen = (ops[2], factor(ops[2], 0.5 * h))
        if prev is None:
            prev = []
        st: list = []
        y1 = radau_step(A_of, V, 0.5 * h, y, ops[:3], frozen, _guess(prev, 0.5 * h), rel, st)
        y2 = radau_step(A_of, V + 0.5 * h, 0.5 * h, y1, ops[3:], frozen, _guess([(0.5 * h, st[0])], 0.5 * h), rel, st)
        prev[:] = [(0.5 * h, st[1])]
        return y2
    except _NoConvergence:
        if prev:
            prev.clear()
        try:
            y1 = radau_step(A_of, V, 0.5 * h, y, ops[:3], rel=rel)
            return radau_step(A_of, V + 0.5 * h, 0.5 * h, y1, ops[3:], rel=rel)
        except _NoConvergence:
            if depth >= 3:
                raise
            y = _replay_step(A_of, V, 0.5 * h, y, depth + 1, rel)
            return _replay_step(A_of, V + 0.5 * h, 0.5 * h, y, depth + 1, rel)


def one_sided(A_of, lo: float, hi: float):
    """``A_of`` on the piece [lo, hi] between breaks: points within 1e-12 of an end (a stage on it) are moved
    inside, so that the operator there is its limit from within the piece, not the other side's."""
    lo_in, hi_in = lo * (1.0 + 1e-12), hi * (1.0 - 1e-12)

    def piece(V):
        return A_of(min(max(V, lo_in), hi_in))

    piece.many = lambda Vs: A_of.many(np.clip(Vs, lo_in, hi_in))
    return piece


def _forecast(V, V_a, V_b, h, steps, rejected, pace, tol, time_budget):
    """Raise :class:`MarchTooLong` if the march is forecast to exceed MAX_STEPS or ``time_budget`` seconds.

    The steps left: the smaller of the distance left in ln V at the present step (h / V) and at the mean rate
    per unit ln V so far (the first over-predicts where h dips for a while, the second where the first steps were
    the small ones); the time: ``pace`` (seconds a try, measured after the first tries) times the tries forecast."""
    done, left = math.log(V / V_a), math.log(V_b / V)
    tries = steps + rejected
    more = min(left / math.log1p(h / V), tries * left / done)
    total_steps = tries + more
    secs = pace * more
    over_steps = total_steps > MAX_STEPS
    over_time = time_budget is not None and secs > time_budget
    if not (over_steps or over_time):
        return
    ratio = max(total_steps / MAX_STEPS, secs / max(time_budget, 1e-3) if time_budget is not None else 0.0)
    raise MarchTooLong(
        f"the march is forecast to need ~{total_steps:.0f} Radau steps, ~{secs:.3g} s more, to reach V = {V_b:.6g} "
        f"(after {steps} steps it is at {V:.6g}, h = {h:.3g})"
        + (f", over the {time_budget:.3g} s left to it" if over_time else f", over {MAX_STEPS} steps"),
        tol * (1.2 * ratio) ** ORDER_TOL,
        secs,
    )
