"""The errors of a numerical solution against the exact one: :class:`Comparison`, what ``Solution.compare`` returns."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Comparison", "compare_with_exact"]


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


def compare_with_exact(sol, ex) -> Comparison:
    """The :class:`Comparison` of a numerical solution ``sol`` with the exact solution ``ex`` at its stations.

    Parameters
    ----------
    sol : Solution
        A numerical solution of a problem with a closed form.
    ex : ExactSolution
        ``pf.exact(sol.problem, sol.zeta)`` (or the default-station fast path).

    Returns
    -------
    Comparison
        Arrays of shape ``(n_zeta, n_loads)``.
    """
    shape = (sol.zeta.size, sol.problem.n_loads)
    A_ex = np.asarray(ex.contact_area).reshape(shape)
    diff = sol.P0_all - sol.exact_on_grid(ex)
    L1 = np.abs(diff) @ sol.weights
    Linf = np.max(np.abs(diff), axis=-1)
    dA = np.abs(sol.contact_area_all - A_ex)
    with np.errstate(divide="ignore", invalid="ignore"):
        dA_rel = np.where(dA == 0, 0.0, dA / A_ex)
    drift = np.abs(sol.load_all - sol.problem.p_bar) / sol.problem.p_bar
    if sol.contact_area_flux_all is not None:
        mb = np.abs(sol.contact_area_all - sol.contact_area_flux_all)
    else:
        mb = np.full_like(dA, np.nan)
    hard = {}
    if sol.plastic_area_all is not None:
        hard = {
            "elastic_area_error": np.abs(sol.elastic_area_all - np.asarray(ex.elastic_area).reshape(shape)),
            "plastic_area_error": np.abs(sol.plastic_area_all - np.asarray(ex.plastic_area).reshape(shape)),
            "noncontact_area_error": np.abs(
                (1.0 - sol.contact_area_all) - np.asarray(ex.noncontact_area).reshape(shape)
            ),
        }
    return Comparison(
        zeta=sol.zeta,
        p_bar=sol.problem.p_bar,
        L1=L1,
        Linf=Linf,
        area_error=dA,
        load_drift=drift,
        mass_balance=mb,
        reference="cell averages" if sol.kind == "cell" else "point values",
        stderr_area=sol.stderr_area_all,
        **hard,
        area_error_rel=dA_rel,
        stderr_load=sol.stderr_load_all,
    )
