r"""``method="auto"`` and ``tol=``: ask for an accuracy, not a method.

``pf.solve(problem, method="auto", tol=1e-6)`` models no more than the scene needs and checks what it did:

* **A closed form exists** (no moving wall, no general coefficients; fudge factors and a constant hardness
  included): ``"sines"``, Persson's sine series on [0, p_max] (or on the strip [0, sigma_Y]), which *is* the image
  / strip series summed to ``tol`` -- the fastest method at every tolerance in ``benchmarks/results/
  speed_accuracy.md`` and ``plasticity.md``.  Its error is then measured against :func:`persson_fp.exact`.  If the
  first station is too narrow for the series (a ``ValueError`` from sines), ``"fv"`` with a resolution for ``tol``.
* **General coefficients, no moving wall** (a constant hardness included): ``"chebyshev"``
  (:mod:`persson_fp.solvers.chebyshev`), which meets ``tol`` by its own estimate -- exact exponentials for
  B2 = b(p) g(zeta), B1 = c(p) g(zeta), an adaptive Radau IIA march in V otherwise; where it declines (e.g.
  its march is forecast over its time budget) the problem falls through:
* **A moving wall without a fudge factor, tol < 3e-7** (``_CHEB_WALL_TOL``): ``"chebyshev"`` on its front-fixed
  Radau march (:mod:`persson_fp.solvers.chebyshev.wall`), at most ``_CHEB_WALL_TIME`` seconds; where it declines or
  runs out of time, ``"fv"`` as below.  For 3e-7 <= tol <= 1e-4 fv goes first, while its next attempt's work
  (n_p x n_steps) stays within ``_FV_WALL_WORK``: past it (a wall that moves fast next to the load, where fv needs
  thousands of cells) ``"chebyshev"`` is tried, and fv resumes from its last resolution where that declines.
* **No closed form** (a scale-dependent hardness, general coefficients): ``"fv"`` on the front-fixed engine,
  n_p = n_steps = n from the error models measured in ``benchmarks/plasticity.py`` and ``benchmarks/auto.py``
  (estimate ~ 2e-2 / n^2 for a moving wall, ~ 50 / n^2 for general coefficients, with n cells and n steps), refined
  until its own error estimate (a run at half the resolution) meets ``tol``.

``tol`` bounds both the L1 error of P0 (:math:`\int |P_0 - P_0^{ref}|\,dp`) and the error of every area
(A*, and A_el, A_pl with a hardness) at every output station.  With a named method, ``tol`` chooses the
resolution the same way (fv: steps and cells from its error model; mol: ``rtol`` and the grid; sines: the series
truncation) and the same check follows.  Up to ``MAX_REFINE`` refinements; if ``tol`` is still not met, a
:class:`~persson_fp.SolverError` names the best error reached.  On the front-fixed engine the first attempt puts at
least ``_CELLS_PER_WIDTH`` cells across the PDF's width (never below what the engine accepts), an attempt whose
result breaks an invariant is refined rather than returned, a far-wall loss above tol/4 grows ``k_domain``, and
``max_memory``/``max_time`` bound every attempt and (``max_time``) the whole refinement.  ``sol.info["auto"]``
records the choice, why, every attempt, the estimate and (with a closed form) the true error.
"""

from __future__ import annotations

import math
import time

import numpy as np

from persson_fp.results.solution import SolverError
from persson_fp.solvers.registry import get_solver

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
_CELLS_PER_WIDTH = 4.0
"""The front-fixed engine's first attempt puts at least this many cells across the PDF's width sqrt(V) at the first
station (the engine itself refuses fewer than one; with one or two a moving wall rings: a dip of -0.19 x the peak
measured on the moving-wall scene W at 66 cells)."""
_CHEB_WALL_TOL = 3e-7
"""A moving wall without a fudge factor goes to ``"chebyshev"`` first below this tol (its front-fixed Radau march,
:mod:`persson_fp.solvers.chebyshev.wall`): above it the second-order ``fv`` is the faster one (scene D of
``benchmarks/plasticity.py``: fv 43 ms for 1e-6, chebyshev 0.14 s; for 1e-8 fv 3.4 s, chebyshev 1.5 s)."""
_CHEB_WALL_TIME = 20.0
"""Seconds the chebyshev attempt on a moving wall may take before auto falls back to fv (where its march loses order
next to a fast-moving wall it needs many steps)."""
_FV_WALL_WORK = 150.0 * 150.0
"""On a moving wall at 3e-7 <= tol <= 1e-4: the work n_p x n_steps of an fv attempt beyond which auto tries
``"chebyshev"`` instead (``benchmarks/moving_wall_auto.py``: on the moving-wall scene W fv needs 230 cells and
steps for 1e-4 and 812 for 1e-5, 0.3 s and 1.2 s, where chebyshev takes 0.3 s and 0.4 s and is 20-1000x more
accurate than asked; on scene B of ``benchmarks/plasticity.py`` fv meets 1e-6 with 142, in 0.1 s, 3x faster than
chebyshev)."""
_C_FV_STEPS = 0.06
"""fv TR-BDF2 (compact4, graded steps), closed-form scenes: L1 ~ _C_FV_STEPS / n_steps^2 (speed_accuracy.md)."""
_C_FV_CELLS = 6e-6 * 200.0**4
"""... + _C_FV_CELLS / n_p^4 (4th order in p)."""


class _Plan:
    """How auto reaches ``tol`` on one kind of problem (:data:`_PLANS`): the error it judges by, the first
    resolution and the refinement (the front-fixed engine's here; :class:`_ClosedForm` overrides them)."""

    def __init__(self, C: float = _C_FRONT, what: str = "", chebyshev: str | None = None):
        self.C = C
        """Error model of the front-fixed engine, estimate ~ C / n^2 at n cells and n steps."""
        self.what = what
        """What leaves the closed forms behind, in words."""
        self.chebyshev = chebyshev
        """When ``"chebyshev"`` is tried first: "always", "wall" (no fudge factor, tol < _CHEB_WALL_TOL) or None."""

    def solve(self, problem, zeta_out, tol, budget, max_time):
        """``"chebyshev"`` first where the plan says so, then fv on the front-fixed engine to tol.

        On a moving wall at ``_CHEB_WALL_TOL <= tol <= 1e-4`` fv goes first under the work cap ``_FV_WALL_WORK``;
        where its next attempt would exceed it, chebyshev is tried (capped at ``_CHEB_WALL_TIME`` and at what is
        left of ``max_time``), and where that declines fv resumes at the resolution the cap stopped it at -- its
        attempts before the cap in ``info["auto"]["fv_attempts"]``, the decline in ``info["auto"]["why"]``."""
        t_call = time.perf_counter()
        declined, cheb_err = "", ""
        resume, tried = {}, []  # (fv's options where a work-capped fv attempt stopped for chebyshev, and its attempts)
        cheb_spent = fv_spent = 0.0
        if self.chebyshev == "wall" and problem.fudge.name == "none" and _CHEB_WALL_TOL <= tol <= 1e-4:
            why = (
                f"no closed form ({self.what}): finite volumes on the front-fixed engine, n cells and n steps from "
                "the measured error model C/n^2, checked by a half-resolution partner run"
            )
            try:
                return solve_to_tol(problem, "fv", zeta_out, tol, why=why, max_work=_FV_WALL_WORK, **budget)
            except _TooMuchWork as stop:
                resume, tried = stop.options, stop.attempts
            t_cheb = time.perf_counter()
            fv_spent = t_cheb - t_call
            capped = dict(budget)
            left = math.inf if max_time is None else max_time - fv_spent  # (fv's capped attempts count)
            capped["max_time"] = min(_CHEB_WALL_TIME, left)
            try:
                if left <= 0.0:
                    raise SolverError(f"no time left of max_time = {max_time:g} s")
                sol = _solve_chebyshev(problem, zeta_out, tol, capped)
                sol.info["auto"]["why"] += (
                    f"; fv first ({len(tried)} attempt(s)) would next need n_p x n_steps = "
                    f"{_work(resume):.3g} > {_FV_WALL_WORK:.3g}"
                )
                sol.info["auto"]["fv_attempts"] = tried
                return sol
            except (ValueError, SolverError) as err:
                declined, cheb_err = f"; method 'chebyshev' declined: {err}", str(err)
                cheb_spent = time.perf_counter() - t_cheb
                if max_time is not None:
                    budget["max_time"] = max_time - (time.perf_counter() - t_call)
        cheb_budget = None if resume else self.chebyshev_budget(problem, tol, budget)  # the spectral engine first
        if cheb_budget is not None:
            t_cheb = time.perf_counter()
            try:
                return _solve_chebyshev(problem, zeta_out, tol, cheb_budget)
            except (ValueError, SolverError) as err:
                declined, cheb_err = f"; method 'chebyshev' declined: {err}", str(err)
                cheb_spent = time.perf_counter() - t_cheb
                if max_time is not None and cheb_budget is not budget:  # fv gets what the capped attempt left
                    budget["max_time"] = max_time - (time.perf_counter() - t_cheb)
                elif max_time is None and "over its budget" in cheb_err:  # (the march's forecast: fv, slower at
                    from persson_fp.solvers.chebyshev.solver import MARCH_TIME_BUDGET  # every tol, gets as long)

                    budget["max_time"] = MARCH_TIME_BUDGET
        why = (
            f"no closed form ({self.what}): finite volumes on the front-fixed engine, n cells and n steps from the "
            f"measured error model C/n^2, checked by a half-resolution partner run{declined}"
        )
        if resume:
            why += (
                f"; fv resumed at n_p x n_steps = {_work(resume):.3g}, where the work cap had stopped it after "
                f"{len(tried)} attempt(s)"
            )

        def fv():
            sol = solve_to_tol(problem, "fv", zeta_out, tol, why=why, **budget, **resume)
            if resume:
                sol.info["auto"]["fv_attempts"] = tried
            return sol

        if max_time is None and budget["max_time"] is not None:  # (chebyshev's forecast declined: fv as long)
            try:
                return fv()
            except (ValueError, SolverError) as err:
                if "max_time" not in str(err):
                    raise
                raise SolverError(
                    f"auto: tol = {tol:g} not met: method 'chebyshev' declined ({cheb_err[:300]}), and fv did not "
                    f"meet it within the same {budget['max_time']:g} s ({err}); ask for a looser tol or pass a "
                    "larger max_time (seconds)"
                ) from None
        if max_time is not None and budget["max_time"] != max_time:
            first = f" after fv's {len(tried)} work-capped attempt(s) took {fv_spent:.3g} s" if resume else ""
            try:
                if budget["max_time"] <= 0.0:
                    raise SolverError("no time left")
                return fv()
            except (ValueError, SolverError) as err:
                if "max_time" not in str(err) and str(err) != "no time left":
                    raise
                raise SolverError(
                    f"auto: tol = {tol:g} not met within max_time = {max_time:g} s: the chebyshev attempt took "
                    f"{cheb_spent:.3g} s{first} and was declined ({cheb_err[:200]}), and fv then ran out of the rest "
                    f"({err}); ask for a looser tol or a larger max_time"
                ) from None
        return fv()

    def errors(self, sol):
        """(worst L1, worst area error, kind) of a Solution: the solver's own estimate."""
        est = sol.info["error_estimate"]
        area = max(float(np.max(est[q])) for q in ("elastic_area", "plastic_area", "noncontact_area"))
        L1 = float(np.nanmax(est["L1"])) if np.any(np.isfinite(est["L1"])) else area
        return L1, area, "estimate (" + str(est.get("method", "|run - half-resolution run|")) + ")"

    def first_options(self, problem, method, tol, zeta_out, options):
        """The front-fixed engine (fv, and mol's lines on the same fluxes): n cells and n steps from C / n^2."""
        n = 2 * int(np.clip(math.ceil(math.sqrt(self.C / tol) / 2), 25, 1600))  # even: the partner has n/2
        n = max(n, _min_engine_cells(problem, method, zeta_out, options or {}))
        if method == "mol":
            return {"n_p": n, "rtol": min(max(tol * 1e-2, 1e-12), 1e-3)}
        return {"n_p": n, "n_steps": n}

    def refine_cells(self, n_p: int, f: float) -> int:
        """n_p of the next attempt, ``f`` the growth of the steps (second order in both on the engine)."""
        return 2 * int(math.ceil(n_p * f / 2))

    def mol_growth(self, ratio: float) -> float:
        """Growth of mol's grid on a refinement (error ratio ``ratio``)."""
        return float(np.clip(1.2 * math.sqrt(ratio), 1.5, 8.0))

    def steps_limited(self, opts) -> int:
        """The count a refinement may not take beyond MAX_CELLS: cells, and steps on the engine."""
        return max(opts.get("n_p") or 0, opts.get("n_steps") or 0)

    def chebyshev_budget(self, problem, tol, budget):
        """The budget of a first ``"chebyshev"`` attempt, or None where this plan goes to fv directly."""
        if self.chebyshev == "always":
            return budget
        if self.chebyshev == "wall" and problem.fudge.name == "none" and tol < _CHEB_WALL_TOL:
            capped = dict(budget)
            capped["max_time"] = min(_CHEB_WALL_TIME, budget["max_time"] or math.inf)
            return capped
        return None


class _ClosedForm(_Plan):
    """A closed form exists: its error is measured against :func:`persson_fp.exact`; fv and mol refine on their
    error models of the closed-form scenes."""

    def solve(self, problem, zeta_out, tol, budget, max_time):
        """The sine series (the closed form summed to tol), or fv where the series cannot serve the scene."""
        why = (
            "a closed form exists: the sine series is that solution summed to tol (spectral; the fastest method "
            "at every tolerance measured in benchmarks/results)"
        )
        try:
            return solve_to_tol(problem, "sines", zeta_out, tol, why=why, **budget)
        except (ValueError, SolverError) as err:
            why = f"the sine series could not serve this scene ({err}); finite volumes with a resolution for tol"
            return solve_to_tol(problem, "fv", zeta_out, tol, why=why, **budget)

    def errors(self, sol):
        c = sol.compare()
        areas = [c.area_error]
        if c.plastic_area_error is not None:
            areas += [c.elastic_area_error, c.plastic_area_error]
        return float(np.max(c.L1)), float(max(np.max(a) for a in areas)), "true error (against pf.exact)"

    def first_options(self, problem, method, tol, zeta_out, options):
        if method == "mol":
            return {"rtol": min(max(tol * 1e-2, 1e-12), 1e-3)}
        n_steps = int(np.clip(math.ceil(math.sqrt(2.0 * _C_FV_STEPS / tol)), 20, 20000))
        n_p = int(np.clip(math.ceil((2.0 * _C_FV_CELLS / tol) ** 0.25), 50, 20000))
        return {"n_p": n_p, "n_steps": n_steps}

    def refine_cells(self, n_p: int, f: float) -> int:
        return 2 * int(math.ceil(n_p * f**0.5 / 2))  # (fourth order in p)

    def mol_growth(self, ratio: float) -> float:
        return 1.5

    def steps_limited(self, opts) -> int:
        return max(opts.get("n_p") or 0, 0)


_PLANS = {
    frozenset(): _ClosedForm(),
    frozenset({"general"}): _Plan(_C_GENERAL, "general Fokker-Planck coefficients", "always"),
    frozenset({"moving_wall"}): _Plan(_C_FRONT, "a scale-dependent hardness", "wall"),
    frozenset({"general", "moving_wall"}): _Plan(_C_GENERAL, "a scale-dependent hardness"),
}
"""The plan of each problem kind, keyed by what the problem needs beyond the closed forms (``features`` less a
constant hardness, which the strip solves in closed form)."""


def _plan_of(problem) -> _Plan:
    return _PLANS[problem.features - {"hardness"}]


def _errors(sol):
    """(worst L1, worst area error, kind) of a Solution: against pf.exact, or the solver's own estimate."""
    return _plan_of(sol.problem).errors(sol)


def _min_engine_cells(problem, method, zeta_out, options) -> int:
    """Cells for the front-fixed engine's first attempt: ``_CELLS_PER_WIDTH`` x the fewest it accepts, even."""
    from persson_fp.solvers.front_fixed.moving_wall import min_cells

    k = options.get("k_domain", get_solver(method).OPTIONS.get("k_domain", 10.0))
    z = problem.zeta_max if zeta_out is None else zeta_out
    V_st = np.atleast_1d(np.asarray(problem.V(np.atleast_1d(np.asarray(z, dtype=float))), dtype=float))
    return 2 * int(math.ceil(_CELLS_PER_WIDTH * min_cells(problem, V_st, k) / 2))


def _first_options(problem, method, tol, zeta_out=None, options=None):
    if method == "sines":
        return {"tol": min(max(tol * 1e-2, 1e-14), 1e-2)}
    return _plan_of(problem).first_options(problem, method, tol, zeta_out, options)


def _refine(method, opts, problem, ratio):
    """Options one refinement finer, scaled by the error ratio (err / tol) where the order is known."""
    out = dict(opts)
    if method == "sines":
        out["tol"] = max(opts["tol"] * 1e-2, 1e-15)
    elif method == "mol":
        out["rtol"] = max(opts["rtol"] * 1e-2, 1e-13)
        f = _plan_of(problem).mol_growth(ratio)
        out["n_p"] = 2 * int(math.ceil(f * (opts.get("n_p") or 200) / 2))
    else:
        f = float(np.clip(1.2 * math.sqrt(ratio), 1.5, 8.0))  # second order in both (front-fixed) or in steps
        out["n_steps"] = 2 * int(math.ceil(opts["n_steps"] * f / 2))
        out["n_p"] = _plan_of(problem).refine_cells(opts["n_p"], f)
    return out


class _TooMuchWork(Exception):
    """A work-capped :func:`solve_to_tol` stopped before an attempt over its ``max_work``: ``options`` that attempt's,
    ``attempts`` those run."""

    def __init__(self, options, attempts):
        super().__init__(f"next attempt {options} over the work cap")
        self.options, self.attempts = options, attempts


def solve_to_tol(
    problem,
    method: str,
    zeta_out,
    tol: float,
    why: str = "",
    *,
    max_memory=None,
    max_time=None,
    max_work=None,
    **options,
):
    """Solve with ``method`` at a resolution chosen for ``tol``, check the error, refine until it meets ``tol``.

    ``max_memory`` / ``max_time`` bound every attempt (the solver's own estimate refuses one that would exceed
    them) and ``max_time`` also the whole refinement: a refinement whose predicted time (the last attempt's, scaled
    by the growth of n_p x n_steps) would overrun it is refused with a :class:`~persson_fp.SolverError`.  With
    ``max_work`` (auto's own use), an attempt whose n_p x n_steps would exceed it is not run: ``_TooMuchWork``
    carries its options."""
    from persson_fp.solvers.base import check_budgets, check_zeta_out

    t0 = time.perf_counter()
    check_zeta_out(problem, zeta_out)  # (before _first_options plans with it)
    check_budgets(max_memory, max_time)
    opts = {**_first_options(problem, method, tol, zeta_out, options), **options}
    budget = {"max_memory": max_memory, "max_time": max_time}
    attempts = []
    _check_cells(method, tol, opts, problem, attempts, math.inf, math.inf, "no attempt yet")
    for k in range(MAX_REFINE + 1):
        if max_work is not None and _work(opts) > max_work:
            raise _TooMuchWork(dict(opts), attempts)
        if max_time is not None and attempts:
            prev = attempts[-1]
            grow = _work(opts) / max(_work(prev["options"]), 1.0)
            predicted = prev["wall_time"] * grow
            left = max_time - (time.perf_counter() - t0)
            if predicted > left:
                raise SolverError(
                    f"{method}: tol = {tol:g} not met within max_time = {max_time:g} s (best: L1 {prev['L1']:.3e}, "
                    f"area error {prev['area_error']:.3e}; the next refinement would take about {predicted:.3g} s, "
                    f"{left:.3g} s are left); ask for a looser tol or a larger max_time"
                )
            budget["max_time"] = left
        t_try = time.perf_counter()
        try:
            sol = get_solver(method)(problem, zeta_out=zeta_out, **budget, **opts).run()
        except SolverError as err:  # an invariant breached (e.g. ringing on a coarse grid): refine, unless the last
            if k == MAX_REFINE or "max_time" in str(err):
                raise
            L1 = area = math.inf
            kind = f"failed: {str(err)[:200]}"
            attempts.append({"options": dict(opts), "L1": L1, "area_error": area, "wall_time": 0.0, "failed": kind})
            attempts[-1]["wall_time"] = time.perf_counter() - t_try
            opts = _refine(method, opts, problem, 16.0)
            _check_cells(method, tol, opts, problem, attempts, L1, area, kind)
            continue
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
        far = sol.info.get("error_estimate", {}).get("parts", {}).get("far_wall", 0.0)
        if far > 0.25 * tol:  # the far wall took mass that matters: grow the domain (and the cells with it)
            k = float(opts.get("k_domain", get_solver(method).OPTIONS.get("k_domain", 10.0)))
            opts["k_domain"] = 1.5 * k
            opts["n_p"] = 2 * int(math.ceil(1.5 * opts["n_p"] / 2))
            attempts[-1]["grow_domain"] = f"far-wall loss {far:.2e} > tol / 4: k_domain {k:g} -> {1.5 * k:g}"
        _check_cells(method, tol, opts, problem, attempts, L1, area, kind)
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


def _check_cells(method, tol, opts, problem, attempts, L1, area, kind) -> None:
    """SolverError when the next attempt would need more than MAX_CELLS cells or steps (refused before it runs)."""
    if _plan_of(problem).steps_limited(opts) > MAX_CELLS:
        best = attempts[-1]["options"] if attempts else opts
        raise SolverError(
            f"{method}: tol = {tol:g} would need more than {MAX_CELLS} cells/steps (best so far: L1 {L1:.3e}, area "
            f"error {area:.3e}, {kind}, with {best}); ask for a looser tol"
        )


def _work(opts) -> float:
    """Relative cost of an attempt: n_p x n_steps (or n_p alone where no steps are set)."""
    return float(opts.get("n_p") or 200) * float(opts.get("n_steps") or 1)


def solve_auto(problem, zeta_out=None, tol: float = 1e-6, *, max_memory=None, max_time=None, **options):
    """``method="auto"``: the cheapest way to ``tol`` (module docstring)."""
    from persson_fp.solvers.base import check_budgets, check_float, check_zeta_out

    tol = check_float(tol, "tol", 1e-15, 1e-1, lo_open=False)  # no double-precision result is checkable below
    if options:
        raise TypeError(f"method 'auto' chooses the resolution itself; it takes only tol and zeta_out, got {options}")
    # checked here, before any attempt: a bad value would otherwise meet auto's own planning first
    check_zeta_out(problem, zeta_out)
    check_budgets(max_memory, max_time)
    budget = {"max_memory": max_memory, "max_time": max_time}
    return _plan_of(problem).solve(problem, zeta_out, tol, budget, max_time)


_CHEB_PATHS = {
    "moving-wall": "a moving yield wall, front-fixed (x = p / sigma_Y): Chebyshev collocation in x, an adaptive "
    "exponential march in V",
    **{
        path: "general coefficients (path {path!r}): Chebyshev collocation in p, exact exponentials or an adaptive "
        "march in V (Radau IIA; or exponential steps)"
        for path in ("exponential", "clock", "radau", "magnus")
    },
}
"""auto's words for each path of ``"chebyshev"`` (``sol.info["path"]``)."""


def _solve_chebyshev(problem, zeta_out, tol, budget):
    """General coefficients without a moving wall: method "chebyshev" (spectral in p; exact in V for b(p) g(zeta),
    an adaptive Radau IIA march otherwise; its own loop meets ``tol`` -- 5-25 ms for 1e-4 ... 1e-10 on the
    reference problem in ``benchmarks/results/general_engine.md``, where fv needs seconds for 1e-6; the
    zeta-dependent and hardness cases in ``benchmarks/results/general_engine_wide.md``)."""
    t0 = time.perf_counter()
    sol = get_solver("chebyshev")(problem, zeta_out=zeta_out, tol=min(tol, 1e-1), **budget).run()
    L1, area, kind = _errors(sol)
    what = _CHEB_PATHS[sol.info["path"]].format(path=sol.info["path"])
    sol.info["auto"] = {
        "method": "chebyshev",
        "why": f"{what}, degree, start and march refined until the estimate (3/4-degree and 4 V0 partners, the "
        "march's own estimate) meets tol",
        "tol": tol,
        "L1": L1,
        "area_error": area,
        "kind": kind,
        "attempts": [{"options": {"tol": tol}, "L1": L1, "area_error": area, "wall_time": sol.wall_time}],
        "total_time": time.perf_counter() - t0,
    }
    return sol
