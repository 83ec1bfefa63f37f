"""The result of :func:`persson_fp.solve` and its comparison with the exact solution.

A :class:`Solution` holds P0 at the output stations on the method's grid, the derived integrals (contact area
``eq:Area``, load ``eq:Load_equilibrium``, variance) and what the solver did (``info``: grid, steps, rhs calls, wall
time, options).  The invariants -- P0 >= 0, A* non-increasing, load = p_bar -- are checked once, here
(:func:`check_invariants`), against tolerances tied to the method's accuracy, and recorded in ``info["checks"]``; a
breach raises :class:`SolverError` (a warning with ``check=False``) and a non-finite field raises
:class:`InstabilityError` instead of being returned.  :meth:`Solution.compare` measures the error actually made
against :func:`persson_fp.exact`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem
from persson_fp.results.comparison import Comparison, compare_with_exact
from persson_fp.results.invariants import DEFAULT_TOLERANCES, InstabilityError, SolverError, check_invariants
from persson_fp.results.output import SolverOutput

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

    from persson_fp.analysis.exact import ExactSolution

__all__ = ["Solution", "Comparison", "SolverError", "InstabilityError", "check_invariants", "DEFAULT_TOLERANCES"]


def _station_axis(a):
    """Grid weights of shape (n_p,) or (n_zeta, n_p) as (n_zeta or 1, 1, n_p), to broadcast over loads."""
    a = np.asarray(a, dtype=float)
    return a[None, None, :] if a.ndim == 1 else a[:, None, :]


@dataclass(frozen=True)
class Solution:
    """What a solver returns: P0 at the output stations, the derived integrals and what the solver did.

    Built by :meth:`from_output` (which checks the invariants, :func:`~persson_fp.results.solution.check_invariants`)
    from what a method of :func:`persson_fp.solve` hands back; a frozen dataclass.  The ``*_all`` arrays keep the load
    axis, their counterparts without the suffix drop it for a scalar load.

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
            Invariant tolerances, keys of ``DEFAULT_TOLERANCES``
            (:func:`~persson_fp.results.solution.check_invariants`).
        load : array_like, pressure, optional
            The method's own estimate of int p P0 dp where the grid quadrature is not the best one
            (Monte Carlo: the mean over the walkers instead of the histogram).
        stderr_load : array_like, pressure, optional
            Standard error of ``load``.

        Returns
        -------
        Solution
            As :meth:`from_output` (which raises what it raises), called with these fields gathered in one
            ``SolverOutput``.
        """
        out = SolverOutput(
            p=p,
            P0=P0,
            weights=weights,
            kind=kind,
            info=info if info else {},
            contact_area=contact_area,
            contact_area_flux=contact_area_flux,
            stderr_area=stderr_area,
            plastic_area=plastic_area,
            load=load,
            stderr_load=stderr_load,
        )
        return cls.from_output(
            problem, out, method=method, zeta=zeta, wall_time=wall_time, check=check, tolerances=tolerances
        )

    @classmethod
    def from_output(
        cls,
        problem: ContactProblem,
        output: SolverOutput,
        *,
        method: str,
        zeta: ArrayLike,
        wall_time: float,
        check: bool = True,
        tolerances: dict | None = None,
    ) -> Solution:
        """A Solution from what a method handed back: the integrals computed and the invariants checked.

        The one constructor the solvers use (``Solver.run``); :meth:`build` takes the same
        fields one by one.

        Parameters
        ----------
        problem : ContactProblem
            The problem solved.
        output : SolverOutput
            The method's grid, P0 at the stations, quadrature weights, areas and ``info`` (copied).
        method : str
            Name of the method (quoted in messages).
        zeta : float or 1-D array, dimensionless
            Output stations, shape ``(n_zeta,)``.
        wall_time : float, seconds
            Time spent solving.
        check : bool
            True: a breached invariant raises :class:`SolverError`; False: it only warns.
        tolerances : dict, optional
            Invariant tolerances, keys of ``DEFAULT_TOLERANCES``
            (:func:`~persson_fp.results.solution.check_invariants`).

        Returns
        -------
        Solution
            With ``info["checks"]`` holding the result of :func:`~persson_fp.results.solution.check_invariants`.

        Raises
        ------
        InstabilityError
            P0 holds NaN or inf values (the scheme went unstable).
        SolverError
            With ``check=True``, a breached invariant, named with its remedy.
        """
        o = output
        p, weights, kind, info = o.p, o.weights, o.kind, o.info
        contact_area, contact_area_flux, plastic_area = o.contact_area, o.contact_area_flux, o.plastic_area
        stderr_area, load, stderr_load = o.stderr_area, o.load, o.stderr_load
        P0 = o.P0
        zeta = np.asarray(zeta, dtype=float)
        zeta = zeta.reshape(1) if zeta.ndim == 0 else zeta
        n_z, n_l = zeta.size, problem.n_loads
        P0 = np.asarray(P0, dtype=float).reshape(n_z, n_l, -1)
        # min and max propagate NaN and reach +-inf: both finite <=> all finite (the positivity check reuses them)
        extrema = (float(P0.min()), float(P0.max())) if P0.size else (0.0, 0.0)
        if not (math.isfinite(extrema[0]) and math.isfinite(extrema[1])):
            raise InstabilityError(
                f"{method}: the solution holds NaN or inf values -- the scheme went unstable; "
                "reduce the step (n_steps) or use an implicit scheme"
            )
        weights = np.asarray(weights, dtype=float)
        if contact_area is None:
            contact_area = np.sum(P0 * _station_axis(weights), axis=-1)
        contact_area = np.asarray(contact_area, dtype=float).reshape(n_z, n_l)
        # the yield wall's stress and plastic area (A* = A_el + A_pl); None, None and A_el without one
        sigma_Y, plastic_area, contact_area = problem.upper_wall.solution_areas(zeta, contact_area, plastic_area)
        # every field set at once (what the frozen dataclass's __init__ does one object.__setattr__ at a time)
        sol = object.__new__(cls)
        sol.__dict__.update(
            method=method,
            problem=problem,
            zeta=zeta,
            p=np.asarray(p, dtype=float),
            P0_all=P0,
            weights=weights,
            kind=kind,
            contact_area_all=contact_area,
            wall_time=float(wall_time),
            info=dict(info) if info else {},
            contact_area_flux_all=None
            if contact_area_flux is None
            else np.asarray(contact_area_flux, float).reshape(n_z, n_l),
            stderr_area_all=None if stderr_area is None else np.asarray(stderr_area, float).reshape(n_z, -1),
            plastic_area_all=plastic_area,
            sigma_Y=sigma_Y,
            load_estimate_all=None if load is None else np.asarray(load, float).reshape(n_z, n_l),
            stderr_load_all=None if stderr_load is None else np.asarray(stderr_load, float).reshape(n_z, -1),
        )
        sol._check(tolerances, raise_on_breach=bool(check), extrema=extrema)
        return sol

    def _check(self, tolerances=None, raise_on_breach=True, extrema=None):
        """Check the invariants (:func:`check_invariants`); record them in ``info["checks"]``."""
        self.info["checks"] = check_invariants(self, tolerances, raise_on_breach=raise_on_breach, extrema=extrema)

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
        w = self.weights * (self.p if k == 1 else self.p**k)
        if w.ndim == 1:  # one grid: a matrix-vector product (~1 us for one load, against ~3 us multiply-and-sum)
            return self.P0_all @ w
        return (self.P0_all * w[:, None, :]).sum(axis=-1)  # (n_zeta, n_p): a moving grid, one row per station

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
        self.problem.require_closed_form(
            "compare() has no exact solution to compare with; the solver's own error estimate is in "
            "info['error_estimate'] (and the conservation residuals in info['checks'])"
        )
        return compare_with_exact(self, exact(self.problem, self._exact_zeta()))

    @property
    def error_estimate(self) -> dict:
        """The error of this result at every station and load, whatever the problem.

        Keys ``"L1"`` (``int |P0 - P0_ref| dp``) and ``"contact_area"`` (and, with a hardness, ``"elastic_area"``,
        ``"plastic_area"``, ``"noncontact_area"``), arrays of shape (n_zeta, n_loads), and ``"kind"``: where a closed
        form exists the *true* error against :func:`persson_fp.exact`; otherwise (a moving yield wall, general
        coefficients) the solver's own estimate, as ``info["error_estimate"]["method"]`` states (fv, mol: the run
        against half the resolution; chebyshev: partner runs, far wall, march); Monte Carlo adds the standard error
        of A* as ``"stderr_area"``.  Computed once and kept in ``info["error_estimate_view"]``.
        """
        cached = self.info.get("error_estimate_view")
        if cached is not None:
            return cached
        est = self.info.get("error_estimate")
        if est is not None:
            out = {
                "kind": "estimate: " + str(est.get("method", "|result - half-resolution result| (conservative)")),
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

        Where a closed form exists the error is the true one from :meth:`compare`; otherwise (a moving yield wall,
        general coefficients) it is the solver's own estimate (:attr:`error_estimate`, marked "~" and
        "estimate"), and the load drift is that of the result itself.  Where an earlier station's L1 is larger than
        the last one's, the line ends with that worst station and its errors (the accuracy stated for the last
        station does not hold at every station).

        Returns
        -------
        str
            The method, ``n_p``, steps, wall time (ms), L1 error, ``|dA*|`` (absolute and relative) and load
            drift (the worst over the loads); with a hardness, A_pl.
        """
        from persson_fp.results.display import summary_line

        return summary_line(self)

    def plot(self, ax: Axes | None = None, pressure_unit: str | None = None, **kwargs: Any) -> Figure:
        """P0 against the exact solution where there is one, every load (needs matplotlib).

        Draws :func:`persson_fp.plotting.plot_solution`, p in units of sqrt(V(zeta_max)): one load, a curve per
        station and its error in the title; several loads, a curve per load (at the last station), each legend
        entry giving its p_bar (with ``pressure_unit``), p_bar/sqrt(V) and its own L1 error.  Without a closed form
        (a moving yield wall, general coefficients) the numerical P0 alone, with the solver's error estimates.  The
        time shown is ``wall_time``, as :meth:`summary` gives it.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; default a new figure.
        pressure_unit : str, optional
            Unit of the problem's pressures (e.g. ``"Pa"``) for the legend; the problem itself carries no units.
        **kwargs
            Passed to :func:`~persson_fp.plotting.plot_solution` (``stations``, ``loads``).

        Returns
        -------
        matplotlib.figure.Figure
            The figure drawn on.
        """
        from persson_fp import plotting

        return plotting.plot_solution(self, ax=ax, pressure_unit=pressure_unit, **kwargs)

    # -- display (compact: never the arrays) -----------------------------------------------------------------
    def _summary_rows(self) -> list:
        from persson_fp._display import span
        from persson_fp.results.display import error_label

        z = self.zeta
        return [
            ("method", "method", repr(self.method)),
            ("fudge", "fudge", repr(self.problem.fudge.name)),
            ("p_bar", "p_bar (pressure)", span(self.problem.p_bar)),
            ("zeta", "zeta (stations)", span(z)),
            ("n_p", f"grid ({self.kind})", np.shape(self.p)[-1]),
            ("steps", "steps", self.info.get("steps")),
            ("A", f"A* at zeta = {z[-1]:.4g}", span(self.contact_area_all[-1])),
            ("error", "error of A* (at the last station)", error_label(self)),
            ("wall_time", "wall time", f"{self.wall_time * 1e3:.3g} ms"),
            ("warnings", "warnings", len(self.info.get("warnings", []))),
        ]

    def __repr__(self):
        return "Solution(" + ", ".join(f"{k}={v}" for k, _, v in self._summary_rows()) + ")"

    def _repr_html_(self):
        from persson_fp._display import html_table

        return html_table("persson-fp Solution", [(label, v) for _, label, v in self._summary_rows()])
