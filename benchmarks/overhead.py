"""Per-call overheads of repeated questions (issue 16): pf.exact for one load against a bare erf, building a
ContactProblem, a new load through ``with_loads``, and what a ``pf.solve`` call costs beyond the solver.

Every figure is a median over ``--repeats`` (default 7) timed loops of many calls.  The ratios to
``scipy.special.erf`` on a 1-element array are taken inside each repeat (erf loop, then the loop of the row,
back to back) and the median ratio is reported, so machine load affects both sides alike.  A* = erf(p_bar /
sqrt(2 tau)) is the closed form of Xu et al.'s tutorial, Eq. 'eq:Area_Persson'.

Output: overhead.csv (row, fudge, seconds per call, ratio to erf, notes) and overhead.md.

    python benchmarks/overhead.py [--quick] [--repeats 7]
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import warnings

import numpy as np
from scipy.special import erf

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

TARGET_RATIO = 20.0
"""Issue 16: pf.exact for one load within 20x a bare erf call on a 1-element array."""


def per_call(fn, n: int) -> float:
    t0 = time.perf_counter()
    for _ in range(n):
        fn()
    return (time.perf_counter() - t0) / n


def paired(fn, base, n: int, repeats: int):
    """(median seconds per call of fn, median seconds of base, median ratio fn/base), paired per repeat."""
    fn()
    base()
    ts, bs, rs = [], [], []
    for _ in range(repeats):
        b = per_call(base, n)
        t = per_call(fn, n)
        ts.append(t)
        bs.append(b)
        rs.append(t / b)
    return statistics.median(ts), statistics.median(bs), statistics.median(rs)


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    repeats = args.repeats or (3 if args.quick else 7)
    n_fast = 2000 if args.quick else 20000
    n_slow = 50 if args.quick else 500
    print(machine())
    x1 = np.array([0.3])

    def erf1():
        return erf(x1)

    rows = []

    def add(name, fudge, fn, n, note=""):
        t, b, r = paired(fn, erf1, n, repeats)
        rows.append(
            {"row": name, "fudge": fudge, "seconds_per_call": t, "erf_seconds": b, "ratio_to_erf": r, "note": note}
        )

    for fz in ("none", "YP08"):
        fudge = None if fz == "none" else fz
        pr = pf.ContactProblem.reference(fudge=fudge)  # one load (a scalar)
        pr1 = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=[0.5])  # one load in a 1-element array
        sv = float(np.sqrt(pr.V_max))
        add(
            "pf.exact(problem).contact_area, one scalar load",
            fz,
            lambda: pf.exact(pr).contact_area,
            n_fast,
            f"target <= {TARGET_RATIO:g}x erf",
        )
        add("pf.exact(problem).contact_area, 1-element load array", fz, lambda: pf.exact(pr1).contact_area, n_fast)
        add(
            "pf.exact(problem, zeta=64.0).contact_area",
            fz,
            lambda: pf.exact(pr, 64.0).contact_area,
            n_slow,
            "zeta validated, V(zeta) and tau(zeta) computed",
        )
        add(
            "pf.exact(problem.with_loads(p)).contact_area",
            fz,
            lambda: pf.exact(pr.with_loads(0.3 * sv)).contact_area,
            n_slow,
            "a new load: loads validated, tau(zeta_max) for it",
        )
        add(
            "pf.ContactProblem(psd, E, p_bar, fudge)",
            fz,
            lambda: pf.ContactProblem(pr.psd, 1.0, 0.3 * sv, fudge),
            n_slow,
            "everything validated, V(zeta_max)",
        )
        # a solve: the whole call against the solver's own wall_time
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            pf.solve(pr, "sines")
            calls, walls, comps = [], [], []
            for _ in range(max(repeats, 5)):
                t0 = time.perf_counter()
                sol = pf.solve(pr, "sines")
                calls.append(time.perf_counter() - t0)
                walls.append(sol.wall_time)
                t0 = time.perf_counter()
                sol.compare()
                comps.append(time.perf_counter() - t0)
        call, wall, comp = (statistics.median(v) for v in (calls, walls, comps))
        rows.append(
            {
                "row": "pf.solve(problem, 'sines'): whole call",
                "fudge": fz,
                "seconds_per_call": call,
                "note": f"sol.wall_time (solver alone) {wall * 1e3:.3f} ms, whole call / solver "
                f"{statistics.median(c / w for c, w in zip(calls, walls)):.2f}x (paired); the rest is validation, "
                "the Solution and its checks",
            }
        )
        rows.append(
            {
                "row": "sol.compare()",
                "fudge": fz,
                "seconds_per_call": comp,
                "note": "errors against pf.exact at every station",
            }
        )
    from persson_fp.solvers._threads import blas_threads

    def limited():
        with blas_threads(1):
            pass

    add("blas_threads(1) context (inside every pf.solve)", "-", limited, n_slow * 4)

    write_csv(os.path.join(out, "overhead.csv"), rows)
    body = [
        [
            r["row"],
            r["fudge"],
            f"{r['seconds_per_call'] * 1e6:.3g} us",
            f"{r['ratio_to_erf']:.3g}x" if "ratio_to_erf" in r else "-",
            r.get("note", ""),
        ]
        for r in rows
    ]
    erf_t = statistics.median([r["erf_seconds"] for r in rows if "erf_seconds" in r])
    text = (
        f"# Per-call overheads\n\nMachine: {machine()}\nCommand: `python benchmarks/overhead.py"
        f"{' --quick' if args.quick else ''}`; medians of {repeats} loops; scipy.special.erf on a 1-element "
        f"array: {erf_t * 1e6:.3g} us per call (median over the rows)\n\n"
        + markdown_table(["call", "fudge", "time per call", "ratio to erf (paired)", "note"], body)
        + "\n"
    )
    with open(os.path.join(out, "overhead.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows


if __name__ == "__main__":
    main()
