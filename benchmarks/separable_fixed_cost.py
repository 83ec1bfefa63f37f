r"""The separable scene's fixed cost: what a whole ``chebyshev`` / ``auto`` call spends around its numerical work, and
the whole call against a hand-written Crank--Nicolson at L1 1e-4.

Scene S: the reference problem's spectrum, p_bar = 0.5 sqrt(V(zeta_max)), ``pf.FokkerPlanckProblem`` with
B2 = (1 + p/(2 p_bar)) dV/dzeta (separable: b(p) dV/dzeta), B1 = 0.  Reference: the squared-Bessel solution of
``benchmarks/general_engine.py`` (its uncertainty ~1e-10).

Parts of a ``chebyshev`` call at tol = 1e-4 (medians over ``--repeats`` calls, the parts timed within the same
calls; the shares of medians need not add to 100 %, and a part below the timing noise can come out negative):
building the solver (options, the coefficients' sampling that finds the separable form and checks the callables:
validation), the solver's own numerical work (``sol.wall_time``), the rest of ``Solver.run`` (building
the ``Solution``, its invariant checks), and what ``pf.solve`` adds (whole call less those; BLAS thread limits,
dispatch); ``auto``'s probe is ``auto call - chebyshev call`` (called in turn).

The hand peer: general_engine.py's Crank--Nicolson (uniform cells on [0, p_bar + 40 sqrt(V)], a sparse LU
factorised once, the exact density at V_s = 2e-3 V as its start -- more start information than persson-fp gets),
at the cheapest (cells, steps) of a doubling grid whose L1 is within 1e-4.  The chebyshev call, the auto call and
the hand CN are called in turn within each repeat; medians and the median of the per-repeat ratios are reported.

Output: separable_fixed_cost.csv and separable_fixed_cost.md.

    python benchmarks/separable_fixed_cost.py [--quick] [--repeats 21]
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import warnings

import numpy as np

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import general_engine as ge  # noqa: E402
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

TARGET = 1e-4


def scene():
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    fp = pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + p / (2 * pb)))
    return fp, 1.0 / (2 * pb)


def _median_of(fn, repeats):
    fn()
    ts = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    repeats = args.repeats or (5 if args.quick else 21)
    fp, slope = scene()
    pb, V = float(fp.p_bar[0]), float(fp.V_max)
    pdf, _, unc = ge.reference("S", fp, slope)
    L = pb + 40.0 * np.sqrt(V)
    print(machine())
    # the cheapest hand CN within TARGET (doubling grid of cells and steps)
    best = None
    for n in (200, 400, 800, 1600, 3200):
        for m in (25, 50, 100, 200, 400, 800):
            p, P, dp = ge.hand_cn(pb, V, slope, L, n, m)
            l1 = ge.cell_l1(p, P, dp, pdf)
            if l1 <= TARGET:
                t = _median_of(lambda n=n, m=m: ge.hand_cn(pb, V, slope, L, n, m), max(3, repeats // 4))
                if best is None or t < best[0]:
                    best = (t, n, m, l1)
                break  # (more steps at these cells only cost more)
    _, n_cn, m_cn, l1_cn = best
    # the parts of a chebyshev call
    from persson_fp.solvers._threads import blas_threads
    from persson_fp.solvers.registry import get_solver

    solver_cls = get_solver("chebyshev")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        parts = []  # (validation, numerical work, the rest of run(), pf.solve's own) of the same repeat
        calls = []
        for _ in range(repeats + 1):
            with blas_threads(1):  # (as pf.solve runs it)
                t0 = time.perf_counter()
                solver = solver_cls(fp, tol=TARGET)
                t1 = time.perf_counter()
                sol = solver.run()
                t2 = time.perf_counter()
            t3 = time.perf_counter()
            pf.solve(fp, "chebyshev", tol=TARGET)  # (in turn: its own = this call less the parts just timed)
            t4 = time.perf_counter()
            parts.append((t1 - t0, sol.wall_time, t2 - t1 - sol.wall_time, (t4 - t3) - (t2 - t0)))
            calls.append(t4 - t3)
        t_valid, t_work, t_rest, t_own = (statistics.median(x[k] for x in parts[1:]) for k in range(4))
        t_call = statistics.median(calls[1:])
        auto = pf.solve(fp, "auto", tol=TARGET)
        # the whole calls in turn
        tc, ta, th = [], [], []
        for _ in range(repeats):
            for fn, acc in (
                (lambda: pf.solve(fp, "chebyshev", tol=TARGET), tc),
                (lambda: pf.solve(fp, "auto", tol=TARGET), ta),
                (lambda: ge.hand_cn(pb, V, slope, L, n_cn, m_cn), th),
            ):
                t0 = time.perf_counter()
                fn()
                acc.append(time.perf_counter() - t0)
    l1_cheb = ge.tcheb.chebyshev_l1(sol, pdf)
    l1_auto = ge.tcheb.chebyshev_l1(auto, pdf) if auto.method == "chebyshev" else float("nan")
    rows = [
        {"part": "validation (options, coefficients sampled once, the form found)", "seconds": t_valid},
        {"part": "numerical work (sol.wall_time)", "seconds": t_work},
        {"part": "Solution and its invariant checks (run() less the work)", "seconds": t_rest},
        {"part": "pf.solve's own (threads, dispatch: a call less the three timed just before it)",
         "seconds": t_own},
        {"part": "whole chebyshev call", "seconds": t_call},
        {"part": "auto's probe (auto call less chebyshev call, in turn: median of the differences)",
         "seconds": statistics.median(a - c for a, c in zip(ta, tc))},
    ]  # fmt: skip
    for r in rows:
        r["share"] = r["seconds"] / t_call
    ratio_c = statistics.median(h / c for h, c in zip(th, tc))
    ratio_a = statistics.median(h / a for h, a in zip(th, ta))
    cmp_rows = [
        {"who": "chebyshev tol=1e-4", "median_s": statistics.median(tc), "true_L1": l1_cheb, "hand_over_this": ratio_c},
        {"who": f"auto tol=1e-4 ({auto.method})", "median_s": statistics.median(ta), "true_L1": l1_auto,
         "hand_over_this": ratio_a},
        {"who": f"hand CN, {n_cn} cells, {m_cn} steps", "median_s": statistics.median(th), "true_L1": l1_cn,
         "hand_over_this": 1.0},
    ]  # fmt: skip
    write_csv(os.path.join(out, "separable_fixed_cost.csv"), rows + cmp_rows)
    text = (
        "# Separable scene S: fixed cost of a call, and the whole call against a hand Crank-Nicolson at L1 1e-4\n\n"
        f"Machine: {machine()}\nCommand: `python benchmarks/separable_fixed_cost.py"
        f"{' --quick' if args.quick else ''}`; medians of {repeats} calls (the comparison: in turn within each "
        f"repeat, the ratio the median of per-repeat ratios); reference uncertainty {unc:.1e}\n\n"
        + markdown_table(
            ["part of a chebyshev call (tol=1e-4)", "time", "share"],
            [[r["part"], f"{r['seconds'] * 1e3:.3g} ms", f"{r['share']:.0%}"] for r in rows],
        )
        + "\n\nThe parts are medians over calls: they need not add up, and one below the timing noise (a few 0.1 ms "
        "on this shared machine) can come out negative.\n\n"
        + markdown_table(
            ["whole call", "median", "true L1", "hand CN time / this"],
            [
                [r["who"], f"{r['median_s'] * 1e3:.3g} ms", f"{r['true_L1']:.1e}", f"{r['hand_over_this']:.2f}"]
                for r in cmp_rows
            ],
        )
        + "\n"
    )
    with open(os.path.join(out, "separable_fixed_cost.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows, cmp_rows


if __name__ == "__main__":
    main()
