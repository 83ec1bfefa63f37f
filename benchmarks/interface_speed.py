"""Speed of the interface physics: whole user calls, medians of repeats, the first call apart.

Issue target: a gap distribution on 200 points and a leak rate per load <= 5 ms; 1 000 loads vectorised <= 0.5 s.
Surface: the BEM reference spectrum (H = 0.8, rms slope 0.1, q_l = 2 pi, q_r = 4 q_l, q_s = 64 q_l, E* = 1), model
WM17; one load p̄ = 0.002 and 1 000 loads log-spaced over [1e-4, 0.05] (contact fraction ~1e-3 to ~0.7).  Also the
effective medium's own error estimate (``full_output``'s ``effective_gap_error``, an upper estimate) over those loads.

    python benchmarks/interface_speed.py [--quick] [--repeats N]  ->  results/interface_speed.{csv,md}
"""

from __future__ import annotations

import os
import time

import numpy as np
from _common import machine, median_time, outdir, parser, write_csv

import persson_fp as pf

Q_L = 2.0 * np.pi


def cases(n_many):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, Q_L, 4 * Q_L, 64 * Q_L)
    u = np.linspace(0, 8 * psd.rms_height, 200)
    one = pf.ContactProblem(psd, 1.0, 0.002, fudge="WM17")
    many = pf.ContactProblem(psd, 1.0, np.geomspace(1e-4, 0.05, n_many), fudge="WM17")
    return [
        ("gap distribution + pdf on 200 points", 1, lambda: pf.gap_distribution(one).pdf(u)),
        ("leak rate, critical junction", 1, lambda: pf.leak_rate(one, 1.0, 1.0)),
        ("leak rate, effective medium", 1, lambda: pf.leak_rate(one, 1.0, 1.0, method="effective-medium")),
        ("gap distribution", n_many, lambda: pf.gap_distribution(many)),
        ("leak rate, critical junction", n_many, lambda: pf.leak_rate(many, 1.0, 1.0)),
        ("leak rate, effective medium", n_many, lambda: pf.leak_rate(many, 1.0, 1.0, method="effective-medium")),
    ], many


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    d = outdir(args)
    repeats = args.repeats or (3 if args.quick else 9)
    n_many = 100 if args.quick else 1000
    rows = []
    todo, many = cases(n_many)
    for label, n, fn in todo:
        t0 = time.perf_counter()
        fn()  # the first call (builds the per-spectrum rule) is timed apart
        first = time.perf_counter() - t0
        t, _ = median_time(fn, repeats, warmup=0)
        rows.append(dict(call=label, loads=n, first_call_s=first, median_s=t, repeats=repeats))
    em = pf.leak_rate(many, 1.0, 1.0, method="effective-medium", full_output=True)
    err = em["effective_gap_error"][em["effective_gap"] > 0]
    write_csv(os.path.join(d, "interface_speed.csv"), rows)
    lines = [
        "# Interface physics: speed of whole calls",
        "",
        f"Machine: {machine()}. Medians of {repeats} repeats after a first call (timed apart). Target: <= 5 ms "
        "per single load, <= 0.5 s for 1 000 loads.",
        "",
        "| call | loads | first call (s) | median (s) |",
        "|---|---|---|---|",
        *[f"| {r['call']} | {r['loads']} | {r['first_call_s']:.4f} | {r['median_s']:.4f} |" for r in rows],
        "",
        f"Effective medium over the {n_many} loads: estimated relative error of the effective gap (upper estimate) "
        f"median {np.median(err):.1e}, max {np.max(err):.1e}; {np.sum(em['sealed'])} loads sealed.",
    ]
    with open(os.path.join(d, "interface_speed.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return rows


if __name__ == "__main__":
    for r in main():
        print(r)
