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
