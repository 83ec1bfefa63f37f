r"""The effective-variance map of the ``"sines"`` solver: tau at each output station V(zeta) for every load.

With a fudge factor the series of :mod:`persson_fp.solvers.sines` is evaluated at the effective variance
:math:`\tau = \int S(A^*)\,dV` (Xu et al. tutorial, Eq. 'eq:new_B2'), so every station needs the root of
:math:`F(\tau) = V_{sw} + \int_{\tau_{sw}}^{\tau} dt / S(A_h(t)) - V_{out}`.  Here: the scaled integral of 1/S tabulated
once per fudge model (Gauss--Legendre panels and Gauss--Laguerre for the tail), the dropped-mode bound, the per-load
terms and Newton's method on F for all (station, load) pairs at once (:class:`_TauMap`).  The rules and their
accuracy are described in :mod:`persson_fp.solvers.sines`.
"""

from __future__ import annotations

import functools
import math
import warnings
import weakref

import numpy as np
from scipy.special import erf, roots_laguerre

from persson_fp.solvers.sines.series import _X_SWITCH, _Y_SW, _margin, image_area, series_area
from persson_fp.theory.fudge import Xu24

_TABLE_W = 0.25
"""Panel width (in y = ln(t / p_bar^2)) of the load-free table; halved where a panel fails its check."""
_TABLE_Q = 6
"""Gauss--Legendre nodes per panel of a call (the partial panel): round-off on 1/4 for the built-in models."""
_TABLE_TOL = 1e-15
"""A panel's _TABLE_Q-point value must agree with two 16-point halves to this (relative to J there)."""
_TABLE_DEPTH = 40
"""Halvings of a panel that fails its check (a kink in S is resolved to round-off within ~30)."""
_LAG_Q = 12
"""Gauss--Laguerre nodes of the dropped-mode correction."""
_DIRECT_W, _DIRECT_Q = 0.5, 16
"""Panel width (in x = ln t) and nodes of the direct rule used where the far wall matters."""
_FAR_WALL_Z = 6.5
"""The far wall is ignored while (L - p_bar) / sqrt(2 tau) >= 6.5 (erfc(6.5) = 3.8e-20)."""
_LAMBDA_T_END = 60.0
"""Dropped modes are ignored beyond lambda t = 60 (e^-60 = 9e-27)."""
_MAX_NEWTON = 50
_SHORT_STEP = 1e-3
"""After a Newton step up to this (in ln tau) the residual is bounded by Taylor's theorem (~ step^2)."""
_RTOL_FLOOR = 8.0 * np.finfo(float).eps
"""The residual of the tau map is computed to a few ulps: ``rtol`` below this is raised to it."""


def _gl01(q: int):
    """q-point Gauss--Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(q)
    return 0.5 * (x + 1.0), 0.5 * w


_XT, _WT = _gl01(_TABLE_Q)
_X16, _W16 = _gl01(16)
_XD, _WD = _gl01(_DIRECT_Q)
_NODES_T = np.concatenate([[0.0], _XT, [1.0]])  # the partial panel's nodes and both ends (for e^-s, F')
_NODES_T_H = -0.5 * _NODES_T
_W_T = np.concatenate([[0.0], _WT, [0.0]])
_S_LAG, _W_LAG = roots_laguerre(_LAG_Q)
_W_LAG = _W_LAG * np.exp(_S_LAG)  # weights for int_0^inf f(s) ds (f decaying like e^-s)


class _ScaledIntegral:
    r"""The load-free part of the tau map of one fudge factor (built once, see :func:`_scaled_integral`).

    :math:`J(y) = e^{-y}\int_{y_{sw}}^{y} e^{y'} h(y')\,dy'`, :math:`h = 1/S(\mathrm{erf}(e^{-y/2}/\sqrt2))`,
    so that :math:`\int_{\tau_{sw}}^{\tau} dt / S(\mathrm{erf}(\bar p/\sqrt{2t})) = \tau J(\ln(\tau/\bar p^2))`.
    ``psi[i]`` is J at ``edges[i]``; the table grows on demand.  Also holds S(1), min and max of S and
    ``dh_max``, a bound on |d(1/S)/dA| (4 x its maximum on a grid) for the dropped-mode estimates.
    """

    def __init__(self, fudge):
        self.S = fudge.S
        if type(fudge) is Xu24:  # 1/S(erf(z)) in closed form, erfinv(erf(z)) = z: cheaper, and exact near A = 1
            gamma, c = fudge.gamma, (1.0 - fudge.gamma) / math.sqrt(math.pi)

            def h(z):
                g = gamma + (1.0 - gamma) * erf(z)
                return (g + c * z * np.exp(-z * z)) / (g * g)

            self.h = h
        A = np.concatenate([np.linspace(0.0, 1.0, 2001), 1.0 - np.logspace(-16.0, -3.0, 27)])
        s = np.asarray(fudge.S(A), dtype=float)
        self.S1 = float(fudge.S(np.array(1.0)))
        self.S_min = float(np.min(s))
        self.S_max = float(np.max(s))
        self.dh_max = 4.0 * float(np.max(np.abs(np.asarray(fudge.dS_dA(A), dtype=float)) / s**2))
        self.edges = np.array([_Y_SW])
        self.psi = np.array([0.0])
        self.extend(_Y_SW + 40.0)

    def h(self, z):
        """1 / S(erf(z)), the integrand's factor (z = e^{-y/2} / sqrt 2 = p_bar / sqrt(2 t))."""
        return 1.0 / self.S(erf(z))

    def _rule(self, lo, hi, b, x, w):
        """int_lo^hi e^{y - b} h(y) dy by the rule (x, w) on [0, 1], per panel."""
        d = hi - lo
        y = lo[:, None] + d[:, None] * x
        return d * ((np.exp(y - b[:, None]) * self.h(np.exp(-0.5 * y) * math.sqrt(0.5))) @ w)

    def extend(self, y_top: float) -> None:
        """Tabulate J up to at least ``y_top``."""
        a0 = float(self.edges[-1])
        if y_top <= a0:
            return
        K = max(1, math.ceil((y_top - a0) / _TABLE_W))
        a = a0 + _TABLE_W * np.arange(K)
        b = a + _TABLE_W
        acc_a, acc_b, acc_J = [], [], []
        for depth in range(_TABLE_DEPTH + 1):
            m = 0.5 * (a + b)
            J_ref = self._rule(a, m, b, _X16, _W16) + self._rule(m, b, b, _X16, _W16)
            err = np.abs(self._rule(a, b, b, _XT, _WT) - J_ref)
            ok = err <= _TABLE_TOL * -np.expm1(_Y_SW - b) / self.S_max  # J(b) >= (1 - e^-(b - y_sw)) / S_max
            if depth == _TABLE_DEPTH and not ok.all():  # pragma: no cover - S jumps
                warnings.warn(
                    f"sines: the fudge factor's S(A) is not smooth: the tau map's table is accurate to "
                    f"{float(np.max(err)):.1e} only",
                    RuntimeWarning,
                    stacklevel=2,
                )
                ok[:] = True
            acc_a.append(a[ok])
            acc_b.append(b[ok])
            acc_J.append(J_ref[ok])
            if ok.all():
                break
            a, b = np.concatenate([a[~ok], m[~ok]]), np.concatenate([m[~ok], b[~ok]])
        a, b, J = np.concatenate(acc_a), np.concatenate(acc_b), np.concatenate(acc_J)
        order = np.argsort(a)
        psi = [float(self.psi[-1])]
        for i in order:
            psi.append(psi[-1] * math.exp(a[i] - b[i]) + J[i])
        self.edges = np.concatenate([self.edges, b[order]])
        self.psi = np.concatenate([self.psi, psi[1:]])
        # per panel (rows): its left end, -(left + ln 2)/2 and J there; the right ends to search (a y beyond
        # the table finds row K, out of range: IndexError, and __call__ extends the table)
        self.inner = self.edges[1:]
        left = self.edges[:-1]
        self.panels = np.stack([left, -0.5 * (left + math.log(2.0)), self.psi[:-1]], axis=-1)

    def __call__(self, y):
        """(J(y), 1/S(A_c(y))) at y (any shape, y >= y_sw): the table plus _TABLE_Q points on the partial panel."""
        try:
            a = self.panels[np.searchsorted(self.inner, y)]  # (..., 3)
        except IndexError:  # beyond the table (or NaN)
            y_max = float(np.max(y))
            if not math.isfinite(y_max):  # (from a NaN guess: evaluated at y_sw, Newton goes on from tau_sw)
                return self(np.where(np.isfinite(y), y, _Y_SW))
            self.extend(y_max + 8.0)
            return self(y)
        s = y - a[..., 0]  # in [0, panel width]
        z = np.exp(a[..., 1:2] + s[..., None] * _NODES_T_H)  # e^{-y_i/2} / sqrt 2 at the nodes y_i
        e = z[..., -1:] / z
        e *= e  # e^{y_i - y}: e^{-s} at the left end, 1 at y
        hv = self.h(z)
        return a[..., 2] * e[..., 0] + s * ((hv * e) @ _W_T), hv[..., -1]


_TABLES: dict = {}


def _scaled_integral(fudge) -> _ScaledIntegral:
    """The cached :class:`_ScaledIntegral` of ``fudge`` (built on first use, ~1 ms)."""
    try:
        return _TABLES[fudge]
    except KeyError:
        pass
    except TypeError:  # pragma: no cover - an unhashable user FudgeFactor: no caching
        return _ScaledIntegral(fudge)
    tab = _ScaledIntegral(fudge)
    if len(_TABLES) > 64:
        _TABLES.clear()
    _TABLES[fudge] = tab
    return tab


@functools.lru_cache(maxsize=64)
def _mode_terms(L: float, N: int, tol: float, dh_max: float):
    """(tau_N, ln tau_N, n1, lam, tau_end, C_bound) of the dropped modes n > N (pressure^2 where dimensional).

    tau_N: from here on the N modes are converged to ``tol``; n1: the first dropped odd mode (even modes carry
    no area), decaying like e^{-lam t}; beyond tau_end = 60 / lam the dropped modes are ignored; C_bound bounds
    |int_a^tau [1/S(A_h) - 1/S(A_c)] dt| <= dh_max sum_{n>N odd} (4 / L k_n) e^{-k_n^2 a/2} / (k_n^2/2) for
    a >= tau_N, geometric from n1 (ratio e^{-(k_{n1+2}^2 - k_{n1}^2) tau_N/2}).
    """
    tau_N = 2.0 * _margin(tol) * (L / (math.pi * (N + 1))) ** 2
    n1 = N + 1 if N % 2 == 0 else N + 2
    k1 = n1 * math.pi / L
    lam = 0.5 * k1 * k1
    ratio = math.exp(-0.5 * ((n1 + 2) ** 2 - n1**2) * (math.pi / L) ** 2 * tau_N)
    C_bound = dh_max * 4.0 / (L * k1 * lam) * math.exp(-lam * tau_N) / (1.0 - ratio)
    return tau_N, math.log(tau_N), n1, lam, _LAMBDA_T_END / lam, C_bound


_LOADS = weakref.WeakKeyDictionary()


def _load_terms(problem, S1: float):
    """(ln p_bar^2, ln tau_sw, tau_sw, V_sw, max V_sw) of a problem's loads, tau_sw = p_bar^2 / 72, V_sw = tau_sw / S1.

    Cached per problem while its ``p_bar`` is read-only (an immutable problem); else computed.
    """
    pb = problem.p_bar
    try:
        hit = _LOADS.get(problem)
    except TypeError:  # pragma: no cover - an unhashable problem
        hit = None
    if hit is not None and hit[0] is pb and hit[1] == S1:
        return hit[2]
    lp2 = 2.0 * np.log(pb)
    x_sw = lp2 + _Y_SW
    tau_sw = np.exp(x_sw)
    V_sw = tau_sw * (1.0 / S1)
    terms = (lp2, x_sw, tau_sw, V_sw, float(V_sw.max()))
    if not pb.flags.writeable:
        try:
            _LOADS[problem] = (pb, S1, terms)
        except TypeError:  # pragma: no cover - not weakly referable
            pass
    return terms


class _TauMap:
    r"""Newton's method on F(tau) = V_sw + int_{tau_sw}^{tau} dt / S(A_h) - V_out for every (station, load).

    Shapes: ``V_out`` (n_zeta,), ``guess`` (n_zeta, n_loads); the loads ``p_bar`` (n_loads,).
    ``direct``: integrate on A_h itself (the far wall is not negligible) instead of the table + correction.
    Written for small arrays too (few numpy calls; bounds in Python floats decide what may be skipped).
    """

    def __init__(self, tab, L, N, tol, problem, direct):
        self.tab = tab
        self.S = tab.S
        self.L, self.N, self.tol, self.direct, self.pb = L, N, tol, direct, problem.p_bar
        self.tau_N, self.x_N, self.n1, self.lam, self.tau_end, self.C_bound = _mode_terms(L, N, tol, tab.dh_max)
        self.lp2, self.x_sw, self.tau_sw, self.V_sw, self.V_sw_max = _load_terms(problem, tab.S1)
        if direct:  # the far wall may take area early: A_h = 1 only while both walls are >= 6 sigma away
            tau_sw = np.minimum(self.tau_sw, (L - self.pb) ** 2 / (2.0 * _X_SWITCH**2))
            self.tau_sw, self.x_sw, self.V_sw = tau_sw, np.log(tau_sw), tau_sw / tab.S1
            self.V_sw_max = float(self.V_sw.max())
        self.correct = False  # with the dropped-mode correction (set by solve)
        self._L_a = self._tail = None  # its value from a = max(tau_N, tau_sw) on, and the dropped modes
        self.nodes = 0  # evaluations of the area

    # -- the dropped modes (t >= tau_N, far wall negligible) ------------------------------------------
    def _laguerre(self, b):
        """int_b^inf [1/S(A_h) - 1/S(A_c)] dt for b (n_loads,) or (n_zeta, n_loads) >= tau_N, where
        A_c - A_h = sum_{n>N odd} (4/L) sin(k_n p_bar)/k_n e^{-k_n^2 t/2} (the series beyond its N modes):
        12-point Gauss--Laguerre in lam (t - b)."""
        if self._tail is None:
            n_hi = max(self.n1, int(self.n1 * math.sqrt(_LAMBDA_T_END / (self.lam * self.tau_N))) + 1)
            k = np.arange(self.n1, n_hi + 1, 2, dtype=float) * (math.pi / self.L)
            c = (4.0 / self.L) * np.sin(np.outer(self.pb, k)) / k  # (n_loads, n_tail)
            self._tail = (-0.5 * k * k, c[:, :, None], self.pb[:, None] * math.sqrt(0.5))
        mk2, c, pbs = self._tail
        t = b[..., None] + _S_LAG / self.lam
        self.nodes += t.size
        Ac = erf(pbs / np.sqrt(t))
        Ah = np.minimum(np.maximum(Ac - (np.exp(t[..., None] * mk2) @ c)[..., 0], 0.0), 1.0)
        return ((1.0 / self.S(Ah) - 1.0 / self.S(Ac)) @ _W_LAG) / self.lam

    # -- the integral from tau_sw ----------------------------------------------------------------
    def _integral_table(self, x, tau, base):
        """(F / tau, 1 / S(A_c(tau))) at x = ln tau (n_zeta, n_loads), F = base + int_{tau_sw}^{tau} dt / S(A_h)."""
        J, h = self.tab(x - self.lp2)
        self.nodes += J.size * _NODES_T.size
        if self.correct:  # the dropped modes: int_a^tau = L(a) - L(tau), a = max(tau_N, tau_sw); L ~ 0 beyond tau_end
            a = np.maximum(self.tau_N, self.tau_sw)
            past = (tau > a) & (a < self.tau_end)
            if past.any():
                if self._L_a is None:
                    self._L_a = self._laguerre(a)
                C = self._L_a
                near = past & (tau < self.tau_end)
                if near.any():
                    C = C - np.where(near, self._laguerre(np.minimum(np.maximum(tau, a), self.tau_end)), 0.0)
                base = base + np.where(past, C, 0.0)
        return J + base / tau, h

    def _area(self, t):
        """A_h at t (n_zeta, n_loads, q) from its definition (the direct path), clipped to [0, 1]."""
        self.nodes += t.size
        pb = np.broadcast_to(self.pb[:, None], t.shape)
        A = image_area(self.L, pb, t)
        above = np.flatnonzero(t >= self.tau_N)
        chunk = max(1, 2**22 // (self.N // 2 + 1))  # nodes per series_area call (memory ~ nodes x N/2)
        for i in range(0, above.size, chunk):
            k = above[i : i + chunk]
            A.flat[k] = series_area(self.L, pb.flat[k], t.flat[k], self.N)
        return np.minimum(np.maximum(A, 0.0), 1.0)

    def _integral_direct(self, x, tau, base):
        """As :meth:`_integral_table` (with the exact F'), by composite Gauss--Legendre on A_h (split at tau_N)."""
        I = base
        for lo, hi in ((self.x_sw, np.minimum(x, self.x_N)), (np.maximum(self.x_sw, self.x_N), x)):
            d = np.maximum(hi - lo, 0.0)
            d_max = float(d.max())
            if d_max <= 0.0:
                continue
            P = math.ceil(d_max / _DIRECT_W)
            u = ((np.arange(P)[:, None] + _XD) / P).ravel()  # nodes of P equal panels on [0, 1]
            t = np.exp(lo[..., None] + d[..., None] * u)
            I = I + (d / P) * ((t / self.S(self._area(t))) @ np.tile(_WD, P))
        return I / tau, 1.0 / self.S(self._area(tau[..., None]))[..., 0]

    def solve(self, V_out, guess, rtol):
        """tau (n_zeta, n_loads) with |F| <= rtol V_out; also (Newton steps, max |F| / V_out, sum of steps).

        F is evaluated at every iterate; the step from it is accepted when it is short and Taylor's theorem
        bounds the residual at its end below rtol (then that bound is the residual reported).
        """
        Vo = V_out[:, None]
        V_sw = self.V_sw
        V_min = float(V_out[0])
        has_early = V_min <= self.V_sw_max
        early = (Vo <= V_sw) if has_early else None  # A_h = 1: tau = S(1) V exactly
        # the dropped-mode correction is left out where its bound is below rtol / 10; the target is tightened by it
        skipped = 0.0 if self.direct else self.C_bound / V_min
        self.correct = skipped > 0.1 * rtol
        if not self.correct:
            rtol = rtol - skipped
        # Taylor: F(x - dx) = F(x) - dx F'(x) + R, |R| <= dx^2/2 max|F''|, |F''| <= tau (1/S_min + 3 dh_max) as
        # |dA_h/d ln t| <= 3 (<= 0.25 per erf of the image sum, and the dropped modes' derivative is below tol);
        # the F' used differs from F' on the step by <= 2 tau dh_max tol (tau / S(A_c) in the table path, and
        # the jump of A_h at tau_N); tau <= S_max V e^{2|dx|} near the root.  So |F(x - dx)| / V_out <= res:
        tab = self.tab
        c1 = 2.0 * tab.dh_max * self.tol
        c2 = 0.5 * (1.0 / tab.S_min + 3.0 * tab.dh_max)
        integral = self._integral_direct if self.direct else self._integral_table
        base = V_sw - Vo
        x, tau = np.log(guess), guess
        moved = 0.0
        for it in range(1, _MAX_NEWTON + 1):
            Q, h = integral(x, tau, base)  # F / tau and F' / tau (F' = dF / d ln tau)
            F_tau = tau
            dx = Q / h
            if has_early:
                dx = np.where(early, 0.0, dx)
            step = float(np.abs(dx).max())
            if not step <= 2.0:  # (NaN: from a NaN guess; fmax takes it to tau_sw)
                dx = np.minimum(np.maximum(dx, -2.0), 2.0)
                step = 2.0
            x = np.fmax(x - dx, self.x_sw)
            moved += step
            if step <= _SHORT_STEP:
                res = step * tab.S_max * math.exp(2.0 * step) * (c1 + c2 * step)
                if res <= rtol:
                    tau = np.exp(x)
                    if has_early:
                        tau = np.where(early, tab.S1 * Vo, tau)
                    return tau, it, res, moved
            tau = np.exp(x)
        F = F_tau * Q
        if has_early:
            F = np.where(early, 0.0, F)
        raise RuntimeError(
            f"sines: the tau(V) map did not converge in {_MAX_NEWTON} Newton steps (max |F|/V_out = "
            f"{float((np.abs(F) / Vo).max()):.3e}, rtol = {rtol:.3e}); is the fudge factor's S(A) smooth?"
        )
