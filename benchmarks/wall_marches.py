"""The two marches of ``method="chebyshev"`` on the moving wall: Radau IIA steps (the default) against the
commutator-free exponential (Magnus) steps (``march="magnus"``), whole calls at the same tol.

Scene W (``benchmarks/moving_wall_auto.py``): ``SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1, q_r=2, q_s=128)``,
p_bar = 0.03, ``hardness=PowerLaw(sigma_1=0.035, n=0.2)``, one station at zeta_max.  For each tol both calls are
made in turn (radau, magnus, radau, magnus, ...: the machine is shared), the first call of each apart; medians of the
timed rounds; ``max_time`` 300 s (the Magnus march exceeds the default budget of the path at tol 1e-6).  Also the
areas of the two results against each other (both within tol of the truth, they differ by at most 2 tol) and each
call's own estimate.

    python benchmarks/wall_marches.py [--quick] [--repeats 3]  ->  results/wall_marches.{csv,md}

``--quick`` (CI): tol 1e-4 only, the station at zeta = 8, one timed round.
"""

from __future__ import annotations

import os
import statistics
import time
import warnings

import numpy as np
from _common import machine, markdown_table, outdir, parser, write_csv
from moving_wall_auto import scene

import persson_fp as pf

MARCHES = ("radau", "magnus")


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    out = outdir(args)
    rounds = args.repeats or (1 if args.quick else 3)
    tols = (1e-4,) if args.quick else (1e-4, 1e-5, 1e-6)
    pr = scene(8.0 if args.quick else 128.0)
    rows = []
    for tol in tols:
        times = {m: [] for m in MARCHES}
        sols = {}
        for r in range(rounds + 1):  # round 0: the first calls, apart
            for march in MARCHES:
                t = time.perf_counter()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    sols[march] = pf.solve(pr, method="chebyshev", tol=tol, march=march, max_time=300)
                dt = time.perf_counter() - t
                if r == 0:
                    first = dt
                    sols[march + " first"] = first
                else:
                    times[march].append(dt)
        area = {m: float(np.ravel(sols[m].contact_area)[-1]) for m in MARCHES}
        plastic = {m: float(np.ravel(sols[m].plastic_area)[-1]) for m in MARCHES}
        for march in MARCHES:
            s = sols[march]
            est = max(float(np.max(s.info["error_estimate"][q])) for q in ("L1", "elastic_area", "plastic_area"))
            rows.append(
                {
                    "tol": tol,
                    "march": march,
                    "median_s": statistics.median(times[march]),
                    "first_call_s": sols[march + " first"],
                    "estimate": est,
                    "A_el": area[march],
                    "A_pl": plastic[march],
                    "steps": s.info.get("march", {}).get("steps"),
                    "A_el_radau_minus_magnus": area["radau"] - area["magnus"],
                    "A_pl_radau_minus_magnus": plastic["radau"] - plastic["magnus"],
                }
            )
            print(f"tol {tol:g} {march}: {rows[-1]['median_s']:.3g} s, estimate {est:.2g}", flush=True)
    write_csv(os.path.join(out, "wall_marches.csv"), rows)
    table = []
    for tol in tols:
        rr = {r["march"]: r for r in rows if r["tol"] == tol}
        ratio = rr["magnus"]["median_s"] / rr["radau"]["median_s"]
        table.append(
            [
                f"{tol:g}",
                f"{rr['radau']['median_s']:.3g} s",
                f"{rr['magnus']['median_s']:.3g} s",
                f"{ratio:.3g}x",
                f"{abs(rr['radau']['A_el_radau_minus_magnus']):.1e} / "
                f"{abs(rr['radau']['A_pl_radau_minus_magnus']):.1e}",
            ]
        )
    md = [
        "# The moving wall's two marches (`benchmarks/wall_marches.py`)",
        "",
        f"Machine: {machine()}. Scene W at zeta_max = {float(pr.psd.zeta_max):g}; whole `pf.solve(problem, "
        f"'chebyshev', tol=tol, march=...)` calls in turn, medians of {rounds} round(s), first calls apart.",
        "",
        markdown_table(["tol", "radau (default)", "magnus", "magnus / radau", "|A_el| / |A_pl| radau - magnus"], table),
        "",
    ]
    with open(os.path.join(out, "wall_marches.md"), "w") as fh:
        fh.write("\n".join(md))
    print("\n".join(md))
    return rows


if __name__ == "__main__":
    main()
