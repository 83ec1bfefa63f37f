"""Honesty of the general engine's error estimate over random general problems (fv and mol, resolution or tol=).

The cases and their independent references (Brownian motion with drift and zeta-dependent diffusion, the squared
Bessel process for B2 = (1 + p/(2 p_bar)) dV/dzeta, the strip series with a hardness) are those of
``tests/solvers/test_honesty.py``.  For every case: the worst ratio over stations of the true error (L1 of P0,
contact area) to the solver's own estimate, and for tol= runs whether the true error exceeded tol.

    python benchmarks/honesty.py [--quick] [--n 320] [--seed 2026]  ->  results/honesty.{csv,md}
"""

from __future__ import annotations

import csv
import os
import sys
import time

import numpy as np
from _common import machine, outdir, parser, write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "solvers"))

import test_honesty as th  # noqa: E402


def main(argv=None):
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=None, help="number of random cases (default 320, --quick 8)")
    p.add_argument("--seed", type=int, default=2026)
    p.add_argument("--summarise", action="store_true", help="only rewrite honesty.md from honesty.csv")
    args = p.parse_args(argv)
    if args.summarise:
        with open(os.path.join(outdir(args), "honesty.csv")) as fh:
            rows = list(csv.DictReader(fh))
        summarise(rows, len(rows), args.seed, outdir(args))
        return rows
    n = args.n or (8 if args.quick else 320)
    rng = np.random.default_rng(args.seed)
    rows = []
    for k in range(n):
        t0 = time.perf_counter()
        ratio, over_tol, label = th.check_case(rng)
        rows.append(
            {
                "case": k,
                "label": label,
                "refused": ratio is None,
                "worst_error_over_estimate": np.nan if ratio is None else ratio,
                "over_tol": over_tol,
                "seconds": time.perf_counter() - t0,
            }
        )
    d = outdir(args)
    write_csv(os.path.join(d, "honesty.csv"), rows)
    summarise(rows, n, args.seed, d)
    return rows


def summarise(rows, n, seed, d):
    """results/honesty.md from the per-case rows (also: ``--summarise`` re-reads results/honesty.csv)."""
    ran = [r for r in rows if r["refused"] in (False, "False")]
    ratios = np.array([float(r["worst_error_over_estimate"]) for r in ran])
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
    with open(os.path.join(d, "honesty.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
