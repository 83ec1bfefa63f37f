r"""Viscoelastic materials: the complex modulus :math:`E(\omega, T)` of a rubber, from a model or a DMA master curve.

Persson's theory of rubber friction (Persson, J. Chem. Phys. 115 (2001) 3840; J. Phys.: Condens. Matter 18 (2006)
7789) needs the rubber only through its complex Young's modulus :math:`E(\omega) = E'(\omega) + iE''(\omega)` at
the frequencies :math:`\omega = q v \cos\phi` that a road's roughness of wavenumber :math:`q` excites at sliding
speed :math:`v`, and its Poisson ratio :math:`\nu`.

Conventions (each explicit; every object prints its own in ``repr``):

* **Frequencies** are angular, :math:`\omega` in rad/s, everywhere in this module's methods.  A
  :class:`MasterCurve` is given in ``frequency_unit`` "Hz" (:math:`\omega = 2\pi f`, the unit of most DMA
  instruments) or "rad/s".  Relaxation times ``tau`` are in s.
* **Moduli** are in the user's pressure unit (the unit of the loads and of the spectrum's pressures: Pa for a
  spectrum in metres and loads in Pa).  :math:`E''\ge 0`: a passive material dissipates.
* **Temperatures** are in degrees Celsius.  Time–temperature superposition (Williams, Landel, Ferry, J. Am. Chem.
  Soc. 77 (1955) 3701): :math:`E(\omega, T) = b_T(T)\,E_{ref}(\omega\,a_T(T))`, where :math:`E_{ref}` is the curve
  at the reference temperature ``T_ref``, :math:`a_T` the horizontal shift factor (``shift``: :class:`WLF`,
  :class:`Arrhenius` or :class:`ShiftTable`; :math:`a_T(T_{ref}) = 1`, :math:`a_T < 1` above ``T_ref``: a warmer
  rubber behaves as the reference rubber at lower frequency) and :math:`b_T` the optional vertical factor
  (``vertical``; it *multiplies* the reference modulus: ``"kelvin"`` is the entropic
  :math:`b_T = (T + 273.15)/(T_{ref} + 273.15)`, or a callable of T; default 1).
* **Strain softening** (the Payne effect; Lorenz, Persson, Dieluweit, Tada, Eur. Phys. J. E 34 (2011) 129):
  :class:`StrainSoftening` multiplies :math:`E'` by :math:`f(\epsilon)` and :math:`E''` by :math:`g(\epsilon)` at
  the local strain :math:`\epsilon`.

The materials are :class:`Zener` (standard linear solid), :class:`Prony` (generalised Maxwell) and
:class:`MasterCurve` (a tabulated DMA curve, interpolated in log–log).  :func:`kramers_kronig_misfit`
measures whether a tabulated :math:`E'` and :math:`E''` belong to one causal material.

This module imports numpy only (scipy's interpolation and least squares load when a master curve is built).
"""

from __future__ import annotations

import math

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp._warn import warn_user

__all__ = [
    "ViscoelasticMaterial",
    "Zener",
    "Prony",
    "MasterCurve",
    "WLF",
    "Arrhenius",
    "ShiftTable",
    "StrainSoftening",
    "kramers_kronig_misfit",
    "KK_TOLERANCE",
    "R_GAS",
    "KELVIN",
]

R_GAS = 8.314462618
"""Molar gas constant, J/(mol K) (CODATA 2018, exact)."""

KELVIN = 273.15
"""Degrees Celsius to kelvin."""

KK_TOLERANCE = 0.05
r"""Relative rms misfit above which :class:`MasterCurve` warns that :math:`E'` and :math:`E''` disagree.

A causal linear material's :math:`E'` and :math:`E''` are one generalised Maxwell model; a joint non-negative fit
(ten relaxation times per decade over the table's range and a decade beyond) matches a consistent table to
0.01–0.2 % in either column (Prony models and single-time Zener solids tabulated at 5 points per decade).  A table
whose :math:`E''` is doubled is missed by 26–34 % when :math:`E_{glassy}/E_{rubbery} = 10^3`, by 13 % at 2 and by
3.5 % at 1.1: the check detects a doubled loss modulus on curves with at least a factor 2 of dispersion (a curve
with less carries too little Kramers–Kronig information).  5 % leaves room for measurement scatter."""


def check_temperature(T, name: str = "temperature") -> np.ndarray:
    T = as_float_array(T, name)
    if np.any(T <= -KELVIN):
        raise ValueError(f"{name} must be above absolute zero (> -273.15 degrees C), got {float(np.min(T))!r}")
    return T


# -- time-temperature shift laws --------------------------------------------------------------------------------
class ShiftLaw:
    r"""A horizontal shift law :math:`\log_{10} a_T(T)` about a reference temperature (base class)."""

    def log10_aT(self, T, T_ref: float) -> np.ndarray:  # pragma: no cover - abstract
        """log10 of the shift factor a_T at temperatures ``T`` (degrees C) for the curve at ``T_ref``."""
        raise NotImplementedError

    def check_reference(self, T_ref: float) -> None:
        """Called once by the material with its reference temperature (nothing by default)."""

    def _key(self):  # pragma: no cover - abstract
        raise NotImplementedError

    def __eq__(self, other):
        return isinstance(other, ShiftLaw) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())


class WLF(ShiftLaw):
    r"""Williams–Landel–Ferry shift: :math:`\log_{10} a_T = -C_1 (T - T_{ref})/(C_2 + T - T_{ref})`.

    Williams, Landel, Ferry, J. Am. Chem. Soc. 77 (1955) 3701.

    Parameters
    ----------
    C1 : float, dimensionless
        Finite and > 0 (typically 8–17).
    C2 : float, kelvin (= degrees C difference)
        Finite and > 0 (typically 50–120).

    Raises
    ------
    ValueError
        ``C1`` or ``C2`` not finite and > 0; :meth:`log10_aT` at :math:`T \le T_{ref} - C_2` (the law diverges).
    """

    def __init__(self, C1: float, C2: float):
        self.C1 = as_positive_scalar(C1, "C1")
        self.C2 = as_positive_scalar(C2, "C2")

    def __repr__(self):
        return f"WLF(C1={self.C1!r}, C2={self.C2!r})"

    def _key(self):
        return ("WLF", self.C1, self.C2)

    def log10_aT(self, T, T_ref: float) -> np.ndarray:
        """log10 a_T(T), degrees C; a ``ValueError`` naming ``temperature`` at T <= T_ref - C2."""
        T = check_temperature(T)
        dT = T - T_ref
        if np.any(dT <= -self.C2):
            raise ValueError(
                f"temperature must be above T_ref - C2 = {T_ref - self.C2!r} degrees C for the WLF shift "
                f"(C2 = {self.C2!r}); got {float(np.min(T))!r}"
            )
        return -self.C1 * (dT / (self.C2 + dT))  # (the ratio first: no overflow at absurd temperatures)


class Arrhenius(ShiftLaw):
    r"""Arrhenius shift: :math:`\log_{10} a_T = \frac{E_a}{R\ln 10}\left(\frac{1}{T_K} - \frac{1}{T_{ref,K}}\right)`.

    Temperatures in degrees C are converted to kelvin inside (:math:`T_K = T + 273.15`).

    Parameters
    ----------
    E_a : float, J/mol
        Activation energy, finite and > 0.
    """

    def __init__(self, E_a: float):
        self.E_a = as_positive_scalar(E_a, "E_a")

    def __repr__(self):
        return f"Arrhenius(E_a={self.E_a!r} J/mol)"

    def _key(self):
        return ("Arrhenius", self.E_a)

    def log10_aT(self, T, T_ref: float) -> np.ndarray:
        """log10 a_T(T), degrees C."""
        T = check_temperature(T)
        return self.E_a / (R_GAS * math.log(10.0)) * (1.0 / (T + KELVIN) - 1.0 / (T_ref + KELVIN))


class ShiftTable(ShiftLaw):
    r"""A measured shift: :math:`\log_{10} a_T` interpolated linearly in :math:`T` between tabulated points.

    The table is used as given: its :math:`a_T` is relative to the curve's ``T_ref`` (which labels the curve; a
    warning when the table's :math:`a_T(T_{ref})` is more than 10 % from 1).  Outside the table
    :math:`\log_{10} a_T` is extended linearly from the end segments, with a warning naming the range.

    Parameters
    ----------
    T : array_like, degrees C
        Temperatures, at least 2, strictly increasing, above -273.15.
    a_T : array_like, dimensionless
        Shift factors, finite and > 0.
    """

    def __init__(self, T, a_T):
        T = check_temperature(T, "T")
        a = as_float_array(a_T, "a_T")
        if T.ndim != 1 or T.size < 2 or a.shape != T.shape:
            raise ValueError(f"T and a_T must be 1-D of one length >= 2, got shapes {T.shape} and {a.shape}")
        if np.any(np.diff(T) <= 0):
            raise ValueError("T must be strictly increasing (no duplicated temperature)")
        if np.any(a <= 0):
            raise ValueError(f"a_T must be > 0, got {float(np.min(a))!r}")
        self.T, self.a_T = T, a
        self._log = np.log10(a)

    def __repr__(self):
        return f"ShiftTable({self.T.size} points, T in [{self.T[0]:g}, {self.T[-1]:g}] degrees C)"

    def _key(self):
        return ("ShiftTable", self.T.tobytes(), self.a_T.tobytes())

    def _interp(self, T: np.ndarray) -> np.ndarray:
        x, y = self.T, self._log
        out = np.interp(T, x, y)
        lo, hi = T < x[0], T > x[-1]
        out = np.where(lo, y[0] + (T - x[0]) * (y[1] - y[0]) / (x[1] - x[0]), out)
        return np.where(hi, y[-1] + (T - x[-1]) * (y[-1] - y[-2]) / (x[-1] - x[-2]), out)

    def check_reference(self, T_ref: float) -> None:
        """Warn when the table's a_T at the curve's reference temperature is far from 1."""
        a_ref = 10.0 ** float(self._interp(np.asarray(T_ref, dtype=float)))
        if abs(a_ref - 1.0) > 0.1:
            warn_user(
                f"the shift table gives a_T(T_ref = {T_ref!r} degrees C) = {a_ref:.4g}, not 1: the table is used as "
                "given (E(omega, T) = E_ref(omega a_T(T))); check that T_ref is the master curve's reference"
            )

    def log10_aT(self, T, T_ref: float) -> np.ndarray:
        """log10 a_T(T), interpolated linearly in T; extended linearly (with a warning) outside the table."""
        T = check_temperature(T)
        if np.any(T < self.T[0]) or np.any(T > self.T[-1]):
            warn_user(
                f"temperature {float(T.min()):g}..{float(T.max()):g} degrees C lies outside the shift table "
                f"[{self.T[0]:g}, {self.T[-1]:g}]: log10 a_T is extrapolated linearly"
            )
        return self._interp(T)


def _shift_law(shift) -> ShiftLaw | None:
    if shift is None or isinstance(shift, ShiftLaw):
        return shift
    raise ValueError(f"shift must be None, WLF(C1, C2), Arrhenius(E_a) or ShiftTable(T, a_T); got {shift!r}")


# -- strain softening -------------------------------------------------------------------------------------------
class StrainSoftening:
    r"""Strain softening (the Payne effect): :math:`E' \to E' f(\epsilon)`, :math:`E'' \to E'' g(\epsilon)`.

    Lorenz, Persson, Dieluweit, Tada, Eur. Phys. J. E 34 (2011) 129: the local strain at wavenumber :math:`q` is
    :math:`\epsilon(q) = \xi(q)/2`, half the rms slope of the roughness with wavenumbers up to :math:`q`,
    :math:`\xi^2(q) = 2\pi\int_{q_0}^{q} q'^3 C(q')\,dq'`.  :math:`f` and :math:`g` come from a strain sweep,
    normalised to 1 at small strain; they are interpolated linearly in :math:`\ln\epsilon` and held at their end
    values outside the table.

    Parameters
    ----------
    strain : array_like, dimensionless (a fraction: 0.01 is 1 %)
        Strain amplitudes, at least 2, strictly increasing, > 0.
    f, g : array_like, dimensionless
        Factors on the storage and the loss modulus at each strain, finite and > 0.
    """

    def __init__(self, strain, f, g):
        eps = as_float_array(strain, "strain")
        f = as_float_array(f, "f")
        g = as_float_array(g, "g")
        if eps.ndim != 1 or eps.size < 2 or f.shape != eps.shape or g.shape != eps.shape:
            raise ValueError(
                f"strain, f and g must be 1-D of one length >= 2, got shapes {eps.shape}, {f.shape}, {g.shape}"
            )
        if np.any(eps <= 0):
            raise ValueError(f"strain must be > 0 (a fraction), got {float(np.min(eps))!r}")
        if np.any(np.diff(eps) <= 0):
            raise ValueError("strain must be strictly increasing (no duplicated strain)")
        for name, v in (("f", f), ("g", g)):
            if np.any(v <= 0):
                raise ValueError(f"{name} must be > 0, got {float(np.min(v))!r}")
        self.strain, self.f, self.g = eps, f, g

    def __repr__(self):
        return f"StrainSoftening({self.strain.size} strains in [{self.strain[0]:g}, {self.strain[-1]:g}])"

    def _key(self):
        return ("StrainSoftening", self.strain.tobytes(), self.f.tobytes(), self.g.tobytes())

    def __eq__(self, other):
        return isinstance(other, StrainSoftening) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def factors(self, strain) -> tuple[np.ndarray, np.ndarray]:
        """(f, g) at strain amplitudes ``strain`` (fractions, > 0; 0 gives the small-strain end values)."""
        eps = as_float_array(strain, "strain")
        if np.any(eps < 0):
            raise ValueError(f"strain must be >= 0, got {float(np.min(eps))!r}")
        x = np.log(np.maximum(eps, self.strain[0]))
        xs = np.log(self.strain)
        return np.interp(x, xs, self.f), np.interp(x, xs, self.g)


# -- materials --------------------------------------------------------------------------------------------------
_EXTRAPOLATIONS = ("clamp", "loglinear", "raise")


class ViscoelasticMaterial:
    r"""A linear viscoelastic solid: complex Young's modulus :math:`E(\omega, T)` and Poisson ratio (base class).

    A subclass defines :meth:`modulus_ref` (the modulus at the reference temperature, vectorised in
    :math:`\omega`); the base applies the shift :math:`E(\omega, T) = b_T(T)\,E_{ref}(\omega\,a_T(T))`.
    """

    nu: float
    T_ref: float | None
    shift: ShiftLaw | None
    vertical: object

    def _init_common(self, nu, T_ref, shift, vertical):
        try:
            nu_ = as_positive_scalar(nu, "nu", allow_zero=True)
        except ValueError:
            raise ValueError(f"nu (Poisson's ratio) must lie in [0, 0.5], got {nu!r}") from None
        if nu_ > 0.5:
            raise ValueError(f"nu (Poisson's ratio) must lie in [0, 0.5], got {nu_!r}")
        self.nu = nu_
        self.shift = _shift_law(shift)
        if T_ref is None:
            if self.shift is not None:
                raise ValueError("T_ref (degrees C) is required with a shift law: it is the curve's temperature")
            self.T_ref = None
        else:
            T_ref = check_temperature(T_ref, "T_ref")
            if T_ref.ndim != 0:
                raise ValueError(f"T_ref must be one temperature (degrees C), got shape {T_ref.shape}")
            self.T_ref = float(T_ref)
        if self.shift is not None:
            self.shift.check_reference(self.T_ref)
        if vertical is not None and vertical != "kelvin" and not callable(vertical):
            raise ValueError(f"vertical must be None, 'kelvin' or a callable b_T(T), got {vertical!r}")
        if vertical is not None and self.T_ref is None:
            raise ValueError("T_ref (degrees C) is required with a vertical shift factor")
        self.vertical = vertical

    # -- what a subclass defines
    def modulus_ref(self, omega) -> np.ndarray:  # pragma: no cover - abstract
        """Complex modulus at the reference temperature, omega in rad/s (>= 0)."""
        raise NotImplementedError

    @property
    def frequency_range(self) -> tuple[float, float] | None:
        """(omega_min, omega_max) in rad/s where the modulus is known from data; None for a model (everywhere)."""
        return None

    # -- temperature
    @property
    def needs_temperature(self) -> bool:
        """True when the modulus depends on temperature (a shift law or a vertical factor)."""
        return self.shift is not None or self.vertical is not None

    def log10_aT(self, temperature=None) -> np.ndarray:
        """log10 of the horizontal shift factor at ``temperature`` (degrees C); 0 without a shift law."""
        if self.shift is None:
            return np.zeros(np.shape(temperature)) if temperature is not None else np.float64(0.0)
        if temperature is None:
            raise ValueError(f"temperature (degrees C) is required: the material has a shift law {self.shift!r}")
        return self.shift.log10_aT(temperature, self.T_ref)

    def b_T(self, temperature=None) -> np.ndarray:
        """Vertical shift factor b_T at ``temperature`` (degrees C), multiplying the modulus; 1 without one."""
        if self.vertical is None:
            return np.ones(np.shape(temperature)) if temperature is not None else np.float64(1.0)
        if temperature is None:
            raise ValueError("temperature (degrees C) is required: the material has a vertical shift factor")
        T = check_temperature(temperature)
        if self.vertical == "kelvin":
            return (T + KELVIN) / (self.T_ref + KELVIN)
        b = np.asarray(self.vertical(T), dtype=float)
        if not np.all(np.isfinite(b)) or np.any(b <= 0):
            raise ValueError(f"vertical: b_T(T) must be finite and > 0, got {b!r}")
        return b

    def modulus(self, omega, temperature=None) -> np.ndarray:
        r"""Complex Young's modulus :math:`E(\omega, T) = b_T E_{ref}(\omega a_T)`, pressure.

        Parameters
        ----------
        omega : array_like, rad/s
            Angular frequencies, finite and >= 0.
        temperature : array_like, optional, degrees C
            Required when the material has a shift law; broadcast against ``omega``.

        Returns
        -------
        numpy.ndarray of complex, pressure
            :math:`E' + iE''` at each (omega, temperature).
        """
        w = as_float_array(omega, "omega")
        if np.any(w < 0):
            raise ValueError(f"omega must be >= 0 (rad/s), got {float(np.min(w))!r}")
        if not self.needs_temperature:
            return self.modulus_ref(w)
        aT = 10.0 ** self.log10_aT(temperature)
        return self.b_T(temperature) * self.modulus_ref(w * aT)

    def storage_modulus(self, omega, temperature=None) -> np.ndarray:
        """E'(omega, T), pressure (the real part of :meth:`modulus`)."""
        return self.modulus(omega, temperature).real

    def loss_modulus(self, omega, temperature=None) -> np.ndarray:
        """E''(omega, T), pressure (the imaginary part of :meth:`modulus`)."""
        return self.modulus(omega, temperature).imag

    def _conventions(self) -> str:
        parts = [f"nu={self.nu!r}"]
        if self.T_ref is not None:
            parts.append(f"T_ref={self.T_ref!r} degrees C")
        if self.shift is not None:
            parts.append(f"shift={self.shift!r}")
        if self.vertical is not None:
            parts.append(f"vertical={'kelvin' if self.vertical == 'kelvin' else 'b_T(T)'}")
        return ", ".join(parts)

    def _base_key(self):
        return (self.nu, self.T_ref, self.shift, self.vertical)

    def __eq__(self, other):
        return type(other) is type(self) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())


class Zener(ViscoelasticMaterial):
    r"""Standard linear solid: :math:`E(\omega) = E_r + (E_g - E_r)\,\frac{i\omega\tau}{1 + i\omega\tau}`.

    One relaxation time; :math:`E_g = E_r` is an elastic solid.

    Parameters
    ----------
    E_rubbery : float, pressure
        Low-frequency (rubbery) modulus, finite and > 0.
    E_glassy : float, pressure
        High-frequency (glassy) modulus, finite and >= ``E_rubbery``.
    tau : float, s
        Relaxation time, finite and > 0.
    nu : float, dimensionless
        Poisson ratio in [0, 0.5]; default 0.5 (incompressible rubber).
    T_ref, shift, vertical
        Optional time–temperature superposition (module docstring).
    """

    def __init__(self, E_rubbery, E_glassy, tau, nu=0.5, T_ref=None, shift=None, vertical=None):
        self.E_rubbery = as_positive_scalar(E_rubbery, "E_rubbery")
        self.E_glassy = as_positive_scalar(E_glassy, "E_glassy")
        if self.E_glassy < self.E_rubbery:
            raise ValueError(f"E_glassy must be >= E_rubbery = {self.E_rubbery!r}, got {self.E_glassy!r}")
        self.tau = as_positive_scalar(tau, "tau")
        self._init_common(nu, T_ref, shift, vertical)

    def __repr__(self):
        return (
            f"Zener(E_rubbery={self.E_rubbery:.6g}, E_glassy={self.E_glassy:.6g}, tau={self.tau:.6g} s, "
            f"{self._conventions()})"
        )

    def _key(self):
        return ("Zener", self.E_rubbery, self.E_glassy, self.tau, *self._base_key())

    def modulus_ref(self, omega) -> np.ndarray:
        """E_r + (E_g - E_r) i omega tau / (1 + i omega tau), omega in rad/s."""
        x = np.asarray(omega, dtype=float) * self.tau
        d = self.E_glassy - self.E_rubbery
        den = 1.0 + x * x
        return (self.E_rubbery + d * x * x / den) + 1j * (d * x / den)


class Prony(ViscoelasticMaterial):
    r"""Generalised Maxwell solid: :math:`E(\omega) = E_r + \sum_i E_i\,\frac{i\omega\tau_i}{1 + i\omega\tau_i}`.

    Parameters
    ----------
    E_rubbery : float, pressure
        Equilibrium (rubbery) modulus, finite and > 0.
    E_i : array_like, pressure
        Relaxation strengths, finite and >= 0, at least one.
    tau_i : array_like, s
        Relaxation times, finite and > 0, the shape of ``E_i``.
    nu, T_ref, shift, vertical
        As :class:`Zener`.
    """

    def __init__(self, E_rubbery, E_i, tau_i, nu=0.5, T_ref=None, shift=None, vertical=None):
        self.E_rubbery = as_positive_scalar(E_rubbery, "E_rubbery")
        E_i = np.atleast_1d(as_float_array(E_i, "E_i"))
        tau_i = np.atleast_1d(as_float_array(tau_i, "tau_i"))
        if E_i.ndim != 1 or E_i.size == 0 or tau_i.shape != E_i.shape:
            raise ValueError(f"E_i and tau_i must be 1-D of one length >= 1, got shapes {E_i.shape}, {tau_i.shape}")
        if np.any(E_i < 0):
            raise ValueError(f"E_i must be >= 0, got {float(np.min(E_i))!r}")
        if np.any(tau_i <= 0):
            raise ValueError(f"tau_i must be > 0 (s), got {float(np.min(tau_i))!r}")
        self.E_i, self.tau_i = E_i, tau_i
        self._init_common(nu, T_ref, shift, vertical)

    def __repr__(self):
        return (
            f"Prony(E_rubbery={self.E_rubbery:.6g}, {self.E_i.size} elements, tau in "
            f"[{self.tau_i.min():.3g}, {self.tau_i.max():.3g}] s, {self._conventions()})"
        )

    def _key(self):
        return ("Prony", self.E_rubbery, self.E_i.tobytes(), self.tau_i.tobytes(), *self._base_key())

    @property
    def E_glassy(self) -> float:
        """High-frequency modulus E_r + sum E_i, pressure."""
        return float(self.E_rubbery + self.E_i.sum())

    def modulus_ref(self, omega) -> np.ndarray:
        """E_r + sum_i E_i i omega tau_i / (1 + i omega tau_i), omega in rad/s."""
        w = np.asarray(omega, dtype=float)
        x = w[..., None] * self.tau_i
        den = 1.0 + x * x
        return (self.E_rubbery + (self.E_i * x * x / den).sum(-1)) + 1j * (self.E_i * x / den).sum(-1)


class MasterCurve(ViscoelasticMaterial):
    r"""A tabulated DMA master curve :math:`E'(f), E''(f)` at a reference temperature.

    Interpolated in log–log by cubic splines (not-a-knot) of :math:`\ln E'` and :math:`\ln E''` in
    :math:`\ln\omega`: the moduli stay positive, and a smooth curve tabulated at 10 points per decade is reproduced
    to ~3e-5 between its points (5 per decade: ~5e-4).  Outside the table (``extrapolation``):
    "clamp" holds the end values (default), "loglinear" extends the end segments' log–log slopes, "raise" refuses
    a frequency outside the table in :meth:`~ViscoelasticMaterial.modulus` (the friction integrals still clamp where
    :math:`\cos\phi \to 0` takes the frequency to 0: that part always leaves a table).

    Parameters
    ----------
    frequency : array_like, ``frequency_unit``
        At least 3 frequencies, strictly increasing (no duplicates), finite and > 0.
    E_storage, E_loss : array_like, pressure
        Storage and loss moduli at each frequency, finite and > 0.
    frequency_unit : {"Hz", "rad/s"}
        "Hz": ``frequency`` is f and :math:`\omega = 2\pi f`; "rad/s": it is :math:`\omega`.
    T_ref : float, optional, degrees C
        The curve's temperature; required with ``shift``.
    shift : WLF, Arrhenius, ShiftTable or None
        Horizontal shift law.
    vertical : None, "kelvin" or callable
        Vertical factor :math:`b_T` multiplying the modulus.
    nu : float
        Poisson ratio in [0, 0.5]; default 0.5.
    extrapolation : {"clamp", "loglinear", "raise"}
        Outside the table (above).
    check_kk : bool
        Warn when :func:`kramers_kronig_misfit` exceeds :data:`KK_TOLERANCE` (default True).
    """

    def __init__(
        self,
        frequency,
        E_storage,
        E_loss,
        frequency_unit: str = "Hz",
        T_ref=None,
        shift=None,
        nu=0.5,
        vertical=None,
        extrapolation: str = "clamp",
        check_kk: bool = True,
    ):
        f = as_float_array(frequency, "frequency")
        E1 = as_float_array(E_storage, "E_storage")
        E2 = as_float_array(E_loss, "E_loss")
        if f.ndim != 1 or f.size < 3 or E1.shape != f.shape or E2.shape != f.shape:
            raise ValueError(
                f"frequency, E_storage and E_loss must be 1-D of one length >= 3, got shapes {f.shape}, {E1.shape}, "
                f"{E2.shape}"
            )
        if np.any(f <= 0):
            raise ValueError(f"frequency must be > 0, got {float(np.min(f))!r}")
        if np.any(np.diff(f) <= 0):
            i = int(np.argmax(np.diff(f) <= 0))
            raise ValueError(
                f"frequency must be strictly increasing (no duplicates): {f[i]!r} is followed by {f[i + 1]!r}"
            )
        if np.any(E1 <= 0):
            raise ValueError(f"E_storage must be > 0, got {float(np.min(E1))!r}")
        if np.any(E2 <= 0):
            raise ValueError(f"E_loss must be > 0 (a passive material dissipates), got {float(np.min(E2))!r}")
        if frequency_unit not in ("Hz", "rad/s"):
            raise ValueError(f"frequency_unit must be 'Hz' or 'rad/s', got {frequency_unit!r}")
        if extrapolation not in _EXTRAPOLATIONS:
            raise ValueError(f"extrapolation must be one of {_EXTRAPOLATIONS}, got {extrapolation!r}")
        self.frequency, self.E_storage, self.E_loss = f, E1, E2
        self.frequency_unit = frequency_unit
        self.extrapolation = extrapolation
        self.omega = f * (2.0 * np.pi if frequency_unit == "Hz" else 1.0)
        self._init_common(nu, T_ref, shift, vertical)
        from scipy.interpolate import CubicSpline

        x = np.log(self.omega)
        self._x = x
        self._y1, self._y2 = np.log(E1), np.log(E2)
        self._p1 = CubicSpline(x, self._y1)
        self._p2 = CubicSpline(x, self._y2)
        self._slopes = (
            ((self._y1[1] - self._y1[0]) / (x[1] - x[0]), (self._y1[-1] - self._y1[-2]) / (x[-1] - x[-2])),
            ((self._y2[1] - self._y2[0]) / (x[1] - x[0]), (self._y2[-1] - self._y2[-2]) / (x[-1] - x[-2])),
        )
        self.kk_misfit = None
        if check_kk:
            self.kk_misfit = kramers_kronig_misfit(self.omega, E1, E2)
            if self.kk_misfit > KK_TOLERANCE:
                warn_user(
                    f"the master curve's E_storage and E_loss disagree with one causal material (Kramers-Kronig): "
                    f"the best generalised Maxwell fit to both misses them by {100 * self.kk_misfit:.1f} % rms "
                    f"(tolerance {100 * KK_TOLERANCE:g} %); check the columns, their units and the shift"
                )

    @classmethod
    def from_csv(cls, path, **kwargs) -> MasterCurve:
        """Read a master curve from a CSV file with a header naming ``frequency, E_storage, E_loss``.

        Parameters
        ----------
        path : str or path-like
            The file (comma-separated, one header line; other columns are ignored).
        **kwargs
            Passed to :class:`MasterCurve` (``frequency_unit``, ``T_ref``, ``shift``, ``nu``, ...).
        """
        from persson_fp._csv import read_columns

        f, E1, E2 = read_columns(path, ("frequency", "E_storage", "E_loss"), "path")
        return cls(f, E1, E2, **kwargs)

    def __repr__(self):
        return (
            f"MasterCurve({self.frequency.size} points, f in [{self.frequency[0]:.3g}, {self.frequency[-1]:.3g}] "
            f"{self.frequency_unit}, extrapolation={self.extrapolation!r}, {self._conventions()})"
        )

    def _key(self):
        return (
            "MasterCurve",
            self.omega.tobytes(),
            self.E_storage.tobytes(),
            self.E_loss.tobytes(),
            self.extrapolation,
            *self._base_key(),
        )

    @property
    def frequency_range(self) -> tuple[float, float]:
        """(omega_min, omega_max) of the table, rad/s."""
        return float(self.omega[0]), float(self.omega[-1])

    def modulus_ref(self, omega, extrapolation: str | None = None) -> np.ndarray:
        """The interpolated modulus at the reference temperature (omega in rad/s), with the extrapolation policy."""
        policy = self.extrapolation if extrapolation is None else extrapolation
        w = np.asarray(omega, dtype=float)
        lo, hi = self._x[0], self._x[-1]
        if policy == "raise" and (np.any(w < self.omega[0] * (1 - 1e-12)) or np.any(w > self.omega[-1] * (1 + 1e-12))):
            raise ValueError(
                f"omega must lie in the master curve's range [{self.omega[0]:.6g}, {self.omega[-1]:.6g}] rad/s "
                "(extrapolation='raise')"
            )
        with np.errstate(divide="ignore"):
            x = np.log(w)
        xc = np.clip(x, lo, hi)
        y1, y2 = self._p1(xc), self._p2(xc)
        if policy == "loglinear":
            (s1l, s1h), (s2l, s2h) = self._slopes
            below, above = x < lo, x > hi
            y1 = np.where(below, self._y1[0] + s1l * (x - lo), np.where(above, self._y1[-1] + s1h * (x - hi), y1))
            y2 = np.where(below, self._y2[0] + s2l * (x - lo), np.where(above, self._y2[-1] + s2h * (x - hi), y2))
        with np.errstate(under="ignore", over="ignore"):
            return np.exp(y1) + 1j * np.exp(y2)

    def modulus_for_integrals(self, omega) -> np.ndarray:
        """The modulus as the friction integrals see it: the policy above the table, a clamp below it."""
        policy = "clamp" if self.extrapolation == "raise" else self.extrapolation
        w = np.asarray(omega, dtype=float)
        out = self.modulus_ref(w, policy)
        if policy == "loglinear":  # below the table cos(phi) -> 0 drives omega to 0: hold the low end there
            low = self.modulus_ref(np.full(1, self.omega[0]), "clamp")[0]
            out = np.where(w < self.omega[0], low, out)
        return out


def kramers_kronig_misfit(omega, E_storage, E_loss, per_decade: float = 10.0) -> float:
    r"""Relative rms misfit of the best causal (generalised Maxwell) model to a tabulated :math:`E'` and :math:`E''`.

    A causal linear material's storage and loss moduli are tied by the Kramers–Kronig relations; every such
    material with a relaxation spectrum is a limit of Prony series.  The check fits
    :math:`E_0 + \sum_i a_i\,(\omega\tau_i)^2/(1+(\omega\tau_i)^2)` and
    :math:`\sum_i a_i\,\omega\tau_i/(1+(\omega\tau_i)^2)`
    jointly to both columns, relative to the data, with :math:`a_i, E_0 \ge 0` (non-negative least squares) and
    ``per_decade`` relaxation times per decade over the table and one decade beyond each end.  A consistent table is
    matched to 0.1–0.5 %; :class:`MasterCurve` warns above :data:`KK_TOLERANCE`.

    Parameters
    ----------
    omega : array_like, rad/s
        Angular frequencies, increasing, > 0.
    E_storage, E_loss : array_like, pressure
        The table, > 0.
    per_decade : float
        Relaxation times per decade (default 10).

    Returns
    -------
    float
        The larger of the two columns' rms of (model - data) / data.
    """
    from scipy.optimize import nnls

    w = as_float_array(omega, "omega")
    E1, E2 = as_float_array(E_storage, "E_storage"), as_float_array(E_loss, "E_loss")
    if w.ndim != 1 or w.size < 3 or E1.shape != w.shape or E2.shape != w.shape:
        raise ValueError(
            f"omega, E_storage and E_loss must be 1-D of one length >= 3, got shapes {w.shape}, {E1.shape}, {E2.shape}"
        )
    if np.any(w <= 0) or np.any(np.diff(w) <= 0):
        raise ValueError("omega must be > 0 and strictly increasing (rad/s)")
    for name, col in (("E_storage", E1), ("E_loss", E2)):
        if np.any(col <= 0):
            raise ValueError(f"{name} must be > 0, got {float(np.min(col))!r}")
    per_decade = as_positive_scalar(per_decade, "per_decade")
    lo, hi = np.log10(1.0 / w[-1]) - 1.0, np.log10(1.0 / w[0]) + 1.0
    tau = np.logspace(lo, hi, max(int(np.ceil((hi - lo) * per_decade)) + 1, 2))
    x = w[:, None] * tau[None, :]
    A1 = np.hstack([np.ones((w.size, 1)), x * x / (1 + x * x)]) / E1[:, None]
    A2 = np.hstack([np.zeros((w.size, 1)), x / (1 + x * x)]) / E2[:, None]
    A = np.vstack([A1, A2])
    b = np.ones(2 * w.size)
    scale = np.max(np.abs(A), axis=0)
    scale[scale == 0] = 1.0
    coef, _ = nnls(A / scale, b, maxiter=50 * A.shape[1])
    r = (A / scale) @ coef - b
    n = w.size  # the worse of the two columns: a low-loss table hides a wrong E'' in a joint rms
    return float(max(np.sqrt(np.mean(r[:n] ** 2)), np.sqrt(np.mean(r[n:] ** 2))))
