"""The invariants every numerical solution of Persson's diffusion problem keeps, and the errors a breach raises.

:func:`check_invariants` is called once per :class:`~persson_fp.Solution` (in ``Solution.from_output``): finite
values, A* in [0, 1] and non-increasing (the Xu et al. tutorial, Eq. 'eq:Area'), the load balance
(Eq. 'eq:Load_equilibrium'; with a hardness the plastic load counts) and P0 >= 0, each against a tolerance tied
to the method's own accuracy.  A breach raises :class:`~persson_fp.SolverError` naming the invariant and the remedy.

This module imports no solver.
"""

from __future__ import annotations

import math
import warnings
from types import MappingProxyType

import numpy as np

from persson_fp._errors import InstabilityError, SolverError

__all__ = ["SolverError", "InstabilityError", "DEFAULT_TOLERANCES", "check_invariants"]


DEFAULT_TOLERANCES = MappingProxyType({"load": 1e-2, "area": 1e-6, "negative": 1e-2})
"""Invariant tolerances of :func:`check_invariants` unless a method states its own (read-only: a method copies it)
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


def check_invariants(sol, tolerances=None, *, raise_on_breach=True, extrema=None) -> dict:
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
        True: a breached invariant raises :class:`~persson_fp.SolverError` naming it and the remedy; False: a
        ``RuntimeWarning`` with the same text (and ``info["warnings"]``).
    extrema : tuple of float, optional
        ``(min P0, max P0)`` over every element, where the caller has them (``Solution.from_output`` takes them for its
        finiteness check); default computed here.

    Returns
    -------
    dict
        ``min_P0``, ``negative_P0`` (any undershoot), ``area_increase`` (largest, relative to A*),
        ``area_monotone``, ``max_load_drift`` (relative), ``breaches`` (names of the broken invariants).
    """
    if tolerances is None or tolerances is DEFAULT_TOLERANCES:
        tol = DEFAULT_TOLERANCES
    else:
        tol = {**DEFAULT_TOLERANCES, **tolerances}
    A = sol.contact_area_all  # (a model with more contact states checks each area and their sum here)
    load = sol.load_all  # the supported load; a model with a yield wall adds its plastic share here
    if A.size == 1 and extrema is not None:
        checks = _one_clean(sol, tol, A.item(), load.item(), extrema)
        if checks is not None:
            return checks
    p_bar = sol.problem.p_bar
    P = sol.P0_all
    checks = {}
    breaches = []  # (invariant, message)

    finite = _all_finite(A) and _all_finite(load)
    if not finite:
        breaches.append(("finite", "A* or the load is NaN or inf"))
        A = np.nan_to_num(A, nan=np.inf)

    # 2. A* in [0, 1], non-increasing (relative to A*, so that tiny loads are checked as closely)
    a_min, a_max = _lo_hi(A)
    checks["area_range"] = (a_min, a_max)
    if a_min < -tol["area"] or a_max > 1.0 + tol["area"]:
        bad = (A < -tol["area"]) | (A > 1.0 + tol["area"])
        i, j = np.argwhere(bad)[0]
        breaches.append(("area_range", f"A* = {A[i, j]:.6g} outside [0, 1] at {_where(sol, i, j)}"))
    if A.shape[0] > 1:
        with np.errstate(invalid="ignore", divide="ignore"):
            # (an area drained to round-off -- 1e-160 after a drift into the wall -- is judged against 1e-13 of the
            # load's largest area, not against itself; a tiny load's areas are all tiny and still checked closely)
            floor = np.maximum(1e-13 * np.max(np.abs(A), axis=0, keepdims=True), np.finfo(float).tiny)
            rel_inc = np.diff(A, axis=0) / np.maximum(np.abs(A[:-1]), floor)
        if not np.isfinite(rel_inc).all():
            rel_inc = np.nan_to_num(rel_inc, nan=np.inf)
        checks["area_increase"] = float(max(rel_inc.max(initial=0.0), 0.0))
    else:  # one station: nothing can grow
        checks["area_increase"] = 0.0
    checks["area_monotone"] = checks["area_increase"] <= tol["area"]
    if not checks["area_monotone"]:
        i, j = np.unravel_index(np.argmax(rel_inc), rel_inc.shape)
        breaches.append(
            (
                "area_monotone",
                f"A* grows by {rel_inc[i, j]:.3e} (relative, > {tol['area']:.1e}) up to {_where(sol, i + 1, j)} "
                "(contact can only be lost, eq:Area)",
            )
        )

    # 2b. mass balance: A* from the PDF against 1 - (what the walls absorbed), where the solver kept the wall fluxes
    #     (fv, the engine); the far wall's loss is allowed, being reported (info["far_wall_mass"]) and estimated
    flux = getattr(sol, "contact_area_flux_all", None)
    if flux is not None:
        far = float(sol.info.get("far_wall_mass") or 0.0)
        with np.errstate(invalid="ignore"):  # (A* holds A_pl where a yield wall makes one: the walls' balance is 1)
            gap = np.abs(A - flux)
        gap = np.nan_to_num(gap, nan=np.inf)
        checks["mass_balance"] = float(np.max(gap, initial=0.0))
        if checks["mass_balance"] > far + MASS_BALANCE_TOL:
            i, j = np.unravel_index(np.argmax(gap), gap.shape)
            breaches.append(
                (
                    "mass_balance",
                    f"A* = {A[i, j]:.6g} but 1 - (absorbed at the walls) = {flux[i, j]:.6g} at {_where(sol, i, j)} "
                    f"(off by {gap[i, j]:.3e} > the far-wall loss {far:.3e} + {MASS_BALANCE_TOL:.0e})",
                )
            )

    # 3. load balance, or for general coefficients the first-moment law the solver integrated alongside
    #    (d/dzeta int p P dp = int B1 P dp - p_max J(p_max): info["load_law"], what the load must be at each station)
    law = sol.info.get("load_law")
    conserved = sol.problem.conserved_load  # p_bar (eq:Load_equilibrium), or None where a drift moves the load
    if law is None and load.size == 1:  # one station, one load: Python floats (inf on overflow, never a warning)
        pb = float(p_bar[0])
        d = abs(float(load.item()) - pb) / pb
        checks["max_load_drift"] = d = d if math.isfinite(d) else math.inf
        drift = None  # (an array only where the element-wise test below needs it)
    else:
        expected = p_bar if law is None else np.asarray(law, dtype=float).reshape(load.shape)
        with np.errstate(invalid="ignore", over="ignore"):
            drift = np.abs(load - expected) / p_bar
        if not (finite and _all_finite(drift)):
            drift = np.nan_to_num(drift, nan=np.inf)
        checks["max_load_drift"] = _lo_hi(drift)[1]
    tol_l = tol["load"]
    extra = sol.info.get("load_law_tolerance")  # the solver's estimate of the law's and the load's own errors
    checks["load_law"] = "first-moment law" if law is not None else ("none" if conserved is None else "load balance")
    if conserved is None and law is None:  # a solver without the moment law has nothing to check the load against
        sol.info.setdefault("warnings", []).append("general coefficients: the solver gave no first-moment law")
    tol_min = tol_l if isinstance(tol_l, float) else float(np.min(tol_l))
    over = None
    # the element-wise test only where the largest drift exceeds the smallest tolerance (the common case skips it)
    if (law is not None or conserved is not None) and (extra is not None or checks["max_load_drift"] > tol_min):
        if drift is None:
            drift = np.full(load.shape, d)
        tol_load = np.broadcast_to(np.asarray(tol_l, dtype=float), drift.shape)
        if law is not None and extra is not None:
            tol_load = tol_load + np.asarray(extra, dtype=float).reshape(drift.shape) / p_bar
        over = drift > tol_load
    if over is not None and over.any():
        i, j = np.unravel_index(np.argmax(np.where(over, drift / tol_load, -np.inf)), drift.shape)
        what = (
            "the first-moment law int p P0 dp = p_bar + int int B1 P0 dp dzeta - p_max J"
            if law is not None
            else ("p_bar (eq:Load_equilibrium)")
        )
        breaches.append(
            (
                "load_balance",
                f"int p P0 dp deviates from {what} by {drift[i, j]:.3e} (relative to p_bar, > {tol_load[i, j]:.1e}) "
                f"at {_where(sol, i, j)}",
            )
        )

    # 4. P0 >= 0 (small undershoots are reported, large ones are breaches).  A dip is judged against the peak
    #    only where it carries mass: a strip that has drained (peak 1e-117) may dip to -1 x its peak in round-off,
    #    and that is no error in any area (the areas are fractions of the nominal area, which starts at 1)
    if extrema is None:
        extrema = (float(P.min()), float(P.max())) if P.size else (0.0, 0.0)
    checks["min_P0"] = p_lo = extrema[0]
    rel_neg = None
    if p_lo >= 0.0:  # no undershoot anywhere (the common case): nothing to weigh
        checks["negative_mass"] = 0.0
        checks["negative_P0"] = False
    elif tol["negative"] >= 1e-10 and P.size == P.shape[-1] and -p_lo <= 1e-10 * max(extrema[1], -p_lo):
        # one (station, load) whose dips are round-off of its own peak (max |P0| = max(max P0, -min P0)): neither a
        # breach (tol["negative"] >= 1e-10) nor an undershoot to report; the negative mass is then bounded by
        # -min(P0) x the grid's width
        checks["negative_mass"] = -p_lo * float(sol.weights.sum())
        checks["negative_P0"] = False
    else:
        peak = np.max(np.abs(P), axis=-1)
        low = np.min(P, axis=-1)
        neg_mass = _negative_mass(sol, P)
        checks["negative_mass"] = float(np.max(neg_mass, initial=0.0))
        checks["negative_P0"] = bool(np.any((low < -1e-10 * np.max(peak, initial=0.0)) & (neg_mass > NEGLIGIBLE_MASS)))
        with np.errstate(invalid="ignore", divide="ignore"):
            rel_neg = np.where(peak > 0, -low / np.where(peak > 0, peak, 1.0), 0.0)
        rel_neg = np.where(neg_mass > NEGLIGIBLE_MASS, rel_neg, 0.0)
    if rel_neg is not None and np.any(rel_neg > tol["negative"]):
        i, j = np.unravel_index(np.argmax(rel_neg), rel_neg.shape)
        breaches.append(
            (
                "positivity",
                f"P0 dips to {low[i, j]:.3e} = -{rel_neg[i, j]:.2e} x its peak (> {tol['negative']:.1e}) at "
                f"{_where(sol, i, j)} (oscillations: refine, or use an L-stable scheme)",
            )
        )
    elif checks["negative_P0"]:
        msg = f"P0 has negative values down to {checks['min_P0']:.3e} (oscillations: refine or use an L-stable scheme)"
        sol.info.setdefault("warnings", []).append(msg)
        warnings.warn(f"{sol.method}: {msg}", RuntimeWarning, stacklevel=6)

    checks["breaches"] = [name for name, _ in breaches] if breaches else []
    if breaches:
        text = f"{sol.method}: invariant(s) broken: " + "; ".join(f"{n}: {m}" for n, m in breaches) + f". {_REMEDY}"
        if raise_on_breach:
            raise SolverError(text)
        sol.info.setdefault("warnings", []).append(text)
        warnings.warn(text, RuntimeWarning, stacklevel=6)
    return checks


def _one_clean(sol, tol, a, load, extrema):
    """The checks of one station and one load that keeps every invariant, in Python floats (the lean path of a
    single solve: ~2 us instead of ~5); None where anything needs the full check (a breach to name, an undershoot
    to weigh, wall fluxes, a first-moment law), which then decides."""
    if getattr(sol, "contact_area_flux_all", None) is not None or sol.info.get("load_law") is not None:
        return None
    if sol.problem.conserved_load is None:  # (a drift moves the load: the full check decides)
        return None
    t_area, t_load = tol["area"], tol["load"]
    if not (math.isfinite(a) and math.isfinite(load) and -t_area <= a <= 1.0 + t_area) or type(t_load) is not float:
        return None
    pb = float(sol.problem.p_bar[0])
    d = abs(load - pb) / pb
    if not d <= t_load:  # (NaN included)
        return None
    p_lo, p_hi = extrema
    if p_lo >= 0.0:
        neg = 0.0
    elif tol["negative"] >= 1e-10 and -p_lo <= 1e-10 * max(p_hi, -p_lo):  # round-off of its own peak (as below)
        neg = -p_lo * float(np.add.reduce(sol.weights, axis=None))
    else:
        return None
    return {
        "area_range": (a, a),
        "area_increase": 0.0,
        "area_monotone": True,
        "max_load_drift": d,
        "load_law": "load balance",
        "min_P0": p_lo,
        "negative_mass": neg,
        "negative_P0": False,
        "breaches": [],
    }


MASS_BALANCE_TOL = 1e-8
"""Allowed |A* - (1 - absorbed)| beyond the reported far-wall loss (round-off of the flux accumulation)."""

NEGLIGIBLE_MASS = 1e-13
"""A negative part of P0 with less mass than this (a fraction of the nominal area) is round-off, whatever its
ratio to a vanishing peak."""


def _negative_mass(sol, P):
    """int max(-P0, 0) dp per (station, load), with the solution's quadrature weights where it has them."""
    if not P.shape[-1]:
        return np.zeros(P.shape[:-1])
    w = np.asarray(sol.weights, dtype=float)
    w = w[:, None, :] if w.ndim == 2 else w  # (n_zeta, n_p) weights of a moving grid: one row per station
    return np.sum(np.maximum(-P, 0.0) * np.asarray(w, dtype=float), axis=-1)


def _lo_hi(a):
    """(min, max) of an array as floats; one element is read directly (numpy's reductions cost ~1 us each)."""
    if a.size == 1:
        x = float(a.item())
        return x, x
    return float(a.min()), float(a.max())


def _all_finite(a) -> bool:
    """Whether every element of ``a`` is finite (one element read directly)."""
    if a.size == 1:
        return math.isfinite(a.item())
    return bool(np.isfinite(a).all())


def _where(sol, i, j) -> str:
    """Station ``i`` (and load ``j`` where there are several) of ``sol``, for a message."""
    s = f"zeta = {sol.zeta[i]:.6g}"
    if sol.problem.n_loads > 1 or not sol.problem.scalar_load:
        s += f", p_bar = {sol.problem.p_bar[j]:.6g}"
    return s
