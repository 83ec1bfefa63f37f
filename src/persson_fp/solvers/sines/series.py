r"""Persson's sine series on [0, L] and its image dual (Xu et al. tutorial, Eq. 'eq:P0_solution'): the contact area
and PDF of the series, the mode count for a tolerance, and the quadrature and sine bases used to evaluate them.

The solver that uses them is :mod:`persson_fp.solvers.sines` (where the series, its error and the dual form are
described); the effective-variance map with a fudge factor is :mod:`persson_fp.solvers.sines.taumap`.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import erf

_MAX_MODES = 5000
"""Most modes sines will use for the output (the P0 evaluation holds ~1.2 N^2 numbers: 240 MB at 5000) and
asks for by default; beyond, the stations' PDFs are too narrow for the domain and it refuses (ValueError)."""

_X_SWITCH = 6.0
"""A* = 1 to round-off while p_bar / sqrt(2 tau) >= 6 (erfc(6) = 2.2e-17)."""
_Y_SW = -math.log(2.0 * _X_SWITCH**2)
"""ln(tau_sw / p_bar^2) = ln(1/72): start of the tau map's integral in y = ln(t / p_bar^2)."""


def _margin(tol: float) -> float:
    """c with 2 e^{-c} / (1 - r) < tol for the dropped modes (``modes_needed``; margin ln 4 for r <= 3/4)."""
    return math.log(2.0 / tol) + math.log(4.0)


def modes_needed(L: float, tau, tol: float) -> np.ndarray:
    r"""Smallest mode count N with :math:`2 e^{-\frac12 k_{N+1}^2 \tau}/(1-r) <` ``tol``.

    ``2 e^{-k^2 tau/2}`` bounds the L1 norm (and the area) contributed by mode
    k; r is the ratio of successive dropped terms.  ``L`` pressure, ``tau``
    pressure^2 (> 0).
    """
    tau = np.asarray(tau, dtype=float)
    n = np.ceil(L / np.pi * np.sqrt(2.0 * _margin(tol) / tau))
    return n.astype(int)


def _modes_needed_scalar(L: float, tau: float, tol: float) -> int:
    """:func:`modes_needed` for one tau (> 0), without numpy's per-call overhead (at most 1e18)."""
    n = L / math.pi * math.sqrt(2.0 * _margin(tol) / tau) if tau > 0.0 else math.inf
    return int(math.ceil(min(n, 1e18)))


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


_BASIS_CACHED = 1 << 20
"""Output bases up to this many entries (8 MB) are cached per (L, modes, nodes); larger ones formed per call."""


def _form_sine_basis(L: float, n_modes: int, n_eval: int) -> np.ndarray:
    """sin(k_n p_i), (n_modes, n_eval), at the Gauss--Legendre output nodes p_i of [0, L]."""
    x, _ = _gauss_legendre(n_eval)
    k = np.arange(1, n_modes + 1, dtype=float) * np.pi / L
    return np.sin(np.outer(k, 0.5 * L * (x + 1.0)))


@functools.lru_cache(maxsize=32)
def _sine_basis_cached(L: float, n_modes: int, n_eval: int) -> np.ndarray:
    B = _form_sine_basis(L, n_modes, n_eval)
    B.setflags(write=False)
    return B


def _sine_basis(L: float, n_modes: int, n_eval: int) -> np.ndarray:
    """:func:`_form_sine_basis`, cached when small (repeated solves of a problem share it)."""
    if n_modes * n_eval <= _BASIS_CACHED:
        return _sine_basis_cached(L, n_modes, n_eval)
    return _form_sine_basis(L, n_modes, n_eval)


def _form_output_rule(L: float, n_modes: int, n_eval: int):
    """What a solve on [0, L] with ``n_modes`` output modes and ``n_eval`` nodes needs besides tau: the nodes p
    and weights w of Gauss--Legendre on [0, L] (pressure), k_n = n pi / L (1/pressure), -k_n^2 / 2 and 2 / k_n of
    the odd modes (the area weights, pressure), all read-only."""
    xg, wg = _gauss_legendre(n_eval)
    p = (0.5 * L) * (xg + 1.0)
    w = (0.5 * L) * wg
    k = np.arange(1, n_modes + 1, dtype=float) * np.pi / L
    out = (p, w, k, -0.5 * k * k, 2.0 / k[::2])
    for a in out:
        a.setflags(write=False)
    return out


_output_rule_cached = functools.lru_cache(maxsize=32)(_form_output_rule)


def _output_rule(L: float, n_modes: int, n_eval: int):
    """:func:`_form_output_rule`, cached with the basis (repeated solves of a problem share it)."""
    if n_modes * n_eval <= _BASIS_CACHED:
        return _output_rule_cached(L, n_modes, n_eval)
    return _form_output_rule(L, n_modes, n_eval)
