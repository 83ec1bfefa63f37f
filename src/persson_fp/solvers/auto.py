r"""``method="auto"`` and ``tol=``: ask for an accuracy, not a method.

``pf.solve(problem, method="auto", tol=1e-6)`` models no more than the scene needs and checks what it did:

* **A closed form exists** (no moving wall, no general coefficients; fudge factors and a constant hardness
  included): ``"sines"``, Persson's sine series on [0, p_max] (or on the strip [0, sigma_Y]), which *is* the image
  / strip series summed to ``tol`` -- the fastest method at every tolerance in ``benchmarks/results/
  speed_accuracy.md`` and ``plasticity.md``.  Its error is then measured against :func:`persson_fp.exact`.  If the
  first station is too narrow for the series (a ``ValueError`` from sines), ``"fv"`` with a resolution for ``tol``.
* **General coefficients B2 = b(p) dV/dzeta, B1 = c(p) dV/dzeta, no hardness**: ``"chebyshev"``
  (:mod:`persson_fp.solvers.chebyshev`), which meets ``tol`` by its own estimate; other coefficients fall through:
* **No closed form** (a scale-dependent hardness, general coefficients): ``"fv"`` on the front-fixed engine,
  n_p = n_steps = n from the error models measured in ``benchmarks/plasticity.py`` and ``benchmarks/auto.py``
  (estimate ~ 2e-2 / n^2 for a moving wall, ~ 50 / n^2 for general coefficients, with n cells and n steps), refined
  until its own error estimate (a run at half the resolution) meets ``tol``.

``tol`` bounds both the L1 error of P0 (:math:`\int |P_0 - P_0^{ref}|\,dp`) and the error of every area
(A*, and A_el, A_pl with a hardness) at every output station.  With a named method, ``tol`` chooses the
resolution the same way (fv: steps and cells from its error model; mol: ``rtol`` and the grid; sines: the series
truncation) and the same check follows.  Up to ``MAX_REFINE`` refinements; if ``tol`` is still not met, a
:class:`~persson_fp.SolverError` names the best error reached.  ``sol.info["auto"]`` records the choice, why,
every attempt, the estimate and (with a closed form) the true error.
"""

from __future__ import annotations

import math
import time

import numpy as np

from persson_fp.results.solution import SolverError

__all__ = ["solve_auto", "solve_to_tol", "MAX_REFINE"]

MAX_REFINE = 4
"""Refinements after the first attempt before ``tol`` is declared out of reach."""
MAX_CELLS = 8192
"""Largest n_p (and n_steps on the front-fixed engine) a refinement may ask for; beyond it ``tol`` is out of reach."""
_C_FRONT = 2e-2
"""Front-fixed engine, moving wall: the (conservative) error estimate ~ _C_FRONT / n^2 at n cells and n steps
(1.5e-2 measured on the moving-wall scene of benchmarks/plasticity.py, rounded up)."""
_C_GENERAL = 50.0
"""General coefficients on [0, p_max] (a wider domain in units of the PDF's width): estimate ~ _C_GENERAL / n^2
(about 40 measured on the scene of benchmarks/auto.py)."""
_C_FV_STEPS = 0.06
"""fv TR-BDF2 (compact4, graded steps), closed-form scenes: L1 ~ _C_FV_STEPS / n_steps^2 (speed_accuracy.md)."""
_C_FV_CELLS = 6e-6 * 200.0**4
"""... + _C_FV_CELLS / n_p^4 (4th order in p)."""


def _errors(sol):
    """(worst L1, worst area error, kind) of a Solution: against pf.exact, or the solver's own estimate."""
    if sol.problem.has_closed_form:
        c = sol.compare()
        areas = [c.area_error]
        if c.plastic_area_error is not None:
            areas += [c.elastic_area_error, c.plastic_area_error]
        return float(np.max(c.L1)), float(max(np.max(a) for a in areas)), "true error (against pf.exact)"
    est = sol.info["error_estimate"]
    area = max(float(np.max(est[q])) for q in ("elastic_area", "plastic_area", "noncontact_area"))
    L1 = float(np.nanmax(est["L1"])) if np.any(np.isfinite(est["L1"])) else area
    return L1, area, "estimate (|run - half-resolution run|)"


def _attempt(problem, method, zeta_out, options):
    from persson_fp.solvers import get_solver

    return get_solver(method)(problem, zeta_out=zeta_out, **options).run()


def _first_options(problem, method, tol):
    if method == "sines":
        return {"tol": min(max(tol * 1e-2, 1e-14), 1e-2)}
    if method == "mol":
        return {"rtol": min(max(tol * 1e-2, 1e-12), 1e-3)}
    if not problem.has_closed_form:
        C = _C_GENERAL if problem.general else _C_FRONT
        n = 2 * int(np.clip(math.ceil(math.sqrt(C / tol) / 2), 25, 1600))  # even: the partner has n/2
        return {"n_p": n, "n_steps": n}
    n_steps = int(np.clip(math.ceil(math.sqrt(2.0 * _C_FV_STEPS / tol)), 20, 20000))
    n_p = int(np.clip(math.ceil((2.0 * _C_FV_CELLS / tol) ** 0.25), 50, 20000))
    return {"n_p": n_p, "n_steps": n_steps}


def _refine(method, opts, problem, ratio):
    """Options one refinement finer, scaled by the error ratio (err / tol) where the order is known."""
    out = dict(opts)
    if method == "sines":
        out["tol"] = max(opts["tol"] * 1e-2, 1e-15)
    elif method == "mol":
        out["rtol"] = max(opts["rtol"] * 1e-2, 1e-13)
        out["n_p"] = int(math.ceil(1.5 * (opts.get("n_p") or 200)))
    else:
        f = float(np.clip(1.2 * math.sqrt(ratio), 1.5, 8.0))  # second order in both (front-fixed) or in steps
        out["n_steps"] = 2 * int(math.ceil(opts["n_steps"] * f / 2))
        out["n_p"] = 2 * int(math.ceil(opts["n_p"] * (f if not problem.has_closed_form else f**0.5) / 2))
    return out


def solve_to_tol(problem, method: str, zeta_out, tol: float, why: str = "", **options):
    """Solve with ``method`` at a resolution chosen for ``tol``, check the error, refine until it meets ``tol``."""
    t0 = time.perf_counter()
    opts = {**_first_options(problem, method, tol), **options}
    attempts = []
    for k in range(MAX_REFINE + 1):
        sol = _attempt(problem, method, zeta_out, opts)
        L1, area, kind = _errors(sol)
        attempts.append({"options": dict(opts), "L1": L1, "area_error": area, "wall_time": sol.wall_time})
        if L1 <= tol and area <= tol:
            break
        if k == MAX_REFINE:
            raise SolverError(
                f"{method}: tol = {tol:g} not met after {MAX_REFINE} refinements (best: L1 {L1:.3e}, area error "
                f"{area:.3e}, {kind}, with {opts}); ask for a looser tol or pass the resolution yourself"
            )
        opts = _refine(method, opts, problem, max(L1, area) / tol)
        if max(opts.get("n_p") or 0, 0 if problem.has_closed_form else opts.get("n_steps", 0)) > MAX_CELLS:
            raise SolverError(
                f"{method}: tol = {tol:g} would need more than {MAX_CELLS} cells/steps (best so far: L1 {L1:.3e}, area "
                f"error {area:.3e}, {kind}, with {attempts[-1]['options']}); ask for a looser tol"
            )
    sol.info["auto"] = {
        "method": method,
        "why": why or f"method {method!r} asked for; resolution chosen for tol",
        "tol": tol,
        "L1": L1,
        "area_error": area,
        "kind": kind,
        "attempts": attempts,
        "total_time": time.perf_counter() - t0,
    }
    return sol


def solve_auto(problem, zeta_out=None, tol: float = 1e-6, **options):
    """``method="auto"``: the cheapest way to ``tol`` (module docstring)."""
    from persson_fp.solvers.base import check_float

    tol = check_float(tol, "tol", 0.0, 1e-1)
    if options:
        raise TypeError(f"method 'auto' chooses the resolution itself; it takes only tol and zeta_out, got {options}")
    if problem.has_closed_form:
        why = (
            "a closed form exists: the sine series is that solution summed to tol (spectral; the fastest method "
            "at every tolerance measured in benchmarks/results)"
        )
        try:
            return solve_to_tol(problem, "sines", zeta_out, tol, why=why)
        except (ValueError, SolverError) as err:
            why = f"the sine series could not serve this scene ({err}); finite volumes with a resolution for tol"
            return solve_to_tol(problem, "fv", zeta_out, tol, why=why)
    declined = ""
    if problem.general and problem.hardness is None:  # (issue 21) the spectral engine, where it applies
        try:
            return _solve_chebyshev(problem, zeta_out, tol)
        except (ValueError, SolverError) as err:
            declined = f"; method 'chebyshev' declined: {err}"
    what = "a scale-dependent hardness" if problem.moving_wall else "general Fokker-Planck coefficients"
    why = (
        f"no closed form ({what}): finite volumes on the front-fixed engine, n cells and n steps from the "
        f"measured error model C/n^2, checked by a half-resolution partner run{declined}"
    )
    return solve_to_tol(problem, "fv", zeta_out, tol, why=why)


def _solve_chebyshev(problem, zeta_out, tol):
    """General coefficients B2 = b(p) dV/dzeta, B1 = c(p) dV/dzeta without a hardness: method "chebyshev"
    (spectral in p, exact in V; its own loop meets ``tol`` -- 5-25 ms for 1e-4 ... 1e-10 on the reference problem
    in ``benchmarks/results/general_engine.md``, where fv needs seconds for 1e-6)."""
    from persson_fp.solvers.chebyshev import ChebyshevSolver

    t0 = time.perf_counter()
    sol = ChebyshevSolver(problem, zeta_out=zeta_out, tol=min(tol, 1e-1)).run()
    L1, area, kind = _errors(sol)
    sol.info["auto"] = {
        "method": "chebyshev",
        "why": "general coefficients of the form b(p) dV/dzeta: Chebyshev collocation in p, exact exponentials in V, "
        "degree and start refined until the estimate (3/4-degree and 4 V0 partners) meets tol",
        "tol": tol,
        "L1": L1,
        "area_error": area,
        "kind": kind,
        "attempts": [{"options": {"tol": tol}, "L1": L1, "area_error": area, "wall_time": sol.wall_time}],
        "total_time": time.perf_counter() - t0,
    }
    return sol
