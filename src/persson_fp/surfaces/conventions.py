r"""Power-spectrum conventions and their conversion to Persson's isotropic C(q).

Persson's theory (Xu et al. tutorial, ``E:PSD`` and ``eq:variance_h_continuous``) uses the
isotropic spectrum with

.. math::  \langle h^2\rangle = \int d^2q\, C(q) = 2\pi\int_0^\infty q\,C(q)\,dq ,

q in radians per length (q = 2 pi / wavelength).  Other tools write the same surface with other
factors (Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5 (2017) 013001):

===============  ==============================================================  ==========================
``convention``   what the numbers are                                            conversion to Persson's C
===============  ==============================================================  ==========================
``"persson"``    Persson's C (the default)                                       C
``"iso2d"``      2-D FFT / SurfaceTopography                                     C = C_iso / (2 pi)^2
                 ``power_spectrum_from_area``:
                 :math:`\langle h^2\rangle = \frac{1}{2\pi}\int q C_{iso} dq`
``"1d"``         1-D PSD of line scans (SurfaceTopography                        Abel inversion, see below
                 ``power_spectrum_from_profile``,
                 contact.engineering "1D PSD along x/y"):
                 :math:`\langle h^2\rangle = \frac1\pi\int_0^\infty C^{1D} dq`
``"q/pi*2d"``    contact.engineering's "q/π × 2D PSD" series                     C = Y / (4 pi q)
                 :math:`Y = q\,C_{iso}/\pi`
===============  ==============================================================  ==========================

A 1-D PSD of an isotropic surface is the Abel transform of the 2-D one,
:math:`C^{1D}(q) = 2\pi\int_{-\infty}^{\infty} C(\sqrt{q^2+q_y^2})\,dq_y`, inverted by

.. math::  C(q) = -\frac{1}{2\pi^2}\int_q^\infty \frac{dC^{1D}/dk}{\sqrt{k^2-q^2}}\,dk
           = -\frac{1}{2\pi^2}\int_0^\infty \frac{dC^{1D}}{dk}\Big|_{k = q\cosh t}\,dt .

For a power law :math:`C^{1D}\propto q^{-1-2H}` this is
:math:`C = \frac{2\sqrt\pi\,\Gamma(H+1)}{\Gamma(H+1/2)}\,\frac{C^{1D}}{4\pi^2 q}`
(:func:`abel_factor`; the factor is pi only at H = 1/2).  :func:`to_persson` applies the factor when
``H`` is given and otherwise inverts the log-log interpolant of the table numerically
(:func:`abel_inverse`).

``q_unit="1/length"`` means that the wavenumbers are cycles per length (f = 1/wavelength) and the
density is per unit f: a 2-D density is divided by (2 pi)^2 and a 1-D density by 2 pi when q is
turned into radians per length, so that :math:`\langle h^2\rangle` is unchanged.

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import gammaln

from persson_fp._validate import as_float_array

__all__ = ["CONVENTIONS", "Q_UNITS", "abel_factor", "abel_inverse", "abel_forward", "to_persson", "check_convention"]

CONVENTIONS = {
    "persson": "Persson's C, <h^2> = 2 pi int q C dq (q in rad/length)",
    "iso2d": "2-D FFT / SurfaceTopography isotropic C_iso = (2 pi)^2 C",
    "1d": "1-D PSD of line scans, <h^2> = (1/pi) int_0^inf C1D dq",
    "q/pi*2d": "contact.engineering 'q/pi x 2D PSD' series Y = q C_iso / pi",
}
"""The accepted values of ``convention`` and what each means."""
Q_UNITS = ("rad/length", "1/length")
"""Accepted wavenumber units: radians per length (q = 2 pi / wavelength) or cycles per length (1 / wavelength)."""

_DENSITY_DIM = {"persson": 2, "iso2d": 2, "1d": 1, "q/pi*2d": 1}


def check_convention(convention: str, q_unit: str = "rad/length") -> tuple[str, str]:
    """Validate a convention name and a wavenumber unit; return them normalised.

    Parameters
    ----------
    convention : str
        One of :data:`CONVENTIONS` (case-insensitive).
    q_unit : str
        One of :data:`Q_UNITS`: ``"rad/length"`` (q = 2 pi / wavelength) or ``"1/length"`` (1 / wavelength).

    Returns
    -------
    convention, q_unit : str
        The convention in lower case and the unit unchanged.

    Raises
    ------
    ValueError
        An unknown convention or unit (the message lists the accepted ones).
    """
    if not isinstance(convention, str) or convention.lower() not in CONVENTIONS:
        raise ValueError(f"convention must be one of {sorted(CONVENTIONS)}, got {convention!r}")
    if q_unit not in Q_UNITS:
        raise ValueError(f"q_unit must be one of {list(Q_UNITS)}, got {q_unit!r}")
    return convention.lower(), q_unit


def abel_factor(H) -> np.ndarray:
    r"""The factor :math:`2\sqrt\pi\,\Gamma(H+1)/\Gamma(H+1/2)` relating a power-law 1-D PSD to C.

    :math:`C(q) = \text{factor}\cdot C^{1D}(q)/(4\pi^2 q)` for :math:`C^{1D}\propto q^{-1-2H}`, the
    Abel transform of a power law (module docstring; PSD conventions as in Jacobs, Junge & Pastewka,
    Surf. Topogr.: Metrol. Prop. 5 (2017) 013001).

    Parameters
    ----------
    H : float or array_like, dimensionless
        Hurst exponent(s) of the power law, > -1/2.

    Returns
    -------
    ndarray, dimensionless
        The factor, of the shape of ``H``: pi at H = 1/2, 2 at H = 0, 4 at H = 1.

    Raises
    ------
    ValueError
        ``H`` <= -1/2 (the Abel integral diverges there).
    """
    H = as_float_array(H, "H")
    out = (H <= -0.5) | (H > 1e6)
    if np.any(out):
        raise ValueError(f"H must be > -0.5 (and <= 1e6) for the Abel factor, got {float(H[out].ravel()[0])!r}")
    return 2.0 * np.sqrt(np.pi) * np.exp(gammaln(H + 1.0) - gammaln(H + 0.5))


def _loglog_derivative(q_tab, C_tab, k):
    """dC/dk of the log-log interpolant of (q_tab, C_tab) at k, power-law continued beyond both ends."""
    lq, lC = np.log(q_tab), np.log(C_tab)
    s = np.diff(lC) / np.diff(lq)
    lk = np.log(k)
    j = np.clip(np.searchsorted(lq, lk, side="right") - 1, 0, q_tab.size - 2)
    logC = lC[j] + s[j] * (lk - lq[j])
    return s[j] * np.exp(logC) / k


def abel_inverse(q, C1D, q_eval=None, n_nodes: int = 400) -> np.ndarray:
    r"""Persson's C from a tabulated 1-D PSD by numerical Abel inversion (length^4).

    Evaluates :math:`C(q) = -\frac{1}{2\pi^2}\int_0^{T} dC^{1D}/dk|_{k=q\cosh t}\,dt` for the
    log-log interpolant of ``(q, C1D)``, continued beyond the last point by its last power law
    (measured spectra rarely end where the surface's roughness ends), by Gauss-Legendre quadrature
    in t on panels split at the table points.  ``T`` is where :math:`k = 10^4 q_{max}`; the
    neglected tail is below :math:`10^{-4(1+2H)}` relative for a tail :math:`\propto k^{-1-2H}`.

    Parameters
    ----------
    q, C1D : array_like, rad/length and length^3
        The 1-D PSD table (q in rad/length, strictly increasing, > 0; C1D in length^3, > 0).
    q_eval : array_like, rad/length, optional
        Where to evaluate C, > 0 (default ``q``).
    n_nodes : int
        About how many Gauss-Legendre nodes in t besides the panels that the table points add (>= 50).

    Returns
    -------
    ndarray, length^4
        Persson's isotropic C (convention ``"persson"``) at ``q_eval``, of its shape.

    Raises
    ------
    ValueError
        Tables of different lengths or shorter than 2, q not > 0 and strictly increasing, C1D not > 0,
        ``q_eval`` not > 0 or ``n_nodes`` < 50.
    """
    q = as_float_array(q, "q")
    C1D = as_float_array(C1D, "C1D")
    if q.ndim != 1 or q.size < 2 or C1D.shape != q.shape:
        raise ValueError(f"q and C1D must be 1-D arrays of the same length >= 2, got {q.shape} and {C1D.shape}")
    if np.any(q <= 0) or np.any(np.diff(q) <= 0) or np.any(C1D <= 0):
        raise ValueError("q must be > 0 and strictly increasing and C1D > 0 for the Abel inversion")
    if (
        isinstance(n_nodes, (bool, np.bool_))
        or not isinstance(n_nodes, (int, np.integer))
        or not 50 <= n_nodes <= 10**6
    ):
        raise ValueError(f"n_nodes must be an integer in [50, 1e6], got {n_nodes!r}")
    qe = q if q_eval is None else as_float_array(q_eval, "q_eval")
    if np.any(qe <= 0):
        raise ValueError("q_eval must be > 0")
    x, w = np.polynomial.legendre.leggauss(16)
    out = np.empty(qe.shape, dtype=float)
    k_top = 1e4 * q[-1]
    for i, qi in np.ndenumerate(qe):
        # panels in t: from 0, through the table points above qi, to k_top (more panels where t is small)
        knots = q[q > qi]
        t_knots = np.arccosh(np.concatenate(([qi], knots, [max(k_top, 2.0 * qi)])) / qi)
        t_knots = np.unique(np.concatenate((t_knots, np.linspace(0.0, t_knots[-1], max(int(n_nodes) // 16, 4)))))
        a, b = t_knots[:-1], t_knots[1:]
        t = (0.5 * (b - a))[:, None] * x[None, :] + (0.5 * (a + b))[:, None]
        dC = _loglog_derivative(q, C1D, qi * np.cosh(t))
        out[i] = -np.sum((0.5 * (b - a))[:, None] * w[None, :] * dC) / (2.0 * np.pi**2)
    return out


def abel_forward(psd, q) -> np.ndarray:
    r"""The 1-D PSD of an isotropic surface with spectrum ``psd`` (length^3), ``"1d"`` convention.

    :math:`C^{1D}(q) = 4\pi\int_q^{q_s} C(k)\,k\,dk/\sqrt{k^2-q^2}`, by Gauss-Legendre quadrature in
    :math:`t = \mathrm{arccosh}(k/q)` on panels split at the spectrum's kinks (a test and
    plotting aid: what a profilometer would see on that surface).  Zero where q >= q_s.

    Parameters
    ----------
    psd : PSD
        The isotropic spectrum in Persson's convention (:class:`~persson_fp.SelfAffinePSD`,
        :class:`~persson_fp.TabulatedPSD`).
    q : float or array_like, rad/length
        Wavenumbers along the scan, > 0.

    Returns
    -------
    ndarray, length^3
        The 1-D PSD :math:`C^{1D}(q)` with :math:`\langle h^2\rangle = \frac1\pi\int_0^\infty C^{1D}dq`,
        of the shape of ``q``.
    """
    from persson_fp.surfaces.psd import PSD

    if not isinstance(psd, PSD):
        raise ValueError(f"psd must be a persson_fp spectrum (PSD), got {type(psd).__name__} {psd!r}")
    q = as_float_array(q, "q")
    if np.any(q <= 0):
        raise ValueError(f"q must be > 0 (rad/length), got {float(q[q <= 0].ravel()[0])!r}")
    x, w = np.polynomial.legendre.leggauss(24)
    kinks = [psd.q_l, psd.q_s] + ([psd.q_r] if hasattr(psd, "q_r") else []) + list(getattr(psd, "q", []))
    kinks = np.unique(np.asarray(kinks, dtype=float))
    out = np.empty(q.shape, dtype=float)
    for i, qi in np.ndenumerate(q):
        lo = max(qi, psd.q_l)
        if lo >= psd.q_s:
            out[i] = 0.0
            continue
        ks = np.concatenate(([lo], kinks[(kinks > lo) & (kinks < psd.q_s)], [psd.q_s]))
        t_knots = np.arccosh(np.maximum(ks / qi, 1.0))
        t_knots = np.unique(np.concatenate([np.linspace(a, b, 9) for a, b in zip(t_knots[:-1], t_knots[1:])]))
        a, b = t_knots[:-1], t_knots[1:]
        t = (0.5 * (b - a))[:, None] * x[None, :] + (0.5 * (a + b))[:, None]
        k = qi * np.cosh(t)
        # C(k) k dk / sqrt(k^2 - q^2) = C(k) k dt
        out[i] = 4.0 * np.pi * np.sum((0.5 * (b - a))[:, None] * w[None, :] * psd.C(k) * k)
    return out


def to_persson(q, C, convention: str = "persson", q_unit: str = "rad/length", H=None):
    """Convert a spectrum table to Persson's convention (q in rad/length, C in length^4).

    Parameters
    ----------
    q : array_like
        Wavenumbers in ``q_unit`` (> 0, strictly increasing).
    C : array_like
        Spectrum values in ``convention`` (see the module docstring), > 0.
    convention : str
        One of :data:`CONVENTIONS`.
    q_unit : str
        ``"rad/length"`` (q = 2 pi / wavelength) or ``"1/length"`` (1 / wavelength).
    H : float, optional
        Only for ``"1d"``: convert with the Abel factor of this Hurst exponent (exact for a power law);
        ``None`` (default) inverts the table numerically (:func:`abel_inverse`).

    Returns
    -------
    q_rad : ndarray, rad/length
        The wavenumbers in radians per length.
    C_persson : ndarray, length^4
        The spectrum in Persson's convention (Xu et al. tutorial, ``E:PSD``).

    Raises
    ------
    ValueError
        An unknown convention or unit, or ``H`` with a convention other than ``"1d"``.
    """
    convention, q_unit = check_convention(convention, q_unit)
    q = as_float_array(q, "q")
    C = as_float_array(C, "C")
    if H is not None and convention != "1d":
        raise ValueError(f"H is used only with convention='1d' (Abel factor), not with {convention!r}")
    if q_unit == "1/length":
        q = 2.0 * np.pi * q
        C = C / (2.0 * np.pi) ** _DENSITY_DIM[convention]
    if convention == "persson":
        return q, C
    if convention == "iso2d":
        return q, C / (2.0 * np.pi) ** 2
    if convention == "q/pi*2d":
        return q, C / (4.0 * np.pi * q)
    if H is not None:
        if np.ndim(H) != 0:  # (abel_factor refuses a complex, bool, string or out-of-range H by name)
            raise ValueError(f"H must be one real number (the Hurst exponent of the spectrum's tail), got {H!r}")
        return q, abel_factor(H) * C / (4.0 * np.pi**2 * q)
    return q, abel_inverse(q, C)
