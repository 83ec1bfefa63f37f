r"""Adaptive fourth-order exponential stepping of a stacked linear system dy/dV = A(V) y, with an error estimate.

For Fokker--Planck coefficients that are *not* of the form b(p) dV/dzeta the collocated operator of
:mod:`persson_fp.solvers.chebyshev.collocation` depends on V, and the exact single exponential of the separable case
becomes a march.  Each step is the commutator-free fourth-order exponential integrator with two Gauss points
(Blanes & Moan, Appl. Numer. Math. 56 (2006) 1519; Thalhammer, SIAM J. Numer. Anal. 44 (2006) 851), a
Magnus-type method without the commutator:

.. math::  y(V + h) \approx e^{h(\beta_2 A_1 + \beta_1 A_2)}\,e^{h(\beta_1 A_1 + \beta_2 A_2)}\,y(V), \qquad
           A_{1,2} = A(V + (\tfrac12 \mp \tfrac{\sqrt3}{6}) h), \quad \beta_{1,2} = \tfrac14 \pm \tfrac{\sqrt3}{6}.

It is exact for an operator constant in V (the separable case) and for one that changes by a scalar factor
(B2 = b(p) g(zeta), any g), unconditionally stable for the stiff collocated diffusion, and each exponent is a
second-order operator with the same Dirichlet walls (the commutator of the classical fourth-order Magnus method is
a fourth-order one, measured to lose accuracy at the walls).

Step control by step doubling: every step is taken once with h and twice with h/2; the Richardson estimate
:math:`|y_{h/2,h/2} - y_h| / 15` of the local error, per load in the caller's norm, must be below ``tol`` per unit
ln V (or below a round-off floor), and the half-step result is kept.  Where the operators at different V do not
commute, the collocated parabolic problem shows the order reduction of exponential integrators at Dirichlet walls
(measured local order 2.3-2.5 on B2 = (1 + p zeta) dV/dzeta), so the local estimate only places the steps.  The
*reported* estimate is global: a companion solution is marched through the same steps with the single step h, and
:math:`|y_{h/2} - y_h|` at the end bounds the error of the kept half-step march for any global order >= 1 (the
factor is 1 / (2^q - 1)), the damping of early errors by the later evolution included; it is reported doubled, for
marches of a few steps outside the asymptotic range (1.4x under it measured on a 6-step march otherwise).
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.linalg as sla

__all__ = ["magnus_march", "cf4_step", "MAX_STEPS", "MarchTooLong"]

MAX_STEPS = 600
"""Accepted plus rejected steps a march may take before it gives up (a ``RuntimeError`` the caller reports)."""
PREDICT_AFTER = 16
"""Accepted steps before the march forecasts its length (the first steps grow from the trial step h0)."""
PREDICT_MARGIN = 1.2
"""A march forecast to need more than this times MAX_STEPS stops at once (:class:`MarchTooLong`)."""
ORDER_TOL = 3.0
"""The exponent q of ``reachable = tol (steps needed / MAX_STEPS)^q`` naming the tol that fits: measured on
B2 = (1 + p zeta) V' the steps grow slowly as tol falls (445 at 1e-6, over 600 at 5.8e-7 and at 1e-7), and the
forecast under-predicts where h keeps shrinking; q = 3 with the forecast doubled names 1.4e-6 there (1e-6 fits)."""


class MarchTooLong(RuntimeError):
    """The march needs (or is forecast to need) more than MAX_STEPS steps; ``reachable`` is a march tolerance
    that would fit, ``tol (2 forecast / MAX_STEPS)^3`` (in the units of ``norm``; :data:`ORDER_TOL`)."""

    def __init__(self, message: str, reachable: float):
        super().__init__(message)
        self.reachable = reachable


_C = math.sqrt(3.0) / 6.0
_B1, _B2 = 0.25 + _C, 0.25 - _C


def cf4_step(A_of, V, h, y):
    """One commutator-free fourth-order step: exp(h (b2 A1 + b1 A2)) exp(h (b1 A1 + b2 A2)) y."""
    A1, A2 = A_of(V + (0.5 - _C) * h), A_of(V + (0.5 + _C) * h)
    y = np.einsum("lij,lj->li", sla.expm(h * (_B1 * A1 + _B2 * A2)), y)
    return np.einsum("lij,lj->li", sla.expm(h * (_B2 * A1 + _B1 * A2)), y)


def magnus_march(
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
    refusal: str = "forecast",
):
    """March dy/dV = A(V) y from V_a to V_b with adaptive fourth-order exponential steps.

    Parameters
    ----------
    A_of : callable
        ``A_of(V) -> (n_loads, m, m)`` the operator at V (pressure^-2; any augmented rows included).
    y0 : ndarray, shape (n_loads, m)
        The state at V_a.
    V_a, V_b : float, pressure^2
        The span, V_b > V_a.
    tol : float
        The error asked for the march, in the units of ``norm``: the local estimates per unit ln V are held to
        tol / ln(V_b / V_a) (per unit V to tol / (V_b - V_a) if V_a = 0) -- an error made early, while the PDF is
        narrow, is measured against a narrow PDF and spread by the later evolution over a wider one.
    norm : callable
        ``norm(dy) -> (n_loads,)``, the error measure of a state difference (e.g. an L1 with quadrature weights).
    floor : float
        Local errors below this are round-off of the exponential: a step whose local error is below it is
        accepted whatever its size, and one whose error does not fall at least 2x on a smaller try is taken as
        round-off if it is below 100 x floor.
    h0 : float or None
        First trial step; default min((V_b - V_a) / 8, 2 V_a) (a narrow start changes on the scale V_a).
    deadline : float or None
        A ``time.perf_counter()`` value: past it the march stops with a ``TimeoutError`` (the caller's max_time).
    nodes : sequence of float or None
        Replay: take exactly these steps (the accepted points of an earlier march, those beyond V_a), no step
        control -- partner runs on the steps of a main run then differ from it by their own changes alone.
    record : list or None
        The accepted points (V_a first) are appended to it (the ``nodes`` of a replay).
    refusal : {"forecast", "pace"}
        The early refusal: "forecast" as below; "pace" (a moving wall, whose steps shrink where the wall speeds up)
        after 60 tries, when the tries exceed 2 MAX_STEPS times the share of ln(V_b / V_a) behind.

    Returns
    -------
    (ndarray, ndarray, dict)
        y(V_b) (n_loads, m); the estimate of its error (n_loads,), 2 |half-step march - companion march|; and the
        march's statistics ``{"steps", "rejected", "expm"}``.

    Raises
    ------
    MarchTooLong
        A ``RuntimeError``: more than :data:`MAX_STEPS` steps (the operator changes too fast for ``tol``), or
        forecast to need more than ``PREDICT_MARGIN`` times that after ``PREDICT_AFTER`` accepted steps and a tenth
        of the span (the smaller of two extrapolations: at the present step size and at the mean rate per unit V so
        far): a refusal within ~1 s.
    """
    span = float(V_b - V_a)
    log_span = math.log(V_b / V_a) if V_a > 0 else 0.0
    V, y = float(V_a), np.array(y0, dtype=float)
    z = y.copy()  # the companion: the same steps, each taken once
    if nodes is not None:
        steps = 0
        for Vn in [v for v in nodes if v > V_a * (1.0 + 1e-12)]:
            h = Vn - V
            z = cf4_step(A_of, V, h, z)
            y = cf4_step(A_of, V + 0.5 * h, 0.5 * h, cf4_step(A_of, V, 0.5 * h, y))
            V = Vn
            steps += 1
        return y, 2.0 * norm(y - z), {"steps": steps, "rejected": 0, "expm": 6 * steps}
    if refusal not in ("forecast", "pace"):
        raise ValueError(f"refusal must be 'forecast' or 'pace', got {refusal!r}")
    if record is not None:
        record.append(V)
    h = min(span, h0 if h0 is not None else min(span / 8.0, 2.0 * V_a if V_a > 0 else span))
    steps = rejected = 0
    last_reject = math.inf  # the error of the last rejected try from this V (a round-off test)
    noise_level = floor  # the local error no step size lowers (learnt: the exponential's round-off)
    while V < V_b:
        if deadline is not None and time.perf_counter() > deadline:
            raise TimeoutError(f"the march stopped at V = {V:.6g} of {V_b:.6g} after {steps} steps")
        tried = steps + rejected
        if refusal == "pace" and (
            tried >= MAX_STEPS or (tried >= 60 and tried > 2.0 * MAX_STEPS * math.log(V / V_a) / log_span)
        ):
            raise MarchTooLong(
                f"{tried} exponential steps reached V = {V:.6g} of {V_b:.6g} (h = {h:.3g}; at most {MAX_STEPS}, "
                "and this pace would need more than 2x that)",
                tol * (1.0 + (V_b - V) / (h * MAX_STEPS)) ** ORDER_TOL,
            )
        if tried >= MAX_STEPS:
            raise MarchTooLong(
                f"{MAX_STEPS} exponential steps did not reach V = {V_b:.6g} (at {V:.6g}, h = {h:.3g})",
                tol * (1.0 + (V_b - V) / (h * MAX_STEPS)) ** ORDER_TOL,
            )
        last = V + h >= V_b * (1.0 - 1e-13)
        if last:
            h = V_b - V
        full = cf4_step(A_of, V, h, y)
        two = cf4_step(A_of, V + 0.5 * h, 0.5 * h, cf4_step(A_of, V, 0.5 * h, y))
        err = norm(two - full) / 15.0
        worst = float(np.max(err))
        allowed = tol * math.log1p(h / V) / log_span if V > 0 else tol * h / span
        if worst >= 0.5 * last_reject and worst <= 100.0 * floor:  # a smaller step did not help: round-off
            noise_level = max(noise_level, 2.0 * worst)
        target = max(allowed, noise_level)
        if worst <= target:
            last_reject = math.inf
            z = full if steps == 0 or z is y else cf4_step(A_of, V, h, z)
            y, V = two, (V_b if last else V + h)
            steps += 1
            if record is not None:
                record.append(V)
            h *= 4.0 if worst == 0.0 else float(np.clip(0.9 * (target / worst) ** 0.25, 0.2, 4.0))
            if refusal == "pace":
                continue
            # the forecast, once a tenth of the span is done (before, the steps grow with V, uniform in ln V): the
            # smaller of the steps so far plus the rest at the present step size and the steps so far at their mean
            # rate per unit V (the first over-predicts where h dips for a while, the second where the first steps
            # were the small ones; both under-predict where h keeps shrinking)
            forecast = min(steps + rejected + (V_b - V) / h, (steps + rejected) * span / (V - V_a))
            early = steps >= PREDICT_AFTER and V - V_a >= 0.1 * span and V < V_b
            if early and forecast > PREDICT_MARGIN * MAX_STEPS:
                raise MarchTooLong(
                    f"the march is forecast to need ~{forecast:.0f} exponential steps (over {MAX_STEPS}) to reach "
                    f"V = {V_b:.6g}: after {steps} steps it is at {V:.6g} with h = {h:.3g}",
                    tol * (2.0 * forecast / MAX_STEPS) ** ORDER_TOL,  # (2x: the forecast under-predicts, h shrinks)
                )
        else:
            rejected += 1
            last_reject = worst
            h *= float(np.clip(0.9 * (target / worst) ** 0.25, 0.05, 0.5))
    est = 2.0 * norm(y - z)  # (1 / (2^q - 1) <= 1 for q >= 1, asymptotically; 2x for a march of few steps)
    return y, est, {"steps": steps, "rejected": rejected, "expm": 6 * (steps + rejected) + 2 * max(steps - 1, 0)}
