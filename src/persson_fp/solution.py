"""The result of :func:`persson_fp.solve` and its comparison with the exact solution.

A :class:`Solution` holds P0 at the output stations on the method's grid, the
derived integrals (contact area ``eq:Area``, load ``eq:Load_equilibrium``,
variance) and what the solver did (``info``: grid, steps, rhs calls, wall
time, options).  The invariants -- P0 >= 0, A* non-increasing, load = p_bar --
are checked once, here (:func:`check_invariants`), against tolerances tied to the
method's accuracy, and recorded in ``info["checks"]``; a breach raises
:class:`SolverError` (a warning with ``check=False``) and a non-finite field
raises :class:`InstabilityError` instead of being returned.  :meth:`Solution.compare` measures the error
actually made against :func:`persson_fp.exact`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .exact import exact
from .problem import ContactProblem

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

    from .exact import ExactSolution

__all__ = ["Solution", "Comparison", "SolverError", "InstabilityError", "check_invariants", "DEFAULT_TOLERANCES"]


def _station_axis(a):
    """Grid weights of shape (n_p,) or (n_zeta, n_p) as (n_zeta or 1, 1, n_p), to broadcast over loads."""
    a = np.asarray(a, dtype=float)
    return a[None, None, :] if a.ndim == 1 else a[:, None, :]


class SolverError(RuntimeError):
    """A solver could not produce a trustworthy result: it failed, or its result breaks an invariant
    (:func:`~persson_fp.solution.check_invariants`); the message names the invariant and the remedy."""


class InstabilityError(SolverError):
    """The discrete evolution went unstable (NaN, negative or growing mass, blow-up)."""


DEFAULT_TOLERANCES = {"load": 1e-2, "area": 1e-6, "negative": 1e-2}
"""Invariant tolerances of :func:`check_invariants` unless a method states its own
(:meth:`persson_fp.solvers.base.Solver.invariant_tolerances`):

- ``load``: relative load drift |int p P0 dp - p_bar| / p_bar (``eq:Load_equilibrium``), a float or an
  array broadcasting to ``(n_zeta, n_loads)``; 1 % by default: a coarse grid may miss it by less (its
  error is measured by :meth:`Solution.compare`), a result beyond it is not an answer;
- ``area``: A* may leave [0, 1] by this much, and grow between stations by this much relative to A*
  (contact is only lost, ``eq:Area``);
- ``negative``: min P0 >= -negative x max P0 at every station and load (smaller undershoots, e.g. the
  Gibbs ripple of a short sine series, are recorded and warned about only).
"""

_REMEDY = (
    "refine the method (n_p, n_steps, rtol/tol), keep k_domain at its default, use method='sines' "
    "or the closed form pf.exact, or pass check=False to inspect the result anyway"
)


def check_invariants(sol, tolerances=None, *, raise_on_breach=True) -> dict:
    """Check the invariants every solution of Persson's diffusion problem keeps.

    1. finite A* and load;
    2. A* in [0, 1] and non-increasing in zeta (``eq:Area``: contact is only lost);
    3. load balance int p P0 dp = p_bar (``eq:Load_equilibrium``; the absorbing wall at p = 0 keeps the
       first moment);
    4. P0 >= 0 up to the method's undershoot (fourth-order differences and truncated sine series are
       not positivity preserving).

    Parameters
    ----------
    sol : Solution
    tolerances : dict, optional
        Keys of ``DEFAULT_TOLERANCES`` (missing keys take the default).
    raise_on_breach : bool
        True: a breached invariant raises :class:`SolverError` naming it and the remedy; False: a
        ``RuntimeWarning`` with the same text (and ``info["warnings"]``).

    Returns
    -------
    dict
        ``min_P0``, ``negative_P0`` (any undershoot), ``area_increase`` (largest, relative to A*),
        ``area_monotone``, ``max_load_drift`` (relative), ``breaches`` (names of the broken invariants).
    """
    tol = {**DEFAULT_TOLERANCES, **(tolerances or {})}
    p_bar = sol.problem.p_bar
    A = sol.contact_area_all  # (a model with more contact states checks each area and their sum here)
    P = sol.P0_all
    load = sol.load_all  # the supported load; a model with a yield wall adds its plastic share here
    checks = {}
    breaches = []  # (invariant, message)
    where = _where(sol)

    if not (np.all(np.isfinite(A)) and np.all(np.isfinite(load))):
        breaches.append(("finite", "A* or the load is NaN or inf"))
        A = np.nan_to_num(A, nan=np.inf)

    # 2. A* in [0, 1], non-increasing (relative to A*, so that tiny loads are checked as closely)
    checks["area_range"] = (float(np.min(A)), float(np.max(A)))
    bad = (A < -tol["area"]) | (A > 1.0 + tol["area"])
    if np.any(bad):
        i, j = np.argwhere(bad)[0]
        breaches.append(("area_range", f"A* = {A[i, j]:.6g} outside [0, 1] at {where(i, j)}"))
    with np.errstate(invalid="ignore", divide="ignore"):
        rel_inc = np.diff(A, axis=0) / np.maximum(np.abs(A[:-1]), np.finfo(float).tiny)
    rel_inc = np.nan_to_num(rel_inc, nan=np.inf)
    checks["area_increase"] = float(max(np.max(rel_inc, initial=0.0), 0.0))
    checks["area_monotone"] = checks["area_increase"] <= tol["area"]
    if not checks["area_monotone"]:
        i, j = np.unravel_index(np.argmax(rel_inc), rel_inc.shape)
        breaches.append(
            (
                "area_monotone",
                f"A* grows by {rel_inc[i, j]:.3e} (relative, > {tol['area']:.1e}) up to {where(i + 1, j)} "
                "(contact can only be lost, eq:Area)",
            )
        )

    # 3. load balance
    with np.errstate(invalid="ignore", over="ignore"):
        drift = np.abs(load - p_bar) / p_bar
    drift = np.nan_to_num(drift, nan=np.inf)
    tol_load = np.broadcast_to(np.asarray(tol["load"], dtype=float), drift.shape)
    checks["max_load_drift"] = float(np.max(drift))
    # general coefficients: a drift B1 moves the load, so the balance is no law of the equation there
    over = (drift > tol_load) & (not getattr(sol.problem, "general", False))
    if np.any(over):
        i, j = np.unravel_index(np.argmax(np.where(over, drift / tol_load, -np.inf)), drift.shape)
        breaches.append(
            (
                "load_balance",
                f"int p P0 dp deviates from p_bar by {drift[i, j]:.3e} (relative, > {tol_load[i, j]:.1e}) at "
                f"{where(i, j)} (eq:Load_equilibrium)",
            )
        )

    # 4. P0 >= 0 (small undershoots are reported, large ones are breaches)
    peak = np.max(np.abs(P), axis=-1) if P.shape[-1] else np.zeros(A.shape)
    low = np.min(P, axis=-1) if P.shape[-1] else np.zeros(A.shape)
    checks["min_P0"] = float(np.min(low)) if low.size else 0.0
    checks["negative_P0"] = bool(np.any(low < -1e-10 * np.max(peak, initial=0.0)))
    with np.errstate(invalid="ignore", divide="ignore"):
        rel_neg = np.where(peak > 0, -low / np.where(peak > 0, peak, 1.0), 0.0)
    if np.any(rel_neg > tol["negative"]):
        i, j = np.unravel_index(np.argmax(rel_neg), rel_neg.shape)
        breaches.append(
            (
                "positivity",
                f"P0 dips to {low[i, j]:.3e} = -{rel_neg[i, j]:.2e} x its peak (> {tol['negative']:.1e}) at "
                f"{where(i, j)} (oscillations: refine, or use an L-stable scheme)",
            )
        )
    elif checks["negative_P0"]:
        msg = f"P0 has negative values down to {checks['min_P0']:.3e} (oscillations: refine or use an L-stable scheme)"
        sol.info.setdefault("warnings", []).append(msg)
        warnings.warn(f"{sol.method}: {msg}", RuntimeWarning, stacklevel=6)

    checks["breaches"] = [name for name, _ in breaches]
    if breaches:
        text = f"{sol.method}: invariant(s) broken: " + "; ".join(f"{n}: {m}" for n, m in breaches) + f". {_REMEDY}"
        if raise_on_breach:
            raise SolverError(text)
        sol.info.setdefault("warnings", []).append(text)
        warnings.warn(text, RuntimeWarning, stacklevel=6)
    return checks


def _where(sol):
    """A formatter of (station, load) indices for messages."""

    def fmt(i, j):
        s = f"zeta = {sol.zeta[i]:.6g}"
        if sol.problem.n_loads > 1 or not sol.problem.scalar_load:
            s += f", p_bar = {sol.problem.p_bar[j]:.6g}"
        return s

    return fmt


@dataclass(frozen=True)
class Comparison:
    """Errors of a :class:`Solution` against the exact solution, per station and load.

    Made by :meth:`Solution.compare` against :func:`persson_fp.exact` (Xu et al. tutorial,
    Eq. 'eq:P0_solution' and Eq. 'eq:Area_Persson').  Arrays have shape ``(n_zeta, n_loads)``.

    Attributes
    ----------
    zeta : ndarray, dimensionless
        The output stations, shape ``(n_zeta,)``.
    p_bar : ndarray, pressure
        The loads, shape ``(n_loads,)``.
    L1 : ndarray, dimensionless
        ``int |P0 - P0_exact| dp`` on the solution's grid.
    Linf : ndarray, 1/pressure
        ``max |P0 - P0_exact|`` over the grid.
    area_error : ndarray, dimensionless
        ``|A*_num - A*_exact|`` (Eq. 'eq:Area').
    load_drift : ndarray, dimensionless
        ``|int p P0 dp - p_bar| / p_bar`` (Eq. 'eq:Load_equilibrium').
    mass_balance : ndarray, dimensionless
        ``|A*(integral) - A*(boundary flux)|`` where the method tracks the flux, else NaN.
    reference : str
        "cell averages" or "point values": what the numerical P0 was compared with.
    stderr_area : ndarray or None, dimensionless
        Standard error of A* (stochastic methods), else None.
    elastic_area_error, plastic_area_error, noncontact_area_error : ndarray or None, dimensionless
        ``|A_el - exact|``, ``|A_pl - exact|``, ``|A_non - exact|`` with a hardness wall; else None.
    area_error_rel : ndarray or None, dimensionless
        ``|A*_num - A*_exact| / A*_exact`` (shows the failures at tiny loads, where A* ~ p_bar).
    stderr_load : ndarray or None, pressure
        Standard error of the load estimate (stochastic methods), else None.
    """

    zeta: np.ndarray
    p_bar: np.ndarray
    L1: np.ndarray
    Linf: np.ndarray
    area_error: np.ndarray
    load_drift: np.ndarray
    mass_balance: np.ndarray
    reference: str
    stderr_area: np.ndarray | None = None
    elastic_area_error: np.ndarray | None = None
    plastic_area_error: np.ndarray | None = None
    noncontact_area_error: np.ndarray | None = None
    area_error_rel: np.ndarray | None = None
    stderr_load: np.ndarray | None = None

    @property
    def max_L1(self) -> float:
        """Largest L1 error of P0 over stations and loads (dimensionless)."""
        return float(np.max(self.L1))

    @property
    def max_area_error(self) -> float:
        """Largest ``|A*_num - A*_exact|`` over stations and loads (dimensionless)."""
        return float(np.max(self.area_error))

    @property
    def max_area_error_rel(self) -> float:
        """Largest ``|dA*| / A*_exact`` over stations and loads."""
        return float(np.max(self.area_error_rel))

    @property
    def area_z_score(self) -> np.ndarray | None:
        """``|A*_num - A*_exact|`` in units of the standard error of A* (stochastic methods), else None.

        Shape ``(n_zeta, n_loads)``; inf where the standard error is 0 and the error is not.
        """
        if self.stderr_area is None:
            return None
        se = np.asarray(self.stderr_area, dtype=float).reshape(self.area_error.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.area_error == 0, 0.0, self.area_error / se)

    def final(self) -> dict[str, float]:
        """Worst case over loads at the last station, as plain floats.

        Returns
        -------
        dict of str to float
            ``"L1"`` (dimensionless), ``"Linf"`` (1/pressure), ``"area_error"``, ``"area_error_rel"`` and
            ``"load_drift"`` (dimensionless); with a hardness wall also ``"elastic_area_error"``,
            ``"plastic_area_error"`` and ``"noncontact_area_error"``.
        """
        out = {
            "L1": float(np.max(self.L1[-1])),
            "Linf": float(np.max(self.Linf[-1])),
            "area_error": float(np.max(self.area_error[-1])),
            "area_error_rel": float(np.max(self.area_error_rel[-1])),
            "load_drift": float(np.max(self.load_drift[-1])),
        }
        if self.plastic_area_error is not None:
            out["elastic_area_error"] = float(np.max(self.elastic_area_error[-1]))
            out["plastic_area_error"] = float(np.max(self.plastic_area_error[-1]))
            out["noncontact_area_error"] = float(np.max(self.noncontact_area_error[-1]))
        return out

    def __str__(self):
        rows = [f"{'zeta':>10} {'L1':>10} {'Linf':>10} {'|dA*|':>10} {'|dA*|/A*':>10} {'load drift':>10}"]
        for i, z in enumerate(self.zeta):
            rows.append(
                f"{z:10.4g} {np.max(self.L1[i]):10.3e} {np.max(self.Linf[i]):10.3e} "
                f"{np.max(self.area_error[i]):10.3e} {np.max(self.area_error_rel[i]):10.3e} "
                f"{np.max(self.load_drift[i]):10.3e}"
            )
        tail = f"\n(worst over {self.p_bar.size} load(s); reference: {self.reference})"
        if self.plastic_area_error is not None:
            tail += (
                f"\nelastoplastic: max |dA_el| {np.max(self.elastic_area_error):.3e}, "
                f"|dA_pl| {np.max(self.plastic_area_error):.3e}, |dA_non| {np.max(self.noncontact_area_error):.3e}"
            )
        z = self.area_z_score
        if z is not None:
            tail += f"\n|dA*| in standard errors (stochastic method): max {np.max(z):.2f}"
        return "\n".join(rows) + tail


@dataclass(frozen=True)
class Solution:
    """What a solver returns: P0 at the output stations, the derived integrals and what the solver did.

    Built by :meth:`build` (which checks the invariants, :func:`~persson_fp.solution.check_invariants`) from
    :func:`persson_fp.solve`; a frozen dataclass.  The ``*_all`` arrays keep the load axis, their
    counterparts without the suffix drop it for a scalar load.

    Attributes
    ----------
    method : str
        Name of the method that produced it.
    problem : ContactProblem
        The problem solved.
    zeta : ndarray, dimensionless
        Output stations, shape ``(n_zeta,)``.
    p : ndarray, pressure
        Grid, shape ``(n_p,)``: cell centres ("cell") or nodes ("point"); shape ``(n_zeta, n_p)`` for a
        moving yield wall (the grid stretches with sigma_Y(zeta)).
    P0_all : ndarray, 1/pressure
        P0, shape ``(n_zeta, n_loads, n_p)`` (Xu et al. tutorial, Eq. 'eq:P0_solution' for its exact value).
    weights : ndarray, pressure
        Quadrature weights of the grid, ``int f dp ~ weights @ f``; the shape of ``p``.
    kind : str
        "cell" (P0 are cell averages) or "point" (P0 are point values).
    contact_area_all : ndarray, dimensionless
        A* = int P0 dp (Eq. 'eq:Area'; + A_pl with a hardness wall), shape ``(n_zeta, n_loads)``.
    wall_time : float, seconds
        Time spent in the solver alone (its stepping; validation, building this Solution, its checks and
        compile time excluded): time the ``pf.solve`` call for the end-to-end cost.
    info : dict
        Grid, steps, rhs calls, options, checks, warnings.
    contact_area_flux_all : ndarray or None, dimensionless
        A* from 1 minus the flux absorbed at p = 0 (finite volumes), or None.
    stderr_area_all : ndarray or None, dimensionless
        Standard error of A* (stochastic methods), or None.
    plastic_area_all : ndarray or None, dimensionless
        A_pl, the mass absorbed at the yield wall, shape ``(n_zeta, n_loads)``, or None without a hardness.
    sigma_Y : ndarray or None, pressure
        The hardness at the stations, shape ``(n_zeta,)``, or None.
    load_estimate_all : ndarray or None, pressure
        The method's own estimate of int p P0 dp (Monte Carlo: the walkers' mean), or None.
    stderr_load_all : ndarray or None, pressure
        Standard error of ``load_estimate_all``, or None.
    """

    method: str
    problem: ContactProblem
    zeta: np.ndarray
    p: np.ndarray
    P0_all: np.ndarray
    weights: np.ndarray
    kind: str
    contact_area_all: np.ndarray
    wall_time: float
    info: dict = field(default_factory=dict)
    contact_area_flux_all: np.ndarray | None = None
    stderr_area_all: np.ndarray | None = None
    plastic_area_all: np.ndarray | None = None
    sigma_Y: np.ndarray | None = None
    load_estimate_all: np.ndarray | None = None
    stderr_load_all: np.ndarray | None = None

    # -- construction -------------------------------------------------------------------
    @classmethod
    def build(
        cls,
        method: str,
        problem: ContactProblem,
        zeta: ArrayLike,
        p: ArrayLike,
        P0: ArrayLike,
        weights: ArrayLike,
        kind: str,
        wall_time: float,
        info: dict | None = None,
        contact_area: ArrayLike | None = None,
        contact_area_flux: ArrayLike | None = None,
        stderr_area: ArrayLike | None = None,
        check: bool = True,
        plastic_area: ArrayLike | None = None,
        tolerances: dict | None = None,
        load: ArrayLike | None = None,
        stderr_load: ArrayLike | None = None,
    ) -> Solution:
        """Assemble a Solution, computing the integrals and checking the invariants.

        ``contact_area`` is the method's int P0 dp (the elastic area); with a hardness wall the method
        also hands over ``plastic_area`` (A_pl, the mass absorbed at sigma_Y) and the Solution's
        ``contact_area`` is their sum.  The invariants (A* in [0, 1] and non-increasing, Xu et al. tutorial,
        Eq. 'eq:Area'; load balance, Eq. 'eq:Load_equilibrium'; P0 >= 0) are checked once, here.

        Parameters
        ----------
        method : str
            Name of the method (quoted in messages).
        problem : ContactProblem
            The problem solved.
        zeta : float or 1-D array, dimensionless
            Output stations, shape ``(n_zeta,)``.
        p : array_like, pressure
            Grid, shape ``(n_p,)``, or ``(n_zeta, n_p)`` for a moving yield wall.
        P0 : array_like, 1/pressure
            P0 at the stations, reshapeable to ``(n_zeta, n_loads, n_p)``.
        weights : array_like, pressure
            Quadrature weights of the grid, the shape of ``p``.
        kind : str
            "cell" (P0 are cell averages) or "point" (point values).
        wall_time : float, seconds
            Time spent stepping.
        info : dict, optional
            Grid, steps, rhs calls, options (copied).
        contact_area : array_like, dimensionless, optional
            The method's int P0 dp, shape ``(n_zeta, n_loads)``; default the grid quadrature of ``P0``.
        contact_area_flux : array_like, dimensionless, optional
            A* from the flux absorbed at p = 0 (finite volumes).
        stderr_area : array_like, dimensionless, optional
            Standard error of A* (stochastic methods).
        check : bool
            True: a breached invariant raises :class:`SolverError`; False: it only warns.
        plastic_area : array_like, dimensionless, optional
            A_pl, the mass absorbed at sigma_Y (with a hardness wall; default 0).
        tolerances : dict, optional
            Invariant tolerances, keys of ``DEFAULT_TOLERANCES`` (:func:`~persson_fp.solution.check_invariants`).
        load : array_like, pressure, optional
            The method's own estimate of int p P0 dp where the grid quadrature is not the best one
            (Monte Carlo: the mean over the walkers instead of the histogram).
        stderr_load : array_like, pressure, optional
            Standard error of ``load``.

        Returns
        -------
        Solution
            With ``info["checks"]`` holding the result of :func:`~persson_fp.solution.check_invariants`.

        Raises
        ------
        InstabilityError
            P0 holds NaN or inf values (the scheme went unstable).
        SolverError
            With ``check=True``, a breached invariant, named with its remedy.
        """
        zeta = np.atleast_1d(np.asarray(zeta, dtype=float))
        P0 = np.asarray(P0, dtype=float).reshape(zeta.size, problem.n_loads, -1)
        if not np.all(np.isfinite(P0)):
            raise InstabilityError(
                f"{method}: the solution holds NaN or inf values -- the scheme went unstable; "
                "reduce the step (n_steps) or use an implicit scheme"
            )
        weights = np.asarray(weights, dtype=float)
        if contact_area is None:
            contact_area = np.sum(P0 * _station_axis(weights), axis=-1)
        contact_area = np.asarray(contact_area, dtype=float).reshape(zeta.size, problem.n_loads)
        sigma_Y = None
        if problem.hardness is not None:
            sigma_Y = np.atleast_1d(problem.hardness.sigma(zeta)).astype(float)
            if plastic_area is None:
                plastic_area = np.zeros_like(contact_area)
            plastic_area = np.asarray(plastic_area, dtype=float).reshape(zeta.size, problem.n_loads)
            contact_area = contact_area + plastic_area
        info = dict(info or {})
        sol = cls(
            method=method,
            problem=problem,
            zeta=zeta,
            p=np.asarray(p, dtype=float),
            P0_all=P0,
            weights=weights,
            kind=kind,
            contact_area_all=contact_area,
            wall_time=float(wall_time),
            info=info,
            contact_area_flux_all=None
            if contact_area_flux is None
            else np.asarray(contact_area_flux, float).reshape(zeta.size, problem.n_loads),
            stderr_area_all=None if stderr_area is None else np.asarray(stderr_area, float).reshape(zeta.size, -1),
            plastic_area_all=plastic_area,
            sigma_Y=sigma_Y,
            load_estimate_all=None if load is None else np.asarray(load, float).reshape(zeta.size, problem.n_loads),
            stderr_load_all=None if stderr_load is None else np.asarray(stderr_load, float).reshape(zeta.size, -1),
        )
        sol._check(tolerances, raise_on_breach=bool(check))
        return sol

    def _check(self, tolerances=None, raise_on_breach=True):
        """Check the invariants (:func:`check_invariants`); record them in ``info["checks"]``."""
        checks = check_invariants(self, tolerances, raise_on_breach=raise_on_breach)
        self.info["checks"] = checks

    # -- public views (load axis dropped for a scalar load) -------------------------------
    def _squeeze(self, a):
        return a[:, 0] if self.problem.scalar_load else a

    @property
    def P0(self) -> np.ndarray:
        """P0 (1/pressure), ``(n_zeta, n_p)`` for a scalar load else ``(n_zeta, n_loads, n_p)``."""
        return self._squeeze(self.P0_all)

    @property
    def contact_area(self) -> np.ndarray:
        """A* = int P0 dp at each station (``eq:Area``)."""
        return self._squeeze(self.contact_area_all)

    @property
    def contact_area_flux(self):
        """A* from 1 minus the flux absorbed at p = 0 (finite volume only), else None."""
        return None if self.contact_area_flux_all is None else self._squeeze(self.contact_area_flux_all)

    def _moment(self, k: int) -> np.ndarray:
        """int p^k P0 dp on the grid, shape (n_zeta, n_loads)."""
        w = _station_axis(self.weights * self.p**k)
        return np.sum(self.P0_all * w, axis=-1)

    @property
    def elastic_area_all(self) -> np.ndarray:
        """A_el = int P0 dp, shape (n_zeta, n_loads) (= contact_area_all without a hardness)."""
        if self.plastic_area_all is None:
            return self.contact_area_all
        return self.contact_area_all - self.plastic_area_all

    @property
    def elastic_area(self) -> np.ndarray:
        """A_el = int_0^sigma_Y P0 dp: the elastically loaded fraction of the nominal area."""
        return self._squeeze(self.elastic_area_all)

    @property
    def plastic_area(self) -> np.ndarray:
        """A_pl: the fraction in plastic contact (absorbed at the yield wall); 0 without a hardness."""
        pa = np.zeros_like(self.contact_area_all) if self.plastic_area_all is None else self.plastic_area_all
        return self._squeeze(pa)

    @property
    def noncontact_area(self) -> np.ndarray:
        """A_non = 1 - A_el - A_pl: the fraction out of contact (the atom at p = 0)."""
        return self._squeeze(1.0 - self.contact_area_all)

    @property
    def elastic_load_all(self) -> np.ndarray:
        """F_el = int p P0 dp (pressure), shape (n_zeta, n_loads)."""
        return self._moment(1)

    @property
    def elastic_load(self) -> np.ndarray:
        """F_el = int p P0 dp (pressure)."""
        return self._squeeze(self.elastic_load_all)

    @property
    def plastic_load(self) -> np.ndarray:
        """F_pl = sigma_Y A_pl (pressure); 0 without a hardness."""
        if self.plastic_area_all is None:
            return self._squeeze(np.zeros_like(self.contact_area_all))
        return self._squeeze(self.sigma_Y[:, None] * self.plastic_area_all)

    @property
    def load_all(self) -> np.ndarray:
        """F_el + F_pl, shape ``(n_zeta, n_loads)``: int p P0 dp (the method's own estimate where it gives one,
        e.g. the walkers' mean pressure for Monte Carlo, else the grid quadrature), plus sigma_Y A_pl."""
        load = self.load_estimate_all if self.load_estimate_all is not None else self._moment(1)
        if self.plastic_area_all is not None:
            load = load + self.sigma_Y[:, None] * self.plastic_area_all
        return load

    @property
    def load(self) -> np.ndarray:
        """F_el + F_pl at each station (pressure); equals p_bar exactly in theory (``eq:Load_equilibrium``)."""
        return self._squeeze(self.load_all)

    @property
    def variance(self) -> np.ndarray:
        """Var(p) = <p^2> - p_bar^2 (pressure^2), atoms at 0 and (with a hardness) at sigma_Y included."""
        m2 = self._moment(2)
        if self.plastic_area_all is not None:
            m2 = m2 + self.sigma_Y[:, None] ** 2 * self.plastic_area_all
        return self._squeeze(m2 - self.problem.p_bar**2)

    @property
    def steps(self) -> int | None:
        """Number of steps the solver took (``info["steps"]``), or None where it does not count them."""
        return self.info.get("steps")

    # -- comparison ------------------------------------------------------------------------
    def _exact_zeta(self):
        """The stations for :func:`persson_fp.exact`: None for the lone default station zeta_max (its V and tau
        are cached on the problem: the fast path), else the stations."""
        if self.zeta.size == 1 and self.zeta[0] == self.problem.zeta_max:
            return None
        return self.zeta

    def exact_on_grid(self, ex: ExactSolution | None = None) -> np.ndarray:
        """The exact P0 on this solution's grid in the same sense (cell averages or point values).

        Cell averages are differences of :meth:`~persson_fp.ExactSolution.cdf_contact`, point values
        :meth:`~persson_fp.ExactSolution.pdf` (Xu et al. tutorial, Eq. 'eq:P0_solution').

        Parameters
        ----------
        ex : ExactSolution, optional
            The exact solution at this solution's stations; default ``pf.exact(problem, zeta)``.

        Returns
        -------
        ndarray, 1/pressure
            Shape ``(n_zeta, n_loads, n_p)``.

        Raises
        ------
        ValueError
            The problem has no closed form (a scale-dependent hardness or general coefficients), or a
            station at zeta = 1 (P0 a delta function there).
        """
        if ex is None:
            ex = exact(self.problem, self._exact_zeta())
        if self.kind == "cell":
            edges = self.info.get("edges")
            if edges is None:
                dp = self.weights
                edges = np.concatenate(([self.p[0] - 0.5 * dp[0]], self.p + 0.5 * dp))
            F = ex.cdf_contact(np.asarray(edges))
            out = np.diff(F, axis=-1) / np.diff(edges)
        else:
            out = ex.pdf(self.p)
        return np.asarray(out).reshape(self.zeta.size, self.problem.n_loads, -1)

    def compare(self) -> Comparison:
        """Errors against :func:`persson_fp.exact` at every station (see :class:`Comparison`).

        The L1 and max errors of P0 (Xu et al. tutorial, Eq. 'eq:P0_solution'), the area error
        (Eq. 'eq:Area_Persson') and the load drift (Eq. 'eq:Load_equilibrium').

        Returns
        -------
        Comparison
            Arrays of shape ``(n_zeta, n_loads)``.

        Raises
        ------
        ValueError
            The problem has no closed form (a scale-dependent hardness or general coefficients); the
            message points to ``info["error_estimate"]``, the solver's own estimate.
        """
        if not self.problem.has_closed_form:
            raise ValueError(
                "compare(): this problem (a scale-dependent hardness or general coefficients) has no exact "
                "solution to compare with; the solver's own "
                "error estimate is in info['error_estimate'] (and the conservation residuals in info['checks'])"
            )
        ex = exact(self.problem, self._exact_zeta())
        shape = (self.zeta.size, self.problem.n_loads)
        A_ex = np.asarray(ex.contact_area).reshape(shape)
        diff = self.P0_all - self.exact_on_grid(ex)
        L1 = np.abs(diff) @ self.weights
        Linf = np.max(np.abs(diff), axis=-1)
        dA = np.abs(self.contact_area_all - A_ex)
        with np.errstate(divide="ignore", invalid="ignore"):
            dA_rel = np.where(dA == 0, 0.0, dA / A_ex)
        drift = np.abs(self.load_all - self.problem.p_bar) / self.problem.p_bar
        if self.contact_area_flux_all is not None:
            mb = np.abs(self.contact_area_all - self.contact_area_flux_all)
        else:
            mb = np.full_like(dA, np.nan)
        hard = {}
        if self.plastic_area_all is not None:
            hard = {
                "elastic_area_error": np.abs(self.elastic_area_all - np.asarray(ex.elastic_area).reshape(shape)),
                "plastic_area_error": np.abs(self.plastic_area_all - np.asarray(ex.plastic_area).reshape(shape)),
                "noncontact_area_error": np.abs(
                    (1.0 - self.contact_area_all) - np.asarray(ex.noncontact_area).reshape(shape)
                ),
            }
        return Comparison(
            zeta=self.zeta,
            p_bar=self.problem.p_bar,
            L1=L1,
            Linf=Linf,
            area_error=dA,
            load_drift=drift,
            mass_balance=mb,
            reference="cell averages" if self.kind == "cell" else "point values",
            stderr_area=self.stderr_area_all,
            **hard,
            area_error_rel=dA_rel,
            stderr_load=self.stderr_load_all,
        )

    @property
    def error_estimate(self) -> dict:
        """The error of this result at every station and load, whatever the problem.

        Keys ``"L1"`` (``int |P0 - P0_ref| dp``) and ``"contact_area"`` (and, with a hardness, ``"elastic_area"``,
        ``"plastic_area"``, ``"noncontact_area"``), arrays of shape (n_zeta, n_loads), and ``"kind"``: where a closed
        form exists the *true* error against :func:`persson_fp.exact`; otherwise (a moving yield wall, general
        coefficients) the solver's own estimate, ``|result - result at half the resolution|`` (conservative: 3x the
        error of a second-order method in its asymptotic range); for Monte Carlo the standard error of A* is
        added as ``"stderr_area"``.  Computed once and kept in ``info["error_estimate_view"]``.
        """
        cached = self.info.get("error_estimate_view")
        if cached is not None:
            return cached
        est = self.info.get("error_estimate")
        if est is not None:
            out = {
                "kind": "estimate: |result - half-resolution result| (conservative)",
                "L1": est["L1"],
                "contact_area": est["noncontact_area"],  # A_el + A_pl = 1 - A_non: the same difference
            }
            if self.plastic_area_all is not None:
                out.update({q: est[q] for q in ("elastic_area", "plastic_area", "noncontact_area")})
        else:
            c = self.compare()
            out = {"kind": "true error against pf.exact", "L1": c.L1, "contact_area": c.area_error}
            if c.plastic_area_error is not None:
                out.update(
                    elastic_area=c.elastic_area_error,
                    plastic_area=c.plastic_area_error,
                    noncontact_area=c.noncontact_area_error,
                )
        if self.stderr_area_all is not None:
            out["stderr_area"] = self.stderr_area_all
        self.info["error_estimate_view"] = out
        return out

    def summary(self) -> str:
        """One line: method, grid, steps, wall time and the error made at the last station.

        Returns
        -------
        str
            The method, ``n_p``, steps, wall time (ms), L1 error, ``|dA*|`` (absolute and relative) and load
            drift from :meth:`compare`.

        Raises
        ------
        ValueError
            The problem has no closed form to compare with (see :meth:`compare`).
        """
        c = self.compare().final()
        return (
            f"{self.method}: n_p={self.p.size}, steps={self.info.get('steps')}, wall={self.wall_time * 1e3:.2f} ms, "
            f"L1={c['L1']:.3e}, |dA*|={c['area_error']:.3e} ({c['area_error_rel']:.2e} relative), "
            f"load drift={c['load_drift']:.3e}"
        )

    def plot(self, ax: Axes | None = None, **kwargs: Any) -> Figure:
        """P0 against the exact solution at every station (needs matplotlib).

        Draws :func:`persson_fp.plotting.plot_solution` (its first load), in units of sqrt(V(zeta_max)).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; default a new figure.
        **kwargs
            Passed to :func:`~persson_fp.plotting.plot_solution` (``stations``).

        Returns
        -------
        matplotlib.figure.Figure
            The figure drawn on.
        """
        from . import plotting

        return plotting.plot_solution(self, ax=ax, **kwargs)

    # -- display (compact: never the arrays) -----------------------------------------------------------------
    def _summary_rows(self) -> list:
        from ._display import span

        z = self.zeta
        return [
            ("method", "method", repr(self.method)),
            ("fudge", "fudge", repr(self.problem.fudge.name)),
            ("p_bar", "p_bar (pressure)", span(self.problem.p_bar)),
            ("zeta", "zeta (stations)", span(z)),
            ("n_p", f"grid ({self.kind})", self.p.size),
            ("steps", "steps", self.info.get("steps")),
            ("A", f"A* at zeta = {z[-1]:.4g}", span(self.contact_area_all[-1])),
            ("wall_time", "wall time", f"{self.wall_time * 1e3:.3g} ms"),
            ("warnings", "warnings", len(self.info.get("warnings", []))),
        ]

    def __repr__(self):
        return "Solution(" + ", ".join(f"{k}={v}" for k, _, v in self._summary_rows()) + ")"

    def _repr_html_(self):
        from ._display import html_table

        return html_table("persson-fp Solution", [(label, v) for _, label, v in self._summary_rows()])
