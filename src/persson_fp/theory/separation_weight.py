r"""The energy weighting of Persson's mean separation with a fudge factor: :math:`\omega(y) = A\,S(A)` at
:math:`y = \bar p/\sqrt{V}`, its derivative in closed form and the tabulated kernel
:math:`g(y) = \int_y^\infty \omega'(s)/s\,ds` that :class:`~persson_fp.theory.separation.MeanSeparation` and
:mod:`persson_fp.theory.resolved` integrate (one table per fudge model and weighting, cached).
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf

from persson_fp.theory import fudge as _fudge
from persson_fp.theory.effective import effective_variance

_Y_MIN, _N_TAB = 1e-9, 6000
_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)
_SQRT_2_PI = np.sqrt(2.0 / np.pi)


class _Weight:
    """omega(y), omega'(y) and the table of g(y) of one fudge model and weighting."""

    def __init__(self, fudge, weighting):
        from scipy.interpolate import CubicHermiteSpline  # here, not at the top: keeps `import persson_fp` light

        self.fudge = fudge
        self.plain = weighting == "yang-persson" or isinstance(fudge, _fudge.NoFudge)
        self.ev = None if self.plain else effective_variance(fudge)
        S1 = float(fudge.S(np.array(1.0)))
        # beyond y_max, omega = 1 and omega' = 0 to double precision, and g < 1e-190 g(1) is returned as 0
        self.y_max = 30.0 * np.sqrt(max(S1, 1.0))
        t = np.linspace(np.log(_Y_MIN), np.log(self.y_max), _N_TAB)
        a, b = t[:-1], t[1:]
        tt = (0.5 * (b - a))[:, None] * _GL_X + (0.5 * (a + b))[:, None]
        # g(y_i) = int_{y_i}^{y_max} omega'(y)/y dy = int omega'(e^t) dt
        piece = np.sum((0.5 * (b - a))[:, None] * _GL_W * self.domega(np.exp(tt)), axis=1)
        g = np.cumsum(piece[::-1])[::-1]  # at t[:-1]; summed from the top: full relative accuracy in the tail
        t = t[:-1]
        self.t_lo, self.t_hi = t[0], t[-1]
        self.g_lo = g[0]
        self.slope_lo = float(self.domega(np.array(_Y_MIN)))  # g ~ g_lo + omega'(0) ln(y_min / y) below
        # ln g in ln y: smooth where g falls like exp(-y^2/2) (a table of g itself loses relative accuracy there)
        self._lng = CubicHermiteSpline(t, np.log(g), -self.domega(np.exp(t)) / g)  # d ln g/d ln y = -omega'/g

    def area(self, y):
        """The contact area the weight uses at y = p_bar / sqrt(V) (plain erf or the model's corrected A*)."""
        if self.plain:
            return erf(y / np.sqrt(2.0))
        with np.errstate(divide="ignore", over="ignore"):
            u = self.ev.u_of_v(np.where(y > 0, 1.0 / (y * y), np.inf))
        return erf(1.0 / np.sqrt(2.0 * u))

    def omega(self, y):
        A = self.area(y)
        return A * self.fudge.S(A)

    def domega(self, y):
        """d omega / dy (closed form: the chain rule through erf and, if corrected, the effective-variance ODE)."""
        y = np.minimum(np.asarray(y, dtype=float), self.y_max)  # omega' = 0 to double precision beyond y_max
        A = self.area(y)
        S = self.fudge.S(A)
        dW_dA = S + A * self.fudge.dS_dA(A)
        if self.plain:
            with np.errstate(under="ignore"):
                return np.where(y >= self.y_max, 0.0, dW_dA * _SQRT_2_PI * np.exp(-0.5 * y * y))
        # A = erf(1/sqrt(2u)), du/dv = S(A), v = 1/y^2:  dA/dy = (2/y^3) S(A) u^(-3/2) e^(-1/(2u)) / sqrt(2 pi)
        u = self.ev.u_of_v(1.0 / (y * y))
        with np.errstate(under="ignore"):
            dA_dy = 2.0 / y**3 * S * u**-1.5 * np.exp(-0.5 / u) / np.sqrt(2.0 * np.pi)
        return np.where(y >= self.y_max, 0.0, dW_dA * dA_dy)

    def g(self, y):
        y = np.asarray(y, dtype=float)
        with np.errstate(divide="ignore"):
            t = np.log(y)
        inside = np.exp(self._lng(np.clip(t, self.t_lo, self.t_hi)))
        below = self.g_lo + self.slope_lo * (self.t_lo - t)
        return np.where(t < self.t_lo, below, np.where(t > self.t_hi, 0.0, inside))

    @property
    def g_infinity(self):
        """lim_{y -> 0} g(y) + omega'(0) ln y (the constant of the small-load law)."""
        return self.g_lo + self.slope_lo * self.t_lo


_WEIGHTS: dict = {}


def _weight(fudge, weighting):
    key = (fudge, weighting)
    if key not in _WEIGHTS:
        if len(_WEIGHTS) > 32:
            _WEIGHTS.clear()
        _WEIGHTS[key] = _Weight(fudge, weighting)
    return _WEIGHTS[key]
