"""The result of :func:`persson_fp.solve` and its comparison with the exact solution.

A :class:`Solution` holds P0 at the output stations on the method's grid, the
derived integrals (contact area ``eq:Area``, load ``eq:Load_equilibrium``,
variance) and what the solver did (``info``: grid, steps, rhs calls, wall
time, options).  The invariants -- P0 >= 0, A* non-increasing, load = p_bar --
are checked once, here, and recorded in ``info["checks"]``; a non-finite field
raises instead of being returned.  :meth:`Solution.compare` measures the error
actually made against :func:`persson_fp.exact`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from .exact import exact
from .problem import ContactProblem

__all__ = ["Solution", "Comparison", "SolverError", "InstabilityError"]


class SolverError(RuntimeError):
    """A solver could not produce a trustworthy result."""


class InstabilityError(SolverError):
    """The discrete evolution went unstable (NaN, negative or growing mass, blow-up)."""


@dataclass(frozen=True)
class Comparison:
    """Errors of a :class:`Solution` against the exact solution, per station and load.

    Arrays have shape ``(n_zeta, n_loads)``.

    Attributes
    ----------
    L1 : int |P0 - P0_exact| dp (dimensionless)
    Linf : max |P0 - P0_exact| (1/pressure)
    area_error : |A*_num - A*_exact|
    load_drift : |int p P0 dp - p_bar| / p_bar
    mass_balance : |A*(integral) - A*(boundary flux)| where the method tracks the flux, else NaN
    reference : "cell averages" or "point values" -- what the numerical P0 was compared with
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

    @property
    def max_L1(self) -> float:
        return float(np.max(self.L1))

    @property
    def max_area_error(self) -> float:
        return float(np.max(self.area_error))

    @property
    def area_z_score(self) -> np.ndarray | None:
        """|A*_num - A*_exact| in units of the standard error of A* (stochastic methods), else None.

        Shape ``(n_zeta, n_loads)``; inf where the standard error is 0 and the error is not.
        """
        if self.stderr_area is None:
            return None
        se = np.asarray(self.stderr_area, dtype=float).reshape(self.area_error.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.area_error == 0, 0.0, self.area_error / se)

    def final(self) -> dict:
        """Worst case over loads at the last station, as plain floats."""
        return {
            "L1": float(np.max(self.L1[-1])),
            "Linf": float(np.max(self.Linf[-1])),
            "area_error": float(np.max(self.area_error[-1])),
            "load_drift": float(np.max(self.load_drift[-1])),
        }

    def __str__(self):
        rows = [f"{'zeta':>10} {'L1':>10} {'Linf':>10} {'|dA*|':>10} {'load drift':>10}"]
        for i, z in enumerate(self.zeta):
            rows.append(
                f"{z:10.4g} {np.max(self.L1[i]):10.3e} {np.max(self.Linf[i]):10.3e} "
                f"{np.max(self.area_error[i]):10.3e} {np.max(self.load_drift[i]):10.3e}"
            )
        tail = f"\n(worst over {self.p_bar.size} load(s); reference: {self.reference})"
        z = self.area_z_score
        if z is not None:
            tail += f"\n|dA*| in standard errors (stochastic method): max {np.max(z):.2f}"
        return "\n".join(rows) + tail


@dataclass(frozen=True)
class Solution:
    """What a solver returns.

    Attributes
    ----------
    method : name of the method that produced it
    problem : the :class:`ContactProblem`
    zeta : output stations (dimensionless), shape ``(n_zeta,)``
    p : grid (pressure), shape ``(n_p,)``: cell centres ("cell") or nodes ("point")
    P0_all : P0 (1/pressure), shape ``(n_zeta, n_loads, n_p)``
    weights : quadrature weights of the grid (pressure), ``int f dp ~ weights @ f``
    kind : "cell" (P0 are cell averages) or "point" (P0 are point values)
    contact_area_all : A* = int P0 dp, shape ``(n_zeta, n_loads)``
    contact_area_flux_all : A* from the absorbed flux (FV), or None
    wall_time : seconds spent in the solver (compile time excluded, see ``info``)
    info : grid, steps, rhs calls, options, checks, warnings
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

    # -- construction -------------------------------------------------------------------
    @classmethod
    def build(
        cls,
        method,
        problem,
        zeta,
        p,
        P0,
        weights,
        kind,
        wall_time,
        info=None,
        contact_area=None,
        contact_area_flux=None,
        stderr_area=None,
        check=True,
    ):
        """Assemble a Solution, computing the integrals and checking the invariants."""
        zeta = np.atleast_1d(np.asarray(zeta, dtype=float))
        P0 = np.asarray(P0, dtype=float).reshape(zeta.size, problem.n_loads, -1)
        if not np.all(np.isfinite(P0)):
            raise InstabilityError(
                f"{method}: the solution holds NaN or inf values -- the scheme went unstable; "
                "reduce the step (n_steps) or use an implicit scheme"
            )
        weights = np.asarray(weights, dtype=float)
        if contact_area is None:
            contact_area = P0 @ weights
        contact_area = np.asarray(contact_area, dtype=float).reshape(zeta.size, problem.n_loads)
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
        )
        if check:
            sol._check()
        return sol

    def _check(self):
        """Record (and warn about) violated invariants: P0 >= 0, A* non-increasing, load."""
        checks = {}
        scale = np.max(np.abs(self.P0_all)) if self.P0_all.size else 1.0
        neg = float(-min(np.min(self.P0_all), 0.0))
        checks["min_P0"] = float(np.min(self.P0_all))
        checks["negative_P0"] = neg > 1e-10 * scale
        dA = np.diff(self.contact_area_all, axis=0)
        checks["area_increase"] = float(max(np.max(dA, initial=0.0), 0.0))
        checks["area_monotone"] = checks["area_increase"] <= 1e-9
        load = self.load_all
        checks["max_load_drift"] = float(np.max(np.abs(load - self.problem.p_bar) / self.problem.p_bar))
        self.info["checks"] = checks
        msgs = []
        if checks["negative_P0"]:
            msgs.append(
                f"P0 has negative values down to {checks['min_P0']:.3e} "
                "(oscillations: refine or use an L-stable scheme)"
            )
        if not checks["area_monotone"]:
            msgs.append(
                f"A* increases by up to {checks['area_increase']:.3e} between stations (contact can only be lost)"
            )
        if msgs:
            self.info.setdefault("warnings", []).extend(msgs)
            warnings.warn(f"{self.method}: " + "; ".join(msgs), RuntimeWarning, stacklevel=3)

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

    @property
    def load_all(self) -> np.ndarray:
        return self.P0_all @ (self.weights * self.p)

    @property
    def load(self) -> np.ndarray:
        """int p P0 dp at each station (pressure); equals p_bar exactly in theory (``eq:Load_equilibrium``)."""
        return self._squeeze(self.load_all)

    @property
    def variance(self) -> np.ndarray:
        """Var(p) = int p^2 P0 dp - p_bar^2 (atom at 0 included), pressure^2."""
        return self._squeeze(self.P0_all @ (self.weights * self.p**2) - self.problem.p_bar**2)

    @property
    def steps(self):
        return self.info.get("steps")

    # -- comparison ------------------------------------------------------------------------
    def exact_on_grid(self) -> np.ndarray:
        """The exact P0 on this solution's grid in the same sense (cell averages or point values)."""
        ex = exact(self.problem.with_loads(self.problem.p_bar), self.zeta)
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
        """Errors against :func:`persson_fp.exact` at every station (see :class:`Comparison`)."""
        ex = exact(self.problem.with_loads(self.problem.p_bar), self.zeta)
        A_ex = np.asarray(ex.contact_area).reshape(self.zeta.size, self.problem.n_loads)
        diff = self.P0_all - self.exact_on_grid()
        L1 = np.abs(diff) @ self.weights
        Linf = np.max(np.abs(diff), axis=-1)
        dA = np.abs(self.contact_area_all - A_ex)
        drift = np.abs(self.load_all - self.problem.p_bar) / self.problem.p_bar
        if self.contact_area_flux_all is not None:
            mb = np.abs(self.contact_area_all - self.contact_area_flux_all)
        else:
            mb = np.full_like(dA, np.nan)
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
        )

    def summary(self) -> str:
        """A few lines: method, grid, steps, wall time and the error made."""
        c = self.compare().final()
        return (
            f"{self.method}: n_p={self.p.size}, steps={self.info.get('steps')}, wall={self.wall_time * 1e3:.2f} ms, "
            f"L1={c['L1']:.3e}, |dA*|={c['area_error']:.3e}, load drift={c['load_drift']:.3e}"
        )

    def plot(self, ax=None, **kwargs):
        """P0 against the exact solution at every station (needs matplotlib)."""
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
