r"""The contact problem: spectrum, modulus, load(s) and fudge factor, validated.

:class:`ContactProblem` is what every solver and :func:`persson_fp.exact`
take.  It knows the diffusion coefficient of ``E:diffusion_equ`` /
``eq:new_B2`` through V(zeta) and dV/dzeta, the effective variance tau(zeta)
of the fudge-factor theory, and how large a pressure domain must be.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf

from . import fudge as _fudge
from . import hardness as _hardness
from ._validate import as_float_array, as_positive_scalar
from .effective import effective_variance
from .spectrum import PSD, SelfAffinePSD
from .strip import StripEffectiveVariance

__all__ = ["ContactProblem"]


def _check_loads(p_bar) -> np.ndarray:
    """``p_bar`` as a float array of shape () or (n,), every load finite, > 0 and <= 1e150 (pressure)."""
    if p_bar is None:
        raise ValueError("p_bar (nominal pressure, > 0) is required")
    pb = as_float_array(p_bar, "p_bar")
    if pb.ndim > 1:
        raise ValueError(f"p_bar must be a scalar or a 1-D array, got shape {pb.shape}")
    if pb.size == 0:
        raise ValueError("p_bar must hold at least one load")
    if np.any(pb <= 0):
        raise ValueError(f"p_bar must be > 0 (every load), got {float(pb[pb <= 0].ravel()[0])!r}")
    if np.any(pb > 1e150):
        raise ValueError(
            f"p_bar must be <= 1e150 (p_bar^2 must be representable; rescale units), got {float(pb.max())!r}"
        )
    return pb


class ContactProblem:
    """Persson's diffusion problem for one surface, one modulus and one or many loads.

    Parameters
    ----------
    psd : PSD
        The surface spectrum (:class:`~persson_fp.SelfAffinePSD` or
        :class:`~persson_fp.TabulatedPSD`); fixes ``zeta_max = q_s / q_l``.
    E_star : float, pressure
        Plane-strain modulus E/(1 - nu^2), > 0.
    p_bar : float or 1-D array, pressure
        Nominal pressure(s), each > 0 and finite.  An array is solved as a
        batch by every method (results get a trailing load axis).
    fudge : None, str, FudgeFactor or callable
        ``None`` (Persson 2001), ``"YP08"``, ``"WM17"``, ``"Xu24"``, a
        :class:`~persson_fp.fudge.FudgeFactor` instance, or any callable
        ``S(A)`` that is finite and > 0 on [0, 1] (``eq:new_B2``).
    hardness : None, float, Hardness or callable, pressure
        Yield stress sigma_Y that caps the contact pressure (elastoplastic contact, Persson, Phys. Rev.
        Lett. 87 (2001) 116101): ``None`` (purely elastic), a number (constant hardness: the strip
        problem, exact in closed form, :mod:`persson_fp.strip`), a :class:`~persson_fp.hardness.PowerLaw`
        ``(sigma_1, n)`` or any callable ``sigma_Y(zeta)`` -- positive, non-decreasing in zeta and above
        every load at zeta = 1 (a scale-dependent hardness is a moving wall: no closed form, the PDE
        solvers ``"fv"`` and ``"mol"`` solve it).  With a fudge factor, S is evaluated at the total
        contact area A_el + A_pl.

    Raises
    ------
    ValueError
        Naming the parameter and its allowed range.

    Notes
    -----
    A problem is an immutable value (attributes refuse assignment, ``p_bar`` is read-only; use
    :meth:`with_loads` for other loads), so V(zeta_max), tau(zeta_max) and ``p_max`` are computed
    once and cached: every solver asks for them in its set-up.
    """

    def __setattr__(self, name, value):
        if self.__dict__.get("_frozen", False):
            raise AttributeError(f"ContactProblem is immutable (attribute {name!r}); use with_loads() or build anew")
        object.__setattr__(self, name, value)

    def __delattr__(self, name):
        raise AttributeError(f"ContactProblem is immutable (attribute {name!r})")

    def __setstate__(self, state):  # pickle / deepcopy: the copied arrays arrive writeable, freeze them again
        for key, value in state.items():
            object.__setattr__(self, key, value)
        for value in self.__dict__.values():
            if isinstance(value, np.ndarray):
                value.setflags(write=False)

    def __init__(self, psd: PSD, E_star: float = 1.0, p_bar=None, fudge=None, hardness=None):
        if not isinstance(psd, PSD):
            raise ValueError(f"psd must be a SelfAffinePSD or TabulatedPSD, got {type(psd).__name__}")
        self.psd = psd
        self.E_star = as_positive_scalar(E_star, "E_star")
        pb = _check_loads(p_bar)
        self.scalar_load = pb.ndim == 0
        self.p_bar = np.atleast_1d(pb).astype(float)
        self.p_bar.setflags(write=False)
        self.fudge = _fudge.resolve(fudge)
        self.hardness = _hardness.resolve(hardness)
        if self.hardness is not None:
            self.hardness.check(self.psd.zeta_max, float(np.max(self.p_bar)))
        self._strip_ev = None  # StripEffectiveVariance, on first use (constant hardness with a fudge factor)
        with np.errstate(over="ignore", under="ignore"):
            self._V_max = float(self.psd.V(None, self.E_star))
        if not (np.isfinite(self._V_max) and self._V_max > 0):  # V = E*^2 <|grad h|^2> / 4 out of range
            raise ValueError(
                f"E_star = {self.E_star!r} and the spectrum give V(zeta_max) = {self._V_max!r}, outside floating-point "
                "range (V = E_star^2 <|grad h|^2> / 4, eq:VV_relation); rescale the pressure or length unit"
            )
        self._tau_max = None  # (n_loads,), on first use
        self._frozen = True

    # -- construction helpers ---------------------------------------------------
    @classmethod
    def reference(cls, fudge=None, p_bar_ratio=0.5, H: float = 0.8, zeta_max: float = 128.0, hardness=None):
        """The reference problem of the tests and benchmarks: H = 0.8, q_l = 1, q_r = 2, q_s = ``zeta_max``,
        rms slope 0.1, E* = 1 and p_bar = ``p_bar_ratio`` * sqrt(V(zeta_max)); ``hardness`` as in the class."""
        psd = SelfAffinePSD.from_rms_slope(0.1, H=H, q_l=1.0, q_r=2.0, q_s=zeta_max)
        ratio = as_float_array(p_bar_ratio, "p_bar_ratio")
        if ratio.ndim > 1 or ratio.size == 0 or np.any(ratio <= 0):
            raise ValueError(f"p_bar_ratio must be a number > 0 or a non-empty 1-D array of them, got {p_bar_ratio!r}")
        return cls(psd, E_star=1.0, p_bar=ratio * np.sqrt(psd.V(E_star=1.0)), fudge=fudge, hardness=hardness)

    def with_loads(self, p_bar) -> ContactProblem:
        """The same surface and fudge factor with other load(s).

        Only the new loads are validated (and the hardness against them): the spectrum, modulus, fudge
        factor and V(zeta_max) were checked and computed when this problem was built and are reused.
        """
        pb = _check_loads(p_bar)
        if self.hardness is not None:
            self.hardness.check(self.psd.zeta_max, float(np.max(pb)))
        state = dict(self.__dict__, scalar_load=pb.ndim == 0, _strip_ev=None, _tau_max=None)
        state["p_bar"] = np.atleast_1d(pb).astype(float)
        new = object.__new__(type(self))
        new.__setstate__(state)  # freezes p_bar
        if self._strip_ev is not None and np.array_equal(new.p_bar, self.p_bar):  # same loads: reuse the tau map
            object.__setattr__(new, "_strip_ev", self._strip_ev)
        return new

    def __repr__(self):
        loads = f"{self.p_bar[0]:.6g}" if self.scalar_load else f"<{self.p_bar.size} loads>"
        hard = "" if self.hardness is None else f", hardness={self.hardness!r}"
        return f"ContactProblem({self.psd!r}, E_star={self.E_star:.6g}, p_bar={loads}, fudge={self.fudge.name!r}{hard})"

    # -- coefficients ---------------------------------------------------------------
    @property
    def zeta_max(self) -> float:
        """Largest magnification q_s / q_l."""
        return self.psd.zeta_max

    @property
    def n_loads(self) -> int:
        return self.p_bar.size

    def V(self, zeta=None) -> np.ndarray:
        """Complete-contact pressure variance V(zeta) (pressure^2), ``eq:Vp_closed_form``."""
        if zeta is None:
            return np.array(self._V_max)
        return self.psd.V(zeta, self.E_star)

    @property
    def V_max(self) -> float:
        """V(zeta_max) (pressure^2), cached."""
        return self._V_max

    @property
    def tau_max(self) -> np.ndarray:
        """tau(zeta_max) per load (pressure^2), shape (n_loads,), cached (a read-only array)."""
        if self._tau_max is None:
            t = np.asarray(self.tau_of_V(self._V_max), dtype=float).reshape(self.n_loads)
            t.setflags(write=False)
            object.__setattr__(self, "_tau_max", t)
        return self._tau_max

    def dV_dzeta(self, zeta=None) -> np.ndarray:
        """dV/dzeta (pressure^2), ``eq:dVdxi``; B2 of the original theory (``eq:B2_xi_1``)."""
        return self.psd.dV_dzeta(zeta, self.E_star)

    def tau_of_V(self, V) -> np.ndarray:
        """Effective variance tau (pressure^2) at complete-contact variance(s) ``V``, for every load.

        Returns shape ``V.shape + (n_loads,)``.  For the original theory tau = V;
        for Xu24 the closed form tau = g(A*) V; otherwise the cached ODE of
        :mod:`persson_fp.effective`.
        """
        V = np.asarray(V, dtype=float)[..., None]
        return self.tau_of_V_each(np.broadcast_to(V, V.shape[:-1] + (self.n_loads,)))

    def tau_of_V_each(self, V) -> np.ndarray:
        """tau (pressure^2) at one complete-contact variance per load: ``V`` has shape (..., n_loads), V >= 0."""
        V = np.asarray(V, dtype=float)
        if not np.all(V >= 0.0):  # (NaN fails too)
            raise ValueError("V must be >= 0 (a complete-contact pressure variance), got a negative value or NaN")
        if isinstance(self.fudge, _fudge.NoFudge):
            return np.array(V)
        if self.hardness is not None:
            return self._strip_effective().tau(V)
        if isinstance(self.fudge, _fudge.Xu24):
            A = self.fudge.area(self.p_bar, V)
            return self.fudge.g(A) * V
        return effective_variance(self.fudge).tau(self.p_bar, V)

    def V_of_tau_each(self, tau) -> np.ndarray:
        """The inverse of :meth:`tau_of_V_each`: V (pressure^2) at one effective variance per load,
        ``tau`` of shape (..., n_loads).  Xu24 in closed form, V = tau / g(A*) with A* = erf(p_bar / sqrt(2 tau));
        the ODE models through the inverse of the same table."""
        tau = np.asarray(tau, dtype=float)
        if not np.all(tau >= 0.0):  # (NaN fails too)
            raise ValueError("tau must be >= 0 (an effective pressure variance), got a negative value or NaN")
        if isinstance(self.fudge, _fudge.NoFudge):
            return np.array(tau)
        if self.hardness is not None:
            return self._strip_effective().V_of_tau(tau)
        if isinstance(self.fudge, _fudge.Xu24):
            with np.errstate(divide="ignore"):
                A = erf(np.divide(self.p_bar, np.sqrt(2.0 * tau), out=np.full(tau.shape, np.inf), where=tau > 0))
            return tau / self.fudge.g(A)
        return effective_variance(self.fudge).V_of_tau(self.p_bar, tau)

    @property
    def general(self) -> bool:
        """True for general Fokker--Planck coefficients (:class:`~persson_fp.FokkerPlanckProblem`)."""
        return False

    @property
    def has_closed_form(self) -> bool:
        """Whether :func:`persson_fp.exact` solves this problem (no moving wall, no general coefficients)."""
        return not (self.moving_wall or self.general)

    @property
    def moving_wall(self) -> bool:
        """True for a scale-dependent hardness (a yield wall that moves with zeta: no closed form)."""
        return self.hardness is not None and not self.hardness.is_constant

    def sigma_Y(self, zeta=None) -> np.ndarray:
        """Hardness sigma_Y at magnification(s) ``zeta``.

        Parameters
        ----------
        zeta : float or array, optional
            Magnification(s); default ``zeta_max``.

        Returns
        -------
        ndarray
            sigma_Y (pressure), the shape of ``zeta``; inf without a hardness.
        """
        z = self.zeta_max if zeta is None else zeta
        if self.hardness is None:
            return np.full(np.shape(z), np.inf)
        return self.hardness.sigma(z)

    def _strip_effective(self) -> StripEffectiveVariance:
        """The effective-variance map of a fudge factor with a hardness wall, solved once per problem."""
        if self.moving_wall:
            raise ValueError(
                "a scale-dependent hardness with a fudge factor has no closed-form effective variance: the "
                "area that S depends on comes from the numerical solution (pf.solve(problem, method='fv'))"
            )
        if self._strip_ev is None:
            ev = StripEffectiveVariance(self.fudge.S, self.p_bar, float(self.hardness.sigma(1.0)), self._V_max)
            object.__setattr__(self, "_strip_ev", ev)
        return self._strip_ev

    def tau(self, zeta=None) -> np.ndarray:
        """Effective variance tau(zeta) = int S dV (pressure^2), shape ``zeta.shape + (n_loads,)``."""
        if zeta is None:
            return self.tau_max.copy()
        return self.tau_of_V(self.V(zeta))

    def B2(self, zeta, A) -> np.ndarray:
        """Diffusion coefficient B2 = S(A*) dV/dzeta (``eq:new_B2``) for the current area(s) ``A``."""
        return self.fudge.S(A) * self.dV_dzeta(zeta)

    def p_max(self, k: float = 10.0) -> float:
        """Far end of a pressure grid: max(p_bar) + k sqrt(tau(zeta_max)) (pressure); sigma_Y for a constant hardness.

        With k = 10 the image solution there is below exp(-50) of its peak.
        """
        k = as_positive_scalar(k, "k")
        if self.hardness is not None and self.hardness.is_constant:
            return float(self.hardness.sigma(1.0))  # the strip: the yield wall is the domain's end
        return float(np.max(self.p_bar + k * np.sqrt(self.tau_max)))
