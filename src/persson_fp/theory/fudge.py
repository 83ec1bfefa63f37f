r"""Fudge factors S(A*) of the corrected theories, ``eq:new_B2``.

The corrected diffusion coefficient is :math:`B_2 = S(A^*)\, dV/d\zeta`, where
:math:`A^*` is the current relative contact area.  A fudge factor here is any
object with a vectorised ``S(A)`` that is finite and > 0 on ``[0, 1]``.

Default parameters are stated **once**, in this module:

=====================  ==========================================  =====================
model                  S(A*)                                       default gamma
=====================  ==========================================  =====================
``None`` (Persson 01)  1                                           --
``"YP08"``             gamma + (1 - gamma) A*^2                    ``GAMMA_YP08`` = 0.45
``"WM17"``             gamma - 2/9 A*^2 + (11/9 - gamma) A*^4      ``GAMMA_WM17`` = 5/9
``"Xu24"``             global: A* = erf(p/sqrt(2 (gamma+(1-gamma)  ``GAMMA_XU24`` = 0.45
                       A*) V)); as a B2 form S = dtau/dV below
=====================  ==========================================  =====================

The models are those of Yang and Persson [1]_, Wang and Müser [2]_ and Xu et al. [3]_.
The Yang--Persson gamma is documented in [0.42, 0.48] (Xu et al. tutorial, Sec.
"Fudge factors"); note that a published MATLAB implementation of these models uses
0.42 in its code while its documentation says 0.45 -- here the default is 0.45,
and it is the value of ``GAMMA_YP08``.

References
----------
.. [1] C. Yang, B.N.J. Persson, J. Phys.: Condens. Matter 20 (2008) 215214.
.. [2] A. Wang, M.H. Müser, Tribol. Lett. 65 (2017) 103.
.. [3] Y. Xu et al., global corrected Persson model (2024).

This module imports no solver.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import erfinv

from persson_fp._validate import as_float_array, as_nonnegative_array

__all__ = [
    "GAMMA_YP08",
    "GAMMA_WM17",
    "GAMMA_XU24",
    "FudgeFactor",
    "NoFudge",
    "YangPersson",
    "WangMuser",
    "Xu24",
    "CallableFudge",
    "resolve",
    "MODELS",
]

GAMMA_YP08 = 0.45
"""Default gamma of Yang & Persson (2008); documented range [0.42, 0.48]."""
GAMMA_WM17 = 5.0 / 9.0
"""Default gamma of Wang & Müser (2017)."""
GAMMA_XU24 = 0.45
"""Default gamma of the global model of Xu et al. (2024)."""

_CHECK_GRID = np.linspace(0.0, 1.0, 2001)
S_MAX = 1e6
"""Largest S(A*) accepted from a user model (physical fudge factors are O(1))."""


class FudgeFactor:
    """Base class: a positive function ``S(A)`` of the relative contact area ``A`` in [0, 1].

    A subclass sets ``name`` and implements :meth:`S` (vectorised); :meth:`dS_dA` defaults to central
    differences and :meth:`check` validates S on a fine grid of [0, 1].
    """

    name: str = "fudge"

    def S(self, A: ArrayLike) -> np.ndarray:  # pragma: no cover - abstract
        r"""The fudge factor S(A*) of ``eq:new_B2``, :math:`B_2 = S(A^*)\,dV/d\zeta`.

        Parameters
        ----------
        A : array_like, dimensionless
            Relative contact area(s) in [0, 1].

        Returns
        -------
        numpy.ndarray, dimensionless
            S at each ``A``, finite and > 0.
        """
        raise NotImplementedError

    def __call__(self, A: ArrayLike) -> np.ndarray:
        return self.S(A)

    def dS_dA(self, A: ArrayLike) -> np.ndarray:
        """Derivative dS/dA (central differences unless a subclass knows it in closed form).

        Parameters
        ----------
        A : array_like, dimensionless
            Relative contact area(s) in [0, 1].

        Returns
        -------
        numpy.ndarray, dimensionless
            dS/dA at each ``A``.
        """
        A = np.asarray(A, dtype=float)
        h = 1e-6
        lo = np.clip(A - h, 0.0, 1.0)
        hi = np.clip(A + h, 0.0, 1.0)
        return (self.S(hi) - self.S(lo)) / (hi - lo)

    def check(self) -> None:
        """Raise ``ValueError`` unless S is a number in (0, S_MAX] on a fine grid of [0, 1].

        (A physical fudge factor is O(1); the bound keeps tau = int S dV representable.)

        Returns
        -------
        None
            Returns only if S passes.

        Raises
        ------
        ValueError
            Naming the model and the first area at which S is not finite, not > 0 or above ``S_MAX``.
        """
        try:
            with np.errstate(all="ignore"):
                raw = self.S(_CHECK_GRID)
                if np.iscomplexobj(raw):
                    raise TypeError("it returned complex values")
                s = np.asarray(raw, dtype=float)
        except Exception as err:  # a user callable may raise anything: report it as bad input
            raise ValueError(
                f"fudge factor {self.name}: S(A*) must return numbers (real) for A* in [0, 1], "
                f"but {type(err).__name__}: {err}"
            ) from None
        if s.shape != _CHECK_GRID.shape:
            s = np.broadcast_to(s, _CHECK_GRID.shape)
        bad = ~np.isfinite(s) | (s <= 0) | (s > S_MAX)
        if np.any(bad):
            a = _CHECK_GRID[np.argmax(bad)]
            raise ValueError(
                f"fudge factor {self.name}: S(A*) must be finite, > 0 and <= {S_MAX:g} for A* in [0, 1]; "
                f"S({a:.4g}) = {float(s[np.argmax(bad)])!r}"
            )


@dataclass(frozen=True)
class NoFudge(FudgeFactor):
    """S = 1: Persson's original theory (``eq:B2_xi_1``).

    Parameters
    ----------
    name : str
        Label used in tables, legends and messages.
    """

    name: str = "none"

    def S(self, A: ArrayLike) -> np.ndarray:
        return np.ones_like(
            A if type(A) is np.ndarray and A.dtype == np.float64 and np.isfinite(A.sum()) else _as_area(A)
        )

    def dS_dA(self, A: ArrayLike) -> np.ndarray:
        return np.zeros_like(np.asarray(A, dtype=float))


def _as_area(A) -> np.ndarray:
    """``A`` (the relative contact area) as a finite float array, else a ``ValueError`` naming ``A``.

    NaN, inf, None, strings, bools and complex values are refused; the range [0, 1] is not enforced here, as the
    solvers evaluate S at trial states a round-off outside it (e.g. 1 + 1e-11 in the method of lines).  The
    common case, a finite float64 array, is let through inline by each ``S`` (no extra frame in a solver's loop).
    """
    return as_float_array(A, "A (relative contact area, in [0, 1])")


def _check_gamma(gamma, name, lo, hi):
    if isinstance(gamma, (bool, np.bool_, str, bytes)) or np.iscomplexobj(gamma) or np.ndim(gamma) != 0:
        raise ValueError(f"gamma of {name} must be a number in ({lo}, {hi}], got {gamma!r}")
    try:
        g = float(gamma)
    except (TypeError, ValueError):
        raise ValueError(f"gamma of {name} must be a number in ({lo}, {hi}], got {gamma!r}") from None
    if not (np.isfinite(g) and lo < g <= hi):
        raise ValueError(f"gamma of {name} must lie in ({lo}, {hi}], got {gamma!r}")
    return g


@dataclass(frozen=True)
class YangPersson(FudgeFactor):
    r"""Yang & Persson (2008): :math:`S = \gamma + (1-\gamma) A^{*2}`.

    Parameters
    ----------
    gamma : float, dimensionless
        S at vanishing contact, in (0, 1]; default ``GAMMA_YP08`` = 0.45 (documented range 0.42--0.48).
    name : str
        Label used in tables, legends and messages.
    """

    gamma: float = GAMMA_YP08
    name: str = "YP08"

    def __post_init__(self):
        object.__setattr__(self, "gamma", _check_gamma(self.gamma, "YP08", 0.0, 1.0))

    def S(self, A: ArrayLike) -> np.ndarray:
        A = A if type(A) is np.ndarray and A.dtype == np.float64 and np.isfinite(A.sum()) else _as_area(A)
        return self.gamma + (1.0 - self.gamma) * A * A

    def dS_dA(self, A: ArrayLike) -> np.ndarray:
        return 2.0 * (1.0 - self.gamma) * np.asarray(A, dtype=float)


@dataclass(frozen=True)
class WangMuser(FudgeFactor):
    r"""Wang & Müser (2017): :math:`S = \gamma - \tfrac29 A^{*2} + (\tfrac{11}{9}-\gamma) A^{*4}`.

    Parameters
    ----------
    gamma : float, dimensionless
        S at vanishing contact, in (0, 11/9] with S > 0 on [0, 1]; default ``GAMMA_WM17`` = 5/9.
    name : str
        Label used in tables, legends and messages.
    """

    gamma: float = GAMMA_WM17
    name: str = "WM17"

    def __post_init__(self):
        object.__setattr__(self, "gamma", _check_gamma(self.gamma, "WM17", 0.0, 11.0 / 9.0))
        self.check()

    def S(self, A: ArrayLike) -> np.ndarray:
        A2 = (A if type(A) is np.ndarray and A.dtype == np.float64 and np.isfinite(A.sum()) else _as_area(A)) ** 2
        return self.gamma - (2.0 / 9.0) * A2 + (11.0 / 9.0 - self.gamma) * A2 * A2

    def dS_dA(self, A: ArrayLike) -> np.ndarray:
        A = np.asarray(A, dtype=float)
        return -(4.0 / 9.0) * A + 4.0 * (11.0 / 9.0 - self.gamma) * A**3


@dataclass(frozen=True)
class Xu24(FudgeFactor):
    r"""Global model of Xu et al. (2024): :math:`A^* = \mathrm{erf}(\bar p/\sqrt{2 g(A^*) V})`,
    :math:`g(A) = \gamma + (1-\gamma)A`.

    Not a B2 form in its own statement, but it is equivalent to one: the
    effective variance is :math:`\tau = g(A^*) V` with :math:`A^* = \mathrm{erf}(\bar p/\sqrt{2\tau})`,
    and differentiating gives :math:`S = d\tau/dV`, a function of A* alone:

    .. math::  S(A) = \frac{g^2}{g + (1-\gamma)\, x e^{-x^2}/\sqrt{\pi}}, \qquad x = \mathrm{erfinv}(A).

    ``pf.exact`` solves the closed form by a robust scalar root find; the PDE
    solvers use this S.  The two agree (a test checks it).

    Parameters
    ----------
    gamma : float, dimensionless
        g(0), in (0, 1]; default ``GAMMA_XU24`` = 0.45.
    name : str
        Label used in tables, legends and messages.
    """

    gamma: float = GAMMA_XU24
    name: str = "Xu24"

    def __post_init__(self):
        object.__setattr__(self, "gamma", _check_gamma(self.gamma, "Xu24", 0.0, 1.0))

    def g(self, A: ArrayLike) -> np.ndarray:
        r"""The variance factor :math:`g(A) = \gamma + (1-\gamma)A` of the global model.

        Parameters
        ----------
        A : array_like, dimensionless
            Relative contact area(s) in [0, 1].

        Returns
        -------
        numpy.ndarray, dimensionless
            g at each ``A``.
        """
        return self.gamma + (1.0 - self.gamma) * np.asarray(A, dtype=float)

    def S(self, A: ArrayLike) -> np.ndarray:
        A = A if type(A) is np.ndarray and A.dtype == np.float64 and np.isfinite(A.sum()) else _as_area(A)
        inside = A < 1.0
        with np.errstate(all="ignore"):
            x = erfinv(np.where(inside, A, 0.0))
            term = np.where(inside, x * np.exp(-x * x), 0.0) / np.sqrt(np.pi)
        g = self.g(A)
        return g * g / (g + (1.0 - self.gamma) * term)

    def area(self, p_bar: ArrayLike, V: ArrayLike) -> np.ndarray:
        """Solve A = erf(p_bar / sqrt(2 g(A) V)) for A in (0, 1], vectorised (bisection + Newton).

        Parameters
        ----------
        p_bar : array_like, pressure
            Nominal pressure(s), > 0.
        V : array_like, pressure^2
            Complete-contact variance(s), >= 0; broadcast against ``p_bar``.

        Returns
        -------
        numpy.ndarray, dimensionless
            The relative contact area A* of the global model, to round-off.
        """
        from scipy.special import erf

        p_bar = as_nonnegative_array(p_bar, "p_bar", allow_zero=False)
        p_bar, V = np.broadcast_arrays(p_bar, as_nonnegative_array(V, "V"))
        x0 = np.divide(p_bar, np.sqrt(2.0 * V), out=np.full(p_bar.shape, np.inf), where=V > 0)
        x0 = np.minimum(x0, 40.0)  # erf(40 / sqrt(g)) == 1 exactly; keeps exp(-x^2) x finite
        lo = np.zeros(p_bar.shape)
        hi = np.ones(p_bar.shape)
        # f(A) = A - erf(x0 / sqrt(g(A))) is strictly increasing: bisection to a 2.4e-4 bracket is safe,
        # then Newton (f' >= 1, f smooth) converges quadratically to round-off inside the bracket
        for _ in range(12):
            mid = 0.5 * (lo + hi)
            f = mid - erf(x0 / np.sqrt(self.g(mid)))
            lo = np.where(f < 0, mid, lo)
            hi = np.where(f < 0, hi, mid)
        A = 0.5 * (lo + hi)
        for _ in range(5):  # Newton: 2.4e-4 -> ~1e-8 -> ~1e-16
            g = self.g(A)
            x = x0 / np.sqrt(g)
            f = A - erf(x)
            df = 1.0 + (2.0 / np.sqrt(np.pi)) * np.exp(-x * x) * x * (1.0 - self.gamma) / (2.0 * g)
            A = np.clip(A - f / df, lo, hi)
        return A


@dataclass(frozen=True, eq=False)
class CallableFudge(FudgeFactor):
    """Wrap a user callable ``S(A)`` (vectorised or scalar), checked finite and > 0 on [0, 1].

    Parameters
    ----------
    fn : callable
        ``fn(A) -> S`` for A* in [0, 1]; called with an array first, element by element if that fails.
    name : str
        Label used in tables and messages; default the callable's ``__name__``.
    """

    fn: Callable = None
    name: str = "user"

    def __post_init__(self):
        if not callable(self.fn):
            raise ValueError(f"fudge must be None, a model name, a FudgeFactor or a callable; got {self.fn!r}")
        if self.name == "user":
            object.__setattr__(self, "name", getattr(self.fn, "__name__", "user"))
        self.check()

    def S(self, A: ArrayLike) -> np.ndarray:
        A = A if type(A) is np.ndarray and A.dtype == np.float64 and np.isfinite(A.sum()) else _as_area(A)
        try:
            raw = self.fn(A)
            vectorised = not np.iscomplexobj(raw)
        except Exception:
            vectorised = False
        if vectorised:
            try:
                out = np.asarray(raw, dtype=float)
                if out.shape != A.shape:
                    out = np.broadcast_to(out, A.shape).copy()
                return out
            except (TypeError, ValueError):
                pass
        return np.vectorize(lambda a: _real(self.fn(float(a))), otypes=[float])(A)

    def __hash__(self):
        return id(self.fn)

    def __eq__(self, other):
        return isinstance(other, CallableFudge) and other.fn is self.fn


def _real(x) -> float:
    """A scalar S value as a float; complex values raise (``float`` of a numpy complex would drop its imaginary
    part)."""
    if np.iscomplexobj(x):
        raise TypeError(f"S(A*) returned a complex value {x!r}")
    return float(x)


MODELS = {"none": NoFudge, "YP08": YangPersson, "WM17": WangMuser, "Xu24": Xu24}
"""Fudge-factor models selectable by name."""


def resolve(fudge: None | str | FudgeFactor | Callable) -> FudgeFactor:
    """Turn ``None``, a model name, a :class:`FudgeFactor` or a callable into a checked FudgeFactor.

    Parameters
    ----------
    fudge : None, str, FudgeFactor or callable
        ``None`` (Persson 2001), a name of ``MODELS`` ("YP08", "WM17", "Xu24", case-insensitive), a
        fudge-factor instance, or a callable S(A*) > 0 on [0, 1].

    Returns
    -------
    FudgeFactor
        The checked model.

    Raises
    ------
    ValueError
        An unknown name, or an S that is not finite and > 0 on [0, 1].
    """
    if fudge is None:
        return NoFudge()
    if isinstance(fudge, FudgeFactor):
        fudge.check()
        return fudge
    if isinstance(fudge, str):
        key = {k.lower(): k for k in MODELS}.get(fudge.lower())
        if key is None:
            raise ValueError(f"fudge must be None, one of {sorted(MODELS)}, a FudgeFactor or a callable; got {fudge!r}")
        return MODELS[key]()
    return CallableFudge(fudge)
