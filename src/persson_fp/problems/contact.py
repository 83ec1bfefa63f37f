r"""The contact problem: spectrum, modulus, load(s) and fudge factor, validated.

:class:`ContactProblem` is what every solver and :func:`persson_fp.exact`
take.  It knows the diffusion coefficient of ``E:diffusion_equ`` /
``eq:new_B2`` through V(zeta) and dV/dzeta, the effective variance tau(zeta)
of the fudge-factor theory, and how large a pressure domain must be.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.problems import walls as _walls
from persson_fp.problems.loads import _check_loads, _warn_unit_slip
from persson_fp.surfaces.psd import PSD, SelfAffinePSD
from persson_fp.theory import fudge as _fudge
from persson_fp.theory.response import ElasticHalfSpace, ElasticResponse

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike

    from persson_fp.theory.fudge import FudgeFactor
    from persson_fp.theory.hardness import Hardness

__all__ = ["ContactProblem"]


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
        :class:`~persson_fp.theory.fudge.FudgeFactor` instance, or any callable
        ``S(A)`` that is finite and > 0 on [0, 1] (``eq:new_B2``).
    hardness : None, float, Hardness or callable, pressure
        Yield stress sigma_Y that caps the contact pressure (elastoplastic contact, Persson, Phys. Rev.
        Lett. 87 (2001) 116101): ``None`` (purely elastic), a number (constant hardness: the strip
        problem, exact in closed form, :mod:`persson_fp.theory.strip`), a :class:`~persson_fp.theory.hardness.PowerLaw`
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
        self.response = ElasticHalfSpace(self.E_star)  # the solid's answer to the roughness: V, dV/dzeta, energy
        self.V_kernels = self.response.kernels(self.psd)
        """The response's dV/dzeta and inverse of V bound to the spectrum, unchecked: the solvers' fast path."""
        pb = _check_loads(p_bar)
        self.scalar_load = pb.ndim == 0
        self.p_bar = np.atleast_1d(pb).astype(float)
        self.p_bar.setflags(write=False)
        self.fudge = _fudge.resolve(fudge)
        self.upper_wall = _walls.upper_wall(hardness)
        self.walls = (_walls.AbsorbingWall(), self.upper_wall)
        """The walls of the pressure domain, low to high (:mod:`persson_fp.problems.walls`)."""
        self.hardness = self.upper_wall.hardness
        self.upper_wall.check(self.psd.zeta_max, float(np.max(self.p_bar)))
        self._tau_map = None  # the fudge factor's effective-variance map (the upper wall's), on first use
        with np.errstate(over="ignore", under="ignore"):
            self._V_max = float(self.response.V(self.psd))
        if not (np.isfinite(self._V_max) and self._V_max > 0):  # V = E*^2 <|grad h|^2> / 4 out of range
            raise ValueError(
                f"E_star = {self.E_star!r} and the spectrum give V(zeta_max) = {self._V_max!r}, outside floating-point "
                "range (V = E_star^2 <|grad h|^2> / 4, eq:VV_relation); rescale the pressure or length unit"
            )
        self._tau_max = None  # (n_loads,), on first use
        self._p_max = None  # (k, p_max) of the last k asked, on first use
        _warn_unit_slip(self.p_bar, self.E_star, self._V_max)
        self._frozen = True

    # -- construction helpers ---------------------------------------------------
    @classmethod
    def reference(
        cls,
        fudge: str | FudgeFactor | Callable | None = None,
        p_bar_ratio: ArrayLike = 0.5,
        H: float = 0.8,
        zeta_max: float = 128.0,
        hardness: float | Hardness | Callable | None = None,
    ) -> ContactProblem:
        """The reference problem of the tests, benchmarks and notebooks.

        A self-affine spectrum (:meth:`~persson_fp.SelfAffinePSD.from_rms_slope`) with rms slope 0.1, Hurst
        exponent ``H``, q_l = 1, roll-off q_r = 2 and cut-off q_s = ``zeta_max`` (inverse length), E* = 1,
        and the load(s) p_bar = ``p_bar_ratio`` x sqrt(V(zeta_max)) (Xu et al. tutorial,
        Eq. 'eq:Vp_closed_form'): in the original theory the contact area at zeta_max is
        erf(``p_bar_ratio`` / sqrt(2)) (Eq. 'eq:Area_Persson').

        Parameters
        ----------
        fudge : None, str, FudgeFactor or callable, optional
            The fudge factor S(A) (Eq. 'eq:new_B2'), as in :class:`ContactProblem`; ``None``: Persson's
            original theory.
        p_bar_ratio : float or 1-D array, dimensionless
            Load(s) in units of sqrt(V(zeta_max)), each > 0; an array gives a batch of loads.
        H : float, dimensionless
            Hurst exponent in [0, 1].
        zeta_max : float, dimensionless
            Largest magnification q_s / q_l, >= 2 (the roll-off is at zeta = 2).
        hardness : None, float, Hardness or callable, pressure, optional
            Yield stress sigma_Y capping the contact pressure, as in :class:`ContactProblem`.

        Returns
        -------
        ContactProblem
            The problem, E* = 1 (so pressures are in units of E*, lengths in units of 1 / q_l).

        Raises
        ------
        ValueError
            ``p_bar_ratio`` not a number > 0 or a non-empty 1-D array of them, ``H`` or ``zeta_max`` out of
            range (from :class:`~persson_fp.SelfAffinePSD`), or a hardness below a load.
        """
        psd = SelfAffinePSD.from_rms_slope(0.1, H=H, q_l=1.0, q_r=2.0, q_s=zeta_max)
        ratio = as_float_array(p_bar_ratio, "p_bar_ratio")
        if ratio.ndim > 1 or ratio.size == 0 or np.any(ratio <= 0):
            raise ValueError(f"p_bar_ratio must be a number > 0 or a non-empty 1-D array of them, got {p_bar_ratio!r}")
        sqrt_V = np.sqrt(ElasticHalfSpace(1.0).V(psd))
        return cls(psd, E_star=1.0, p_bar=ratio * sqrt_V, fudge=fudge, hardness=hardness)

    def with_loads(self, p_bar: ArrayLike) -> ContactProblem:
        """The same surface, modulus, fudge factor and hardness with other load(s).

        Only the new loads are validated (and the hardness against them): the spectrum, modulus, fudge
        factor and V(zeta_max) were checked and computed when this problem was built and are reused.

        Parameters
        ----------
        p_bar : float or 1-D array, pressure
            Nominal pressure(s), each > 0 and <= 1e150; an array is a batch of loads.

        Returns
        -------
        ContactProblem
            A new (immutable) problem; this one is unchanged.

        Raises
        ------
        ValueError
            ``p_bar`` missing, not > 0, not finite, of more than one dimension or empty, or above a
            hardness sigma_Y at zeta = 1.
        """
        pb = _check_loads(p_bar)
        self.upper_wall.check(self.psd.zeta_max, float(np.max(pb)))
        state = dict(self.__dict__, scalar_load=pb.ndim == 0, _tau_map=None, _tau_max=None, _p_max=None)
        state["p_bar"] = np.atleast_1d(pb).astype(float)
        new = object.__new__(type(self))
        new.__setstate__(state)  # freezes p_bar
        return new

    def with_response(self, response) -> ContactProblem:
        """The same surface, loads, fudge factor and walls on another elastic response.

        Persson's diffusion equation needs the solid only through V(zeta) (Xu et al. tutorial,
        Eq. 'eq:Vp_closed_form'): a response with another V -- a coated or layered solid, or a viscoelastic solid in
        sliding contact, whose effective modulus depends on the frequency q v cos(phi) (Persson, J. Chem. Phys. 115
        (2001) 3840) -- gives another contact problem that every method solves unchanged.  The quantities that need
        the stored elastic energy (mean separation, gaps, leakage, adhesion) ask the response for it, and a response
        that has none refuses them with a ``ValueError``.

        Parameters
        ----------
        response : ElasticResponse
            The solid's response (:mod:`persson_fp.theory.response`).  Its ``E_star`` attribute, where it has one,
            becomes the problem's ``E_star`` (a reference modulus for messages and the unit check); otherwise the
            problem keeps its own.

        Returns
        -------
        ContactProblem
            A new (immutable) problem of the same class; this one is unchanged.

        Raises
        ------
        ValueError
            ``response`` not an :class:`~persson_fp.theory.response.ElasticResponse`, or V(zeta_max) not finite and
            > 0 with it.
        """
        if not isinstance(response, ElasticResponse):
            raise ValueError(f"response must be an ElasticResponse, got {type(response).__name__}")
        with np.errstate(over="ignore", under="ignore"):
            V_max = float(response.V(self.psd))
        if not (np.isfinite(V_max) and V_max > 0):
            raise ValueError(f"response {response!r} and the spectrum give V(zeta_max) = {V_max!r}, not finite and > 0")
        E = getattr(response, "E_star", self.E_star)
        state = dict(self.__dict__, response=response, V_kernels=response.kernels(self.psd), E_star=E, _V_max=V_max)
        state.update(_tau_map=None, _tau_max=None, _p_max=None)
        new = object.__new__(type(self))
        new.__setstate__(state)
        return new

    def elastic_counterpart(self) -> ContactProblem:
        """The purely elastic problem of the same surface, response, loads and fudge factor (no yield wall, Persson's
        coefficients): its effective variance tau(V) (Xu et al. tutorial, Eq. 'eq:new_B2') is the start of the
        moving-wall engine.

        Returns
        -------
        ContactProblem
            A new plain :class:`ContactProblem`.
        """
        plain = ContactProblem(self.psd, self.E_star, self.p_bar, self.fudge)
        return plain if self.response == plain.response else plain.with_response(self.response)

    def __repr__(self):
        loads = f"{self.p_bar[0]:.6g}" if self.scalar_load else f"<{self.p_bar.size} loads>"
        hard = self.upper_wall.repr_part()
        resp = "" if self.response == ElasticHalfSpace(self.E_star) else f", response={self.response!r}"
        return (
            f"ContactProblem({self.psd!r}, E_star={self.E_star:.6g}, p_bar={loads}, fudge={self.fudge.name!r}"
            f"{hard}{resp})"
        )

    # -- coefficients ---------------------------------------------------------------
    @property
    def zeta_max(self) -> float:
        """Largest magnification q_s / q_l."""
        return self.psd.zeta_max

    @property
    def n_loads(self) -> int:
        """Number of loads p_bar (1 for a scalar load): the length of every result's load axis."""
        return self.p_bar.size

    def V(self, zeta: ArrayLike | None = None) -> np.ndarray:
        """Complete-contact pressure variance V(zeta) (Xu et al. tutorial, Eq. 'eq:Vp_closed_form').

        V(zeta) = (pi / 2) E*^2 int_{q_l}^{zeta q_l} q^3 C(q) dq, the variance of the pressure if the
        surfaces were in full contact at magnification zeta (Eq. 'eq:VV_relation').

        Parameters
        ----------
        zeta : float or array_like, dimensionless, optional
            Magnification(s) in [1, zeta_max]; default ``zeta_max`` (the cached value).

        Returns
        -------
        ndarray, pressure^2
            V of the shape of ``zeta`` (0-d for a scalar or the default).

        Raises
        ------
        ValueError
            ``zeta`` not finite or outside [1, zeta_max].
        """
        if zeta is None:
            return np.array(self._V_max)
        return self.response.V(self.psd, zeta)

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

    def dV_dzeta(self, zeta: ArrayLike | None = None) -> np.ndarray:
        """Derivative dV/dzeta of the complete-contact variance (Xu et al. tutorial, Eq. 'eq:dVdxi').

        It is the diffusion coefficient B2 of Persson's original theory (Eq. 'eq:B2_xi_1'):
        dV/dzeta = (pi / 2) E*^2 q_l^4 zeta^3 C(zeta q_l).

        Parameters
        ----------
        zeta : float or array_like, dimensionless, optional
            Magnification(s) in [1, zeta_max]; default ``zeta_max``.

        Returns
        -------
        ndarray, pressure^2
            dV/dzeta of the shape of ``zeta``.

        Raises
        ------
        ValueError
            ``zeta`` not finite or outside [1, zeta_max].
        """
        return self.response.dV_dzeta(self.psd, zeta)

    def tau_of_V(self, V: ArrayLike) -> np.ndarray:
        """Effective variance tau at complete-contact variance(s) ``V``, for every load.

        With a fudge factor S(A) (Xu et al. tutorial, Eq. 'eq:new_B2') the diffusion runs on the clock
        tau = int S(A*) dV, and the closed forms of the original theory (Eq. 'eq:P0_solution',
        Eq. 'eq:Area_Persson') hold with V replaced by tau.  For the original theory tau = V; for Xu24 the
        closed form tau = g(A*) V; otherwise the cached ODE of :mod:`persson_fp.theory.effective` (with a constant
        hardness, the strip map of :mod:`persson_fp.theory.strip`).

        Parameters
        ----------
        V : float or array_like, pressure^2
            Complete-contact variance(s), each >= 0.

        Returns
        -------
        ndarray, pressure^2
            tau of shape ``V.shape + (n_loads,)``.

        Raises
        ------
        ValueError
            A negative or NaN ``V``; a fudge factor with a scale-dependent hardness (no closed-form map).
        """
        V = np.asarray(V, dtype=float)[..., None]
        return self.tau_of_V_each(np.broadcast_to(V, V.shape[:-1] + (self.n_loads,)))

    def tau_of_V_each(self, V: ArrayLike) -> np.ndarray:
        """Effective variance tau at one complete-contact variance per load.

        The map of :meth:`tau_of_V` (tau = int S(A*) dV, Xu et al. tutorial, Eq. 'eq:new_B2'), applied
        load by load: the last axis of ``V`` runs over the loads.

        Parameters
        ----------
        V : array_like, pressure^2
            Complete-contact variances of shape ``(..., n_loads)``, each >= 0.

        Returns
        -------
        ndarray, pressure^2
            tau of the shape of ``V``.

        Raises
        ------
        ValueError
            A negative or NaN ``V``; a fudge factor with a scale-dependent hardness (no closed-form map).
        """
        V = np.asarray(V, dtype=float)
        if not np.all(V >= 0.0):  # (NaN fails too)
            raise ValueError("V must be >= 0 (a complete-contact pressure variance), got a negative value or NaN")
        if isinstance(self.fudge, _fudge.NoFudge):
            return np.array(V)
        return self._effective().tau(V)

    def V_of_tau_each(self, tau: ArrayLike) -> np.ndarray:
        """The inverse of :meth:`tau_of_V_each`: the complete-contact variance at one effective variance per load.

        Xu24 in closed form, V = tau / g(A*) with A* = erf(p_bar / sqrt(2 tau)) (Xu et al. tutorial,
        Eq. 'eq:Area_Persson' at the effective variance); the ODE models through the inverse of the same
        table (:mod:`persson_fp.theory.effective`); the original theory V = tau.

        Parameters
        ----------
        tau : array_like, pressure^2
            Effective variances of shape ``(..., n_loads)``, each >= 0.

        Returns
        -------
        ndarray, pressure^2
            V of the shape of ``tau``.

        Raises
        ------
        ValueError
            A negative or NaN ``tau``; a fudge factor with a scale-dependent hardness (no closed-form map).
        """
        tau = np.asarray(tau, dtype=float)
        if not np.all(tau >= 0.0):  # (NaN fails too)
            raise ValueError("tau must be >= 0 (an effective pressure variance), got a negative value or NaN")
        if isinstance(self.fudge, _fudge.NoFudge):
            return np.array(tau)
        return self._effective().V_of_tau(tau)

    @property
    def general(self) -> bool:
        """True for general Fokker--Planck coefficients (:class:`~persson_fp.FokkerPlanckProblem`)."""
        return False

    @property
    def conserved_load(self):
        """The load every result must carry at every station: p_bar (pressure, (n_loads,); the load balance
        int p P0 dp + sigma_Y A_pl = p_bar, Xu et al. tutorial Eq. 'eq:Load_equilibrium'), or None where a drift
        B1 moves it (the solver's first-moment law is then the reference)."""
        return self.p_bar

    @property
    def features(self) -> frozenset:
        """What a method must support to solve this problem (matched against each method's ``SUPPORTS``):
        the walls' features ("hardness", "moving_wall") and "general" for general coefficients."""
        return frozenset(w.feature for w in self.walls) - {None}

    @property
    def has_closed_form(self) -> bool:
        """Whether :func:`persson_fp.exact` solves this problem (no moving wall, no general coefficients)."""
        return not (self.features & {"moving_wall", "general"})

    @property
    def moving_wall(self) -> bool:
        """True for a scale-dependent hardness (a yield wall that moves with zeta: no closed form)."""
        return self.upper_wall.moves

    def require_closed_form(self, remedy: str = "solve it numerically: pf.solve(problem, method='fv') (or 'mol')"):
        """Refuse unless :func:`persson_fp.exact` solves this problem.

        A moving yield wall or general coefficients leave no closed form; the walls
        (:mod:`persson_fp.problems.walls`) and the coefficients say so, each in its own words.

        Parameters
        ----------
        remedy : str
            What to do instead; ends the message.

        Returns
        -------
        None
            Where a closed form exists.

        Raises
        ------
        ValueError
            Naming what leaves no closed form (the scale-dependent hardness, or general coefficients B1, B2).
        """
        for wall in self.walls:
            wall.require_closed_form(remedy)

    def require_elastic(self, what: str, remedy: str = "") -> None:
        """Refuse unless a theory of purely elastic contact covers this problem (no yield wall, Persson's coefficients).

        Parameters
        ----------
        what : str
            The theory, for the message (e.g. ``"the gap physics"``).
        remedy : str
            What to do instead (e.g. ``"; use a ContactProblem"``); ends the message.

        Returns
        -------
        None
            Where the elastic theory covers the problem.

        Raises
        ------
        ValueError
            A hardness, or general coefficients, naming ``what`` and which one.
        """
        for wall in self.walls:
            wall.require_elastic(what, remedy)

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
        return self.upper_wall.sigma(z)

    def _effective(self):
        """The effective-variance map of the fudge factor (the upper wall's: the strip's with a hardness), built
        once per problem."""
        if self._tau_map is None:
            object.__setattr__(self, "_tau_map", self.upper_wall.tau_map(self))
        return self._tau_map

    def tau(self, zeta: ArrayLike | None = None) -> np.ndarray:
        """Effective variance tau(zeta) = int_1^zeta S(A*) dV (Xu et al. tutorial, Eq. 'eq:new_B2').

        Equal to V(zeta) (Eq. 'eq:Vp_closed_form') in the original theory; see :meth:`tau_of_V`.

        Parameters
        ----------
        zeta : float or array_like, dimensionless, optional
            Magnification(s) in [1, zeta_max]; default ``zeta_max`` (the cached value, a copy).

        Returns
        -------
        ndarray, pressure^2
            tau of shape ``zeta.shape + (n_loads,)``; ``(n_loads,)`` by default.

        Raises
        ------
        ValueError
            ``zeta`` not finite or outside [1, zeta_max].
        """
        if zeta is None:
            return self.tau_max.copy()
        return self.tau_of_V(self.V(zeta))

    def B2(self, zeta: ArrayLike, A: ArrayLike) -> np.ndarray:
        """Diffusion coefficient B2 = S(A*) dV/dzeta (Xu et al. tutorial, Eq. 'eq:new_B2').

        Without a fudge factor S = 1 and B2 = dV/dzeta (Eq. 'eq:B2_xi_1').

        Parameters
        ----------
        zeta : float or array_like, dimensionless
            Magnification(s) in [1, zeta_max].
        A : float or array_like, dimensionless
            The current contact area(s) A* in [0, 1] at which S is evaluated; broadcast against
            ``dV_dzeta(zeta)``.

        Returns
        -------
        ndarray, pressure^2
            B2, the broadcast shape of ``A`` and ``zeta``.

        Raises
        ------
        ValueError
            ``zeta`` not finite or outside [1, zeta_max].
        """
        return self.fudge.S(A) * self.dV_dzeta(zeta)

    def p_max(self, k: float = 10.0) -> float:
        """Far end of a pressure grid: max(p_bar + k sqrt(tau(zeta_max))); sigma_Y for a constant hardness.

        With k = 10 the image solution (Xu et al. tutorial, Eq. 'eq:P0_solution') there is below exp(-50)
        of its peak, so a grid cut there loses no mass to double precision.

        Parameters
        ----------
        k : float, dimensionless
            Width in standard deviations sqrt(tau(zeta_max)) beyond the largest load, > 0.

        Returns
        -------
        float, pressure
            The end of the domain (the yield stress sigma_Y with a constant hardness: the wall is the end).

        Raises
        ------
        ValueError
            ``k`` not a finite number > 0.
        """
        cache = self.__dict__.get("_p_max")
        if cache is not None and cache[0] == k and type(k) is float:  # the last k asked (solvers ask one k)
            return cache[1]
        k = as_positive_scalar(k, "k")
        value = self.upper_wall.p_max(self, k)
        object.__setattr__(self, "_p_max", (k, value))  # (a cache of an immutable value; with_loads drops it)
        return value
