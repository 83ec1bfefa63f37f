"""Time-to-accuracy of every method on the reference problem.

For the reference problem ``pf.ContactProblem.reference()`` (p_bar = 0.5 sqrt(V(zeta_max))), without
and with the Yang--Persson fudge factor, every installed method is run over a sweep of its own
resolution knobs (``SWEEPS``: coarse -> fine).  Time is end to end: the whole ``pf.solve(...)`` call
(validation, solve, building the Solution and its checks), the median of ``--repeats`` calls (default 5;
at most 3 when one call takes > 1 s, none beyond the first when > 10 s -- the ``repeats`` column says
which) after a first call timed apart (``first_call_time``; for py-pde it includes the numba compile,
``compile_time``, which the later calls skip because the compiled stepper is cached).  ``sol.wall_time``
(the solver alone) is recorded too, for reference.  Errors at zeta_max against ``pf.exact``: L1 and Linf
of P0, |dA*|, load drift.

Outputs (``benchmarks/results/`` or ``results/quick/`` with ``--quick``):
speed_accuracy.csv (every run), speed_accuracy_table.csv and speed_accuracy.md (time to reach
L1 <= 1e-3, 1e-5, 1e-7 per method and the ratio to the fastest of persson-fp's own methods
fv/mol/sines, measured in the same run), speed_accuracy.png (L1 against time, log-log, one line per
method, the Pareto front marked).

    python benchmarks/speed_accuracy.py [--quick] [--repeats 5] [--output DIR]

Methods are picked by name from ``pf.available_methods()``; a missing one is skipped.  The generic
tools get a wall-clock budget per sweep (``BUDGET_S``): once spent, finer points are skipped.
"""

from __future__ import annotations

import math
import os
import sys
import time

import numpy as np

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (  # noqa: E402
    OWN_METHODS,
    machine,
    markdown_table,
    outdir,
    parser,
    progress,
    timed_solve,
    write_csv,
)

FUDGES = {"none": None, "YP08": "YP08"}
THRESHOLDS = (1e-3, 1e-5, 1e-7)


def explicit_steps(problem, n_p: int, r: float, k_domain: float = 8.0, tau0_fraction: float = 0.05) -> int:
    """Steps of fv/explicit (stepping "tau", exact start) that give r = dtau / (2 dp^2) <= ``r``."""
    dp = problem.p_max(k_domain) / n_p
    tau_max = float(np.max(problem.tau()))
    return int(math.ceil((1.0 - tau0_fraction) * tau_max / (2.0 * r * dp**2)))


def sweeps(problem, quick: bool) -> dict:
    """label -> (method, [options, ...] coarse -> fine)."""
    fv = {"space": "compact4", "stepping": "tau"}
    if quick:
        return {
            "fv tr-bdf2": (
                "fv",
                [dict(fv, scheme="tr-bdf2", n_p=n, n_steps=s) for n, s in ((50, 10), (200, 60), (300, 150))],
            ),
            "fv crank-nicolson": ("fv", [dict(fv, scheme="crank-nicolson", n_p=n, n_steps=s) for n, s in ((200, 60),)]),
            "mol order 4": ("mol", [dict(order=4, n_p=n, rtol=t) for n, t in ((50, 1e-4), (100, 1e-6))]),
            "sines": ("sines", [dict(n_p=n) for n in (10, 20, 160)]),
            "chapman-kolmogorov": ("chapman-kolmogorov", [dict(n_p=50, n_steps=5)]),
            "monte-carlo": ("monte-carlo", [dict(n_walkers=2000, seed=1)]),
        }
    ex16 = [explicit_steps(problem, n, 1.0 / 6.0) for n in (50, 100, 200, 400)]
    return {
        "fv tr-bdf2": (
            "fv",
            [
                dict(fv, scheme="tr-bdf2", n_p=n, n_steps=s)
                for n, s in ((40, 8), (60, 15), (100, 30), (150, 60), (200, 120), (300, 250), (400, 500), (400, 900))
            ],
        ),
        "fv crank-nicolson": (
            "fv",
            [
                dict(fv, scheme="crank-nicolson", n_p=n, n_steps=s)
                for n, s in ((60, 15), (100, 30), (150, 60), (200, 120), (300, 250), (400, 500), (500, 1000))
            ],
        ),
        "fv explicit fv2 r=1/6": (
            "fv",
            [
                dict(scheme="explicit", space="fv2", stepping="tau", n_p=n, n_steps=s)
                for n, s in zip((50, 100, 200, 400), ex16)
            ],
        ),
        "mol order 4": (
            "mol",
            [
                dict(order=4, n_p=n, rtol=t)
                for n, t in ((30, 1e-4), (50, 1e-5), (80, 1e-6), (120, 1e-7), (200, 1e-8), (300, 1e-9), (400, 1e-10))
            ],
        ),
        "mol order 2": (
            "mol",
            [
                dict(order=2, n_p=n, rtol=t)
                for n, t in ((100, 1e-4), (200, 1e-5), (400, 1e-6), (800, 1e-7), (1600, 1e-8))
            ],
        ),
        "sines": ("sines", [dict(n_p=n) for n in (8, 10, 12, 14, 16, 20, 24, 32, 48, 64, 96, 128, 192, 256, 384)]),
        "py-pde euler": ("py-pde", [dict(solver="euler", n_p=n) for n in (25, 50, 100, 200)]),
        "py-pde scipy": (
            "py-pde",
            [dict(solver="scipy", n_p=n, rtol=t) for n, t in ((100, 1e-5), (200, 1e-7), (400, 1e-9))],
        ),
        "py-pde runge-kutta": (
            "py-pde",
            [dict(solver="runge-kutta", n_p=n, rtol=t) for n, t in ((50, 1e-4), (100, 1e-6))],
        ),
        "fipy crank-nicolson": (
            "fipy",
            [
                dict(scheme="crank-nicolson", n_p=n, n_steps=s)
                for n, s in ((50, 15), (100, 30), (200, 60), (400, 120), (800, 240), (1600, 480))
            ],
        ),
        "fipy implicit": ("fipy", [dict(scheme="implicit", n_p=n, n_steps=s) for n, s in ((50, 20), (100, 80))]),
        "chapman-kolmogorov": (
            "chapman-kolmogorov",
            [dict(n_p=n, n_steps=s) for n, s in ((25, 4), (50, 5), (100, 10), (200, 20), (400, 40), (800, 40))],
        ),
        "monte-carlo": ("monte-carlo", [dict(n_walkers=n, seed=1) for n in (1000, 10_000, 100_000, 1_000_000)]),
    }


BUDGET_S = {"py-pde": 75.0, "fipy": 60.0}
"""Wall-clock budget (s) of a generic tool per fudge factor (all its sweeps together); once spent, the
remaining (finer) points are skipped and listed as such in the CSV."""


def family(label: str) -> str:
    return label.split()[0]


def time_to(rows, label, thr, key="call_time"):
    """(fastest time with L1 <= thr, its row) for one method label, or (None, best row)."""
    ok = [r for r in rows if r["label"] == label and r["status"] == "ok"]
    hit = [r for r in ok if r["L1"] <= thr]
    if hit:
        best = min(hit, key=lambda r: r[key])
        return best[key], best
    return None, (min(ok, key=lambda r: r["L1"]) if ok else None)


def pareto(points):
    """Indices of the (time, error) points not beaten in both by another one."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], np.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def fmt_t(t):
    return "-" if t is None or not np.isfinite(t) else (f"{t * 1e3:.3g} ms" if t < 1 else f"{t:.3g} s")


def summary_tables(rows, labels):
    """Time-to-accuracy rows (for CSV) and the markdown text."""
    table, md = [], []
    for fz in FUDGES:
        sub = [r for r in rows if r["fudge"] == fz]
        present = [lab for lab in labels if any(r["label"] == lab and r["status"] == "ok" for r in sub)]
        own = [lab for lab in present if family(lab) in OWN_METHODS]
        md.append(f"\n### fudge = {fz}\n")
        hdr = ["method"] + [f"L1 <= {t:.0e}" for t in THRESHOLDS] + [f"ratio @{t:.0e}" for t in THRESHOLDS]
        body = []
        best_own = {}
        for thr in THRESHOLDS:
            ts = [time_to(sub, lab, thr)[0] for lab in own]
            ts = [t for t in ts if t is not None]
            best_own[thr] = min(ts) if ts else None
        for lab in present:
            cells, ratios = [], []
            for thr in THRESHOLDS:
                t, r = time_to(sub, lab, thr)
                row = {"fudge": fz, "label": lab, "threshold": thr}
                if t is None:
                    row.update(reached=False, time=np.nan, best_L1=r["L1"] if r else np.nan, ratio_to_best_own=np.nan)
                    cells.append(f"not reached (best {r['L1']:.1e} in {fmt_t(r['call_time'])})" if r else "-")
                    ratios.append("-")
                else:
                    ratio = t / best_own[thr] if best_own[thr] else np.nan
                    comp = r.get("compile_time", np.nan)
                    first = r.get("first_call_time", np.nan)
                    row.update(
                        reached=True,
                        time=t,
                        compile_time=comp,
                        first_call_time=first,
                        time_incl_compile=first if np.isfinite(comp) else t,
                        best_L1=r["L1"],
                        options=r["options"],
                        ratio_to_best_own=ratio,
                    )
                    extra = f" (first call {fmt_t(first)})" if np.isfinite(comp) else ""
                    cells.append(fmt_t(t) + extra)
                    ratios.append("-" if not np.isfinite(ratio) else f"{ratio:.3g}x")
                    if np.isfinite(comp) and best_own[thr]:
                        row["ratio_incl_compile"] = first / best_own[thr]
                        ratios[-1] += f" ({first / best_own[thr]:.3g}x first call)"
                table.append(row)
            body.append([lab] + cells + ratios)
        md.append(markdown_table(hdr, body))
        md.append(
            "\nTime = median of the whole `pf.solve(...)` call (end to end, after a first call); py-pde: in "
            "brackets the first call, which compiles the numba stepper (later identical calls reuse it); "
            "ratio = time over the fastest of fv/mol/sines at the same threshold in this run."
        )
    return table, "\n".join(md)


def targets(rows, table):
    """The issue's targets, evaluated on this run (text lines)."""
    lines = []

    def t_of(fz, lab, thr):
        for r in table:
            if r["fudge"] == fz and r["label"] == lab and r["threshold"] == thr and r["reached"]:
                return r["time"], r.get("time_incl_compile", r["time"])
        return None, None

    labels = sorted({r["label"] for r in table})
    for fz in FUDGES:
        own = {lab: t_of(fz, lab, 1e-5)[0] for lab in labels if family(lab) in ("fv", "mol")}
        own = {k: v for k, v in own.items() if v is not None}
        sines5 = t_of(fz, "sines", 1e-5)[0]
        if own:
            best_lab = min(own, key=own.get)
            t_own = own[best_lab]
            for tool, factor in (("py-pde", 10.0), ("fipy", 1000.0)):
                tt = [(t_of(fz, lab, 1e-5), lab) for lab in labels if family(lab) == tool]
                tt = [(t, lab) for t, lab in tt if t[0] is not None]
                if not tt:
                    lines.append(f"- [{fz}] {tool}: no run reached L1 <= 1e-5 (or not installed)")
                    continue
                (t_fast, t_fast_c), lab = min(tt, key=lambda x: x[0][0])
                lines.append(
                    f"- [{fz}] L1 <= 1e-5: {best_lab} {fmt_t(t_own)} vs {lab} {fmt_t(t_fast)} "
                    f"(first call {fmt_t(t_fast_c)}): {t_fast / t_own:.3g}x ({t_fast_c / t_own:.3g}x first call); "
                    f"target >= {factor:g}x: {'met' if t_fast / t_own >= factor else 'NOT met'} on repeated calls, "
                    f"{'met' if t_fast_c / t_own >= factor else 'NOT met'} on a first call"
                )
                if tool == "py-pde" and sines5 is not None:
                    lines.append(
                        f"- [{fz}] L1 <= 1e-5: sines {fmt_t(sines5)} vs {lab}: {t_fast / sines5:.3g}x "
                        f"({t_fast_c / sines5:.3g}x first call); target >= 1000x: "
                        f"{'met' if t_fast / sines5 >= 1000 else 'NOT met'} on repeated calls, "
                        f"{'met' if t_fast_c / sines5 >= 1000 else 'NOT met'} on a first call"
                    )
        own7 = {lab: t_of(fz, lab, 1e-7)[0] for lab in labels if family(lab) in ("fv", "mol")}
        own7 = {k: v for k, v in own7.items() if v is not None}
        if own7:
            lab = min(own7, key=own7.get)
            lines.append(
                f"- [{fz}] L1 <= 1e-7: fastest fv/mol is {lab} in {fmt_t(own7[lab])}; target <= 0.2 s: "
                f"{'met' if own7[lab] <= 0.2 else 'NOT met'}"
            )
        else:
            lines.append(f"- [{fz}] L1 <= 1e-7: no fv/mol run reached it")
    for thr in THRESHOLDS:
        for lab in labels:
            if family(lab) not in OWN_METHODS:
                continue
            a, b = t_of("none", lab, thr)[0], t_of("YP08", lab, thr)[0]
            if a and b:
                lines.append(
                    f"- L1 <= {thr:.0e}: {lab} YP08/none cost = {b / a:.3g} "
                    f"(target <= 2: {'met' if b / a <= 2 else 'NOT met'})"
                )
    # own methods ahead of the generic tools at every accuracy reached by both
    for fz in FUDGES:
        for thr in THRESHOLDS:
            own = [t_of(fz, lab, thr)[0] for lab in labels if family(lab) in OWN_METHODS]
            gen = [(t_of(fz, lab, thr)[0], lab) for lab in labels if family(lab) in ("py-pde", "fipy")]
            own = [t for t in own if t is not None]
            gen = [(t, lab) for t, lab in gen if t is not None]
            if own and gen:
                t_gen, lab = min(gen)
                ahead = min(own) < t_gen
                lines.append(
                    f"- [{fz}] L1 <= {thr:.0e}: fastest own {fmt_t(min(own))} vs fastest generic ({lab}) {fmt_t(t_gen)}"
                    f" (repeated calls, end to end): own ahead: {'yes' if ahead else 'NO'}"
                )
    return lines


def plot(rows, labels, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(FUDGES), figsize=(13, 6.2), sharey=True, layout="constrained")
    cmap = plt.get_cmap("tab20")
    for ax, fz in zip(np.atleast_1d(axes), FUDGES):
        pts = []
        for i, lab in enumerate(labels):
            ok = [r for r in rows if r["fudge"] == fz and r["label"] == lab and r["status"] == "ok"]
            if not ok:
                continue
            t = np.array([r["call_time"] for r in ok])
            e = np.maximum([r["L1"] for r in ok], 1e-17)
            style = "-o" if family(lab) in OWN_METHODS else "--s"
            ax.loglog(t, e, style, color=cmap(i % 20), ms=4, lw=1.2, label=lab)
            comp = np.array([r.get("compile_time", np.nan) for r in ok])
            if np.any(np.isfinite(comp)):
                first = np.array([r.get("first_call_time", np.nan) for r in ok])
                ax.loglog(first, e, ":", color=cmap(i % 20), lw=1, alpha=0.7)
            pts += list(zip(t, e))
        front = pareto(pts)
        if front:
            f = np.array([pts[i] for i in front])
            ax.step(f[:, 0], f[:, 1], where="post", color="k", lw=2, alpha=0.35, zorder=0)
            ax.loglog(f[:, 0], f[:, 1], "o", mfc="none", mec="k", ms=9, label="Pareto front")
        for thr in THRESHOLDS:
            ax.axhline(thr, color="grey", lw=0.5, ls=":")
        ax.set_title(f"reference problem, fudge = {fz}")
        ax.grid(True, which="major", alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("L1 error of P0 at zeta_max")
    for ax in np.atleast_1d(axes):
        ax.set_xlabel("median time of the pf.solve call [s]")
    fig.suptitle("time to accuracy, whole calls (dotted: py-pde's first call, with compile)", fontsize=11)
    handles, names = [], []
    for ax in np.atleast_1d(axes):  # one legend for both panels, below them: it hides no data
        for h, n in zip(*ax.get_legend_handles_labels()):
            if n not in names:
                handles.append(h)
                names.append(n)
    fig.legend(handles, names, loc="outside lower center", ncol=6, fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def replot(out):
    """Redraw speed_accuracy.png from the speed_accuracy.csv in ``out`` (no timing)."""
    import csv

    with open(os.path.join(out, "speed_accuracy.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        for key in ("call_time", "L1", "compile_time", "first_call_time"):
            r[key] = float(r[key]) if r.get(key) not in (None, "") else np.nan
    labels = list(dict.fromkeys(r["label"] for r in rows))
    plot(rows, labels, os.path.join(out, "speed_accuracy.png"))


def main(argv=None):
    p = parser(__doc__)
    p.add_argument("--replot", action="store_true", help="only redraw the figure from the CSV in the output folder")
    args = p.parse_args(argv)
    out = outdir(args)
    if args.replot:
        replot(out)
        return
    repeats = args.repeats or (3 if args.quick else 5)
    avail = pf.available_methods()
    print(machine())
    print(f"methods available: {avail}; repeats = {repeats}")
    rows = []
    labels = []
    spent = {}
    for fz, fudge in FUDGES.items():
        pr = pf.ContactProblem.reference(fudge=fudge)
        pf.exact(pr)  # the effective-variance map is cached outside every timing
        table = sweeps(pr, args.quick)
        for label, (method, opts_list) in table.items():
            if label not in labels:
                labels.append(label)
            if method not in avail:
                print(f"  skip {label}: method {method!r} not available")
                continue
            budget = BUDGET_S.get(method, np.inf) * (0.25 if args.quick else 1.0)
            for i, opts in enumerate(opts_list):
                if spent.get((fz, method), 0.0) > budget:
                    rows.append(
                        {
                            "fudge": fz,
                            "label": label,
                            "method": method,
                            "options": repr(opts),
                            "status": "skipped (budget)",
                        }
                    )
                    continue
                t0 = time.perf_counter()
                row, _ = timed_solve(pr, method, opts, repeats)
                spent[(fz, method)] = spent.get((fz, method), 0.0) + time.perf_counter() - t0
                rows.append({"fudge": fz, "label": label, **row})
                progress(i + 1, len(opts_list), f"[{fz}] {label}")
    write_csv(os.path.join(out, "speed_accuracy.csv"), rows)
    table, md = summary_tables(rows, labels)
    write_csv(os.path.join(out, "speed_accuracy_table.csv"), table)
    tg = targets(rows, table)
    text = (
        f"# Time to accuracy (reference problem, p_bar = 0.5 sqrt(V))\n\nMachine: {machine()}\n"
        f"Command: `python benchmarks/speed_accuracy.py{' --quick' if args.quick else ''}`; repeats {repeats} "
        "(at most 3 for calls > 1 s, 1 for calls > 10 s: column `repeats` of speed_accuracy.csv)\n"
        + md
        + "\n\n## Targets, evaluated on this run\n\n"
        + "\n".join(tg)
        + "\n"
    )
    with open(os.path.join(out, "speed_accuracy.md"), "w") as fh:
        fh.write(text)
    print(text)
    plot(rows, labels, os.path.join(out, "speed_accuracy.png"))
    return rows, table


if __name__ == "__main__":
    main()
