r"""The image solution of Persson's diffusion problem and its closed-form moments (Xu et al. tutorial).

Original theory (Eq. 'eq:P0_solution', 'eq:Area_Persson'): with tau = V(zeta),

.. math::

    P_0(p,\zeta) = \rho(p;\bar p,\tau) - \rho(p;-\bar p,\tau), \qquad
    A^* = \mathrm{erf}\big(\bar p/\sqrt{2\tau}\big),

and an atom :math:`1 - A^*` at p = 0 (Eq. 'eq:PDF_piecewise_explicit'); with a fudge factor the same formulas at
the effective variance (Eq. 'eq:new_B2', :mod:`persson_fp.theory.effective`).  Functions of (p, p_bar, tau) only,
broadcast over their arguments; :func:`persson_fp.exact` builds on them for a whole problem.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.special import erf, erfc

from persson_fp._validate import as_float_array

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["image_pdf", "area_from_tau", "variance_closed_form", "tail_mass"]

_SQRT2PI = np.sqrt(2.0 * np.pi)
_P_MAX = 1e150
"""Largest |p| and p_bar accepted (p_bar^2 must stay representable; pressures are O(E*) in any unit)."""
_TAU_MAX = 1e300
"""Largest tau accepted (pressure^2)."""


def _checked(p_bar, tau, *, tau_positive: bool):
    """p_bar (finite, in (0, 1e150]) and tau (finite, in [0, 1e300], or (0, 1e300]) as float arrays, else a
    ValueError naming the argument."""
    p_bar = as_float_array(p_bar, "p_bar")
    out = (p_bar <= 0) | (p_bar > _P_MAX)
    if np.any(out):
        raise ValueError(f"p_bar must lie in (0, {_P_MAX:g}] (pressure), got {float(p_bar[out].ravel()[0])!r}")
    tau = as_float_array(tau, "tau")
    low = tau <= 0 if tau_positive else tau < 0
    if np.any(low) or np.any(tau > _TAU_MAX):
        side = "(0" if tau_positive else "[0"
        raise ValueError(
            f"tau must lie in {side}, {_TAU_MAX:g}] (pressure^2), got {float(tau[low | (tau > _TAU_MAX)].ravel()[0])!r}"
        )
    return p_bar, tau


def _broadcast(p_bar, tau):
    try:
        return np.broadcast_arrays(p_bar, tau)
    except ValueError:
        raise ValueError(f"p_bar and tau must broadcast together, got shapes {p_bar.shape} and {tau.shape}") from None


def image_pdf(p: ArrayLike, p_bar: ArrayLike, tau: ArrayLike) -> np.ndarray:
    r"""Image solution :math:`\rho(p;\bar p,\tau) - \rho(p;-\bar p,\tau)` for p > 0 (0 for p <= 0).

    The pressure distribution of Persson's original theory (Xu et al. tutorial, Eq. 'eq:P0_solution'),
    :math:`\rho` the Gaussian of mean :math:`\pm\bar p` and variance :math:`\tau`; with a fudge factor
    the same formula at the effective variance (Eq. 'eq:new_B2').  Written as
    :math:`\rho(p;\bar p,\tau)\,(1 - e^{-2p\bar p/\tau})` with ``-expm1``, so it keeps full relative
    accuracy near p = 0 and for tiny tau and never overflows.

    Parameters
    ----------
    p : float or array_like, pressure
        Contact pressure(s); broadcast with the other arguments.
    p_bar : float or array_like, pressure
        Nominal pressure(s), > 0.
    tau : float or array_like, pressure^2
        (Effective) variance(s), > 0 (at tau = 0 the distribution is a delta function).

    Returns
    -------
    ndarray, 1/pressure
        P0 of the broadcast shape of the arguments; 0 where p <= 0.

    Raises
    ------
    ValueError
        Naming ``p``, ``p_bar`` or ``tau`` when one is not real and finite, ``p_bar`` or ``tau`` not > 0, a
        magnitude above 1e150 (``p``, ``p_bar``) or 1e300 (``tau``), or shapes that do not broadcast.
    """
    p_bar, tau = _checked(p_bar, tau, tau_positive=True)
    p = as_float_array(p, "p")
    if np.any(np.abs(p) > _P_MAX):
        raise ValueError(f"p must lie in [-{_P_MAX:g}, {_P_MAX:g}] (pressure)")
    try:
        p, p_bar, tau = np.broadcast_arrays(p, p_bar, tau)
    except ValueError:
        raise ValueError(
            f"p, p_bar and tau must broadcast together, got shapes {p.shape}, {p_bar.shape}, {tau.shape}"
        ) from None
    pos = p > 0
    pp = np.where(pos, p, 0.0)
    with np.errstate(under="ignore"):
        gauss = np.exp(-((pp - p_bar) ** 2) / (2.0 * tau)) / (_SQRT2PI * np.sqrt(tau))
        out = gauss * -np.expm1(-2.0 * pp * p_bar / tau)
    return np.where(pos, out, 0.0)


def area_from_tau(p_bar: ArrayLike, tau: ArrayLike) -> np.ndarray:
    """Relative contact area A* = erf(p_bar / sqrt(2 tau)) (Xu et al. tutorial, Eq. 'eq:Area_Persson').

    Persson's area at the complete-contact variance tau = V, or, with a fudge factor, at the effective
    variance tau = int S dV (Eq. 'eq:new_B2').

    Parameters
    ----------
    p_bar : float or array_like, pressure
        Nominal pressure(s), > 0; broadcast with ``tau``.
    tau : float or array_like, pressure^2
        (Effective) variance(s), >= 0.

    Returns
    -------
    ndarray, dimensionless
        A* in [0, 1] of the broadcast shape; 1 where tau = 0 (full contact at zeta = 1).

    Raises
    ------
    ValueError
        Naming ``p_bar`` or ``tau`` when one is not real and finite, ``p_bar`` not in (0, 1e150] or ``tau``
        not in [0, 1e300], or the shapes do not broadcast.
    """
    p_bar, tau = _broadcast(*_checked(p_bar, tau, tau_positive=False))
    x = np.divide(p_bar, np.sqrt(2.0 * tau), out=np.full(p_bar.shape, np.inf), where=tau > 0)
    return erf(x)


def tail_mass(p, p_bar, tau) -> np.ndarray:
    r"""Mass of the image solution beyond p: :math:`\int_p^\infty P_0\,dp' =
    \tfrac12[\mathrm{erfc}((p-\bar p)/s) - \mathrm{erfc}((p+\bar p)/s)]`, :math:`s = \sqrt{2\tau}`.

    What a domain cut at p = p_max loses (dimensionless); arguments broadcast, ``tau`` > 0 (pressure^2).

    Raises
    ------
    ValueError
        Naming ``p`` when it is not real and finite, ``p_bar`` or ``tau`` as :func:`area_from_tau` does (``tau``
        must be > 0 here: at tau = 0 the tail is a step, not a number).
    """
    p = as_float_array(p, "p")
    p_bar, tau = _checked(p_bar, tau, tau_positive=True)
    s = np.sqrt(2.0 * tau)
    return 0.5 * (erfc((p - p_bar) / s) - erfc((p + p_bar) / s))


def variance_closed_form(p_bar: ArrayLike, tau: ArrayLike) -> np.ndarray:
    r"""Var(p) over the whole interface, atom at p = 0 included: :math:`\int_0^\tau A^*(t)\,dt`.

    Closed form of the Xu et al. tutorial's Eq. 'eq:variance_p_form1' in the effective variance (for the
    original theory tau = V):

    .. math::  \mathrm{Var} = \tau\,\mathrm{erf}(x) - \bar p^2\,\mathrm{erfc}(x)
                              + \bar p\sqrt{2\tau/\pi}\,e^{-x^2}, \quad x = \bar p/\sqrt{2\tau}.

    Parameters
    ----------
    p_bar : float or array_like, pressure
        Nominal pressure(s), > 0; broadcast with ``tau``.
    tau : float or array_like, pressure^2
        (Effective) variance(s), >= 0.

    Returns
    -------
    ndarray, pressure^2
        Var(p) of the broadcast shape; 0 where tau = 0.  The second moment is Var + p_bar^2.

    Raises
    ------
    ValueError
        Naming ``p_bar`` or ``tau`` when one is not real and finite, ``p_bar`` not in (0, 1e150] or ``tau``
        not in [0, 1e300], or the shapes do not broadcast.
    """
    p_bar, tau = _broadcast(*_checked(p_bar, tau, tau_positive=False))
    with np.errstate(divide="ignore", under="ignore"):
        x = np.divide(p_bar, np.sqrt(2.0 * tau), out=np.full(p_bar.shape, np.inf), where=tau > 0)
        out = tau * erf(x) - p_bar**2 * erfc(x) + p_bar * np.sqrt(2.0 * tau / np.pi) * np.exp(-x * x)
    return np.where(tau > 0, out, 0.0)
