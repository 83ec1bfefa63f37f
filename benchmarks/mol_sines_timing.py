"""Time-to-accuracy of the method of lines (to L1 <= 1e-6) and the sine series (to L1 <= 1e-10).

On ``ContactProblem.reference()`` (fudge None, YP08, WM17) at zeta_max: for each
method a small sweep of resolutions, each timed as the median of ``REPEATS``
runs (``Solution.wall_time``: the solver alone; the fudge factor's exact map is
warmed up first and is not part of any solver's time), and the cheapest
setting that meets the target is reported.  Also: the independent variable of
the MOL (tau against zeta) and the stiff/explicit contrast (BDF against RK45).

Run:  python benchmarks/mol_sines_timing.py
"""

from __future__ import annotations

import time
import warnings

import numpy as np

import persson_fp as pf

REPEATS = 5


def timed(pr, method, **opts):
    """Median wall time (s) of REPEATS solves and the last solution."""
    times = []
    for _ in range(REPEATS):
        sol = pf.solve(pr, method, **opts)
        times.append(sol.wall_time)
    return float(np.median(times)), sol


def sweep(pr, method, settings, target):
    rows = []
    for opts in settings:
        t, sol = timed(pr, method, **opts)
        c = sol.compare().final()
        rows.append((opts, t, c["L1"], c["area_error"], sol.info.get("nfev", 0)))
    ok = [r for r in rows if r[2] <= target]
    best = min(ok, key=lambda r: r[1]) if ok else None
    return rows, best


def main():
    warnings.simplefilter("ignore", RuntimeWarning)
    mol_settings = [{"n_p": n, "rtol": r} for n in (161, 201, 241) for r in (1e-5, 1e-6, 1e-7)]
    sines_settings = [{}, {"n_p": 20, "n_eval": 96}, {"n_p": 24, "n_eval": 96}]
    print(f"{'fudge':>6} {'method':>6} {'target':>8} {'setting':>28} {'median ms':>10} {'L1':>10} {'|dA*|':>10}")
    for fudge in (None, "YP08", "WM17"):
        pr = pf.ContactProblem.reference(fudge=fudge)
        pf.exact(pr)  # warm the effective-variance cache
        for method, settings, target in (("mol", mol_settings, 1e-6), ("sines", sines_settings, 1e-10)):
            _rows, best = sweep(pr, method, settings, target)
            if best is None:
                print(f"{fudge or 'none':>6} {method:>6} {target:8.0e} {'(target not reached)':>28}")
                continue
            opts, t, L1, dA, _ = best
            print(
                f"{fudge or 'none':>6} {method:>6} {target:8.0e} {str(opts):>28} {t * 1e3:10.2f} {L1:10.2e} {dA:10.2e}"
            )

    pr = pf.ContactProblem.reference(fudge="YP08")
    print("\nMOL independent variable and integrator (YP08, n_p=201, rtol=1e-6):")
    print(f"{'variable':>9} {'integrator':>10} {'median ms':>10} {'nfev':>7} {'nlu':>5} {'L1':>10}")
    for variable, integ in (("tau", "BDF"), ("zeta", "BDF"), ("tau", "Radau"), ("tau", "LSODA")):
        t, sol = timed(pr, "mol", n_p=201, rtol=1e-6, variable=variable, integrator=integ)
        print(
            f"{variable:>9} {integ:>10} {t * 1e3:10.2f} {sol.info['nfev']:7d} {sol.info['nlu']:5d} "
            f"{sol.compare().final()['L1']:10.2e}"
        )
    print("\nStiff against explicit (no fudge, rtol=1e-6, tau0_fraction=0.1): nfev by grid")
    pr = pf.ContactProblem.reference()
    print(f"{'n_p':>5} {'BDF nfev':>9} {'BDF ms':>8} {'RK45 nfev':>10} {'RK45 ms':>8}")
    for n in (81, 161, 321):
        row = []
        for integ in ("BDF", "RK45"):
            t0 = time.perf_counter()
            sol = pf.solve(pr, "mol", n_p=n, rtol=1e-6, integrator=integ, tau0_fraction=0.1)
            row += [sol.info["nfev"], (time.perf_counter() - t0) * 1e3]
        print(f"{n:5d} {row[0]:9d} {row[1]:8.1f} {row[2]:10d} {row[3]:8.1f}")


if __name__ == "__main__":
    main()
