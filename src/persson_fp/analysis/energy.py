"""Spectral quantities of the closed-form solution: the pressure power spectrum and the elastic energy.

Both follow from the contact area of :mod:`persson_fp.results.exact` at every magnification (the Xu et al. tutorial,
Eq. 'eq:Pf_prime' and Eq. 'eq:Uel_original'); with a fudge factor at the effective variance.

This module imports no solver.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.analysis.exact import _check_problem
from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.image import area_from_tau

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["pressure_spectrum", "elastic_energy"]


def pressure_spectrum(problem: ContactProblem, q: ArrayLike, A_n: float = 1.0) -> np.ndarray | float:
    r"""Power spectrum of the contact pressure, :math:`|\tilde p(q)|^2` (Xu et al. tutorial, Eq. 'eq:Pf_prime').

    .. math::  |\tilde p(q)|^2 = \Big(\frac{E^*}{4\pi}\Big)^2 A_n\, q^2 C(q)\, A^*(\bar p, q/q_l)\, S(A^*)

    with S = 1 in the original theory and A* the model's area at magnification q / q_l
    (Eq. 'eq:Area_Persson' at the effective variance).

    Parameters
    ----------
    problem : ContactProblem
        Spectrum C(q), modulus, load(s) and fudge factor.
    q : float or array_like, 1/length
        Wavenumber(s) in [q_l, q_s].
    A_n : float, length^2
        Nominal contact area, > 0.

    Returns
    -------
    ndarray or float, pressure^2 length^4 / (2 pi)^2
        In the units of the Xu et al. tutorial's Fourier transform; shape ``q.shape + (n_loads,)``, the load
        axis dropped for a scalar load.

    Raises
    ------
    ValueError
        ``problem`` not a :class:`ContactProblem`, ``A_n`` not a finite number > 0, ``q`` not finite or
        q / q_l outside [1, zeta_max].
    """
    _check_problem(problem)
    A_n = as_positive_scalar(A_n, "A_n")
    q = as_float_array(q, "q")
    psd = problem.psd
    z = psd.check_zeta(q / psd.q_l, "q / q_l")
    tau = problem.tau(z)
    A = area_from_tau(problem.p_bar, tau)
    S = problem.fudge.S(A)
    E_eff = problem.response.effective_modulus(q, needed_for="the pressure spectrum")  # E* on the half-space
    if np.ndim(E_eff) != 0:
        E_eff = np.asarray(E_eff)[..., None]
    out = (E_eff / (4.0 * np.pi)) ** 2 * A_n * (q**2 * psd.C(q))[..., None] * A * S
    return out[..., 0] if problem.scalar_load else out


def elastic_energy(problem: ContactProblem, zeta: float | None = None, epsrel: float = 1e-10) -> np.ndarray | float:
    r"""Elastic energy per nominal area :math:`U_{el}/A_n` (Xu et al. tutorial, Eq. 'eq:Uel_original').

    .. math::  \frac{U_{el}}{A_n} = \frac{\pi E^*}{2}\int_{q_l}^{\zeta q_l}
               q^2 C(q)\, A^*(\bar p, q/q_l)\, S(A^*)\,dq

    (the Xu et al. tutorial writes the total energy with the factor :math:`A_n`; multiply by
    it for a finite patch).  S = 1 in the original theory; the corrected models
    carry S(A*) as in Yang & Persson (J. Phys.: Condens. Matter 20 (2008) 215214).  A* comes from the model
    in use at each q (Eq. 'eq:Area_Persson' at the effective variance).  Adaptive quadrature in ln q
    (``scipy.integrate.quad_vec``), split at the roll-off (and a tabulated spectrum's knots), vectorised
    over loads.

    Parameters
    ----------
    problem : ContactProblem
        Spectrum, modulus, load(s) and fudge factor.
    zeta : float, dimensionless, optional
        One magnification in [1, zeta_max] (the upper limit of the integral); default ``zeta_max``.
    epsrel : float, dimensionless
        Relative tolerance of the quadrature, in (0, 0.1].

    Returns
    -------
    ndarray or float, pressure x length
        :math:`U_{el}/A_n`, shape ``(n_loads,)``, a float for a scalar load; 0 at zeta = 1.

    Raises
    ------
    ValueError
        ``problem`` not a :class:`ContactProblem`, ``epsrel`` outside (0, 0.1], ``zeta`` not a scalar or
        outside [1, zeta_max].
    """
    _check_problem(problem)
    psd = problem.psd
    response = problem.response
    # E_eff(q) (E* on the half-space): a float where it does not depend on q (out of the integral), else inside
    E_eff = response.effective_modulus(np.array([psd.q_l, psd.q_s]), needed_for="the elastic energy")
    scaled = np.ndim(E_eff) != 0
    try:
        epsrel = float(epsrel)
    except (TypeError, ValueError):
        raise ValueError(f"epsrel must be a number in (0, 0.1], got {epsrel!r}") from None
    if not (np.isfinite(epsrel) and 0.0 < epsrel <= 0.1):
        raise ValueError(f"epsrel must lie in (0, 0.1], got {epsrel!r}")
    if zeta is not None and np.ndim(zeta) != 0:
        raise ValueError(f"zeta must be a scalar magnification (call once per zeta), got shape {np.shape(zeta)}")
    zeta = psd.zeta_max if zeta is None else float(psd.check_zeta(zeta))
    lo, hi = np.log(psd.q_l), np.log(zeta * psd.q_l)
    if hi <= lo:
        out = np.zeros(problem.n_loads)
        return out[0] if problem.scalar_load else out

    def integrand(t):
        q = np.exp(t)
        z = min(max(q / psd.q_l, 1.0), psd.zeta_max)
        A = area_from_tau(problem.p_bar, problem.tau(np.array(z)))
        f = q**3 * psd.C(q) * A * problem.fudge.S(A)
        return f * response.effective_modulus(q) if scaled else f

    pts = []
    q_r = getattr(psd, "q_r", None)
    if q_r is not None and lo < np.log(q_r) < hi:
        pts.append(np.log(q_r))
    if hasattr(psd, "q"):  # tabulated: the kinks of the interpolant
        pts.extend(np.log(psd.q[(psd.q > np.exp(lo)) & (psd.q < np.exp(hi))]).tolist())
    from scipy.integrate import quad_vec  # here, not at the top: keeps `import persson_fp` light

    val, _err = quad_vec(integrand, lo, hi, epsrel=epsrel, epsabs=0.0, points=pts or None, limit=2000)
    out = 0.5 * np.pi * (1.0 if scaled else E_eff) * np.asarray(val)
    return out[0] if problem.scalar_load else out
