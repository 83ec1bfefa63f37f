r"""Effective variance tau(V) of the fudge-factor theory (Xu et al. tutorial, ``eq:new_B2``).

With :math:`B_2 = S(A^*)\,dV/d\zeta` define :math:`\tau(\zeta) = \int S\,dV`.  In tau
the equation is the plain heat equation with the same data, so :math:`P_0` is
the image solution (``eq:P0_solution``) evaluated at tau, and
:math:`A^* = \mathrm{erf}(\bar p/\sqrt{2\tau})`.  tau obeys the autonomous ODE

.. math::  \frac{d\tau}{dV} = S\big(\mathrm{erf}(\bar p/\sqrt{2\tau})\big), \qquad \tau(0) = 0 .

With :math:`u = \tau/\bar p^2`, :math:`v = V/\bar p^2` it becomes
:math:`du/dv = S(\mathrm{erf}(1/\sqrt{2u}))`, free of the load, the spectrum and
E*.  One tight solve per fudge factor, in log variables with dense output,
serves every load and surface: :class:`EffectiveVariance` caches it.  Evaluation uses a
cubic Hermite table of :math:`w = \ln u` against :math:`s = \ln v` (``_TABLE`` equal steps,
slopes from the ODE itself; scipy's ``CubicHermiteSpline``), within ~2e-12 relative of the solver's
dense output and ~10x cheaper to evaluate than that dense output, which matters
because every solver asks for tau(V) in its set-up.

For :math:`u \le u_0 = 10^{-3}` the area is 1 to double precision
(erfc(22.4) < 1e-200), so there :math:`u = S(1)\,v` exactly.  Beyond
:math:`v_{max} = 10^{16}` (:math:`\bar p/\sqrt V < 10^{-8}`) tau is continued
linearly with the end slope (relative error below 1e-8 there).

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import erf

from persson_fp._validate import as_nonnegative_array
from persson_fp.theory.fudge import FudgeFactor, NoFudge

__all__ = ["EffectiveVariance", "effective_variance"]

_U0 = 1e-3
_V_MAX = 1e16
_RTOL = 1e-13
_TABLE = 8192
"""Nodes of the Hermite table in s = ln v (step ~5e-3; interpolation error below 1e-11 relative: up to 6.4e-12
for YP08 near p_bar / sqrt(V) = 0.01-0.03, against an independent high-precision integration)."""


class EffectiveVariance:
    """The map v -> u of one fudge factor, solved once (see module docstring).

    Parameters
    ----------
    fudge : FudgeFactor
        The model S(A*).  :class:`~persson_fp.theory.fudge.NoFudge` gives u = v exactly.
    """

    def __init__(self, fudge: FudgeFactor):
        if not isinstance(fudge, FudgeFactor):
            raise ValueError(
                f"fudge must be a FudgeFactor (from persson_fp.fudge.resolve), got {type(fudge).__name__} {fudge!r}"
            )
        self.fudge = fudge
        self.identity = isinstance(fudge, NoFudge)
        if self.identity:
            return
        S1 = float(fudge.S(np.array(1.0)))
        self.S1 = S1
        self.v0 = _U0 / S1
        s0, s1 = np.log(self.v0), np.log(_V_MAX)

        def rhs(s, w):
            u = np.exp(w)
            A = erf(np.exp(-0.5 * w) / np.sqrt(2.0))
            return np.exp(s) / u * fudge.S(A)

        from scipy.integrate import solve_ivp  # here, not at the top: keeps `import persson_fp` light
        from scipy.interpolate import CubicHermiteSpline

        sol = solve_ivp(rhs, (s0, s1), [np.log(_U0)], method="DOP853", rtol=_RTOL, atol=_RTOL, dense_output=True)
        if not sol.success:  # pragma: no cover - a positive finite S always integrates
            raise RuntimeError(f"effective-variance ODE failed for {fudge!r}: {sol.message}")
        self._sol = sol.sol
        self.nfev = sol.nfev
        s_tab = np.linspace(s0, s1, _TABLE)
        w_tab = sol.sol(s_tab)[0]
        dw_ds = rhs(s_tab, w_tab)
        self._w_of_s = CubicHermiteSpline(s_tab, w_tab, dw_ds)  # slopes from the ODE itself
        self._s_of_w = CubicHermiteSpline(w_tab, s_tab, 1.0 / dw_ds)  # its inverse (dw/ds = S v/u > 0)
        self._w_lo, self._w_hi = float(w_tab[0]), float(w_tab[-1])
        w_end = sol.y[0, -1]
        self.u_end = float(np.exp(w_end))
        self.slope_end = float(fudge.S(erf(np.exp(-0.5 * w_end) / np.sqrt(2.0))))

    def u_of_v(self, v: ArrayLike) -> np.ndarray:
        """Scaled effective variance u = tau / p_bar^2 at scaled variance v = V / p_bar^2.

        Parameters
        ----------
        v : array_like, dimensionless
            Scaled complete-contact variance(s) V / p_bar^2, >= 0.

        Returns
        -------
        numpy.ndarray, dimensionless
            u at each ``v``.
        """
        v = np.asarray(v, dtype=float)
        if self.identity:
            return v.copy()
        # (written without masks and branches: every solver calls this in its set-up, on small arrays)
        s = np.log(np.minimum(np.maximum(v, self.v0), _V_MAX))  # (NaN only from 0/0 in tau: masked there)
        u = np.exp(self._w_of_s(s))
        u = np.where(v <= self.v0, self.S1 * v, u)
        return np.where(v > _V_MAX, self.u_end + self.slope_end * (v - _V_MAX), u)

    def v_of_u(self, u: ArrayLike) -> np.ndarray:
        """The inverse of :meth:`u_of_v`: scaled variance v at scaled effective variance u (same table).

        Parameters
        ----------
        u : array_like, dimensionless
            Scaled effective variance(s) tau / p_bar^2, >= 0.

        Returns
        -------
        numpy.ndarray, dimensionless
            v at each ``u``.
        """
        u = np.asarray(u, dtype=float)
        if self.identity:
            return u.copy()
        w = np.log(np.minimum(np.maximum(u, _U0), self.u_end))
        v = np.exp(self._s_of_w(np.minimum(np.maximum(w, self._w_lo), self._w_hi)))
        v = np.where(u <= _U0, u / self.S1, v)
        return np.where(u > self.u_end, _V_MAX + (u - self.u_end) / self.slope_end, v)

    def w_dense(self, s: ArrayLike) -> np.ndarray:
        """ln u at s = ln v from the ODE solver's own dense output (the reference of the table).

        Parameters
        ----------
        s : array_like, dimensionless
            ln v, inside the solved range ``[ln(1e-3 / S(1)), ln(1e16)]``.

        Returns
        -------
        numpy.ndarray, dimensionless
            ln u at each ``s``.
        """
        return self._sol(np.asarray(s, dtype=float))[0]

    def tau(self, p_bar: ArrayLike, V: ArrayLike) -> np.ndarray:
        """Effective variance tau = int S dV reached at complete-contact variance ``V`` under load ``p_bar``.

        Parameters
        ----------
        p_bar : array_like, pressure
            Nominal pressure(s), > 0.
        V : array_like, pressure^2
            Complete-contact variance(s), >= 0; broadcast against ``p_bar``.

        Returns
        -------
        numpy.ndarray, pressure^2
            tau(p_bar, V).
        """
        p_bar = as_nonnegative_array(p_bar, "p_bar", allow_zero=False)
        V = as_nonnegative_array(V, "V")
        if self.identity:
            return np.array(np.broadcast_to(V, np.broadcast_shapes(p_bar.shape, V.shape)))
        p2 = p_bar * p_bar
        # beyond v = V_MAX the map is linear, tau = slope V + p^2 (u_end - slope V_MAX): written without
        # forming V / p^2, which overflows for extreme loads (p_bar < 1e-154 sqrt(V))
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            v = V / p2
            v = np.where(v <= _V_MAX, v, np.inf)  # 0/0 (V = 0 with p_bar^2 underflowed) -> far branch, tau = 0
            near = p2 * self.u_of_v(np.minimum(v, _V_MAX))
        far = self.slope_end * V + p2 * (self.u_end - self.slope_end * _V_MAX)
        out = np.where(v <= _V_MAX, near, far)
        # A* = 1 branch written without V / p^2, which underflows for huge loads (p_bar ~ 1e150, small V)
        return np.where(V <= self.v0 * p2, self.S1 * V, out)

    def V_of_tau(self, p_bar: ArrayLike, tau: ArrayLike) -> np.ndarray:
        """The complete-contact variance V at which the effective variance reaches ``tau`` (inverse of :meth:`tau`).

        Parameters
        ----------
        p_bar : array_like, pressure
            Nominal pressure(s), > 0.
        tau : array_like, pressure^2
            Effective variance(s), >= 0; broadcast against ``p_bar``.

        Returns
        -------
        numpy.ndarray, pressure^2
            V(p_bar, tau).
        """
        p_bar = as_nonnegative_array(p_bar, "p_bar", allow_zero=False)
        tau = as_nonnegative_array(tau, "tau")
        if self.identity:
            return np.array(np.broadcast_to(tau, np.broadcast_shapes(p_bar.shape, tau.shape)))
        p2 = p_bar * p_bar
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            u = tau / p2
            u = np.where(u <= self.u_end, u, np.inf)
            near = p2 * self.v_of_u(np.minimum(u, self.u_end))
            far = _V_MAX * p2 + (tau - self.u_end * p2) / self.slope_end  # (overflows only where unused)
        out = np.where(u <= self.u_end, near, far)
        return np.where(tau <= _U0 * p2, tau / self.S1, out)  # (as in tau: no tau / p^2 underflow)


_CACHE: dict = {}


def effective_variance(fudge: FudgeFactor) -> EffectiveVariance:
    """The cached :class:`EffectiveVariance` of ``fudge`` (solved on first use, ~10 ms).

    Parameters
    ----------
    fudge : FudgeFactor
        The model S(A*), e.g. from :func:`persson_fp.theory.fudge.resolve`.

    Returns
    -------
    EffectiveVariance
        The map of that model, shared by every caller.
    """
    if not isinstance(fudge, FudgeFactor):
        raise ValueError(
            f"fudge must be a FudgeFactor (from persson_fp.fudge.resolve), got {type(fudge).__name__} {fudge!r}"
        )
    try:
        return _CACHE[fudge]
    except KeyError:
        ev = EffectiveVariance(fudge)
        if len(_CACHE) > 64:
            _CACHE.clear()
        _CACHE[fudge] = ev
        return ev
