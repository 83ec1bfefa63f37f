r"""Magnification-resolved contact: area, separation and the gap of the area losing contact, at each ζ.

**Magnification-resolved quantities** (Persson, Phys. Rev. Lett. 99 (2007) 125502; Lorenz & Persson, EPL 86 (2009)
44006; Almqvist, Campañá, Prodanov, Persson, J. Mech. Phys. Solids 59 (2011) 2355).  At magnification
:math:`\zeta` the surfaces touch in apparent contact regions of area fraction :math:`A(\zeta)` (the theory's
:math:`A^*(\zeta)`, Xu, Li, Chen, Zhou tutorial ``eq:Area_Persson``, or a fudge model's corrected area), where the
mean pressure is :math:`\bar p/A(\zeta)`.  :math:`\bar u(\zeta)` is the mean separation in those regions caused by
the roughness finer than :math:`\zeta` (wavenumbers :math:`[\zeta q_l, q_s]`) under :math:`\bar p/A(\zeta)`: Persson
2007's :math:`\bar u` (:mod:`persson_fp.theory.separation`, same weighting and fudge model) for the truncated
spectrum, whose complete-contact variance at :math:`q` is :math:`V(q) - V(\zeta)`.  In the variable
:math:`\sigma = \sqrt{V(q) - V(\zeta)}`,

.. math::  \bar u(\zeta) = \frac{2}{E^*}\int_0^{\Sigma(\zeta)} \frac{g\big(\bar p/(A(\zeta)\sigma)\big)}{q(\sigma)}\,
           d\sigma, \qquad \Sigma(\zeta) = \sqrt{V(\zeta_{max}) - V(\zeta)},

with the universal function g of :mod:`persson_fp.theory.separation`; :math:`2/(E^* q)` is the half-space's
surface compliance :math:`M(q)`, and V, its inverse and M come from the solid's response
(:class:`~persson_fp.theory.response.ElasticHalfSpace`, the attribute ``response``).  The area lost between
:math:`\zeta` and :math:`\zeta + d\zeta`, :math:`-A'd\zeta`, has the mean gap (Lorenz & Persson)
:math:`u_1(\zeta) = \bar u + \bar u' A/A' = d(A\bar u)/dA`.

Checked here (the formula for :math:`\bar u(\zeta)` is reconstructed from the papers' statements, not copied):
:math:`\bar u(1) = \bar u(\bar p)` of :class:`~persson_fp.MeanSeparation` (tests: to 1e-6 relative),
:math:`\bar u(\zeta_{max}) = 0`, and the identity :math:`\int_1^{\zeta_{max}}(-A')u_1\,d\zeta = \bar u(\bar p)`
(it telescopes because :math:`A(1) = 1` and :math:`\bar u(\zeta_{max}) = 0`), which the discrete form of
:mod:`persson_fp.theory.gaps` keeps exactly.

The distribution of gaps built on these is :mod:`persson_fp.theory.gaps`.

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf, erfinv

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.surfaces.psd import PSD
from persson_fp.theory import fudge as _fudge
from persson_fp.theory.effective import effective_variance
from persson_fp.theory.response import ElasticResponse, check_response
from persson_fp.theory.separation import WEIGHTINGS
from persson_fp.theory.separation_weight import _weight

__all__ = ["MagnificationResolved"]

_DECADES = 8.0
_Y_CUT = 10.0
_CHUNK = 128


def _kinks(psd):
    """Wavenumbers inside (q_l, q_s) where C(q) changes power law: a tabulated spectrum's knots, the roll-off."""
    q = getattr(psd, "q", None)
    if q is None:
        q = [getattr(psd, "q_r", psd.q_l)]
    q = np.asarray(q, dtype=float).reshape(-1)
    return q[(q > psd.q_l) & (q < psd.q_s)]


def _show(x) -> str:
    """A value for a message: an array by its shape and first element."""
    if np.ndim(x) == 0:
        return repr(x)
    a = np.asarray(x)
    return f"an array of shape {a.shape}, first element {a.flat[0]!r}" if a.size else f"an empty array {a.shape}"


def _in(x, name: str, allowed: str, ok) -> np.ndarray:
    """``x`` as a float array with ``ok(x)`` true everywhere, else ValueError naming ``name`` and ``allowed``."""
    try:
        a = as_float_array(x, name)
    except ValueError:  # not real, or NaN / inf: stated with the range
        a = None
    if a is None or not np.all(ok(a)):
        raise ValueError(f"{name} must lie in {allowed}, got {_show(x)}")
    return a


def _loads(p_bar) -> np.ndarray:
    """``p_bar`` as a float array, every element finite and > 0 (else ValueError naming ``p_bar``)."""
    return _in(p_bar, "p_bar", "(0, inf) (pressure, finite)", lambda p: p > 0)


def _areas(A, name: str, lo_open: bool) -> np.ndarray:
    """Area fractions in (0, 1] (``lo_open``) or [0, 1] (else ValueError naming ``name``)."""
    if lo_open:
        return _in(A, name, "(0, 1] (contact area fraction)", lambda a: (a > 0) & (a <= 1.0))
    return _in(A, name, "[0, 1] (contact area fraction)", lambda a: (a >= 0) & (a <= 1.0))


def _zetas(psd, zeta) -> np.ndarray:
    """Magnifications in [1, zeta_max] (NaN and inf refused with the range)."""
    _in(zeta, "zeta", f"[1, {psd.zeta_max:.17g}] (magnification)", lambda z: np.isfinite(z))
    return psd.check_zeta(zeta)


class MagnificationResolved:
    r"""Contact area :math:`A(\zeta)`, separation :math:`\bar u(\zeta)` and gap :math:`u_1(\zeta)` at any stations.

    Formulas in :mod:`persson_fp.theory.gaps`.  The integral over :math:`\ln\sigma` runs on
    :math:`[\max(\ln(\bar p/(10 A\sigma)), \ln\Sigma - 8\ln 10), \ln\Sigma]` (the part cut below is smaller than
    :math:`10^{-8}` of :math:`\bar u` or has :math:`g < e^{-45}`), in six equal panels split again at every kink of
    :math:`q(\sigma)` inside: the roll-off :math:`q_r`, or a tabulated spectrum's knots, where C changes power law
    (Gauss-Legendre, 8 nodes a panel; 4 on a tabulated spectrum's many short ones).  Against
    :class:`~persson_fp.MeanSeparation` (tests, random self-affine spectra with H from 0.05 to 1, q_s/q_l to 1e6,
    with and without roll-off, every fudge model): :math:`\bar u(1)` to 3e-5 relative at loads from 1e-3 to
    3 :math:`\sqrt{V}` (1.5e-5 measured), to 2e-4 relative at light loads from 1e-8 to 1e-3 :math:`\sqrt{V}` (8e-5
    measured, 6e-4 of the rms height: the six panels span eight decades of :math:`\sigma` there), and above
    3 :math:`\sqrt{V}`, where :math:`\bar u` is below 1e-9 of the rms height, to 1e-9 of the rms height
    absolute (2e-10 measured; the cut-off at :math:`y = 10` gives 0 where the closed form gives ~1e-29); and
    :math:`\bar u(\zeta)` on a measured (tabulated, 64-shell) spectrum against adaptive quadrature in q split at the
    knots (tests: 2e-6 measured over loads 1e-3 to 1 sqrt(V) and ζ up to 20; it was 2e-3 before the
    split).

    Parameters
    ----------
    psd : PSD
        The spectrum (Persson's convention).
    E_star : float, pressure
        Plane-strain modulus (> 0).
    fudge : None, str, FudgeFactor or callable
        The model S(A*) (None: Persson's original theory).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of a fudge model (:mod:`persson_fp.theory.separation`).
    response : ElasticResponse, optional
        The solid's response (:mod:`persson_fp.theory.response`); default the elastic half-space of ``E_star``.
        One without stored elastic energy raises ``ValueError`` where the separation is asked.

    Raises
    ------
    ValueError
        ``psd`` not a PSD, ``E_star`` not > 0, an unknown fudge model or weighting.
    """

    def __init__(
        self,
        psd: PSD,
        E_star: float = 1.0,
        fudge=None,
        weighting: str = "yang-persson",
        *,
        response: ElasticResponse | None = None,
    ):
        if not isinstance(psd, PSD):
            raise ValueError(f"psd must be a persson_fp PSD (SelfAffinePSD, TabulatedPSD), got {type(psd).__name__}")
        if weighting not in WEIGHTINGS:
            raise ValueError(f"weighting must be one of {list(WEIGHTINGS)}, got {weighting!r}")
        self.psd = psd
        self.E_star = as_positive_scalar(E_star, "E_star")
        self.response = check_response(response, self.E_star)
        # (a response without stored elastic energy is refused here, before any table is built)
        self.response.effective_modulus(psd.q_l, needed_for="the magnification-resolved separation and gaps")
        self.fudge = _fudge.resolve(fudge)
        self.weighting = weighting
        self._w = _weight(self.fudge, weighting)
        self._ev = effective_variance(self.fudge)
        with np.errstate(over="ignore", under="ignore"):
            self.V_max = float(self.response.V(psd))
        if not (np.isfinite(self.V_max) and self.V_max > 1e-280):
            raise ValueError(
                f"E_star = {self.E_star!r} and the spectrum give V(zeta_max) = {self.V_max!r} (V = E_star^2 "
                "<|grad h|^2> / 4), outside floating-point range; rescale the pressure unit (e.g. MPa)"
            )
        self.h2_max = float(psd.h2())
        self._y_cut = _Y_CUT * np.sqrt(max(float(self.fudge.S(np.array(1.0))), 1.0))
        # ln g on a fine uniform table in ln y, interpolated linearly (error ~1e-6 relative in g where it matters;
        # about 4x faster than the separation module's Hermite spline, which is the reference of the tests)
        self._t = np.linspace(np.log(1e-9), np.log(self._y_cut), 1 << 14)
        self._lng = np.log(np.maximum(self._w.g(np.exp(self._t)), 1e-300))
        self._dlng = np.append(np.diff(self._lng), 0.0)
        self._dt_inv = 1.0 / (self._t[1] - self._t[0])
        # ln q against ln V on a fine uniform table (the spectrum's exact inverse zeta_of_V, interpolated linearly;
        # ~1e-7 relative in q); in the few cells that hold a kink of q(V) (the roll-off, a tabulated spectrum's
        # knots) the interpolation runs to the kink's exact point from either side
        self._kinks = _kinks(psd)
        self._V_k = np.asarray(self.response.V(psd, self._kinks / psd.q_l), dtype=float).reshape(-1)
        self._lnV = np.linspace(np.log(self.V_max) - 46.0, np.log(self.V_max), 1 << (13 if self._V_k.size <= 2 else 16))
        self._lnq = np.log(self.response.zeta_of_V(psd, np.exp(self._lnV)) * psd.q_l)
        self._dlnq = np.append(np.diff(self._lnq), 0.0)
        self._dV_inv = 1.0 / (self._lnV[1] - self._lnV[0])
        self._kink_cell = np.zeros(self._lnV.size, dtype=bool)
        self._kink_lnV = np.zeros(self._lnV.size)
        self._kink_lnq = np.zeros(self._lnV.size)
        with np.errstate(divide="ignore"):
            lnV_k = np.log(self._V_k)
            cells = np.floor((lnV_k - self._lnV[0]) * self._dV_inv).astype(np.intp)
        ok = (cells >= 0) & (cells < self._lnV.size - 1)
        self._kink_cell[cells[ok]] = True
        self._kink_lnV[cells[ok]], self._kink_lnq[cells[ok]] = lnV_k[ok], np.log(self._kinks[ok])
        # Gauss-Legendre on [0, 1]: 8 nodes on each of the six panels and at most two kinks, 4 on a tabulated
        # spectrum's many short panels between knots (measured: 1e-6 against adaptive quadrature either way)
        n_gl = 8 if self._V_k.size <= 2 else 4
        self._split = np.linspace(0.0, 1.0, (5 if self._V_k.size == 1 else 6) + 1)  # with the roll-off: six panels
        x, w = np.polynomial.legendre.leggauss(n_gl)
        self._x, self._wx = (x + 1.0) / 2.0, w / 2.0

    # -- areas and stations ----------------------------------------------------------------------------------
    def area(self, p_bar, zeta) -> np.ndarray:
        r"""The model's contact area :math:`A(\zeta) = \mathrm{erf}(\bar p/\sqrt{2\tau(\zeta)})` (``eq:new_B2``).

        Parameters
        ----------
        p_bar : array_like, pressure
            Loads (> 0), broadcast against ``zeta``.
        zeta : array_like, dimensionless
            Magnifications in [1, zeta_max].

        Returns
        -------
        ndarray, dimensionless
            A in [0, 1].

        Raises
        ------
        ValueError
            ``p_bar`` not finite and > 0, or ``zeta`` outside [1, zeta_max].
        """
        p = _loads(p_bar)
        V = self.response.V(self.psd, _zetas(self.psd, zeta))
        tau = self._ev.tau(p, V)
        with np.errstate(divide="ignore"):
            return np.where(tau > 0, erf(p / np.sqrt(2.0 * np.where(tau > 0, tau, 1.0))), 1.0)

    def zeta_of_area(self, p_bar, A) -> np.ndarray:
        r"""The magnification at which the area has fallen to ``A`` (the inverse of :meth:`area` in ζ).

        Parameters
        ----------
        p_bar : array_like, pressure
            Loads (> 0), broadcast against ``A``.
        A : array_like, dimensionless
            Areas in (0, 1] (1: ζ = 1); where :math:`A(\zeta_{max})` is above ``A`` the result is zeta_max.

        Returns
        -------
        ndarray, dimensionless
            ζ in [1, zeta_max].

        Raises
        ------
        ValueError
            ``p_bar`` not finite and > 0, or ``A`` outside (0, 1].
        """
        p = _loads(p_bar)
        A = np.clip(_areas(A, "A", lo_open=True), 1e-300, 1.0 - 1e-16)
        tau = p * p / (2.0 * erfinv(A) ** 2)
        V = self._ev.V_of_tau(p, tau)
        return self.response.zeta_of_V(self.psd, np.minimum(V, self.V_max))

    def h(self, zeta) -> np.ndarray:
        r"""Rms height of the roughness finer than ζ, :math:`h_\zeta = (2\pi\int_{\zeta q_l}^{q_s} qC\,dq)^{1/2}`.

        Parameters
        ----------
        zeta : array_like, dimensionless
            Magnifications in [1, zeta_max] (round-off outside, 1e-12 relative, clipped).

        Returns
        -------
        ndarray, length
            :math:`h_\zeta`, 0 at zeta_max.

        Raises
        ------
        ValueError
            ``zeta`` not finite or outside [1, zeta_max].
        """
        z = _zetas(self.psd, zeta)
        h2 = self.h2_max - np.asarray(self.psd.h2(np.clip(z, 1.0, self.psd.zeta_max).ravel())).reshape(z.shape)
        return np.sqrt(np.maximum(h2, 0.0))

    # -- the separation --------------------------------------------------------------------------------------
    def separation(self, p_bar, zeta, A=None) -> np.ndarray:
        r"""Mean separation :math:`\bar u(\zeta)` in the apparent contact regions at magnification ζ.

        Parameters
        ----------
        p_bar : array_like, pressure
            Loads (> 0), broadcast against ``zeta``.
        zeta : array_like, dimensionless
            Magnifications in [1, zeta_max].
        A : array_like, optional, dimensionless
            :math:`A(\zeta)` at those points (a numerical solution's areas), in [0, 1]; default :meth:`area`.

        Returns
        -------
        ndarray, length
            :math:`\bar u(\zeta)`, of the broadcast shape; 0 at zeta_max and wherever the local pressure exceeds
            10 :math:`\Sigma(\zeta)\sqrt{S(1)}` (full contact of the finer roughness to :math:`e^{-45}`).

        Raises
        ------
        ValueError
            ``p_bar`` not finite and > 0, ``zeta`` outside [1, zeta_max], or ``A`` outside [0, 1].
        """
        p, z = np.broadcast_arrays(_loads(p_bar), _zetas(self.psd, zeta))
        if A is None:
            A = self.area(p, z)
        A = np.broadcast_to(_areas(A, "A", lo_open=False), p.shape)
        shape = p.shape
        p, z, A = p.ravel(), z.ravel(), A.ravel()
        out = np.zeros(p.size)
        V_z = self.response.V(self.psd, self.psd.check_zeta(z))
        rest = np.maximum(self.V_max - V_z, 0.0)
        with np.errstate(divide="ignore"):
            p_loc = p / np.maximum(A, 1e-300)
            s_hi = 0.5 * np.log(rest)
            s_lo = np.maximum(np.log(p_loc / self._y_cut), s_hi - _DECADES * np.log(10.0))
        live = np.flatnonzero(np.isfinite(s_hi) & (s_lo < s_hi) & (A > 0))
        # panels: [s_lo, s_hi] in six, and split again at every kink of q(sigma) inside (the roll-off; a tabulated
        # spectrum's knots, where C changes power law), each panel Gauss-Legendre
        with np.errstate(divide="ignore", invalid="ignore"):
            s_k = 0.5 * np.log(self._V_k[None, :] - V_z[:, None])  # -inf / nan below zeta: clipped to s_lo
        n_kinks = self._V_k.size
        if n_kinks > 2:  # like stations share a chunk (and their empty panels)
            live = live[np.argsort(V_z[live], kind="stable")]
        for i in range(0, live.size, _CHUNK * 8 // max(1, (6 + n_kinks) // 6)):
            k = live[i : i + _CHUNK * 8 // max(1, (6 + n_kinks) // 6)]
            lo, hi = s_lo[k][:, None], s_hi[k][:, None]
            cuts = np.where(np.isfinite(s_k[k]), np.clip(s_k[k], lo, hi), lo)
            b = np.sort(np.concatenate((lo + (hi - lo) * self._split[None, :], cuts), axis=1), axis=1)
            if n_kinks > 2:  # knots below s_lo: their empty panels dropped
                b = b[:, max(int(np.min(np.sum(b <= lo, axis=1))) - 1, 0) :]
            d = np.diff(b, axis=1)[:, :, None]
            s = (b[:, :-1, None] + d * self._x[None, None, :]).reshape(k.size, -1)
            wts = (d * self._wx[None, None, :]).reshape(k.size, -1)
            sigma = np.exp(s)
            lnV = np.log(sigma * sigma + V_z[k][:, None])
            x = np.clip((lnV - self._lnV[0]) * self._dV_inv, 0.0, self._lnV.size - 1.000001)
            i = x.astype(np.intp)
            x -= i
            q = np.exp(self._lnq[i] + x * self._dlnq[i])  # below the table: q = q_l to 1e-20
            kink = self._kink_cell[i]
            if np.any(kink):
                ik, xk = i[kink], lnV[kink]
                left = xk < self._kink_lnV[ik]
                j = np.where(left, ik, ik + 1)  # the cell's end on the node's side of the kink
                a_V, a_q = self._lnV[j], self._lnq[j]
                b_V, b_q = self._kink_lnV[ik], self._kink_lnq[ik]
                with np.errstate(invalid="ignore", divide="ignore"):
                    fr = np.where(b_V != a_V, (xk - a_V) / (b_V - a_V), 0.0)
                q[kink] = np.exp(a_q + fr * (b_q - a_q))
            t = np.log(p_loc[k])[:, None] - s
            x = np.clip((t - self._t[0]) * self._dt_inv, 0.0, self._t.size - 1.000001)
            i = x.astype(np.intp)
            x -= i
            g = np.exp(self._lng[i] + x * self._dlng[i])
            low = t < self._t[0]  # y < 1e-9: g is logarithmic there (the separation module's small-y law)
            if np.any(low):
                g[low] = self._w.g(np.exp(t[low]))
            # the surface compliance M(q) = 2 / (E_eff(q) q): 2 / (E* q) on the half-space
            E_eff = self.response.effective_modulus(q, needed_for="the magnification-resolved separation")
            f = g * sigma / q
            if np.ndim(E_eff) == 0:  # a modulus without scale (the half-space): out of the sum
                out[k] = (2.0 / E_eff) * np.sum(f * wts, axis=1)
            else:
                out[k] = np.sum((2.0 / E_eff) * f * wts, axis=1)
        return out.reshape(shape)

    def u1(self, p_bar, zeta, dA: float = 1e-3) -> np.ndarray:
        r"""Mean gap :math:`u_1 = d(A\bar u)/dA` of the area that loses contact at magnification ζ.

        A central difference in A of half-width ``dA`` (error :math:`O(dA^2)`); it diverges as ζ → 1 (module
        docstring).  Where A is within ``dA`` of 1 or of :math:`A(\zeta_{max})` a one-sided difference is used.

        Parameters
        ----------
        p_bar : array_like, pressure
            Loads (> 0), broadcast against ``zeta``.
        zeta : array_like, dimensionless
            Magnifications in [1, zeta_max].
        dA : float
            Half-width of the difference in area, in (0, 0.05].

        Returns
        -------
        ndarray, length
            :math:`u_1`.

        Raises
        ------
        ValueError
            ``p_bar`` not finite and > 0, ``zeta`` outside [1, zeta_max], or ``dA`` outside (0, 0.05].
        """
        dA = as_positive_scalar(dA, "dA")
        if dA > 0.05:
            raise ValueError(f"dA must lie in (0, 0.05], got {dA!r}")
        p, z = np.broadcast_arrays(_loads(p_bar), _zetas(self.psd, zeta))
        A = self.area(p, z)
        A_end = self.area(p, self.psd.zeta_max)
        A_hi = np.minimum(A + dA, 1.0)
        A_lo = np.maximum(A - dA, A_end)
        z_hi = np.where(A_hi >= 1.0, 1.0, self.zeta_of_area(p, A_hi))
        z_lo = np.where(A_lo <= A_end, self.psd.zeta_max, self.zeta_of_area(p, A_lo))
        A_hi, A_lo = self.area(p, z_hi), self.area(p, z_lo)
        u_hi, u_lo = self.separation(p, z_hi, A_hi), self.separation(p, z_lo, A_lo)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = (A_hi * u_hi - A_lo * u_lo) / (A_hi - A_lo)
        return np.where(A_hi - A_lo > 0, out, 0.0)
