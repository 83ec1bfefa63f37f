r"""The solid's elastic response to the roughness: what turns a spectrum C(q) into pressures and energies.

Persson's theory (Persson, J. Chem. Phys. 115 (2001) 3840) needs the solid only through the pressure that full
contact at magnification :math:`\zeta` produces, the complete-contact variance

.. math::  V(\zeta) = \frac14 \int_{q_l}^{\zeta q_l} dq\, q^3 C(q) \int_0^{2\pi} d\phi\, |E_{eff}(q, \phi)|^2

(Xu, Li, Chen, Zhou tutorial ``eq:Vp_closed_form``), and, for the mean separation, the gaps, the stiffness and
adhesion, through the elastic energy stored by a surface displacement: the surface compliance
:math:`M(q) = u(q)/p(q) = 2/(E_{eff}(q)\,q)`.

A response object answers these given the spectrum.  :class:`ElasticResponse` is the base: a subclass defines
:meth:`~ElasticResponse.V` and :meth:`~ElasticResponse.dV_dzeta` (the inverse :meth:`~ElasticResponse.zeta_of_V`
has a numerical default), and, where the solid stores elastic energy, :meth:`~ElasticResponse.effective_modulus`
and :meth:`~ElasticResponse.elastic_energy_complete`.  Without those two the energy side raises ``ValueError``
naming the quantity asked (a sliding viscoelastic solid has V but no stored elastic energy).

:class:`ElasticHalfSpace` is the homogeneous elastic half-space of the theory's papers: :math:`E_{eff} = E^*`, the
plane-strain modulus :math:`E/(1-\nu^2)`, so :math:`V = \frac{\pi}{2}E^{*2}\int q^3C\,dq` (``eq:VV_relation``)
and :math:`M(q) = 2/(E^* q)`.

This module imports only numpy (the spectrum arrives as an argument).
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar, check_in_range

__all__ = ["ElasticResponse", "ElasticHalfSpace", "Kernels", "check_response"]


class Kernels(NamedTuple):
    """A response's fast paths bound to one spectrum (what the solvers call inside their loops, unchecked).

    Attributes
    ----------
    dV_dzeta : callable
        ``dV_dzeta(z)``: dV/dzeta (pressure^2) at magnifications ``z`` already in [1, zeta_max].
    zeta_of_V : callable
        ``zeta_of_V(V)``: the inverse of V (dimensionless) at finite variances ``V`` (pressure^2).
    """

    dV_dzeta: object
    zeta_of_V: object


_BISECTIONS = 64
"""Halvings of the bracket in ln zeta of :meth:`ElasticResponse.zeta_of_V` (2^-64 of ln zeta_max: below round-off)."""


class ElasticResponse:
    r"""How a solid answers a rough surface pressed into full contact (base class).

    A subclass defines :meth:`V` and :meth:`dV_dzeta`; :meth:`zeta_of_V` defaults to a bisection of :meth:`V` in
    :math:`\ln\zeta`.  The energy side (:meth:`effective_modulus`, :meth:`compliance`,
    :meth:`elastic_energy_complete`) raises ``ValueError`` unless a subclass defines it: a response without stored
    elastic energy (sliding on a viscoelastic solid) still gives the contact area, not the mean separation.

    Subclasses should be immutable values with ``__eq__`` and ``__hash__`` (results cache their quadrature rules on
    the response).
    """

    # -- the pressure side (every response) ------------------------------------------------------------------
    def kernels(self, psd) -> Kernels:
        """:meth:`dV_dzeta_unchecked` and :meth:`zeta_of_V_unchecked` bound to the spectrum ``psd``.

        Parameters
        ----------
        psd : PSD
            The spectrum.

        Returns
        -------
        Kernels
            The two callables of one argument.
        """
        return Kernels(partial(self.dV_dzeta_unchecked, psd), partial(self.zeta_of_V_unchecked, psd))

    def V(self, psd, zeta=None) -> np.ndarray:  # pragma: no cover - abstract
        r"""Complete-contact pressure variance :math:`V(\zeta)` (``eq:Vp_closed_form``).

        Parameters
        ----------
        psd : PSD
            The spectrum.
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, pressure^2
            V at each ``zeta``.
        """
        raise NotImplementedError(f"{type(self).__name__} defines no V(zeta)")

    def dV_dzeta(self, psd, zeta=None) -> np.ndarray:  # pragma: no cover - abstract
        r"""Growth rate :math:`dV/d\zeta`, the diffusion coefficient :math:`B_2` (``eq:dVdxi``, ``eq:B2_xi_1``).

        Parameters
        ----------
        psd : PSD
            The spectrum.
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, pressure^2
            dV/dzeta at each ``zeta``.
        """
        raise NotImplementedError(f"{type(self).__name__} defines no dV/dzeta")

    def dV_dzeta_unchecked(self, psd, z) -> np.ndarray:
        """:meth:`dV_dzeta` at magnifications already checked (a solver's inner loop); default :meth:`dV_dzeta`.

        Parameters
        ----------
        psd : PSD
            The spectrum.
        z : float or ndarray, dimensionless
            Magnification(s), finite floats in ``[1, zeta_max]`` (the caller's responsibility).

        Returns
        -------
        numpy.ndarray, pressure^2
            dV/dzeta at each ``z``.
        """
        return self.dV_dzeta(psd, z)

    def zeta_of_V(self, psd, V) -> np.ndarray:
        r"""Magnification at which the complete-contact variance reaches ``V``: the inverse of :meth:`V`.

        The default bisects :meth:`V` (non-decreasing in :math:`\zeta`) in :math:`\ln\zeta` to round-off.

        Parameters
        ----------
        psd : PSD
            The spectrum.
        V : array_like, pressure^2
            Complete-contact pressure variance(s), finite.

        Returns
        -------
        numpy.ndarray, dimensionless
            zeta with V(zeta) = ``V``: 1 for V <= 0, ``zeta_max`` for V >= V(zeta_max).
        """
        return self.zeta_of_V_unchecked(psd, np.asarray(as_float_array(V, "V"), dtype=float))

    def zeta_of_V_unchecked(self, psd, V) -> np.ndarray:
        """:meth:`zeta_of_V` at variances already checked (finite floats): nothing validated.

        Parameters
        ----------
        psd : PSD
            The spectrum.
        V : ndarray, pressure^2
            Complete-contact pressure variance(s), finite floats (the caller's responsibility).

        Returns
        -------
        numpy.ndarray, dimensionless
            zeta with V(zeta) = ``V``: 1 for V <= 0, ``zeta_max`` for V >= V(zeta_max).
        """
        V = np.asarray(V, dtype=float)
        lo = np.zeros(V.shape)
        hi = np.full(V.shape, np.log(psd.zeta_max))
        for _ in range(_BISECTIONS):
            mid = 0.5 * (lo + hi)
            below = np.asarray(self.V(psd, np.exp(mid)), dtype=float) < V
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        z = np.clip(np.exp(0.5 * (lo + hi)), 1.0, psd.zeta_max)
        V_max = float(self.V(psd))
        return np.where(V >= V_max, psd.zeta_max, np.where(V <= 0.0, 1.0, z))

    # -- the energy side (a solid that stores elastic energy) ------------------------------------------------
    def _no_energy(self, needed_for: str):
        return ValueError(
            f"the elastic energy is not defined for this response ({type(self).__name__}: it defines no real "
            f"effective modulus E_eff(q)), needed for {needed_for}; use a response that stores elastic energy, "
            "e.g. ElasticHalfSpace(E_star)"
        )

    def plane_strain_modulus(self, needed_for: str) -> float:
        """The one modulus E* of a homogeneous elastic half-space, for the relations derived for it alone.

        Parameters
        ----------
        needed_for : str
            The relation asking (e.g. "Barber's relation"), for the message.

        Returns
        -------
        float, pressure
            E* (only :class:`ElasticHalfSpace`).

        Raises
        ------
        ValueError
            This response is not a homogeneous half-space, naming ``needed_for``.
        """
        raise ValueError(
            f"{needed_for} is derived for a homogeneous elastic half-space of one modulus E*; this response "
            f"({type(self).__name__}) has none"
        )

    def effective_modulus(self, q, needed_for: str = "the elastic energy"):
        r"""Effective modulus :math:`E_{eff}(q) = 2/(q\,M(q))` of the surface compliance :math:`M(q)`.

        Persson, J. Chem. Phys. 115 (2001) 3840: the surface displacement answers a pressure of wavevector q as
        :math:`u(q) = M(q)\,p(q)`; the elastic energy per nominal area is
        :math:`\frac14\int d^2q\,q\,E_{eff}(q)\,|u(q)|^2/(2\pi)^2` (``eq:Uel_original``).

        Parameters
        ----------
        q : float or array_like, 1/length
            Wavenumber(s) in ``[q_l, q_s]``.
        needed_for : str
            What asks (named in the error of a response without stored elastic energy).

        Returns
        -------
        float or numpy.ndarray, pressure
            :math:`E_{eff}` at each ``q`` (a float where it does not depend on q).

        Raises
        ------
        ValueError
            The response stores no elastic energy (the base class and, e.g., sliding on a viscoelastic solid).
        """
        raise self._no_energy(needed_for)

    def compliance(self, q, needed_for: str = "the elastic energy"):
        r"""Surface compliance :math:`M(q) = u(q)/p(q) = 2/(E_{eff}(q)\,q)` (Persson, J. Chem. Phys. 115 (2001) 3840).

        Parameters
        ----------
        q : float or array_like, 1/length
            Wavenumber(s) in ``[q_l, q_s]``, > 0.
        needed_for : str
            What asks (named in the error of a response without stored elastic energy).

        Returns
        -------
        float or numpy.ndarray, length / pressure
            :math:`M(q)` at each ``q``.

        Raises
        ------
        ValueError
            The response stores no elastic energy.
        """
        return 2.0 / (self.effective_modulus(q, needed_for) * np.asarray(q, dtype=float))

    def elastic_energy_complete(self, psd, zeta=None, needed_for: str = "the elastic energy") -> np.ndarray:
        r"""Elastic energy per nominal area at complete contact, :math:`\frac{\pi}{2}\int q^2 C E_{eff}\,dq`.

        ``eq:Uel_complete_2`` divided by :math:`A_n`, up to magnification ``zeta``.

        Parameters
        ----------
        psd : PSD
            The spectrum.
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.
        needed_for : str
            What asks (named in the error of a response without stored elastic energy).

        Returns
        -------
        numpy.ndarray, pressure x length
            Elastic energy per unit nominal area.

        Raises
        ------
        ValueError
            The response stores no elastic energy.
        """
        raise self._no_energy(needed_for)


class ElasticHalfSpace(ElasticResponse):
    r"""Homogeneous elastic half-space of plane-strain modulus :math:`E^* = E/(1-\nu^2)`.

    :math:`E_{eff}(q) = E^*` at every wavevector, so (Xu, Li, Chen, Zhou tutorial ``eq:Vp_closed_form``,
    ``eq:VV_relation``, ``eq:dVdxi``, ``eq:Uel_complete_2``; Persson, J. Chem. Phys. 115 (2001) 3840)

    .. math::  V(\zeta) = \frac{\pi}{2}E^{*2}\int_{q_l}^{\zeta q_l} q^3C\,dq, \quad
               \frac{dV}{d\zeta} = \frac{\pi}{2}E^{*2} q_l q^3 C(q)\big|_{q=\zeta q_l}, \quad
               M(q) = \frac{2}{E^* q}, \quad \frac{U_{el}}{A_n} = \frac{\pi}{2}E^*\int q^2C\,dq.

    The spectrum's closed forms compute them (the moments of :meth:`persson_fp.PSD.moment_unchecked`, the inverse
    :meth:`persson_fp.PSD.zeta_of_V`): the numbers are those of :meth:`persson_fp.PSD.V` and its kin, bit for bit.

    Parameters
    ----------
    E_star : float, pressure
        Plane-strain modulus, finite and > 0.

    Raises
    ------
    ValueError
        ``E_star`` not a finite real number > 0.
    """

    __slots__ = ("E_star",)

    def __init__(self, E_star: float):
        object.__setattr__(self, "E_star", as_positive_scalar(E_star, "E_star"))

    def __setattr__(self, name, value):
        raise AttributeError(f"ElasticHalfSpace is immutable (attribute {name!r})")

    def __repr__(self):
        return f"ElasticHalfSpace(E_star={self.E_star!r})"

    def __eq__(self, other):
        if type(other) is not ElasticHalfSpace:
            return NotImplemented
        return self.E_star == other.E_star

    def __hash__(self):
        return hash((ElasticHalfSpace, self.E_star))

    def __reduce__(self):  # pickle / deepcopy through the constructor (the instance refuses attribute assignment)
        return (ElasticHalfSpace, (self.E_star,))

    def plane_strain_modulus(self, needed_for: str) -> float:
        """E*."""
        return self.E_star

    def kernels(self, psd) -> Kernels:
        """The spectrum's own unchecked kernels at E* (no call between a solver and the spectrum)."""
        return Kernels(
            partial(psd.dV_dzeta_unchecked, E_star=self.E_star), partial(psd.zeta_of_V_unchecked, E_star=self.E_star)
        )

    def V(self, psd, zeta=None) -> np.ndarray:
        """V(zeta) = (pi/2) E*^2 int q^3 C dq (the spectrum's closed form, bit for bit :meth:`persson_fp.PSD.V`)."""
        # the arithmetic of persson_fp.PSD.V, one call less on the stack (a solver's set-up asks it)
        E_star = np.float64(self.E_star)
        m = psd.moment_unchecked(3, psd.zeta_max if zeta is None else check_in_range(zeta, "zeta", 1.0, psd.zeta_max))
        with np.errstate(over="ignore"):  # out of range -> inf (ContactProblem refuses it), never OverflowError
            return 0.25 * E_star**2 * (2.0 * np.pi * m)

    def dV_dzeta(self, psd, zeta=None) -> np.ndarray:
        """dV/dzeta = (pi/2) E*^2 q_l q^3 C(q) at q = zeta q_l (bit for bit :meth:`persson_fp.PSD.dV_dzeta`)."""
        # the arithmetic of persson_fp.PSD.dV_dzeta, one call less on the stack (a coefficient B2 asks it every step)
        E_star = self.E_star
        if type(zeta) is float and 1.0 - 1e-12 <= zeta <= psd.zeta_max * (1.0 + 1e-12):  # no array round trip
            q = np.float64(min(max(zeta, 1.0), psd.zeta_max) * psd.q_l)
            return 0.5 * np.pi * E_star**2 * psd.q_l * q**3 * psd.C(float(q))
        z = psd.zeta_max if zeta is None else check_in_range(zeta, "zeta", 1.0, psd.zeta_max)
        return psd.dV_dzeta_unchecked(z, E_star)

    def dV_dzeta_unchecked(self, psd, z) -> np.ndarray:
        """The spectrum's unchecked kernel :meth:`persson_fp.PSD.dV_dzeta_unchecked` at E*."""
        return psd.dV_dzeta_unchecked(z, self.E_star)

    def zeta_of_V(self, psd, V) -> np.ndarray:
        """The spectrum's closed-form inverse :meth:`persson_fp.PSD.zeta_of_V` at E*."""
        return psd.zeta_of_V(V, self.E_star)

    def zeta_of_V_unchecked(self, psd, V) -> np.ndarray:
        """The spectrum's unchecked inverse :meth:`persson_fp.PSD.zeta_of_V_unchecked` at E*."""
        return psd.zeta_of_V_unchecked(V, self.E_star)

    def effective_modulus(self, q, needed_for: str = "the elastic energy") -> float:
        """E_eff(q) = E* at every wavevector."""
        return self.E_star

    def compliance(self, q, needed_for: str = "the elastic energy"):
        """M(q) = 2 / (E* q)."""
        return 2.0 / self.E_star / np.asarray(q, dtype=float)

    def elastic_energy_complete(self, psd, zeta=None, needed_for: str = "the elastic energy") -> np.ndarray:
        """U_el / A_n = (pi/2) E* int q^2 C dq (the spectrum's :meth:`persson_fp.PSD.elastic_energy_complete`)."""
        return psd.elastic_energy_complete(zeta, self.E_star)


def check_response(response, E_star: float) -> ElasticResponse:
    """The response a theory module works with: ``response`` (checked), or the half-space of ``E_star``.

    Parameters
    ----------
    response : ElasticResponse or None
        The solid's response; None: :class:`ElasticHalfSpace` of ``E_star``.
    E_star : float, pressure
        Plane-strain modulus (validated by the caller).

    Returns
    -------
    ElasticResponse

    Raises
    ------
    ValueError
        ``response`` neither None nor an :class:`ElasticResponse`.
    """
    if response is None:
        return ElasticHalfSpace(E_star)
    if not isinstance(response, ElasticResponse):
        raise ValueError(f"response must be None or an ElasticResponse, got {type(response).__name__}")
    return response
