"""Time-to-accuracy of the finite-volume solver (DESIGN §5): medians of repeated runs.

Run ``python benchmarks/fv_timing.py [--repeats 7]``.  Prints one table: scheme, space
discretisation, stepping, n_p, n_steps, median wall time, L1 of P0 and |dA*| at zeta_max on
the reference problem, then the 1000-load batch with YP08.  No plots, no files.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import persson_fp as pf

CASES = [
    # (fudge, scheme, space, stepping, n_p, n_steps)
    (None, "crank-nicolson", "fv2", "geometric", 400, 120),
    (None, "crank-nicolson", "fv2", "tau", 800, 200),
    (None, "tr-bdf2", "fv2", "tau", 800, 200),
    (None, "tr-bdf2", "compact4", "geometric", 200, 100),
    (None, "tr-bdf2", "compact4", "zeta", 200, 100),
    (None, "tr-bdf2", "compact4", "tau", 200, 100),
    (None, "crank-nicolson", "compact4", "tau", 200, 100),
    (None, "crank-nicolson", "compact4", "tau", 200, 400),
    (None, "tr-bdf2", "compact4", "tau", 200, 250),
    (None, "rannacher", "compact4", "tau", 200, 400),
    (None, "implicit", "compact4", "tau", 200, 400),
    ("YP08", "tr-bdf2", "compact4", "tau", 200, 100),
    ("YP08", "tr-bdf2", "compact4", "tau", 200, 250),
    ("YP08", "crank-nicolson", "compact4", "tau", 200, 400),
    ("WM17", "tr-bdf2", "compact4", "tau", 200, 250),
]


def median_time(fn, repeats):
    times = []
    out = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def main(repeats: int = 7) -> None:
    print(
        f"{'fudge':6} {'scheme':15} {'space':9} {'stepping':9} {'n_p':>5} {'steps':>5} "
        f"{'median ms':>9} {'L1':>9} {'|dA*|':>9}"
    )
    for fudge, scheme, space, stepping, n_p, n_steps in CASES:
        pr = pf.ContactProblem.reference(fudge=fudge)
        pf.exact(pr)  # effective-variance map cached outside the timing

        def run(pr=pr, scheme=scheme, space=space, stepping=stepping, n_p=n_p, n_steps=n_steps):
            return pf.solve(pr, "fv", scheme=scheme, space=space, stepping=stepping, n_p=n_p, n_steps=n_steps)

        run()  # warm-up
        t, sol = median_time(run, repeats)
        c = sol.compare().final()
        print(
            f"{fudge or 'none':6} {scheme:15} {space:9} {stepping:9} {n_p:5d} {n_steps:5d} "
            f"{t * 1e3:9.2f} {c['L1']:9.2e} {c['area_error']:9.2e}"
        )

    # batch: 1000 loads p_bar / sqrt(V) in [0.01, 3], YP08, one common grid
    base = pf.ContactProblem.reference(fudge="YP08")
    loads = np.sqrt(float(base.V())) * np.geomspace(0.01, 3.0, 1000)
    pr = base.with_loads(loads)
    pf.exact(pr)
    for n_p, n_steps in ((200, 60), (250, 80)):

        def run(pr=pr, n_p=n_p, n_steps=n_steps):
            return pf.solve(pr, "fv", n_p=n_p, n_steps=n_steps)

        t, sol = median_time(run, max(3, repeats // 2))
        c = sol.compare()
        print(
            f"batch 1000 loads YP08 tr-bdf2 compact4 tau n_p={n_p} steps={n_steps}: median {t * 1e3:.0f} ms "
            f"(solver wall {sol.wall_time * 1e3:.0f} ms), worst L1 {c.L1[-1].max():.2e}, "
            f"worst |dA*| {c.area_error[-1].max():.2e}"
        )


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=7)
    main(ap.parse_args().repeats)
