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


def _station_axis(a):
    """Grid weights of shape (n_p,) or (n_zeta, n_p) as (n_zeta or 1, 1, n_p), to broadcast over loads."""
    a = np.asarray(a, dtype=float)
    return a[None, None, :] if a.ndim == 1 else a[:, None, :]


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
    elastic_area_error, plastic_area_error, noncontact_area_error : |A_el - exact|, |A_pl - exact|,
        |A_non - exact| (with a hardness wall; else None)
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
        out = {
            "L1": float(np.max(self.L1[-1])),
            "Linf": float(np.max(self.Linf[-1])),
            "area_error": float(np.max(self.area_error[-1])),
            "load_drift": float(np.max(self.load_drift[-1])),
        }
        if self.plastic_area_error is not None:
            out["elastic_area_error"] = float(np.max(self.elastic_area_error[-1]))
            out["plastic_area_error"] = float(np.max(self.plastic_area_error[-1]))
            out["noncontact_area_error"] = float(np.max(self.noncontact_area_error[-1]))
        return out

    def __str__(self):
        rows = [f"{'zeta':>10} {'L1':>10} {'Linf':>10} {'|dA*|':>10} {'load drift':>10}"]
        for i, z in enumerate(self.zeta):
            rows.append(
                f"{z:10.4g} {np.max(self.L1[i]):10.3e} {np.max(self.Linf[i]):10.3e} "
                f"{np.max(self.area_error[i]):10.3e} {np.max(self.load_drift[i]):10.3e}"
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
    """What a solver returns.

    Attributes
    ----------
    method : name of the method that produced it
    problem : the :class:`ContactProblem`
    zeta : output stations (dimensionless), shape ``(n_zeta,)``
    p : grid (pressure), shape ``(n_p,)``: cell centres ("cell") or nodes ("point"); shape
        ``(n_zeta, n_p)`` for a moving yield wall (the grid stretches with sigma_Y(zeta))
    P0_all : P0 (1/pressure), shape ``(n_zeta, n_loads, n_p)``
    weights : quadrature weights of the grid (pressure), ``int f dp ~ weights @ f``
    kind : "cell" (P0 are cell averages) or "point" (P0 are point values)
    contact_area_all : A* = int P0 dp (+ A_pl with a hardness wall), shape ``(n_zeta, n_loads)``
    plastic_area_all : A_pl, the mass absorbed at the yield wall, shape ``(n_zeta, n_loads)``, or None
    sigma_Y : the hardness at the stations (pressure), shape ``(n_zeta,)``, or None
    contact_area_flux_all : A* from the absorbed flux (FV), or None
    wall_time : seconds spent in the solver alone (its stepping; validation, building this Solution, its
        checks and compile time excluded): time the ``pf.solve`` call for the end-to-end cost
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
    plastic_area_all: np.ndarray | None = None
    sigma_Y: np.ndarray | None = None

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
        plastic_area=None,
    ):
        """Assemble a Solution, computing the integrals and checking the invariants.

        ``contact_area`` is the method's int P0 dp (the elastic area); with a hardness wall the method
        also hands over ``plastic_area`` (A_pl, the mass absorbed at sigma_Y) and the Solution's
        ``contact_area`` is their sum.  ``p`` and ``weights`` may have a leading station axis (moving wall).
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
        load = self._moment(1)
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
        """Errors against :func:`persson_fp.exact` at every station (see :class:`Comparison`).

        A scale-dependent hardness (moving yield wall) has no closed form: then a ``ValueError``
        points to ``info["error_estimate"]``, the solver's own estimate.
        """
        if self.problem.moving_wall:
            raise ValueError(
                "compare(): a scale-dependent hardness has no exact solution to compare with; the solver's own "
                "error estimate is in info['error_estimate'] (and the conservation residuals in info['checks'])"
            )
        ex = exact(self.problem.with_loads(self.problem.p_bar), self.zeta)
        shape = (self.zeta.size, self.problem.n_loads)
        A_ex = np.asarray(ex.contact_area).reshape(shape)
        diff = self.P0_all - self.exact_on_grid()
        L1 = np.abs(diff) @ self.weights
        Linf = np.max(np.abs(diff), axis=-1)
        dA = np.abs(self.contact_area_all - A_ex)
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
