r"""Persson's original solution form: a sum of sines on [0, p_max] (``eq:P0_solution``).

With absorbing walls at p = 0 and p = L = p_max the diffusion equation
``E:diffusion_equ`` / ``eq:new_B2``, written in the effective variance
:math:`\tau = \int S\,dV`, is the plain heat equation, whose solution from
:math:`\delta(p - \bar p)` is

.. math::

    P_0(p, \tau) = \sum_{n\ge1} \frac{2}{L}\,\sin(k_n \bar p)\,\sin(k_n p)\,
                   e^{-\frac12 k_n^2 \tau}, \qquad k_n = n\pi/L .

The delta initial condition is represented exactly (no start-up zeta0), and
the error is the truncation of the series alone: it falls faster than any
power of the mode count (like :math:`e^{-\frac12 k_N^2\tau}`).  The far wall
adds an error of order :math:`e^{-(L-\bar p)^2/2\tau}` (< 1e-21 for the
default domain).

Contact area and load are exact integrals of the series,

.. math::

    A^* = \sum_n \frac{2}{L}\sin(k_n\bar p)\,\frac{1-\cos n\pi}{k_n}\,e^{-\frac12 k_n^2\tau},
    \qquad \int_0^L p\,\sin(k_n p)\,dp = -\frac{L\cos n\pi}{k_n},

so neither is limited by an output grid.  P0 is returned on Gauss--Legendre
nodes of [0, L] with their weights, spectrally accurate for the load and
variance integrals that :class:`~persson_fp.Solution` forms from the weights.

**Fudge factors** (``eq:new_B2``).  tau(zeta) must come from the *numerical*
area of the series: :math:`d\tau/dV = S(A^*_{series}(\tau))`.  The series
area depends on tau alone, so the ODE is separable,

.. math::  V(\tau) = V_{sw} + \int_{\tau_{sw}}^{\tau} \frac{dt}{S(A^*_{series}(t))},

and is solved per load by a Chebyshev interpolant of the integrand in
:math:`x = \ln\tau` (sizes 33, 65, ..., until the coefficient tail is below
``rtol``), integrated exactly, and inverted by Newton's method at the output
stations.  This is the "scalar ODE per load", solved to ``rtol`` with
spectral rather than step-size control.

*Tiny tau.*  For :math:`\tau \le \tau_{sw} = \bar p^2/72` the series area is 1 to round-off:
the infinite series equals the image sum on [0, L] (Poisson summation), whose mass defect is
:math:`\mathrm{erfc}(\bar p/\sqrt{2\tau}) < 2\cdot10^{-17}` there, so :math:`\tau = S(1)\,V` exactly.
Between :math:`\tau_{sw}` and :math:`\tau_N` (where the chosen N modes are converged to ``tol``)
the same infinite series is summed in that dual form (:func:`image_area`, images |k| <= 1,
the rest below e^-200), so the mode count only has to serve the output stations: the default
is the one that makes the truncation below ``tol`` at the first station.  (Before, N was sized
for :math:`\bar p^2/72`, and a load of 1e-4 sqrt(V) with a fudge factor needed 1.4 million modes.)
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.fft import dct

from ..fudge import NoFudge
from .base import Solver, SolverOutput, check_float, check_int

__all__ = ["SineSeriesSolver", "series_area", "image_area", "series_pdf", "modes_needed"]

_X_SWITCH = 6.0
"""A* = 1 to round-off while p_bar / sqrt(2 tau) >= 6 (erfc(6) = 2.2e-17)."""


def modes_needed(L: float, tau, tol: float) -> np.ndarray:
    r"""Smallest mode count N with :math:`2 e^{-\frac12 k_{N+1}^2 \tau}/(1-r) <` ``tol``.

    ``2 e^{-k^2 tau/2}`` bounds the L1 norm (and the area) contributed by mode
    k; r is the ratio of successive dropped terms.  ``L`` pressure, ``tau``
    pressure^2 (> 0).
    """
    tau = np.asarray(tau, dtype=float)
    c = np.log(2.0 / tol) + np.log(4.0)  # margin for the geometric tail (r <= 3/4 below)
    n = np.ceil(L / np.pi * np.sqrt(2.0 * c / tau))
    return n.astype(int)


def series_area(L: float, p_bar, tau, n_modes: int) -> np.ndarray:
    r"""Contact area of the truncated series (dimensionless),

    .. math:: A^* = \sum_n \frac{2}{L}\sin(k_n\bar p)\frac{1-\cos n\pi}{k_n}e^{-k_n^2\tau/2}.

    ``p_bar`` and ``tau`` broadcast (pressure, pressure^2); only odd modes contribute.
    """
    p_bar, tau = np.broadcast_arrays(np.asarray(p_bar, float), np.asarray(tau, float))
    n = np.arange(1, n_modes + 1, 2, dtype=float)  # odd modes: 1 - cos(n pi) = 2
    k = n * np.pi / L
    with np.errstate(under="ignore"):
        terms = (4.0 / L) * np.sin(k * p_bar[..., None]) / k * np.exp(-0.5 * k * k * tau[..., None])
    return terms.sum(axis=-1)


def image_area(L: float, p_bar, tau) -> np.ndarray:
    r"""Area of the infinite sine series summed as its Poisson dual, the image sum on [0, L].

    :math:`P_0 = \sum_k [\rho(p; 2kL+\bar p) - \rho(p; 2kL-\bar p)]` integrated over [0, L], k = -1, 0, 1
    (the others are below :math:`e^{-(2L-\bar p)^2/2\tau}`, < e^-200 on the default domain).  Equal to
    :func:`series_area` with infinitely many modes; cheap where the series needs many.
    """
    from scipy.special import erf

    p_bar, tau = np.broadcast_arrays(np.asarray(p_bar, float), np.asarray(tau, float))
    s = np.sqrt(2.0 * tau)

    def F(c):  # int_0^L rho(p; c, tau) dp
        return 0.5 * (erf((L - c) / s) + erf(c / s))

    return sum(F(2.0 * k * L + p_bar) - F(2.0 * k * L - p_bar) for k in (-1, 0, 1))


def series_pdf(p, L: float, p_bar: float, tau: float, n_modes: int) -> np.ndarray:
    r"""P0(p) of the truncated series (``eq:P0_solution``), readable reference form (1/pressure)."""
    p = np.asarray(p, dtype=float)
    n = np.arange(1, n_modes + 1, dtype=float)
    k = n * np.pi / L
    with np.errstate(under="ignore"):
        coef = (2.0 / L) * np.sin(k * p_bar) * np.exp(-0.5 * k * k * tau)
    return np.sin(p[..., None] * k) @ coef


_PANEL = 64
"""Nodes per panel of the composite Gauss--Legendre rule used for many output points."""


@functools.lru_cache(maxsize=32)
def _gauss_legendre(n: int):
    """Gauss--Legendre nodes and weights on [-1, 1] (cached).

    Up to 512 nodes one rule (``leggauss``, O(n^3) but < 0.1 s); beyond, a composite rule of
    ceil(n / 64) equal panels with 64 nodes each -- O(n), and still exact for the sine series as
    long as each panel holds few wavelengths (n >= 1.2 x modes guarantees < 27 half-waves per panel,
    well inside a 64-point rule's reach).
    """
    if n <= 512:
        x, w = np.polynomial.legendre.leggauss(n)
    else:
        m = -(-n // _PANEL)
        xp, wp = np.polynomial.legendre.leggauss(_PANEL)
        left = -1.0 + 2.0 * np.arange(m) / m
        x = (left[:, None] + (xp[None, :] + 1.0) / m).ravel()
        w = np.tile(wp / m, m)
    x.setflags(write=False)
    w.setflags(write=False)
    return x, w


def _cheb_nodes(m: int) -> np.ndarray:
    """Chebyshev points of the first kind on [-1, 1] (ascending)."""
    return -np.cos(np.pi * (np.arange(m) + 0.5) / m)


def _cheb_coeffs(f: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients (axis 0) of values ``f`` at :func:`_cheb_nodes` (axis 0)."""
    m = f.shape[0]
    # nodes ascending = reversed standard order: T_j(-x) = (-1)^j T_j(x)
    c = dct(f[::-1], type=2, axis=0) / m
    c[0] *= 0.5
    return c


class SineSeriesSolver(Solver):
    r"""Sum of sines on [0, p_max] (``eq:P0_solution``), exact in zeta once tau(zeta) is known.

    Options
    -------
    n_p : int or None
        Number of sine modes N; ``None`` chooses it so that the truncation is
        below ``tol`` at the smallest tau that matters (module docstring).
    n_eval : int or None
        Gauss--Legendre output nodes on [0, p_max]; ``None``: enough for the
        load integral to round-off at the first output station.
    tol : float
        Truncation target of the automatic mode count (L1 of P0, dimensionless).
    rtol : float
        Tolerance of the tau(V) map with a fudge factor (Chebyshev tail,
        relative); unused without one.
    k_domain : float
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)).
    """

    name = "sines"
    OPTIONS = {"n_p": None, "n_eval": None, "tol": 1e-13, "rtol": 1e-14, "k_domain": 10.0}

    def validate(self) -> None:
        o = self.opts
        if o["n_p"] is not None:
            o["n_p"] = check_int(o["n_p"], "n_p", 1, 10_000_000)
        if o["n_eval"] is not None:
            o["n_eval"] = check_int(o["n_eval"], "n_eval", 2, 10_000_000)
        o["tol"] = check_float(o["tol"], "tol", 0.0, 1e-2)
        o["rtol"] = check_float(o["rtol"], "rtol", 0.0, 1e-3)
        o["k_domain"] = check_float(o["k_domain"], "k_domain", 0.0, 1e3)

    # -- tau(V) from the series area -------------------------------------------------------------
    def _tau_map(self, L, N, V_out):
        """tau at the complete-contact variances ``V_out`` (n_zeta,) for every load, shape (n_zeta, n_loads)."""
        pr = self.problem
        pb = pr.p_bar
        fudge = pr.fudge
        if isinstance(fudge, NoFudge):
            return np.repeat(V_out[:, None], pb.size, axis=1), {"chebyshev_nodes": 0}
        tol = self.opts["tol"]
        rtol = self.opts["rtol"]
        S1 = float(fudge.S(np.array(1.0)))
        S_max = float(np.max(fudge.S(np.linspace(0.0, 1.0, 2001))))
        tau_N = 2.0 * (np.log(2.0 / tol) + np.log(4.0)) * (L / (np.pi * (N + 1))) ** 2
        tau_sw = pb**2 / (2.0 * _X_SWITCH**2)  # (n_loads,) A* = 1 to round-off below
        V_sw = tau_sw / S1
        V_max = float(V_out[-1])
        tau_hi = tau_sw + max(V_max - V_sw.min(), 0.0) * S_max * (1.0 + 1e-9) + 1e-300
        x_lo, x_hi = np.log(tau_sw), np.log(np.maximum(tau_hi, tau_sw * (1 + 1e-12)))
        half = 0.5 * (x_hi - x_lo)

        # per load, the modes that matter at tau >= tau_sw (the rest are below tol there)
        N_j = np.minimum(N, modes_needed(L, tau_sw, tol))

        def g(x):  # dV/dx = tau / S(A(tau)), x = ln tau; shape (m, n_loads)
            tau = np.exp(x)
            A = np.stack([series_area(L, pb[j], tau[:, j], int(N_j[j])) for j in range(pb.size)], axis=1)
            # where N modes are not yet converged (tau < tau_N) the same infinite series is summed in its
            # Poisson-dual form, the image sum on [0, L] (exact; images beyond |k| = 1 are below e^-200)
            small = tau < tau_N
            if np.any(small):
                A = np.where(small, image_area(L, pb[None, :], tau), A)
            return tau / fudge.S(np.clip(A, 0.0, 1.0))

        for m in (33, 65, 129, 257, 513, 1025, 2049):
            xk = x_lo + half * (_cheb_nodes(m)[:, None] + 1.0)
            c = _cheb_coeffs(g(xk))
            tail = np.max(np.abs(c[-4:]), axis=0) / np.max(np.abs(c), axis=0)
            if np.all(tail < rtol):
                break
        from numpy.polynomial import chebyshev as C

        Ci = C.chebint(c, lbnd=-1.0, axis=0) * half  # V - V_sw as a Chebyshev series in t in [-1, 1]

        def Vof(t):  # t (k, n_loads) in [-1, 1] -> V
            return V_sw + C.chebval(t, Ci, tensor=False)

        if np.any(Vof(np.ones((1, pb.size)))[0] < V_max * (1 - 1e-12)):  # pragma: no cover - S_max bound
            raise RuntimeError("sines: tau range too short for V_max (S bound violated)")
        # invert V(t) = V_out: a coarse bracketing table, then Newton steps (dV/dt = half * g)
        tt = np.linspace(-1.0, 1.0, 257)
        Vt = Vof(np.repeat(tt[:, None], pb.size, axis=1))  # (257, n_loads), increasing
        Vo = np.repeat(V_out[:, None], pb.size, axis=1)
        t = np.empty_like(Vo)
        for j in range(pb.size):
            i = np.clip(np.searchsorted(Vt[:, j], Vo[:, j]) - 1, 0, tt.size - 2)
            t[:, j] = tt[i] + (Vo[:, j] - Vt[i, j]) / (Vt[i + 1, j] - Vt[i, j]) * (tt[1] - tt[0])
        t = np.clip(t, -1.0, 1.0)
        for _ in range(10):
            dt = (Vof(t) - Vo) / (C.chebval(t, c, tensor=False) * half)
            t = np.clip(t - dt, -1.0, 1.0)
            if np.all(np.abs(dt) < 1e-15):
                break
        tau_out = np.exp(x_lo + half * (t + 1.0))
        early = Vo <= V_sw
        tau_out[early] = S1 * Vo[early]
        return tau_out, {"chebyshev_nodes": m, "chebyshev_tail": float(np.max(tail)), "tau_switch": tau_sw}

    # -- the solve --------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        pr = self.problem
        o = self.opts
        pb = pr.p_bar
        L = pr.p_max(o["k_domain"])
        V_out = np.atleast_1d(pr.V(self.zeta_out)).astype(float)
        tol = o["tol"]
        with np.errstate(divide="ignore"):
            if o["n_p"] is not None:
                N = o["n_p"]
            else:
                # smallest tau that matters: the first station (tau >= min(S) V there); below it the
                # fudge factor's tau map evaluates the series area through its image dual (_tau_map)
                S_min = float(np.min(pr.fudge.S(np.linspace(0.0, 1.0, 201))))
                N = int(modes_needed(L, S_min * V_out[0], tol))
        tau, tinfo = self._tau_map(L, N, V_out)  # (n_zeta, n_loads)

        # output modes: those above tol / 1e3 at the first station, at most N
        N_out = int(min(N, modes_needed(L, float(np.min(tau[0])), tol * 1e-3)))
        n_eval = o["n_eval"] or int(max(64, np.ceil(1.2 * N_out + 40)))
        xg, wg = _gauss_legendre(n_eval)
        p = 0.5 * L * (xg + 1.0)
        w = 0.5 * L * wg

        n = np.arange(1, N_out + 1, dtype=float)
        k = n * np.pi / L
        with np.errstate(under="ignore"):
            coef = (
                (2.0 / L) * np.sin(k[None, None, :] * pb[None, :, None]) * np.exp(-0.5 * k * k * tau[..., None])
            )  # (n_zeta, n_loads, N_out)
        P0 = coef @ np.sin(np.outer(k, p))  # (n_zeta, n_loads, n_eval)
        odd = (n % 2) == 1
        A = (coef[..., odd] * (2.0 / k[odd])).sum(axis=-1)
        info = {
            "grid": "Gauss-Legendre",
            "p_max": L,
            "n_modes": N,
            "n_modes_out": N_out,
            "n_eval": n_eval,
            "tau": tau,
            "zeta0": 1.0,
            "steps": 0,
            **tinfo,
        }
        return SolverOutput(p=p, P0=P0, weights=w, kind="point", info=info, contact_area=A)
