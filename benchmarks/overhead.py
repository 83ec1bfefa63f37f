"""Per-call overheads of repeated questions (issues 16 and 21): pf.exact for one load against a bare erf, building a
ContactProblem, a new load through ``with_loads``, what a ``pf.solve(problem, "sines")`` call costs beyond the
solver, and that whole call against py-pde's compiled stepper at the same accuracy.

Every figure is a median over ``--repeats`` (default 7) timed loops of many calls.  The ratios to
``scipy.special.erf`` on a 1-element array are taken inside each repeat (erf loop, then the loop of the row,
back to back) and the median ratio is reported, so machine load affects both sides alike.  A* = erf(p_bar /
sqrt(2 tau)) is the closed form of Xu et al.'s tutorial, Eq. 'eq:Area_Persson'.

*The whole sines call against its core.*  The core is ``sol.wall_time``: the time of the sine-series solver's own
numerical work (``SineSeriesSolver._solve``: the domain, the mode counts, the coefficients, P0 on the output nodes
and the area sums), timed inside the same call.  Everything else the call does -- validating the problem type and
options, the output station, the load range and memory checks, building the ``Solution`` and checking its
invariants (finite, A* in [0, 1], load balance, P0 >= 0) -- is the overhead, ``call - wall_time`` of the same
call.  Each repeat times ``n`` calls one by one; the medians over the calls of the call time, the core, their
difference and their ratio are taken per repeat, and the median over the repeats is reported.

*Against py-pde.*  ``pf.solve(problem, "py-pde", solver="euler", n_p=n)`` (explicit Euler at r = 1/6, the
method's default, numba) on the same reference problem at the grids whose L1 error of P0 at zeta_max
(``sol.compare()``, against the closed form) is within 1e-3 and 1e-5; its first call (numba compilation) is
timed apart; then each repeat times a loop of 100 whole sines calls and a loop of 100 py-pde calls back to back,
each call on its own (interleaved one by one, the sines call measured 1.5x slower in one run, 62 against 40 us:
py-pde's call, ~0.6 ms of Python, evicts its working set from the caches), and py-pde's ``sol.wall_time`` (its
compiled stepper alone, without persson-fp's set-up, start data, Solution and checks around it) is set against
the whole sines call: per-call medians within a repeat, their ratio, and the median over the repeats.

Output: overhead.csv (row, fudge, seconds per call, ratio to erf, notes), overhead_pypde.csv and overhead.md.

    python benchmarks/overhead.py [--quick] [--repeats 7]
"""

from __future__ import annotations

import gc
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
"""pf.exact for one load within 20x a bare erf call on a 1-element array."""


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


def whole_call_vs_core(pr, n: int, repeats: int):
    """Medians of (whole call, sol.wall_time, call - wall_time, call / wall_time) of ``pf.solve(pr, "sines")``:
    per repeat the medians over ``n`` calls timed one by one, then the median over the repeats."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(50):
            pf.solve(pr, "sines")  # (first calls apart: imports, cached bases)
        per = []
        for _ in range(repeats):
            calls, walls = np.empty(n), np.empty(n)
            for i in range(n):
                t0 = time.perf_counter()
                sol = pf.solve(pr, "sines")
                calls[i] = time.perf_counter() - t0
                walls[i] = sol.wall_time
            per.append([float(np.median(v)) for v in (calls, walls, calls - walls, calls / walls)])
    return tuple(statistics.median(col) for col in zip(*per))


PYPDE_GRIDS = {"none": (25, 50, 100), "YP08": (50, 100, 200)}
"""py-pde's explicit-Euler grids (cells): the coarsest to reach L1 <= 1e-3 and 1e-5 at zeta_max on the reference
problem are among them (benchmarks/results/speed_accuracy.csv; YP08 does not reach 1e-5 with Euler)."""


def against_pypde(repeats: int, quick: bool):
    """Rows: per fudge and py-pde grid, py-pde's L1, first call, stepper time and whole call, against the whole
    sines call timed in the same repeats (see the module docstring); [] without py-pde."""
    if quick or "py-pde" not in pf.available_methods():  # (not in --quick: each grid compiles for ~10 s)
        return []
    rows = []
    n_loop = 100
    for fz in ("none", "YP08"):
        pr = pf.ContactProblem.reference(fudge=None if fz == "none" else fz)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            s_sines = pf.solve(pr, "sines")
            for n_p in PYPDE_GRIDS[fz]:
                opts = {"solver": "euler", "n_p": n_p}
                t0 = time.perf_counter()
                sol = pf.solve(pr, "py-pde", **opts)  # compiles the stepper (cached for the process)
                first = time.perf_counter() - t0
                l1 = float(np.max(sol.compare().L1))
                gc.collect()  # (the compilation's garbage, not the timed calls')
                sines_t, pde_call, pde_step, ratios = [], [], [], []
                for _ in range(repeats):  # a loop of each, back to back; per-call medians within each repeat
                    ts, tc, tw = np.empty(n_loop), np.empty(n_loop), np.empty(n_loop)
                    for i in range(n_loop):
                        t0 = time.perf_counter()
                        pf.solve(pr, "sines")
                        ts[i] = time.perf_counter() - t0
                    for i in range(n_loop):
                        t0 = time.perf_counter()
                        tw[i] = pf.solve(pr, "py-pde", **opts).wall_time
                        tc[i] = time.perf_counter() - t0
                    sines_t.append(float(np.median(ts)))
                    pde_call.append(float(np.median(tc)))
                    pde_step.append(float(np.median(tw)))
                    ratios.append(sines_t[-1] / pde_step[-1])
                rows.append(
                    {
                        "fudge": fz,
                        "pypde_n_p": n_p,
                        "pypde_L1": l1,
                        "pypde_first_call_s": first,
                        "pypde_stepper_s": statistics.median(pde_step),
                        "pypde_whole_call_s": statistics.median(pde_call),
                        "sines_whole_call_s": statistics.median(sines_t),
                        "sines_L1": float(np.max(s_sines.compare().L1)),
                        "sines_over_stepper": statistics.median(ratios),
                    }
                )
    return rows


def pypde_summary(rows) -> list[str]:
    """Lines: for L1 <= 1e-3 and 1e-5 and each fudge, the fastest py-pde stepper reaching it against sines."""
    out = []
    for fz in ("none", "YP08"):
        for thr in (1e-3, 1e-5):
            ok = [r for r in rows if r["fudge"] == fz and r["pypde_L1"] <= thr]
            if not ok:
                if any(r["fudge"] == fz for r in rows):
                    out.append(f"- {fz}, L1 <= {thr:g}: no py-pde grid of this run reaches it")
                continue
            r = min(ok, key=lambda r: r["pypde_stepper_s"])
            verdict = "ahead" if r["sines_over_stepper"] < 1.0 else "BEHIND"
            out.append(
                f'- {fz}, L1 <= {thr:g}: whole `pf.solve(problem, "sines")` {r["sines_whole_call_s"] * 1e3:.3f} ms '
                f"(L1 {r['sines_L1']:.1e}) vs py-pde's compiled stepper alone {r['pypde_stepper_s'] * 1e3:.3f} ms "
                f"({r['pypde_n_p']} cells, L1 {r['pypde_L1']:.1e}; "
                f"its whole call {r['pypde_whole_call_s'] * 1e3:.3f} ms, "
                f"first call {r['pypde_first_call_s']:.3g} s): sines / stepper = {r['sines_over_stepper']:.2f} "
                f"(paired): sines {verdict}"
            )
    return out


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
        # a solve: the whole call against the solver's own wall_time, paired call by call
        n_solve = 200 if args.quick else 2000
        call, wall, over, ratio = whole_call_vs_core(pr, n_solve, repeats)
        rows.append(
            {
                "row": "pf.solve(problem, 'sines'): whole call",
                "fudge": fz,
                "seconds_per_call": call,
                "core_seconds": wall,
                "overhead_seconds": over,
                "note": f"sol.wall_time (solver alone) {wall * 1e3:.3f} ms, overhead {over * 1e6:.1f} us, whole call / "
                f"solver {ratio:.2f}x (paired); the overhead is validation, the Solution and its checks",
            }
        )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = pf.solve(pr, "sines")
            comps = []
            for _ in range(max(repeats, 5)):
                t0 = time.perf_counter()
                sol.compare()
                comps.append(time.perf_counter() - t0)
        rows.append(
            {
                "row": "sol.compare()",
                "fudge": fz,
                "seconds_per_call": statistics.median(comps),
                "note": "errors against pf.exact at every station",
            }
        )
    from persson_fp.solvers._threads import blas_threads

    def limited():
        with blas_threads(1):
            pass

    add("blas_threads(1) context (inside every pf.solve)", "-", limited, n_slow * 4)

    pde_rows = against_pypde(repeats, args.quick)
    write_csv(os.path.join(out, "overhead.csv"), rows)
    if pde_rows:
        write_csv(os.path.join(out, "overhead_pypde.csv"), pde_rows)
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
    if pde_rows:
        text += (
            "\n## The whole sines call against py-pde's compiled stepper (reference problem, L1 of P0 at zeta_max)\n\n"
            + "\n".join(pypde_summary(pde_rows))
            + "\n\n"
            + markdown_table(
                [
                    "fudge",
                    "py-pde cells",
                    "py-pde L1",
                    "stepper",
                    "py-pde whole call",
                    "first call",
                    "sines whole call",
                    "sines / stepper",
                ],
                [
                    [
                        r["fudge"],
                        r["pypde_n_p"],
                        f"{r['pypde_L1']:.2e}",
                        f"{r['pypde_stepper_s'] * 1e3:.3f} ms",
                        f"{r['pypde_whole_call_s'] * 1e3:.3f} ms",
                        f"{r['pypde_first_call_s']:.3g} s",
                        f"{r['sines_whole_call_s'] * 1e3:.3f} ms",
                        f"{r['sines_over_stepper']:.2f}",
                    ]
                    for r in pde_rows
                ],
            )
            + "\n"
        )
    with open(os.path.join(out, "overhead.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows


if __name__ == "__main__":
    main()
