"""Time-to-accuracy of the finite-volume solver: medians of repeated runs.

Run ``python benchmarks/fv_timing.py [--repeats 7]``.  Prints one table: scheme, space
discretisation, stepping, n_p, n_steps, then for the banded path (tridiagonal solves) and the
spectral path (``linalg="dst"``, the default) the median solver wall time (``sol.wall_time``),
the speedup, the largest difference of the two P0 relative to max P0 (the same discrete solution:
round-off), and L1 of P0 and |dA*| at zeta_max on the reference problem (of the dst run); then
the 1000-load batch with YP08, both paths; then, with YP08, the whole-trajectory coupling against the
step-by-step march for 1-10 loads (why fv uses the former for one load only).  No plots, no files.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import persson_fp as pf
import persson_fp.solvers.fv.spectral as fv_spectral

CASES = [
    # (fudge, scheme, space, stepping, n_p, n_steps)
    (None, "crank-nicolson", "fv2", "geometric", 400, 120),
    (None, "crank-nicolson", "fv2", "tau", 800, 200),
    (None, "tr-bdf2", "fv2", "tau", 800, 200),
    (None, "tr-bdf2", "compact4", "geometric", 200, 100),
    (None, "tr-bdf2", "compact4", "zeta", 200, 100),
    (None, "tr-bdf2", "compact4", "tau", 60, 60),
    (None, "tr-bdf2", "compact4", "tau", 200, 100),
    (None, "crank-nicolson", "compact4", "tau", 200, 100),
    (None, "crank-nicolson", "compact4", "tau", 200, 400),
    (None, "tr-bdf2", "compact4", "tau", 200, 250),
    (None, "rannacher", "compact4", "tau", 200, 400),
    (None, "implicit", "compact4", "tau", 200, 400),
    ("YP08", "tr-bdf2", "compact4", "tau", 60, 60),
    ("YP08", "tr-bdf2", "compact4", "tau", 200, 100),
    ("YP08", "tr-bdf2", "compact4", "tau", 200, 250),
    ("YP08", "crank-nicolson", "compact4", "tau", 200, 400),
    ("WM17", "tr-bdf2", "compact4", "tau", 200, 250),
]


def median_time(fn, repeats):
    """(median of sol.wall_time, median of the whole call, last solution)."""
    walls, calls = [], []
    sol = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        sol = fn()
        calls.append(time.perf_counter() - t0)
        walls.append(sol.wall_time)
    return float(np.median(walls)), float(np.median(calls)), sol


def main(repeats: int = 7) -> None:
    print(
        f"{'fudge':6} {'scheme':15} {'space':9} {'stepping':9} {'n_p':>5} {'steps':>5} "
        f"{'banded ms':>9} {'dst ms':>9} {'speedup':>7} {'|dP|/max':>9} {'L1':>9} {'|dA*|':>9}"
    )
    for fudge, scheme, space, stepping, n_p, n_steps in CASES:
        pr = pf.ContactProblem.reference(fudge=fudge)
        pf.exact(pr)  # effective-variance map cached outside the timing
        res = {}
        for linalg in ("banded", "dst"):

            def run(pr=pr, scheme=scheme, space=space, stepping=stepping, n_p=n_p, n_steps=n_steps, linalg=linalg):
                return pf.solve(
                    pr, "fv", scheme=scheme, space=space, stepping=stepping, n_p=n_p, n_steps=n_steps, linalg=linalg
                )

            run()  # warm-up
            res[linalg] = median_time(run, repeats)
        (tb, _, sb), (td, _, sd) = res["banded"], res["dst"]
        dP = float(np.max(np.abs(sd.P0_all - sb.P0_all)) / np.max(np.abs(sb.P0_all)))
        c = sd.compare().final()
        print(
            f"{fudge or 'none':6} {scheme:15} {space:9} {stepping:9} {n_p:5d} {n_steps:5d} "
            f"{tb * 1e3:9.2f} {td * 1e3:9.2f} {tb / td:6.1f}x {dP:9.1e} {c['L1']:9.2e} {c['area_error']:9.2e}"
        )

    # batch: 1000 loads p_bar / sqrt(V) in [0.01, 3], YP08, one common grid
    base = pf.ContactProblem.reference(fudge="YP08")
    loads = np.sqrt(float(base.V())) * np.geomspace(0.01, 3.0, 1000)
    pr = base.with_loads(loads)
    pf.exact(pr)
    for n_p, n_steps in ((200, 60), (250, 80), (200, 100)):
        res = {}
        for linalg in ("banded", "dst"):

            def run(pr=pr, n_p=n_p, n_steps=n_steps, linalg=linalg):
                return pf.solve(pr, "fv", n_p=n_p, n_steps=n_steps, linalg=linalg)

            res[linalg] = median_time(run, max(3, repeats // 2))
        (tb, cb, sb), (td, cd, sd) = res["banded"], res["dst"]
        dP = float(np.max(np.abs(sd.P0_all - sb.P0_all)) / np.max(np.abs(sb.P0_all)))
        c = sd.compare()
        print(
            f"batch 1000 loads YP08 tr-bdf2 compact4 tau n_p={n_p} steps={n_steps}: solver wall banded "
            f"{tb * 1e3:.0f} ms, dst {td * 1e3:.0f} ms ({tb / td:.1f}x; "
            f"whole call {cb * 1e3:.0f} / {cd * 1e3:.0f} ms), "
            f"|dP|/max {dP:.1e}, worst L1 {c.L1[-1].max():.2e}, worst |dA*| {c.area_error[-1].max():.2e}"
        )

    # whole-trajectory coupling (one load) against the step march, YP08, n_p = 200, 100 steps
    for m in (1, 2, 3, 5, 10):
        pr = base.with_loads(np.sqrt(float(base.V())) * np.geomspace(0.05, 3.0, m))
        times = {}
        for label, size in (("trajectory", 10**12), ("step march", 0)):
            saved = (fv_spectral._TRAJECTORY_SIZE, fv_spectral._fudge_trajectory_max_loads)
            fv_spectral._TRAJECTORY_SIZE, fv_spectral._fudge_trajectory_max_loads = size, m
            try:
                pf.solve(pr, "fv", n_p=200, n_steps=100)  # warm-up
                times[label] = median_time(lambda pr=pr: pf.solve(pr, "fv", n_p=200, n_steps=100), repeats)[0]
            finally:
                fv_spectral._TRAJECTORY_SIZE, fv_spectral._fudge_trajectory_max_loads = saved
        print(
            f"YP08 {m:2d} load(s), n_p=200, 100 steps: trajectory {times['trajectory'] * 1e3:.2f} ms, "
            f"step march {times['step march'] * 1e3:.2f} ms"
        )


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=7)
    main(ap.parse_args().repeats)
