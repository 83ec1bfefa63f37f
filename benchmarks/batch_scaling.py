"""Batches of loads: time and peak memory of one call for 1 -> 1e4 loads, BLAS threads 1 vs the library's.

For the reference surface with the Yang--Persson fudge factor and loads p_bar / sqrt(V) log-spaced on
[1e-3, 3], each method answers every load in one call at its default settings: ``pf.exact(problem).contact_area``
and ``pf.solve(problem, method)`` for sines, fv and mol.  Per (method, loads): the median time of the whole
call (``--repeats``, default 5; 3 when a call takes > 1 s, 1 when > 10 s), with ``pf.solve``'s default of one
BLAS thread and with ``blas_threads=None`` (the BLAS library's own thread count; numpy's OpenBLAS starts
one per core), the two called in turn within each repeat; the peak of Python-traced memory during one
more call (``tracemalloc``, which sees numpy's buffers); and the worst |dA*| against ``pf.exact``.

Output: batch_scaling.csv and batch_scaling.md (time per load, growth from 1000 to 1e4 loads, the ratio of
the two thread settings, memory).

With ``--chebyshev``: method ``"chebyshev"`` on loads that share their coefficients (no fudge factor), one
batched call against a Python loop of one call per load, for 100 and 1000 loads p_bar / sqrt(V) log-spaced on
[1e-3, 3] and two problems of the reference spectrum: the homogenised ``ContactProblem`` and the
``FokkerPlanckProblem`` with B2 = (1 + p / (2 p0)) dV/dzeta, p0 = 0.5 sqrt(V) fixed (the same B2 for every
load), at tol 1e-4 and 1e-6 (one call per load refuses 1e-8 at some of these loads).  Per case: the median
time of the batched call and of the loop (called in turn within each repeat; one repeat of a loop over 1000
loads), their ratio, the largest |A*_batch - A*_loop| and the largest estimate, and the peak memory of the
batched call in a fresh process after a call on two of its loads (lazy imports, caches): ``tracemalloc``'s
peak and the growth of the resident set's peak (``ru_maxrss``) over it.
Output: batch_chebyshev.csv and batch_chebyshev.md.

    python benchmarks/batch_scaling.py [--quick] [--repeats 5] [--chebyshev]
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
import tracemalloc
import warnings

import numpy as np

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

METHODS = ("exact", "sines", "fv", "mol")
MEMORY_LIMIT_MB = 300.0


def call_of(method, problem, threads):
    if method == "exact":
        return lambda: pf.exact(problem).contact_area
    return lambda: pf.solve(problem, method, blas_threads=threads)


def timed(fns, repeats):
    """Median time of each function in ``fns``, called in turn within each repeat (paired under load).

    Returns (medians, repeats done, last result of the first function).
    """
    t0 = time.perf_counter()
    out = fns[0]()
    first = time.perf_counter() - t0
    n = repeats if first <= 1.0 else (min(repeats, 3) if first <= 10.0 else 1)
    ts = [[] for _ in fns]
    for i in range(n):
        for k, fn in enumerate(fns):
            if i == 0 and k == 0 and n == 1:
                ts[0].append(first)
                continue
            t0 = time.perf_counter()
            res = fn()
            ts[k].append(time.perf_counter() - t0)
            if k == 0:
                out = res
    return [statistics.median(t) for t in ts], n, out


def main(argv=None):
    p = parser(__doc__)
    p.add_argument("--chebyshev", action="store_true", help="chebyshev: one batched call vs a loop of single calls")
    args = p.parse_args(argv)
    if args.chebyshev:
        return chebyshev_main(args)
    out = outdir(args)
    repeats = args.repeats or (3 if args.quick else 5)
    loads = (1, 10, 100) if args.quick else (1, 10, 100, 1000, 10_000)
    base = pf.ContactProblem.reference()
    sv = float(np.sqrt(base.V_max))
    print(machine())
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for n in loads:
            ratios = np.geomspace(1e-3, 3.0, n) if n > 1 else np.array([0.5])
            pr = pf.ContactProblem(base.psd, 1.0, ratios * sv, fudge="YP08")
            A_exact = np.atleast_1d(pf.exact(pr).contact_area)  # also caches the effective-variance map
            for method in METHODS:
                row = {"method": method, "n_loads": n}
                fns = [call_of(method, pr, 1)] + ([call_of(method, pr, None)] if method != "exact" else [])
                try:
                    ts, reps, res = timed(fns, repeats)
                except ValueError as err:  # refused at the default budget (memory / time estimate)
                    row["refused"] = str(err).split(";")[0]
                    rows.append(row)
                    print(f"{method:6s} {n:6d} loads: refused ({row['refused']})", flush=True)
                    continue
                t1 = ts[0]
                row.update(time_1_thread=t1, repeats=reps, us_per_load=t1 / n * 1e6)
                if method != "exact":
                    row.update(time_blas_default=ts[1], default_over_1_thread=ts[1] / t1)
                    A = res.contact_area
                    A = np.asarray(A)[-1] if np.ndim(A) > 1 else A
                    row["max_area_error"] = float(np.max(np.abs(np.atleast_1d(A) - A_exact)))
                tracemalloc.start()
                call_of(method, pr, 1)()
                row["peak_MB"] = tracemalloc.get_traced_memory()[1] / 1e6
                tracemalloc.stop()
                rows.append(row)
                print(
                    f"{method:6s} {n:6d} loads: {t1 * 1e3:10.3f} ms ({row['us_per_load']:.3g} us/load), "
                    f"peak {row['peak_MB']:.1f} MB"
                    + (
                        f", BLAS default/1 thread {row['default_over_1_thread']:.2f}"
                        if "default_over_1_thread" in row
                        else ""
                    ),
                    flush=True,
                )
    write_csv(os.path.join(out, "batch_scaling.csv"), rows)
    body = []
    for r in rows:
        if "refused" in r:
            body.append([r["method"], r["n_loads"], "refused: " + r["refused"], "-", "-", "-", "-"])
            continue
        body.append(
            [
                r["method"],
                r["n_loads"],
                f"{r['time_1_thread'] * 1e3:.3g} ms",
                f"{r['us_per_load']:.3g}",
                f"{r['default_over_1_thread']:.2f}" if "default_over_1_thread" in r else "-",
                f"{r['peak_MB']:.3g}",
                f"{r['max_area_error']:.1e}" if "max_area_error" in r else "-",
            ]
        )
    lines = []
    big, mid = max(loads), (1000 if 1000 in loads else None)
    for method in METHODS:
        by_n = {r["n_loads"]: r for r in rows if r["method"] == method and "refused" not in r}
        if mid and big in by_n and mid in by_n:
            g = by_n[big]["time_1_thread"] / by_n[mid]["time_1_thread"]
            lines.append(f"- {method}: {mid} -> {big} loads costs {g:.3g}x the time ({big / mid:g}x the loads)")
        worst = max(r["peak_MB"] for r in by_n.values())
        lines.append(
            f"- {method}: largest peak memory {worst:.3g} MB "
            f"({'within' if worst <= MEMORY_LIMIT_MB else 'ABOVE'} {MEMORY_LIMIT_MB:g} MB)"
        )
    slow = [r for r in rows if "default_over_1_thread" in r and r["default_over_1_thread"] < 1.0]
    refused = [f"{r['method']} {r['n_loads']}" for r in rows if "refused" in r]
    if refused:
        lines.append("- refused at the default max_memory / max_time: " + ", ".join(refused))
    lines.append(
        "- BLAS library default faster than one thread in "
        + (", ".join(f"{r['method']} {r['n_loads']} ({r['default_over_1_thread']:.2f})" for r in slow) or "no case")
    )
    text = (
        f"# Batch scaling (YP08, loads 1e-3..3 sqrt(V))\n\nMachine: {machine()}\n"
        f"Command: `python benchmarks/batch_scaling.py{' --quick' if args.quick else ''}`; medians of up to "
        f"{repeats} calls (column `repeats` of the CSV)\n\n"
        + markdown_table(
            ["method", "loads", "call (1 BLAS thread)", "us / load", "BLAS default / 1 thread", "peak MB", "max |dA*|"],
            body,
        )
        + "\n\n"
        + "\n".join(lines)
        + "\n"
    )
    with open(os.path.join(out, "batch_scaling.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows


CHEB_TARGET_RATIO, CHEB_TARGET_MB = 10.0, 200.0

_PEAK_CHILD = """
import json, resource, sys, tracemalloc, warnings
import numpy as np
import persson_fp as pf
sys.path.insert(0, {here!r})
from batch_scaling import cheb_problem
warnings.simplefilter("ignore")
pr = cheb_problem({scene!r}, {n})
pf.solve(pr.with_loads(pr.p_bar[:2]), "chebyshev", tol={tol!r})  # (lazy imports and caches: not measured)
rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
tracemalloc.start()
sol = pf.solve(pr, "chebyshev", tol={tol!r})
peak = tracemalloc.get_traced_memory()[1]
tracemalloc.stop()
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss0
print(json.dumps({{"peak_MB": peak / 1e6, "rss_growth_MB": rss / 1e3, "n_p": sol.info["grid"]["n_p"]}}))
"""


def cheb_problem(scene: str, n: int):
    """The batch of ``n`` loads (p_bar / sqrt(V) log-spaced on [1e-3, 3]) of a chebyshev scene."""
    base = pf.ContactProblem.reference()
    sv = float(np.sqrt(base.V_max))
    loads = (np.geomspace(1e-3, 3.0, n) if n > 1 else np.array([0.5])) * sv
    if scene == "homogenised":
        return pf.ContactProblem(base.psd, base.E_star, loads)
    psd, E, p0 = base.psd, base.E_star, 0.5 * sv
    return pf.FokkerPlanckProblem(psd, E, loads, B2=lambda p, z: (1 + p / (2 * p0)) * psd.dV_dzeta(z, E))


def _peak_in_fresh_process(scene, n, tol):
    code = _PEAK_CHILD.format(here=os.path.dirname(os.path.abspath(__file__)), scene=scene, n=n, tol=tol)
    env = dict(os.environ)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def chebyshev_main(args):
    out = outdir(args)
    repeats = args.repeats or (3 if args.quick else 5)
    loads = (10, 30) if args.quick else (100, 1000)
    print(machine())
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for scene in ("homogenised", "B2 = (1 + p/(2 p0)) dV/dzeta"):
            for tol in (1e-4, 1e-6):
                for n in loads:
                    pr = cheb_problem(scene, n)
                    singles = [pr.with_loads(float(pb)) for pb in pr.p_bar]
                    batch = lambda pr=pr, tol=tol: pf.solve(pr, "chebyshev", tol=tol)  # noqa: E731
                    loop = lambda singles=singles, tol=tol: [pf.solve(q, "chebyshev", tol=tol) for q in singles]  # noqa: E731
                    sol, sols = batch(), loop()  # (first calls: caches and imports, not timed)
                    reps = repeats if n <= 100 else 1
                    tb, tl = [], []
                    for _ in range(reps):
                        t0 = time.perf_counter()
                        sol = batch()
                        tb.append(time.perf_counter() - t0)
                        t0 = time.perf_counter()
                        sols = loop()
                        tl.append(time.perf_counter() - t0)
                    A = np.reshape(sol.contact_area, (-1, n))[-1]
                    A1 = np.array([float(np.ravel(s1.contact_area)[-1]) for s1 in sols])
                    mem = _peak_in_fresh_process(scene, n, tol)
                    row = {
                        "scene": scene,
                        "tol": tol,
                        "n_loads": n,
                        "batch_s": statistics.median(tb),
                        "loop_s": statistics.median(tl),
                        "repeats": reps,
                        "n_p": sol.info["grid"]["n_p"],
                        "shared": sol.info.get("loads", "per load")[:6],
                        "max_dA_batch_vs_loop": float(np.max(np.abs(A - A1))),
                        "max_estimate": float(np.max(sol.info["error_estimate"]["elastic_area"])),
                        **mem,
                    }
                    row["loop_over_batch"] = row["loop_s"] / row["batch_s"]
                    rows.append(row)
                    print(
                        f"{scene:30s} tol {tol:.0e} {n:5d} loads: batch {row['batch_s'] * 1e3:8.1f} ms, loop "
                        f"{row['loop_s'] * 1e3:9.1f} ms, x{row['loop_over_batch']:.0f}, peak {mem['peak_MB']:.1f} MB"
                        f", |dA| {row['max_dA_batch_vs_loop']:.1e}",
                        flush=True,
                    )
    write_csv(os.path.join(out, "batch_chebyshev.csv"), rows)
    body = [
        [
            r["scene"],
            f"{r['tol']:.0e}",
            r["n_loads"],
            f"{r['batch_s'] * 1e3:.3g} ms",
            f"{r['loop_s'] * 1e3:.4g} ms",
            f"{r['loop_over_batch']:.0f}x",
            r["n_p"],
            f"{r['peak_MB']:.3g}",
            f"{r['rss_growth_MB']:.3g}",
            f"{r['max_dA_batch_vs_loop']:.1e}",
            f"{r['max_estimate']:.1e}",
        ]
        for r in rows
    ]
    worst_ratio = min(r["loop_over_batch"] for r in rows)
    worst_mb = max(r["peak_MB"] for r in rows)
    text = (
        f"# chebyshev: one batched call vs a loop of single calls (loads 1e-3..3 sqrt(V))\n\nMachine: {machine()}\n"
        f"Command: `python benchmarks/batch_scaling.py --chebyshev{' --quick' if args.quick else ''}`; medians of "
        f"{repeats} interleaved repeats (1 for a loop over 1000 loads); peak memory of the batched call in a fresh "
        "process\n\n"
        + markdown_table(
            [
                "problem",
                "tol",
                "loads",
                "batched call",
                "loop of single calls",
                "loop / batch",
                "degree",
                "peak MB (tracemalloc)",
                "RSS growth MB",
                "max |A*_batch - A*_loop|",
                "max estimate",
            ],
            body,
        )
        + f"\n\n- smallest loop / batch ratio {worst_ratio:.0f}x "
        f"({'at or above' if worst_ratio >= CHEB_TARGET_RATIO else 'BELOW'} {CHEB_TARGET_RATIO:g}x); largest peak "
        f"{worst_mb:.3g} MB ({'within' if worst_mb <= CHEB_TARGET_MB else 'ABOVE'} {CHEB_TARGET_MB:g} MB)\n"
    )
    with open(os.path.join(out, "batch_chebyshev.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows


if __name__ == "__main__":
    main()
