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

    python benchmarks/batch_scaling.py [--quick] [--repeats 5]
"""

from __future__ import annotations

import os
import statistics
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
    args = parser(__doc__).parse_args(argv)
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


if __name__ == "__main__":
    main()
