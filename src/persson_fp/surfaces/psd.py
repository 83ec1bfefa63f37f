r"""Power spectral densities of isotropic rough surfaces and their moments.

The spectrum enters Persson's theory only through the complete-contact
pressure variance (Xu et al. tutorial, Appendix B)

.. math::

    V(\zeta) = \frac{\pi}{2} E^{*2} \int_{q_l}^{\zeta q_l} q^3 C(q)\,dq
             = \tfrac14 E^{*2} \langle|\nabla h|^2\rangle(\zeta)
    \qquad \text{(eq:V_equ, eq:VV_relation)}

and its derivative :math:`dV/d\zeta = \frac{\pi}{2} E^{*2} q_l\, q^3 C(q)`
at :math:`q = \zeta q_l` (``eq:dVdxi``).  ``C(q)`` follows the convention
:math:`\langle h^2\rangle = \int d^2q\, C(q) = 2\pi \int q C(q)\,dq`
(``eq:variance_h_continuous``).

Units: wavenumbers in 1/length, ``C`` in length^4, heights in length,
slopes dimensionless, ``E_star`` and ``V`` in pressure and pressure^2.
This module imports no solver.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from persson_fp._validate import as_float_array, as_positive_scalar, check_in_range

__all__ = ["PSD", "SelfAffinePSD", "powint", "powint_inverse"]


def powint(a, b, e):
    r"""Return :math:`\int_a^b q^{e-1}\,dq = (b^e - a^e)/e`, continuous at ``e = 0``.

    Written as :math:`a^e\,\mathrm{expm1}(e \ln(b/a))/e`, which keeps full relative
    accuracy as ``e -> 0`` (where it tends to :math:`\ln(b/a)`): this is what makes
    the closed forms of the spectrum moments valid at H = 0 and H = 1.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    e = np.asarray(e, dtype=float)
    log_ratio = np.log(b / a)
    x = e * log_ratio
    e_safe = np.where(e == 0.0, 1.0, e)
    val = np.power(a, e) * np.expm1(x) / e_safe
    return np.where(e == 0.0, log_ratio, val)


def powint_inverse(a, I, e):
    r"""The ``b`` with :math:`\int_a^b q^{e-1}\,dq = I` (inverse of :func:`powint` in its upper limit).

    :math:`b = a\,(1 + e I / a^e)^{1/e}`, written with ``log1p``/``exp`` so that it is continuous
    at ``e = 0`` (where :math:`b = a\,e^{I}`).
    """
    a = np.asarray(a, dtype=float)
    I = np.asarray(I, dtype=float)
    e = np.asarray(e, dtype=float)
    x = e * I / np.power(a, e)
    e_safe = np.where(e == 0.0, 1.0, e)
    with np.errstate(invalid="ignore", divide="ignore"):
        log_ratio = np.where(e == 0.0, I, np.log1p(x) / e_safe)
    return a * np.exp(log_ratio)


class PSD:
    """Base class of isotropic spectra on ``[q_l, q_s]``.

    Subclasses set ``q_l`` (lower cut-off, 1/length; the magnification is
    ``zeta = q / q_l``) and ``q_s`` (upper cut-off, 1/length) and implement
    :meth:`C` and :meth:`moment`; everything else (heights, slopes, pressure
    variance) is derived here.

    A spectrum is an immutable value (its attributes refuse assignment once built): problems and
    solvers cache quantities derived from it, such as V(zeta_max).
    """

    q_l: float
    q_s: float

    def __setattr__(self, name, value):
        if self.__dict__.get("_frozen", False):
            raise AttributeError(f"{type(self).__name__} is immutable (attribute {name!r}); build a new spectrum")
        object.__setattr__(self, name, value)

    def __delattr__(self, name):
        raise AttributeError(f"{type(self).__name__} is immutable (attribute {name!r})")

    def __setstate__(self, state):  # pickle / deepcopy: copies arrive writeable, freeze them again
        for key, value in state.items():
            object.__setattr__(self, key, value)
        self._freeze_arrays()

    def _freeze_arrays(self) -> None:
        for value in self.__dict__.values():
            if isinstance(value, np.ndarray):
                value.setflags(write=False)

    def _freeze(self) -> None:
        """End of a subclass's ``__init__``: check the range, make the instance (and its arrays) read-only."""
        self._check_range()
        self._freeze_arrays()
        self._frozen = True

    def _check_range(self) -> None:
        """Raise ``ValueError`` unless C at the band's ends and the moments used (k = 1, 2, 3: heights,
        elastic energy, slopes) are finite and > 0 -- an over- or underflow would give V = inf or 0."""
        with np.errstate(all="ignore"):
            vals = [float(self.C(np.array(q))) for q in (self.q_l, self.q_s)]
            vals += [float(self.moment(k)) for k in (1, 2, 3)]
        if not all(np.isfinite(v) and v > 0 for v in vals):
            raise ValueError(
                f"{self!r}: C(q) or its moments (<h^2>, <|grad h|^2>) leave floating-point range "
                f"(got {[float(v) for v in vals]}); rescale the length unit"
            )

    @property
    def zeta_max(self) -> float:
        """Largest magnification ``q_s / q_l`` (dimensionless)."""
        return self.q_s / self.q_l

    def check_zeta(self, zeta: ArrayLike, name: str = "zeta") -> np.ndarray:
        """Validate magnifications: finite and in ``[1, zeta_max]``.

        Parameters
        ----------
        zeta : array_like, dimensionless
            Magnifications to check.
        name : str
            Parameter name quoted in the error message.

        Returns
        -------
        numpy.ndarray
            ``zeta`` as a float array.

        Raises
        ------
        ValueError
            If a value is not finite or lies outside ``[1, zeta_max]``.
        """
        return check_in_range(zeta, name, 1.0, self.zeta_max)

    def C(self, q: ArrayLike) -> np.ndarray:  # pragma: no cover - abstract
        """Spectrum C(q) (``E:PSD``); zero outside ``[q_l, q_s]``.

        Parameters
        ----------
        q : array_like, 1/length
            Wavenumbers.

        Returns
        -------
        numpy.ndarray, length^4
            C at ``q``, same shape as ``q``.
        """
        raise NotImplementedError

    def moment(self, k: float, zeta: ArrayLike | None = None) -> np.ndarray:  # pragma: no cover - abstract
        r"""Spectral moment :math:`\int_{q_l}^{\zeta q_l} q^k C(q)\,dq`.

        Parameters
        ----------
        k : float
            Power of q.
        zeta : array_like, optional, dimensionless
            Upper magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, length^(3-k)
            The moment at each ``zeta``.
        """
        raise NotImplementedError

    def moment_unchecked(self, k: float, z) -> np.ndarray:
        r"""Spectral moment :math:`\int_{q_l}^{z q_l} q^k C(q)\,dq` at magnifications already checked.

        The kernel behind :meth:`moment` for a solver's inner loop: nothing is checked.  A subclass that writes
        only :meth:`moment` gets the checked one.

        Parameters
        ----------
        k : float
            Power of q.
        z : float or ndarray, dimensionless
            Upper magnification(s), finite floats in ``[1, zeta_max]`` (the caller's responsibility).

        Returns
        -------
        numpy.ndarray, length^(3-k)
            The moment at each ``z``.
        """
        return self.moment(k, z)

    # -- derived quantities -------------------------------------------------
    def _zeta(self, zeta):  # (check_zeta's check, one call less: it runs on every checked evaluation)
        return self.zeta_max if zeta is None else check_in_range(zeta, "zeta", 1.0, self.zeta_max)

    def dV_dzeta_unchecked(self, z, E_star: float) -> np.ndarray:
        """:meth:`dV_dzeta` at magnifications already checked: the kernel for a solver's inner loop.

        Nothing is validated; round-off beyond the ends is clipped, as :meth:`dV_dzeta` clips it (C vanishes
        outside [q_l, q_s]).

        Parameters
        ----------
        z : float or ndarray, dimensionless
            Magnification(s), finite floats in ``[1, zeta_max]`` (the caller's responsibility).
        E_star : float, pressure
            Effective modulus, a finite float > 0 (the caller's responsibility).

        Returns
        -------
        numpy.ndarray, pressure^2
            dV/dzeta at each ``z``.
        """
        if type(z) is float:  # one magnification (a coefficient B2(p, zeta) asks at every step): no array round trip
            q = np.float64(min(max(z, 1.0), self.zeta_max) * self.q_l)
            return 0.5 * np.pi * E_star**2 * self.q_l * q**3 * self.C(float(q))
        q = np.clip(z, 1.0, self.zeta_max) * self.q_l
        return 0.5 * np.pi * E_star**2 * self.q_l * q**3 * self.C(q)

    def h2(self, zeta: ArrayLike | None = None) -> np.ndarray:
        r"""Mean-square height :math:`\langle h^2\rangle(\zeta) = 2\pi\int q C\,dq` (``eq:Vh_closed_form``).

        Parameters
        ----------
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, length^2
            Mean-square height of the wavenumbers up to ``zeta q_l``.
        """
        return 2.0 * np.pi * self.moment(1, zeta)

    def grad2(self, zeta: ArrayLike | None = None) -> np.ndarray:
        r"""Mean-square slope :math:`\langle|\nabla h|^2\rangle(\zeta) = 2\pi\int q^3 C\,dq` (``eq:V_gradient``).

        Parameters
        ----------
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, dimensionless
            Mean-square slope of the wavenumbers up to ``zeta q_l``.
        """
        return 2.0 * np.pi * self.moment(3, zeta)

    @property
    def rms_height(self) -> float:
        """Root-mean-square height over the whole band (length)."""
        return float(np.sqrt(self.h2()))

    @property
    def rms_slope(self) -> float:
        """Root-mean-square slope over the whole band (dimensionless)."""
        return float(np.sqrt(self.grad2()))

    def V(self, zeta: ArrayLike | None = None, E_star: float = 1.0) -> np.ndarray:
        r"""Complete-contact pressure variance :math:`V(\zeta)`.

        ``eq:Vp_closed_form`` / ``eq:VV_relation``:
        :math:`V = \tfrac14 E^{*2}\langle|\nabla h|^2\rangle`.

        Parameters
        ----------
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.
        E_star : float, pressure
            Effective modulus (> 0).

        Returns
        -------
        numpy.ndarray, pressure^2
            V at each ``zeta``.
        """
        E_star = np.float64(as_positive_scalar(E_star, "E_star"))
        m = self.moment_unchecked(3, self._zeta(zeta))
        with np.errstate(over="ignore"):  # out of range -> a ValueError below, never OverflowError
            V = 0.25 * E_star**2 * (2.0 * np.pi * m)
        if not np.all(np.isfinite(V)):
            raise ValueError(
                f"E_star = {float(E_star)!r} puts V = E_star^2 <|grad h|^2> / 4 outside floating-point range; "
                "rescale (e.g. pressures in MPa)"
            )
        return V

    def zeta_of_V(self, V: ArrayLike, E_star: float = 1.0) -> np.ndarray:
        """Magnification at which the complete-contact variance reaches ``V``.

        The inverse of :meth:`V` in closed form (the moment of a piecewise power law is inverted
        piece by piece, ``powint_inverse``).

        Parameters
        ----------
        V : array_like, pressure^2
            Complete-contact pressure variance(s).
        E_star : float, pressure
            Effective modulus (> 0).

        Returns
        -------
        numpy.ndarray, dimensionless
            zeta with V(zeta) = ``V``: 1 for V = 0, ``zeta_max`` for V >= V(zeta_max).
        """
        V = as_float_array(V, "V")
        if np.any(V < 0.0):
            raise ValueError(f"V must be >= 0 everywhere (a variance), got {float(V[V < 0.0].ravel()[0])!r}")
        E_star = as_positive_scalar(E_star, "E_star")
        if not math.isfinite(E_star * E_star):
            raise ValueError(f"E_star = {E_star!r} is outside floating-point range (E_star^2 overflows); rescale")
        return self.zeta_of_V_unchecked(V, E_star)

    def zeta_of_V_unchecked(self, V, E_star: float) -> np.ndarray:
        """:meth:`zeta_of_V` at variances already checked: the kernel for a solver's inner loop, nothing validated.

        Parameters
        ----------
        V : ndarray, pressure^2
            Complete-contact pressure variance(s), finite floats (the caller's responsibility).
        E_star : float, pressure
            Effective modulus, a finite float > 0 (the caller's responsibility).

        Returns
        -------
        numpy.ndarray, dimensionless
            zeta with V(zeta) = ``V``: 1 for V <= 0, ``zeta_max`` for V >= V(zeta_max).
        """
        E_star = np.float64(E_star)
        M_max = float(self.moment_unchecked(3, self.zeta_max))
        with np.errstate(over="ignore"):
            M = np.clip(V / (0.5 * np.pi * E_star**2), 0.0, M_max)
        z = np.clip(self.moment_inverse(3, M) / self.q_l, 1.0, self.zeta_max)
        return np.where(M >= M_max, self.zeta_max, np.where(M <= 0.0, 1.0, z))

    def moment_inverse(self, k: float, M: ArrayLike) -> np.ndarray:  # pragma: no cover - abstract
        r"""The upper limit q with :math:`\int_{q_l}^{q} q'^k C(q')\,dq' = M`.

        Parameters
        ----------
        k : float
            Power of q, as in :meth:`moment`.
        M : array_like, length^(3-k)
            Target moment(s) in ``[0, moment(k)]``.

        Returns
        -------
        numpy.ndarray, 1/length
            The wavenumber(s) at which the moment reaches ``M``.
        """
        raise NotImplementedError

    def dV_dzeta(self, zeta: ArrayLike | None = None, E_star: float = 1.0) -> np.ndarray:
        r"""Growth rate of the variance, :math:`dV/d\zeta = \frac{\pi}{2} E^{*2} q_l q^3 C(q)` at :math:`q = \zeta q_l`.

        This is the diffusion coefficient :math:`B_2` of Persson's theory (``eq:dVdxi``, ``eq:B2_xi_1``).

        Parameters
        ----------
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.
        E_star : float, pressure
            Effective modulus (> 0).

        Returns
        -------
        numpy.ndarray, pressure^2
            dV/dzeta at each ``zeta``.
        """
        E_star = as_positive_scalar(E_star, "E_star")
        if type(zeta) is float and 1.0 - 1e-12 <= zeta <= self.zeta_max * (1.0 + 1e-12):
            # one magnification (what a coefficient B2(p, zeta) asks at every step): no array round trip, ~3 us
            # instead of ~30; the same clipping and the same C(q) as below
            q = min(max(zeta, 1.0), self.zeta_max) * self.q_l
            q = np.float64(q)
            return 0.5 * np.pi * E_star**2 * self.q_l * q**3 * self.C(float(q))
        return self.dV_dzeta_unchecked(self._zeta(zeta), E_star)

    def elastic_energy_complete(self, zeta: ArrayLike | None = None, E_star: float = 1.0) -> np.ndarray:
        r"""Elastic energy per nominal area at complete contact.

        ``eq:Uel_complete_2`` divided by :math:`A_n`:
        :math:`U_{el}/A_n = \frac{\pi}{2} E^* \int_{q_l}^{\zeta q_l} q^2 C(q)\,dq`.

        Parameters
        ----------
        zeta : array_like, optional, dimensionless
            Magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.
        E_star : float, pressure
            Effective modulus (> 0).

        Returns
        -------
        numpy.ndarray, pressure x length
            Elastic energy per unit nominal area.
        """
        E_star = as_positive_scalar(E_star, "E_star")
        return 0.5 * np.pi * E_star * self.moment(2, zeta)


class SelfAffinePSD(PSD):
    r"""Self-affine spectrum with roll-off, ``E:PSD`` of the Xu et al. tutorial.

    .. math::

        C(q) = \begin{cases} C_0 q_r^{-2(1+H)} & q_l \le q < q_r \\
                             C_0 q^{-2(1+H)}   & q_r \le q \le q_s \\
                             0 & \text{elsewhere} \end{cases}

    Parameters
    ----------
    C0 : float, length^(2-2H)
        Prefactor (> 0, finite).  Use :meth:`from_rms_slope` or
        :meth:`from_rms_height` when the slope or the height is what you know.
    H : float, dimensionless
        Hurst exponent in [0, 1] (the closed forms take their logarithmic
        limits at H = 0 and H = 1).
    q_l, q_r, q_s : float, 1/length
        Lower cut-off, roll-off and upper cut-off, ``0 < q_l <= q_r <= q_s``
        (``q_r = q_l`` means no roll-off).
    """

    def __init__(self, C0: float, H: float, q_l: float, q_r: float, q_s: float):
        C0 = as_positive_scalar(C0, "C0")
        if np.ndim(H) != 0:
            raise ValueError(f"H must be a scalar in [0, 1], got shape {np.shape(H)}")
        H = float(check_in_range(H, "H", 0.0, 1.0, rtol=0.0))
        q_l = as_positive_scalar(q_l, "q_l")
        q_r = as_positive_scalar(q_r, "q_r")
        q_s = as_positive_scalar(q_s, "q_s")
        if not q_l <= q_r:
            raise ValueError(f"q_r must lie in [q_l, q_s] = [{q_l!r}, {q_s!r}], got {q_r!r}")
        if not q_r <= q_s:
            raise ValueError(f"q_s must be >= q_r = {q_r!r}, got {q_s!r}")
        if q_s == q_l:
            raise ValueError(f"q_s must be > q_l = {q_l!r} (an empty band has no roughness)")
        self.C0 = C0
        self.H = H
        self.q_l = q_l
        self.q_r = q_r
        self.q_s = q_s
        self._freeze()

    def __repr__(self):
        return f"SelfAffinePSD(C0={self.C0!r}, H={self.H!r}, q_l={self.q_l!r}, q_r={self.q_r!r}, q_s={self.q_s!r})"

    @classmethod
    def _unit(cls, H, q_l, q_r, q_s):
        """The spectrum with C0 = 1 (the shape that a constructor from rms values scales)."""
        try:
            return cls(1.0, H, q_l, q_r, q_s)
        except ValueError as err:
            if "floating-point range" not in str(err):
                raise
            raise ValueError(
                f"q_l, q_r, q_s = {float(q_l)!r}, {float(q_r)!r}, {float(q_s)!r} put q^(-2(1+H)) out of floating-point "
                "range; rescale the length unit"
            ) from None

    @classmethod
    def _with_rms(cls, value, name: str, moment: str, H, q_l, q_r, q_s) -> SelfAffinePSD:
        """The spectrum whose ``moment`` ("grad2" or "h2") is ``value``^2: C0 scaled from the unit-C0 spectrum."""
        value = as_positive_scalar(value, name)
        unit = cls._unit(H, q_l, q_r, q_s)
        with np.errstate(over="ignore"):
            C0 = np.float64(value) ** 2 / getattr(unit, moment)()
        if not (np.isfinite(C0) and C0 > 0):
            raise ValueError(f"{name} = {value!r} puts C0 out of floating-point range; rescale the units")
        return cls(C0, H, q_l, q_r, q_s)

    @classmethod
    def from_rms_slope(cls, rms_slope: float, H: float, q_l: float, q_r: float, q_s: float) -> SelfAffinePSD:
        """Spectrum whose rms slope over ``[q_l, q_s]`` is ``rms_slope``.

        Parameters
        ----------
        rms_slope : float, dimensionless
            Root-mean-square slope (> 0).
        H, q_l, q_r, q_s : float
            As for :class:`SelfAffinePSD`.

        Returns
        -------
        SelfAffinePSD
            The spectrum with ``C0`` chosen for that slope.
        """
        return cls._with_rms(rms_slope, "rms_slope", "grad2", H, q_l, q_r, q_s)

    @classmethod
    def from_rms_height(cls, rms_height: float, H: float, q_l: float, q_r: float, q_s: float) -> SelfAffinePSD:
        """Spectrum whose rms height over ``[q_l, q_s]`` is ``rms_height``.

        Parameters
        ----------
        rms_height : float, length
            Root-mean-square height (> 0).
        H, q_l, q_r, q_s : float
            As for :class:`SelfAffinePSD`.

        Returns
        -------
        SelfAffinePSD
            The spectrum with ``C0`` chosen for that height.
        """
        return cls._with_rms(rms_height, "rms_height", "h2", H, q_l, q_r, q_s)

    @property
    def zeta_r(self) -> float:
        """Magnification of the roll-off, ``q_r / q_l``."""
        return self.q_r / self.q_l

    def C(self, q: ArrayLike) -> np.ndarray:
        if type(q) is float and math.isfinite(q) and q >= 0.0:  # one wavenumber: the same branches in floats
            if not self.q_l <= q <= self.q_s:
                return np.float64(0.0)
            return self.C0 * np.power(np.float64(self.q_r if q < self.q_r else q), -2.0 * (1.0 + self.H))
        q = as_float_array(q, "q")
        if np.any(q < 0.0):
            raise ValueError(f"q must be >= 0 everywhere (a wavenumber), got {float(q[q < 0.0].ravel()[0])!r}")
        plateau = self.C0 * np.power(np.float64(self.q_r), -2.0 * (1.0 + self.H))
        with np.errstate(divide="ignore"):
            tail = self.C0 * np.power(np.where(q > 0, q, 1.0), -2.0 * (1.0 + self.H))
        inside = (q >= self.q_l) & (q <= self.q_s)
        return np.where(inside, np.where(q < self.q_r, plateau, tail), 0.0)

    def moment(self, k: float, zeta: ArrayLike | None = None) -> np.ndarray:
        r"""Spectral moment :math:`\int_{q_l}^{\zeta q_l} q^k C(q)\,dq` in closed form.

        ``eq:Vh_closed_form`` and ``eq:Vp_closed_form`` for k = 1, 3, exact also in the logarithmic
        limits H = 0 and H = 1.

        Parameters
        ----------
        k : float
            Power of q.
        zeta : array_like, optional, dimensionless
            Upper magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, length^(3-k)
            The moment at each ``zeta``.
        """
        return self.moment_unchecked(k, self._zeta(zeta))

    def moment_unchecked(self, k: float, z) -> np.ndarray:
        # (documented on PSD.moment_unchecked: z finite in [1, zeta_max], nothing validated)
        z = np.asarray(z, dtype=float)
        q_hi = z * self.q_l
        q_mid = np.minimum(q_hi, self.q_r)
        plateau = self.C0 * np.power(np.float64(self.q_r), -2.0 * (1.0 + self.H)) * powint(self.q_l, q_mid, k + 1.0)
        tail_hi = np.maximum(q_hi, self.q_r)
        tail = self.C0 * powint(self.q_r, tail_hi, k - 1.0 - 2.0 * self.H)
        return plateau + tail

    def moment_inverse(self, k: float, M: ArrayLike) -> np.ndarray:
        M = np.asarray(M, dtype=float)
        c_plateau = self.C0 * np.power(np.float64(self.q_r), -2.0 * (1.0 + self.H))
        M_r = c_plateau * powint(self.q_l, self.q_r, k + 1.0)  # the plateau's share
        q_plat = powint_inverse(self.q_l, np.minimum(M, M_r) / c_plateau, k + 1.0)
        q_tail = powint_inverse(self.q_r, np.maximum(M - M_r, 0.0) / self.C0, k - 1.0 - 2.0 * self.H)
        return np.where(M <= M_r, q_plat, q_tail)
