"""Time-to-accuracy of the generic tools (py-pde, FiPy) against persson-fp's own solvers.

For each method and resolution on ``ContactProblem.reference(fudge)`` (stations zeta = 4, 32, 128):
the L1 error of P0 and |dA*| (worst station), the median solve time over ``--repeats`` runs and,
apart, the median compile/set-up time (``info["compile_time"]``: py-pde's numba compilation,
which it repeats on every ``pf.solve`` call).  The own methods ("fv", "mol", "sines") are included
through ``pf.solve`` when they are registered and built, so the ratios come from the same run.

Usage::

    python benchmarks/generic_timing.py                 # YP08, 5 repeats (several minutes: FiPy)
    python benchmarks/generic_timing.py --quick         # fewer configurations, 3 repeats
    python benchmarks/generic_timing.py --fudge none --csv out.csv
"""

from __future__ import annotations

import argparse
import csv
import statistics
import sys
import time
import warnings

import persson_fp as pf

ZETA = [4.0, 32.0, 128.0]


def configs(quick: bool):
    """(method, label, options) triples, cheapest first within a method."""
    out = []
    for n_p in (200, 400, 800) if quick else (200, 400, 800, 1600):
        out.append(("py-pde", f"euler n_p={n_p}", {"solver": "euler", "n_p": n_p}))
    for n_p in (400, 800) if quick else (400, 800, 1600):
        out.append(("py-pde", f"scipy BDF n_p={n_p} rtol=1e-6", {"solver": "scipy", "n_p": n_p, "rtol": 1e-6}))
    out.append(("py-pde", "runge-kutta n_p=400 rtol=1e-6", {"solver": "runge-kutta", "n_p": 400, "rtol": 1e-6}))
    if not quick:
        out.append(("py-pde", "crank-nicolson(fixed pt) n_p=400", {"solver": "crank-nicolson", "n_p": 400}))
        out.append(("py-pde", "implicit(fixed pt) n_p=400", {"solver": "implicit", "n_p": 400}))
        out.append(("py-pde", "euler numpy n_p=200", {"solver": "euler", "n_p": 200, "backend": "numpy"}))
    fipy_res = ((200, 50), (400, 100), (800, 200)) if quick else ((200, 50), (400, 100), (800, 200), (1600, 400))
    for n_p, n in fipy_res:
        out.append(("fipy", f"crank-nicolson n_p={n_p} n={n}", {"n_p": n_p, "n_steps": n}))
    if not quick:
        out.append(("fipy", "implicit n_p=400 n=400", {"scheme": "implicit", "n_p": 400, "n_steps": 400}))
        out.append(("fipy", "explicit n_p=100", {"scheme": "explicit", "n_p": 100}))
        out.append(("fipy", "crank-nicolson pcg n_p=400 n=100", {"n_p": 400, "n_steps": 100, "linear_solver": "pcg"}))
    own = [m for m in ("fv", "mol", "sines") if m in pf.available_methods()]
    for m in own:
        out.append((m, "defaults", {}))
    return out


def measure(problem, method, opts, repeats):
    """(L1, |dA*|, median solve s, median compile s, steps) or an error string."""
    walls, comps = [], []
    err = None
    sol = None
    for _ in range(repeats):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sol = pf.solve(problem, method=method, zeta_out=ZETA, **opts)
        except Exception as exc:  # report and go on
            return f"{type(exc).__name__}: {exc}"[:100]
        walls.append(sol.wall_time)
        comps.append(float(sol.info.get("compile_time", 0.0)))
        if err is None:
            err = sol.compare()
    return (
        err.max_L1,
        err.max_area_error,
        statistics.median(walls),
        statistics.median(comps),
        sol.info.get("steps"),
    )


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fudge", default="YP08", help='"none", "YP08", "WM17" or "Xu24"')
    ap.add_argument("--repeats", type=int, default=None, help="repeats per configuration (default 5, --quick 3)")
    ap.add_argument("--quick", action="store_true", help="fewer configurations")
    ap.add_argument("--only", default=None, help="comma-separated methods to run (e.g. fipy,fv)")
    ap.add_argument("--csv", default=None, help="write the table to this CSV file")
    args = ap.parse_args(argv)
    repeats = args.repeats or (3 if args.quick else 5)
    fudge = None if args.fudge.lower() == "none" else args.fudge
    problem = pf.ContactProblem.reference(fudge=fudge)
    only = set(args.only.split(",")) if args.only else None
    rows = []
    print(f"reference problem, fudge={fudge}, stations {ZETA}, medians of {repeats} runs")
    hdr = (
        f"{'method':8s} {'configuration':36s} {'L1':>9s} {'|dA*|':>9s} {'solve s':>9s} {'compile s':>9s} {'steps':>8s}"
    )
    print(hdr)
    print("-" * len(hdr))
    t_all = time.perf_counter()
    for method, label, opts in configs(args.quick):
        if only and method not in only:
            continue
        if method not in pf.available_methods():
            print(f"{method:8s} {label:36s} (not available)")
            continue
        res = measure(problem, method, opts, repeats)
        if isinstance(res, str):
            print(f"{method:8s} {label:36s} {res}")
            rows.append({"method": method, "config": label, "error": res})
            continue
        L1, dA, wall, comp, steps = res
        print(f"{method:8s} {label:36s} {L1:9.2e} {dA:9.2e} {wall:9.4f} {comp:9.3f} {steps!s:>8s}", flush=True)
        rows.append({"method": method, "config": label, "L1": L1, "area_error": dA, "solve_s": wall, "compile_s": comp})
    # same-run ratios: time of each generic run over the fastest own run at least as accurate
    own = [r for r in rows if r.get("method") in ("fv", "mol", "sines") and "L1" in r]
    if own:
        print("\nratio = solve time / fastest own method (fv, mol, sines) with L1 at least as small")
        for r in rows:
            if r.get("method") in ("py-pde", "fipy") and "L1" in r:
                better = [o for o in own if o["L1"] <= r["L1"]]
                if better:
                    best = min(better, key=lambda o: o["solve_s"])
                    ratio = r["solve_s"] / best["solve_s"]
                    tot = (r["solve_s"] + r["compile_s"]) / best["solve_s"]
                    who = best["method"]
                    print(f"{r['method']:8s} {r['config']:36s} x{ratio:9.1f} (x{tot:.1f} with compile) vs {who}")
    print(f"\ntotal {time.perf_counter() - t_all:.1f} s")
    if args.csv:
        keys = sorted({k for r in rows for k in r})
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
