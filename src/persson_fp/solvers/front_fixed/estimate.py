r"""The error estimate of the front-fixed engine (moving yield wall, general coefficients), and its checks.

Every run is paired with one at half the cells (and, for ``"fv"``, half the steps) from the same start: the
Richardson difference :math:`|Q_h - Q_{2h}|` (taken as the error: conservative, 3x over at second order) for every
area and load at every station.  General coefficients add two parts the pair cannot see: the start-up (a Gaussian
along the mean path, exact only for p-independent coefficients), measured by a third run at n/2 from twice the
start-up variance; and, without a hardness, the mass the far wall took away (``info["far_wall_mass"]``), which the
true elastic and non-contact areas may each hold.  ``info["error_estimate"]["parts"]`` lists the three.  The
first-moment law :math:`F_{el} + s\,a = L_0 + \int\int b_1 P\,dp\,dV` (the absorbing wall at p = 0 carries no
load) is integrated alongside the march and handed to the invariant check as ``info["load_law"]``.
"""

from __future__ import annotations

import time

import numpy as np

from persson_fp._warn import warn_user
from persson_fp.results.solution import SolverError
from persson_fp.solvers.front_fixed.models import STATION_FLOOR, model_of
from persson_fp.solvers.front_fixed.moving_wall import MovingWall, check_resolved

__all__ = ["richardson", "run_pair", "finish", "STATION_FLOOR", "LARGE_ESTIMATE"]

LARGE_ESTIMATE = 1e-2
"""An error estimate of the areas above this is warned about (a RuntimeWarning; the result is still returned)."""

_QUANTITIES = ("elastic_area", "plastic_area", "noncontact_area", "elastic_load", "plastic_load")


def richardson(fine: dict, coarse: dict, order: float = 2.0) -> dict:
    """Richardson estimate of the fine run's error, |Q_h - Q_2h| / (2^order - 1), per quantity (n_st, m)."""
    f = 2.0**order - 1.0
    return {q: np.abs(fine[q] - coarse[q]) / f for q in _QUANTITIES}


def run_pair(problem, V_st, zeta_st, n: int, zeta0, k_domain: float, run, max_time: float = np.inf):
    """The run at n cells and its partner at n/2 from the same start: ``run(mw, V_st, V0=V0, level=level)`` (level 0, 1)
    returns the per-station dict of :meth:`MovingWall.solve`; the resolution of the stations (V_st, zeta_st) is checked
    first, and every run stops with a ``SolverError`` once ``max_time`` seconds have passed.

    General coefficients: the start (a frozen-coefficient Gaussian) is not exact, and a partner that shares it
    cannot see its error.  A third run at n/2 from twice the start-up variance measures it:
    ``fine["start_error"] = |Q(n/2, 2 V0) - Q(n/2, V0)|`` (an upper bound for a start error of order >= 1 in V0;
    the two coarse runs share their grid, so their difference is the start alone)."""
    pr = problem
    V_st = np.asarray(V_st, dtype=float)
    model = model_of(pr)
    p_end, dom = pr.upper_wall.grid_cut(lambda: model.domain_end(pr, k_domain))
    check_resolved(pr, V_st, n, zeta_st, k_domain, p_end)
    deadline = time.perf_counter() + float(max_time)

    def grid(cells):
        mw = MovingWall(pr, cells, k_domain, p_end)
        mw.deadline = deadline
        return mw

    fine = run(grid(n), V_st, V0=_start_V(pr, zeta0), level=0)
    coarse = run(grid(max(n // 2, 4)), V_st, V0=fine["V0"], level=1)
    fine["domain"] = dom
    model.start_partner(run, grid, n, V_st, fine, coarse)  # (general coefficients: the start's own error)
    return fine, coarse


def _parts(parts: dict) -> str:
    return ", ".join(f"{k} {v:.2e}" for k, v in parts.items())


def _start_V(pr, zeta0):
    V0 = None if zeta0 is None else float(pr.V(zeta0))
    if V0 is not None and V0 <= 0.0:
        raise ValueError("zeta0 must be > 1 for a moving yield wall (the start is the PDF at zeta0, not the delta)")
    return V0


def finish(problem, n: int, fine: dict, coarse: dict, what: str, tol, info_extra: dict, name: str) -> dict:
    """Checks and error estimate of a paired run of the engine, and what the method hands on: a dict with the fields
    of ``SolverOutput`` (``persson_fp.results.output``: p, P0, weights, kind, info and the areas); ``name`` (the
    method's) heads a warning."""
    pr = problem
    est = richardson(fine, coarse, order=1.0)  # conservative: exact for first order, 3x over at second
    Wf, Wc = fine["W"], coarse["W"]
    if Wf.shape[-1] == 2 * Wc.shape[-1]:  # L1 of P: the fine cells averaged in pairs onto the coarse grid
        est["L1"] = np.abs(0.5 * (Wf[..., 0::2] + Wf[..., 1::2]) - Wc).sum(axis=-1) / Wc.shape[-1]
    else:
        est["L1"] = np.full(fine["elastic_area"].shape, np.nan)
    parts = {"discretisation": max(float(np.max(est[q])) for q in ("elastic_area", "plastic_area", "noncontact_area"))}
    start = fine.get("start_error")
    if start is not None:  # the approximate start, measured apart from the Richardson pair (run_pair)
        for q in est:
            est[q] = est[q] + start[q]
        parts["start"] = max(float(np.max(start[q])) for q in ("elastic_area", "noncontact_area"))
    model = model_of(pr)
    far = pr.upper_wall.loss(fine["plastic_area"])
    if far is not None:  # mass lost through the far cut: the true A_el and A_non may hold up to it each
        for q in ("elastic_area", "noncontact_area", "L1"):
            est[q] = est[q] + far
        # A* = A_el = 1 - A_non - A_far: Solution reads the A* estimate from the A_non one, so it holds both
        est["noncontact_area"] = np.maximum(est["noncontact_area"], est["elastic_area"])
        parts["far_wall"] = float(np.max(far))
    est = model.floor_stations(est)  # (general coefficients: no station below a fraction of its neighbours')
    area_sum = fine["elastic_area"] + fine["plastic_area"] + fine["noncontact_area"]
    area_residual = float(np.max(np.abs(area_sum - 1.0)))
    # the first-moment law: F_el + s a = L0 + int int b1 P dp dV (the wall at p = 0 carries no load; without a
    # hardness s a is what the far wall took away, with one it is the plastic load)
    L0 = model.start_load(fine, pr)
    law_total = L0[None, :] + fine["drift_load"]
    total = fine["elastic_load"] + fine["plastic_load"]
    # the law and the load are both discrete: each carries its own discretisation error (Richardson, as above);
    # the residual beyond them is what breaks the law
    law_err = model.law_error(fine, coarse, law_total, total)
    load_residual = float(np.max(np.abs(total - law_total) / pr.p_bar))
    load_excess = float(np.max(np.maximum(np.abs(total - law_total) - law_err, 0.0) / pr.p_bar))
    if area_residual > 1e-10:
        raise SolverError(
            f"moving wall: the areas do not sum to 1 (residual {area_residual:.3e}): the conservative scheme broke; "
            "this is a bug or an unstable step -- raise n_steps"
        )
    worst_area = max(float(np.max(est[q])) for q in ("elastic_area", "plastic_area", "noncontact_area"))
    if tol is not None and (worst_area > tol or load_excess > tol):
        raise SolverError(
            f"moving wall / general engine: the error estimate {worst_area:.3e} (areas: {_parts(parts)}) or the "
            f"load residual beyond its estimate {load_excess:.3e} exceeds tol = {tol:.3g}; raise n_p and n_steps "
            "(both enter at second order)"
            + ("; a far-wall loss shrinks with a larger k_domain" if far is not None else "")
        )
    if worst_area > LARGE_ESTIMATE and tol is None:
        msg = (
            f"the error estimate of the areas is {worst_area:.2e} ({_parts(parts)}): a coarse answer; raise n_p and "
            "n_steps, or ask for an accuracy with tol="
        )
        info_extra = {**info_extra, "warnings": [msg]}
        warn_user(f"{name}: {msg}", RuntimeWarning)
    s = fine["s"]
    p = s[:, None] * (np.arange(n) + 0.5)[None, :] / n
    info = {
        "grid": {"n_p": n, "mapping": "x = p / sigma_Y(zeta)", "p_max": s},
        "zeta0": fine["zeta0"],
        **info_extra,
        "moving_wall": True,
        "error_estimate": {**est, "method": what, "max_area": worst_area, "parts": parts},
        "area_residual": area_residual,
        "load_residual": load_residual,
        # what sol.load (int p P0 dp + sigma_Y A_pl) must equal by the first-moment law (checked by the invariants)
        "load_law": law_total - pr.upper_wall.lost_mass(fine["plastic_load"]),
        "load_law_tolerance": law_err,  # (pressure) the discretisation error of law and load, allowed on top
        "start_plastic_area": fine["start_plastic_area"],
        "far_wall_mass": float(np.max(pr.upper_wall.lost_mass(fine["plastic_area"]))),
        "max_cell_peclet": fine["max_cell_peclet"],
        **({"domain": fine["domain"]} if fine.get("domain") else {}),
        **({"start_V": fine["start_V"]} if "start_V" in fine else {}),
    }
    return dict(
        p=p,
        P0=fine["W"] / s[:, None, None],
        weights=np.broadcast_to((s * (1.0 / n))[:, None], p.shape).copy(),
        kind="cell",
        info=info,
        contact_area=fine["elastic_area"],
        contact_area_flux=1.0 - fine["noncontact_area"] - pr.upper_wall.lost_mass(fine["plastic_area"]),
        plastic_area=pr.upper_wall.plastic_area(fine["plastic_area"]),
    )
