"""``method="auto"`` on the moving wall against the best hand-picked fixed ``fv`` resolution.

Scene W, the moving wall: ``SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1, q_r=2, q_s=128)``, p_bar = 0.03,
``hardness=PowerLaw(sigma_1=0.035, n=0.2)`` (the wall 0.1 sqrt(V) above the load at zeta = 1, moving fast at small
zeta), one station at zeta_max.  For each tol (1e-3 ... 1e-6):

* auto: the whole ``pf.solve(problem, "auto", tol=tol)`` call, what it chose, its true errors -- the L1 of P0 and the
  worst of A_el, A_pl, A_non -- against fv on 1600, 3200 and 6400 cells and steps (areas: Aitken's delta-squared
  extrapolation, its spread to the order-2 Richardson value the reference's uncertainty; L1: against the 6400-cell
  CDF, a cubic spline, whose own estimate is its uncertainty; as in ``benchmarks/plasticity.py``, scene D);
* the best hand-picked fixed resolution: the cheapest ``fv`` (n_p, n_steps) on a doubling grid (n_p = 25 x 2^k,
  n_steps = n_p / 2, n_p, 2 n_p) whose true error (the larger of L1 and the areas' error) is no larger than auto's --
  or than the reference's uncertainty, where auto's is below what the reference resolves.  Candidates are tried in
  order of work n_p x n_steps (one skipped where a finer pair in both already failed); the first that passes is the
  cheapest by work;
* auto and that fv run are then timed interleaved (auto, fv, auto, fv, ...: the machine is shared), first calls apart,
  medians; ``ratio`` = auto / best fv (the target: <= 1.2).

    python benchmarks/moving_wall_auto.py [--quick]  ->  results/moving_wall_auto.{csv,md}

``--quick`` (CI): the station at zeta = 8, reference fv on 400 / 800 / 1600, tols 1e-3 and 1e-4, one repeat.
"""

from __future__ import annotations

import math
import os
import statistics
import time
import warnings

import numpy as np
from _common import machine, outdir, parser, write_csv
from plasticity import moving_reference

import persson_fp as pf

SCENE = "W: moving wall (p_bar = 0.03, sigma_Y = 0.035 zeta^0.2, zeta to 128)"


def scene(q_s: float = 128.0) -> pf.ContactProblem:
    """Scene W; a smaller ``q_s`` cuts the same spectrum (the same C0) short: the same problem to zeta = q_s."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    if q_s != 128.0:
        psd = pf.SelfAffinePSD(C0=psd.C0, H=0.8, q_l=1.0, q_r=2.0, q_s=q_s)
    return pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


def true_errors(sol, ref, cdf) -> tuple[float, float]:
    """(L1 of P0 at the last station, worst area error) against the reference (``moving_reference``)."""
    p, w = np.atleast_2d(sol.p)[-1], np.atleast_2d(sol.weights)[-1]
    if sol.kind == "point":  # (point values: the reference density at the nodes, the spline's derivative)
        l1 = float(np.sum(np.abs(sol.P0_all[-1, 0] - cdf(p, 1)) * w))
    else:  # (cell averages: the reference's averages over the same cells)
        e = np.concatenate((p - 0.5 * w, [p[-1] + 0.5 * w[-1]]))
        l1 = float(np.sum(np.abs(sol.P0_all[-1, 0] - np.diff(cdf(e)) / np.diff(e)) * np.diff(e)))
    area = max(abs(float(np.ravel(getattr(sol, q))[-1]) - ref[q]) for q in ref)
    return l1, area


def _call(fn):  # (seconds, result)
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


class FixedFv:
    """fv at fixed (n_p, n_steps): true errors cached, so that every tol's search shares them."""

    def __init__(self, pr, zeta_out, ref, cdf):
        self.pr, self.zeta_out, self.ref, self.cdf = pr, zeta_out, ref, cdf
        self.seen: dict = {}

    def solve(self, n_p, n_steps):
        return pf.solve(self.pr, "fv", n_p=n_p, n_steps=n_steps, zeta_out=self.zeta_out)

    def error(self, n_p, n_steps) -> tuple[float, float]:
        """(max(true L1, true area error), seconds of one call)."""
        key = (n_p, n_steps)
        if key not in self.seen:
            t0 = time.perf_counter()
            try:
                sol = self.solve(n_p, n_steps)
                err = max(true_errors(sol, self.ref, self.cdf))
            except pf.SolverError:  # (too coarse: an invariant broken -- a miss)
                err = math.inf
            self.seen[key] = (err, time.perf_counter() - t0)
        return self.seen[key]

    def cheapest(self, target: float, levels):
        """The cheapest pair by work whose true error <= target, or None (and the pairs tried)."""
        pairs = sorted(
            {(n, s) for n in levels for s in (n // 2, n, 2 * n) if s >= 10},
            key=lambda q: (q[0] * q[1], q[0]),
        )
        failed = []
        for n_p, n_steps in pairs:
            if any(f[0] >= n_p and f[1] >= n_steps for f in failed):
                continue  # (a finer pair in both already missed the target)
            err, _ = self.error(n_p, n_steps)
            if err <= target:
                return (n_p, n_steps), err
            failed.append((n_p, n_steps))
        return None, math.nan


def run_tol(tol, pr, zeta_out, fixed, ref_floor, levels, repeats) -> dict:
    auto_call = lambda: pf.solve(pr, "auto", tol=tol, zeta_out=zeta_out)  # noqa: E731
    first, sol = _call(auto_call)
    l1, area = true_errors(sol, fixed.ref, fixed.cdf)
    auto_err = max(l1, area)
    target = max(auto_err, ref_floor)
    best, best_err = fixed.cheapest(target, levels)
    row = {
        "scene": SCENE,
        "tol": tol,
        "auto_method": sol.method,
        "auto_first_call_s": first,
        "auto_true_L1": l1,
        "auto_true_area": area,
        "auto_estimate": max(float(np.max(sol.error_estimate[q])) for q in ("L1", "elastic_area", "plastic_area")),
        "target": target,
        "target_is_reference_floor": bool(ref_floor > auto_err),
    }
    a_times, f_times = [], []
    if best is not None:
        fixed.solve(*best)  # (its first call apart)
    for _ in range(repeats):  # interleaved: auto, fv, auto, fv, ...
        a_times.append(_call(auto_call)[0])
        if best is not None:
            f_times.append(_call(lambda: fixed.solve(*best))[0])
    row["auto_time_s"] = statistics.median(a_times)
    if best is None:
        finest = max(fixed.seen, key=lambda q: q[0] * q[1])
        row.update(
            best_fv_n_p="",
            best_fv_n_steps="",
            best_fv_true_error=math.nan,
            best_fv_time_s=math.nan,
            ratio=math.nan,
            note=f"no fv pair up to n_p = {max(levels)} reaches it (finest tried {finest}: error "
            f"{fixed.seen[finest][0]:.2e}, one call {fixed.seen[finest][1]:.3g} s)",
        )
    else:
        t_fv = statistics.median(f_times)
        row.update(
            best_fv_n_p=best[0],
            best_fv_n_steps=best[1],
            best_fv_true_error=best_err,
            best_fv_time_s=t_fv,
            ratio=row["auto_time_s"] / t_fv,
            note="",
        )
    return row


def markdown(rows, info) -> str:
    lines = [
        "# method='auto' on the moving wall against the best hand-picked fixed fv resolution "
        "(`benchmarks/moving_wall_auto.py`)",
        "",
        f"Machine: {machine()} (shared: timings are medians of {info['repeats']} interleaved repeats, first calls "
        "apart). Scene W: `SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1, q_r=2, q_s=128)`, p_bar = 0.03, "
        f"`hardness=PowerLaw(sigma_1=0.035, n=0.2)`, station zeta = {info['zeta']:g}. True errors (the larger of the "
        f"L1 of P0 and the areas' errors) against fv on n_p = n_steps = {info['ns']} (areas: Aitken extrapolation, "
        f"uncertainty {info['area_unc']:.1e}; L1: the finest run's CDF, uncertainty {info['l1_unc']:.1e}; the "
        f"reference took {info['ref_time']:.3g} s). The best fixed fv: the cheapest (n_p, n_steps) by work on the "
        "doubling grid (n_steps = n_p / 2, n_p, 2 n_p) whose true error is no larger than auto's, or than the "
        "reference's uncertainty where auto's is below it. ratio = auto time / best fv time (target <= 1.2).",
        "",
        "| tol | auto | auto time | auto true L1 / area | target | best fixed fv (n_p, n_steps) | its true error | "
        "its time | ratio |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        fv = f"({r['best_fv_n_p']}, {r['best_fv_n_steps']})" if r["best_fv_n_p"] != "" else r["note"]
        floor = " (reference floor)" if r["target_is_reference_floor"] else ""
        lines.append(
            f"| {r['tol']:g} | {r['auto_method']} | {1e3 * r['auto_time_s']:.4g} ms | {r['auto_true_L1']:.2e} / "
            f"{r['auto_true_area']:.2e} | {r['target']:.2e}{floor} | {fv} | {r['best_fv_true_error']:.2e} | "
            f"{1e3 * r['best_fv_time_s']:.4g} ms | {r['ratio']:.3g} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    quick = args.quick
    repeats = args.repeats or (1 if quick else 3)
    pr = scene()
    zeta = 8.0 if quick else float(pr.zeta_max)
    ns = (400, 800, 1600) if quick else (1600, 3200, 6400)
    tols = (1e-3, 1e-4) if quick else (1e-3, 1e-4, 1e-5, 1e-6)
    levels = [25 * 2**k for k in range(6 if quick else 8)]  # (25 ... 800 / 3200)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        src = pr if not quick else scene(q_s=zeta)
        ref, spread, cdf, l1_unc = moving_reference(src, ns)
        ref_time = time.perf_counter() - t0
        pr_run = src
        fixed = FixedFv(pr_run, None, ref, cdf)
        floor = max(spread, l1_unc)
        pf.solve(pr_run, "auto", tol=1e-3)  # (first-use costs: imports, caches)
        rows = [run_tol(tol, pr_run, None, fixed, floor, levels, repeats) for tol in tols]
    for r in rows:
        r.update(
            reference=f"fv n_p = n_steps = {ns}", reference_area_uncertainty=spread, reference_L1_uncertainty=l1_unc
        )
    d = outdir(args)
    write_csv(os.path.join(d, "moving_wall_auto.csv"), rows)
    info = {"repeats": repeats, "zeta": zeta, "ns": ns, "area_unc": spread, "l1_unc": l1_unc, "ref_time": ref_time}
    with open(os.path.join(d, "moving_wall_auto.md"), "w") as fh:
        fh.write(markdown(rows, info))
    return rows


if __name__ == "__main__":
    main()
