"""Sweeps end to end: 100 surfaces x 4 models x 1000 loads, serial and through 2 worker processes.

Throughput in loads/s of ``pf.sweep`` (the whole call: pool start-up, submission, result transfer and the
table) against the rate of a plain single-process loop over ``pf.exact`` measured in the same run; the
ratio per core is (sweep rate / workers) / (loop rate).  Every configuration's table is compared with the
serial one (column ``identical``: the same numbers bit for bit).

Configurations: ``executor=None`` (serial); ``executor=2`` (a ProcessPoolExecutor made inside the call,
forked workers, Linux's default); the same pool kept warm across calls; a pool started with ``spawn``
(the macOS/Windows default: every worker imports numpy/scipy and builds its fudge tables afresh).
A second table times the costly ``elastic_energy`` (adaptive quadrature per task) on fewer surfaces.
Output: sweep.csv, sweep.md.

    python benchmarks/sweep.py [--quick]
"""

from __future__ import annotations

import multiprocessing
import os
import statistics
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

import persson_fp as pf

sys.path.insert(0, os.path.dirname(__file__))
from _common import machine, markdown_table, median_time, outdir, parser, write_csv  # noqa: E402

MODELS = [None, "YP08", "WM17", "Xu24"]


def surfaces(n: int) -> dict:
    """n self-affine surfaces spanning H in [0.2, 0.95], rms slope in [0.05, 0.5], zeta_max in [50, 5000]."""
    H = np.linspace(0.2, 0.95, n)
    slope = np.geomspace(0.05, 0.5, n)[::-1]
    zeta = np.geomspace(50.0, 5000.0, n)[(np.arange(n) * 7) % n]
    return {f"s{i:03d}": pf.SelfAffinePSD.from_rms_slope(slope[i], H[i], 1.0, 2.0, zeta[i]) for i in range(n)}


def exact_loop(psds, ratio, quantities):
    """The reference: a plain loop, one ContactProblem per (surface, model), all loads at once."""
    out = []
    for psd in psds.values():
        p_bar = ratio * np.sqrt(psd.V())
        for m in MODELS:
            pr = pf.ContactProblem(psd, 1.0, p_bar, m)
            ex = pf.exact(pr)
            for q in quantities:
                out.append(
                    ex.contact_area
                    if q == "contact_area"
                    else ex.variance
                    if q == "variance"
                    else pf.elastic_energy(pr)
                )
    return out


def run_case(label, psds, ratio, quantities, repeats, workers=2, with_spawn=True):
    """Time every configuration, interleaved (one call of each per round, ``repeats`` rounds after a warm-up
    round), so that a shared machine's changing load hits them alike; medians per configuration."""
    n_loads = len(psds) * len(MODELS) * ratio.size
    kw = dict(models=MODELS, quantities=quantities, relative_loads=True, progress=False)
    spawn = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(workers) as warm:
        configs = [
            ("pf.exact loop (reference)", 1, lambda: exact_loop(psds, ratio, quantities)),
            ("pf.sweep serial", 1, lambda: pf.sweep(psds, ratio, **kw)),
            (
                f"pf.sweep executor={workers} (fork, pool made per call)",
                workers,
                lambda: pf.sweep(psds, ratio, executor=workers, **kw),
            ),
            (f"pf.sweep warm pool of {workers} (fork)", workers, lambda: pf.sweep(psds, ratio, executor=warm, **kw)),
            (
                f"pf.sweep pool of {workers} (spawn, made per call)",
                workers,
                lambda: _with_pool(workers, spawn, lambda pool: pf.sweep(psds, ratio, executor=pool, **kw)),
            ),
        ][: 5 if with_spawn else 4]
        times = {name: [] for name, _, _ in configs}
        results = {}
        for k in range(repeats + 1):
            for name, _, fn in configs:
                t0 = time.perf_counter()
                results[name] = fn()
                if k > 0 or "spawn" in name:  # round 0 warms up (a spawn pool is cold on every call anyway)
                    times[name].append(time.perf_counter() - t0)
    ref = results["pf.sweep serial"]
    t_loop = statistics.median(times["pf.exact loop (reference)"])
    rows = []
    for name, w, _ in configs:
        t = statistics.median(times[name][-repeats:])
        res = results[name]
        rows.append(
            dict(
                case=label,
                config=name,
                workers=w,
                seconds=t,
                identical=True
                if name.startswith("pf.exact")
                else all(np.array_equal(res[q], ref[q]) for q in quantities),
                surfaces=len(psds),
                models=len(MODELS),
                loads=ratio.size,
                quantities=" ".join(quantities),
                repeats=repeats,
                loads_per_s=n_loads / t,
                per_core_vs_exact=t_loop / t / w,
            )
        )
    return rows


def _burn(n: int) -> float:
    """A fixed CPU-bound numpy job (elementwise, no BLAS threads) for the machine calibration."""
    x = np.linspace(0.0, 1.0, 200_000)
    for _ in range(n):
        x = np.sin(x) + 0.5 * x
    return float(x.sum())


def calibrate(workers: int, repeats: int, n_jobs: int = 8, n: int = 10) -> dict:
    """The speed-up this machine gives right now: the same n_jobs CPU-bound jobs, serial vs a warm pool.

    On a shared machine other users' work takes cores; this is the ceiling a sweep can reach in the same run.
    """
    t1, _ = median_time(lambda: [_burn(n) for _ in range(n_jobs)], repeats)
    with ProcessPoolExecutor(workers) as pool:
        t2, _ = median_time(lambda: list(pool.map(_burn, [n] * n_jobs)), repeats)
    return {"serial_s": t1, "pool_s": t2, "speedup": t1 / t2}


def _with_pool(w, ctx, fn):
    with ProcessPoolExecutor(w, mp_context=ctx) as pool:
        return fn(pool)


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    repeats = args.repeats or (2 if args.quick else 5)
    if args.quick:
        cases = [("contact_area", surfaces(6), np.geomspace(1e-3, 3.0, 50), ("contact_area",))]
        heavy = ("contact_area+variance", surfaces(4), np.geomspace(1e-2, 3.0, 20), ("contact_area", "variance"))
    else:
        ratio = np.geomspace(1e-3, 3.0, 1000)
        cases = [
            ("contact_area", surfaces(100), ratio, ("contact_area",)),
            ("contact_area+variance", surfaces(100), ratio, ("contact_area", "variance")),
        ]
        heavy = ("elastic_energy", surfaces(8), ratio, ("contact_area", "elastic_energy"))
    load0 = os.getloadavg()[0]
    cal_n = 3 if args.quick else 10
    cal0 = calibrate(2, repeats, n=cal_n)
    rows = []
    for label, psds, ratio, qs in [*cases, heavy]:
        rows += run_case(label, psds, ratio, qs, repeats, with_spawn=not args.quick)
        print(f"{label}: done", file=sys.stderr)
    cal1 = calibrate(2, repeats, n=cal_n)
    load1 = os.getloadavg()[0]
    for r in rows:
        r["machine_speedup_2_before"] = cal0["speedup"]
        r["machine_speedup_2_after"] = cal1["speedup"]
    write_csv(os.path.join(out, "sweep.csv"), rows)
    table = [
        [
            r["case"],
            f"{r['surfaces']} x {r['models']} x {r['loads']}",
            r["config"],
            f"{r['seconds'] * 1e3:.4g} ms",
            f"{r['loads_per_s']:.3g}",
            f"{r['per_core_vs_exact']:.2f}",
            "yes" if r.get("identical", True) else "NO",
        ]
        for r in rows
    ]
    md = [
        "# pf.sweep end to end (benchmarks/sweep.py)",
        "",
        f"Machine: {machine()}; load average {load0:.2f} before, {load1:.2f} after the run"
        f" ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}).",
        f"Median of {repeats} calls each (rounds interleaved after one warm-up round;"
        " a spawn pool starts cold on every call). Loads are 1000 ratios"
        " p_bar / sqrt(V) in [1e-3, 3] per surface; models none, YP08, WM17, Xu24."
        if not args.quick
        else f"Quick run, median of {repeats}.",
        "",
        "per core vs exact = (loads/s / workers) / (loads/s of the pf.exact loop in the same case);"
        " identical = the table equals the serial sweep's bit for bit.",
        "",
        f"Machine calibration (a fixed CPU-bound numpy job, 8 copies, serial vs a warm pool of 2): speed-up"
        f" {cal0['speedup']:.2f}x before and {cal1['speedup']:.2f}x after the sweeps (2.0x on two idle cores);"
        " a sweep's 2-process speed-up cannot exceed it.",
        "",
        markdown_table(
            ["case", "surfaces x models x loads", "configuration", "time", "loads/s", "per core vs exact", "identical"],
            table,
        ),
        "",
    ]
    with open(os.path.join(out, "sweep.md"), "w") as fh:
        fh.write("\n".join(md))
    print("\n".join(md))
    return rows


if __name__ == "__main__":
    main()
