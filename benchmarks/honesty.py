"""Honesty of the general engine's error estimate over random general problems (fv and mol, resolution or tol=).

The cases and their independent references (Brownian motion with drift and zeta-dependent diffusion, the squared
Bessel process for B2 = (1 + p/(2 p_bar)) dV/dzeta, the strip series with a hardness) are those of
``tests/solvers/front_fixed/test_error_estimates.py``.  For every case: the worst ratio over stations of the true
error (L1 of P0, contact area) to the solver's own estimate, and for tol= runs whether the true error exceeded tol.

    python benchmarks/honesty.py [--quick] [--n 320] [--seed 2026]  ->  results/honesty.{csv,md}
    python benchmarks/honesty.py --method chebyshev [--n 320]  ->  results/honesty_chebyshev.csv, honesty.md

``--method chebyshev`` draws from ``tests/solvers/chebyshev/test_error_estimates.py`` instead: the same families plus
the homogenised strip against pf.exact and a non-separable Ornstein--Uhlenbeck family (Gaussian reference), every class
method "chebyshev" accepts (separable, clock, the adaptive march -- forced on exact clocks too -- and a constant
hardness), with the true L1 error of its polynomial on 3000 cells.  honesty.md then reports both engines.
"""

from __future__ import annotations

import csv
import os
import sys
import time

import numpy as np
from _common import machine, outdir, parser, write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))

import solvers.chebyshev.test_error_estimates as tc  # noqa: E402
import solvers.front_fixed.test_error_estimates as th  # noqa: E402


def main(argv=None):
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=None, help="number of random cases (default 320, --quick 8)")
    p.add_argument("--seed", type=int, default=2026)
    p.add_argument("--summarise", action="store_true", help="only rewrite honesty.md from the csv files")
    p.add_argument("--method", choices=("fv-mol", "chebyshev"), default="fv-mol", help="which engine to sweep")
    args = p.parse_args(argv)
    d = outdir(args)
    name = "honesty.csv" if args.method == "fv-mol" else "honesty_chebyshev.csv"
    if args.summarise:
        with open(os.path.join(d, name)) as fh:
            rows = list(csv.DictReader(fh))
        summarise(rows, len(rows), args.seed, d)
        return rows
    n = args.n or (8 if args.quick else 320)
    rng = np.random.default_rng(args.seed)
    rows = []
    for k in range(n):
        t0 = time.perf_counter()
        if args.method == "chebyshev":
            ratio, over_tol, label, path, err_over_tol = tc.check_case(rng)
        else:
            (ratio, over_tol, label), path, err_over_tol = th.check_case(rng), "", np.nan
        rows.append(
            {
                "case": k,
                "label": label,
                "path": path,
                "refused": ratio is None,
                "worst_error_over_estimate": np.nan if ratio is None else ratio,
                "over_tol": over_tol,
                "true_error_over_tol": err_over_tol,
                "seconds": time.perf_counter() - t0,
            }
        )
        if (k + 1) % 20 == 0:  # (the rows so far, for a long sweep)
            write_csv(os.path.join(d, name), rows)
    write_csv(os.path.join(d, name), rows)
    summarise(rows, n, args.seed, d)
    return rows


def _read(d, name):
    path = os.path.join(d, name)
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        return list(csv.DictReader(fh))


def _median_of(rows, key):
    vals = [float(r.get(key, "nan") or "nan") for r in rows]
    vals = [v for v in vals if np.isfinite(v)]
    return f"{np.median(vals):.3g} (of {len(vals)})" if vals else "-"


def _chebyshev_lines(rows):
    """The chebyshev section of honesty.md, by family and path."""
    ran = [r for r in rows if r["refused"] in (False, "False")]
    ratios = np.array([float(r["worst_error_over_estimate"]) for r in ran])
    tol_runs = [r for r in ran if "'tol'" in r["label"]]
    secs = np.array([float(r["seconds"]) for r in rows])
    lines = [
        "",
        "## method chebyshev",
        "",
        "`python benchmarks/honesty.py --method chebyshev` "
        "(cases of `tests/solvers/chebyshev/test_error_estimates.py`)",
        "",
        f"- cases drawn: {len(rows)}; run: {len(ran)}; refused with an error: {len(rows) - len(ran)} (a fixed coarse "
        "degree breaking an invariant, or a march over its step limit: refused openly)",
        f"- results more than 2x over their estimate: {int(np.sum(ratios > 2.0))} (worst ratio {np.max(ratios):.3g}, "
        f"median {np.median(ratios):.3g})",
        f"- tol= results: {len(tol_runs)}; over tol: {sum(r['over_tol'] in (True, 'True') for r in ran)}; "
        f"true error / tol: median {_median_of(tol_runs, 'true_error_over_tol')}, on the march paths "
        f"{_median_of([r for r in tol_runs if r['path'] in ('radau', 'magnus')], 'true_error_over_tol')}",
        f"- total time {secs.sum():.1f} s (median {np.median(secs):.2f} s a case, longest {secs.max():.1f} s; "
        f"over 10 s: {int(np.sum(secs > 10.0))})",
        "",
        "| family | path | run | refused | > 2x over estimate | worst error / estimate | median s |",
        "|---|---|---|---|---|---|---|",
    ]
    for fam in ("drift", "BESQ", "BESQ-shift", "strip", "hardness-exact", "OU"):
        sel = [r for r in rows if r["label"].startswith(fam + " ")]
        for path in ("exponential", "clock", "radau", "magnus", "refused"):
            sub = [r for r in sel if r["path"] == path]
            if not sub:
                continue
            ok = [float(r["worst_error_over_estimate"]) for r in sub if r["refused"] in (False, "False")]
            worst = f"{max(ok):.3g}" if ok else "-"
            med = float(np.median([float(r["seconds"]) for r in sub]))
            over = sum(x > 2 for x in ok)
            lines.append(f"| {fam} | {path} | {len(ok)} | {len(sub) - len(ok)} | {over} | {worst} | {med:.2f} |")
    return lines


def summarise(rows, n, seed, d):
    """results/honesty.md from the per-case rows of both engines (``--summarise`` re-reads the csv files)."""
    if rows and rows[0].get("path") not in (None, ""):  # a chebyshev sweep: the fv/mol part from its csv
        cheb, rows = rows, _read(d, "honesty.csv") or []
        n = len(rows)
    else:
        cheb = _read(d, "honesty_chebyshev.csv")
    ran = [r for r in rows if r["refused"] in (False, "False")]
    ratios = np.array([float(r["worst_error_over_estimate"]) for r in ran] or [np.nan])
    n_tol = sum("'tol'" in r["label"] for r in ran)
    lines = [
        "# Honesty of the error estimate (general engine)",
        "",
        f"{machine()}; seed {seed}; `python benchmarks/honesty.py`",
        "",
        f"- cases drawn: {n}; run: {len(ran)}; refused with an error: {n - len(ran)}",
        f"- results more than 2x over their estimate: {int(np.sum(ratios > 2.0))} (worst ratio {np.max(ratios):.3g}, "
        f"median {np.median(ratios):.3g})",
        f"- tol= results: {n_tol}; over tol: {sum(r['over_tol'] in (True, 'True') for r in ran)}",
        f"- total time {sum(float(r['seconds']) for r in rows):.1f} s",
        "",
        "| family | method | run | refused | > 2x over estimate | worst error / estimate |",
        "|---|---|---|---|---|---|",
    ]
    for fam in ("drift", "BESQ", "strip"):
        for method in ("fv", "mol"):
            sel = [r for r in rows if r["label"].startswith(fam) and f" {method} " in r["label"]]
            ok = [float(r["worst_error_over_estimate"]) for r in sel if r["refused"] in (False, "False")]
            worst = f"{max(ok):.3g}" if ok else "-"
            lines.append(
                f"| {fam} | {method} | {len(ok)} | {len(sel) - len(ok)} | {sum(x > 2 for x in ok)} | {worst} |"
            )
    if not rows:  # no fv/mol sweep in this folder
        lines = lines[:4]
    if cheb:
        lines += _chebyshev_lines(cheb)
    with open(os.path.join(d, "honesty.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
