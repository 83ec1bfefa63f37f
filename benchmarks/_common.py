"""Shared helpers of the benchmark scripts: timing by medians, CSV output, machine facts."""

from __future__ import annotations

import argparse
import csv
import os
import platform
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "results")


def parser(description: str) -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--quick", action="store_true", help="a small run for CI (seconds, not minutes)")
    p.add_argument("--repeats", type=int, default=None, help="timing repeats per point (median is reported)")
    p.add_argument("--output", default=None, help="folder for CSV/PNG (default benchmarks/results[/quick])")
    return p


def outdir(args) -> str:
    d = args.output or (os.path.join(RESULTS, "quick") if args.quick else RESULTS)
    os.makedirs(d, exist_ok=True)
    return d


def median_time(fn, repeats: int, warmup: int = 1):
    """Run ``fn`` ``warmup`` times untimed, then ``repeats`` times; return (median seconds, last result)."""
    out = None
    for _ in range(warmup):
        out = fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def write_csv(path: str, rows: list[dict]) -> None:
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def machine() -> str:
    import scipy

    return (
        f"{platform.node() or 'host'}: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
        f"Python {sys.version.split()[0]}, numpy {np.__version__}, scipy {scipy.__version__}"
    )


def progress(i: int, n: int, label: str) -> None:
    """A one-line progress indicator on stderr."""
    sys.stderr.write(f"\r{label}: {i}/{n}")
    if i >= n:
        sys.stderr.write("\n")
    sys.stderr.flush()


# -- shared by speed_accuracy.py, convergence.py and stability.py ------------------------------------
OWN_METHODS = ("fv", "mol", "sines")
"""persson-fp's own solvers (the ones the generic tools are compared with)."""


def have(method: str) -> bool:
    """Whether ``method`` is built and its optional packages are installed (by name)."""
    import persson_fp as pf

    return method in pf.available_methods()


def errors_of(sol) -> dict:
    """L1, Linf of P0, |dA*| and load drift at the last station (worst over loads)."""
    c = sol.compare().final()
    return {"L1": c["L1"], "Linf": c["Linf"], "area_error": c["area_error"], "load_drift": c["load_drift"]}


def timed_solve(problem, method: str, options: dict, repeats: int, slow_s: float = 1.0, very_slow_s: float = 10.0):
    """Time the user's call: the whole ``pf.solve(problem, method, **options)``, end to end.

    The first call is timed on its own (``first_call_time``: it pays py-pde's numba compilation, reported
    as ``compile_time``, and any other first-use cost); then ``repeats`` further calls give the median
    ``call_time`` -- the figure to quote -- and the median of ``sol.wall_time`` (the solver's own time, without
    validation, building the Solution and its checks; reported for reference only).

    Runs whose first call (less its compile time) took longer than ``slow_s`` are repeated at most 3 times, longer than
    ``very_slow_s`` not at all (``repeats`` = 1: the first call less its compile time is then the call
    time).  Returns (row dict, last Solution); a solver error gives a row with ``status`` = the
    exception's class and message and Solution None.
    """
    import warnings

    import persson_fp as pf

    row = {"method": method, "options": repr(options)}
    wall, call = [], []
    sol = None
    n = 0
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t0 = time.perf_counter()
            sol = pf.solve(problem, method, **options)
            first = time.perf_counter() - t0
            comp = sol.info.get("compile_time", np.nan)
            once = first - (comp if np.isfinite(comp) else 0.0)  # a repeated call skips the (cached) compile
            n = repeats if once <= slow_s else (min(repeats, 3) if once <= very_slow_s else 0)
            if n == 0:
                wall.append(sol.wall_time)
                call.append(once)
            for _ in range(n):
                t0 = time.perf_counter()
                sol = pf.solve(problem, method, **options)
                call.append(time.perf_counter() - t0)
                wall.append(sol.wall_time)
    except Exception as err:  # noqa: BLE001 - a benchmark records what went wrong and goes on
        row.update(status=f"{type(err).__name__}: {err}", repeats=n)
        return row, None
    row.update(
        status="ok",
        repeats=len(call),
        call_time=statistics.median(call),
        wall_time=statistics.median(wall),
        first_call_time=first,
        compile_time=float(comp) if np.isfinite(comp) else np.nan,
        n_p=int(sol.p.size),
        steps=sol.info.get("steps"),
        **errors_of(sol),
    )
    return row, sol


def fit_order(h, err, n_last: int = 3, floor: float = 1e-13) -> float:
    """Slope of log(err) against log(h) over the ``n_last`` finest points above ``floor`` (NaN if < 2)."""
    h = np.asarray(h, float)
    err = np.asarray(err, float)
    ok = np.isfinite(err) & np.isfinite(h) & (h > 0) & (err > floor)
    h, err = h[ok], err[ok]
    if h.size < 2:
        return float("nan")
    idx = np.argsort(h)[:n_last]
    return float(np.polyfit(np.log(h[idx]), np.log(err[idx]), 1)[0])


def markdown_table(header: list[str], rows: list[list]) -> str:
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)
