r"""Beyond the separable form: whole-call time against accuracy for a zeta-dependent problem, a
genuinely non-separable one and a constant hardness -- method "chebyshev" against "fv" and "mol".

Scenes (the reference problem's spectrum, ``pf.ContactProblem.reference()``):

- **clock**: B2 = V'(zeta) (1 + 0.5 sin(2 ln zeta)), B1 = -0.5 B2 / sqrt(V_max).  Brownian motion with drift in
  the clock T = int B2 dzeta (quadrature split at the roll-off), absorbed at 0: the image solution with drift is
  exact (Cox & Miller 1965).  chebyshev takes its clock path (one exponential); ``march="magnus"`` forces the
  adaptive exponential march on the same problem.
- **non-separable**: B2 = V'(zeta) (1 + 0.2 (p / p_bar) ln zeta) -- no closed form.  The "error" column is the
  difference from chebyshev at tol = 1e-7 (given max_time = 600 s; stated as such: errors
  below ~1e-7 are not resolved), next to each run's own
  estimate.
- **hardness**: the homogenised problem with a constant hardness sigma_Y = 3 p_bar; pf.exact (the strip series)
  is the reference; sines (the series itself) is listed for scale.

Every time is the median of ``--repeats`` whole ``pf.solve`` calls after one untimed call (calls over a second:
one timed repeat).  Errors: |A_el - reference| at zeta_max (and for the hardness scene the worst of A_el, A_pl and
L1 from ``Solution.compare``; for the clock scene chebyshev's L1 too, its polynomial on 3000 cells).

    python benchmarks/general_engine_wide.py [--quick] [--repeats 3]  ->  results/general_engine_wide.{csv,md}
"""

from __future__ import annotations

import math
import os
import sys
import time
import warnings

import numpy as np
from scipy.integrate import quad
from scipy.special import ndtr

import persson_fp as pf

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))
from _common import machine, outdir, parser, write_csv  # noqa: E402
from solvers.chebyshev.test_error_estimates import poly_cell_masses  # noqa: E402

REF = pf.ContactProblem.reference()
PSD, PB, VMAX = REF.psd, float(REF.p_bar[0]), float(REF.V_max)
MU = -0.5 / math.sqrt(VMAX)


def _clock_B2(p, z):
    return np.full(np.shape(p), float(PSD.dV_dzeta(z)) * (1.0 + 0.5 * math.sin(2.0 * math.log(z))))


def clock_exact(edges):
    """(cell masses, A*) of the clock scene at zeta_max: the image solution with drift in T = int B2 dzeta."""
    zr, zm = float(PSD.zeta_r), float(PSD.zeta_max)
    T = sum(
        quad(lambda z: float(_clock_B2(0.0, z)), a, b, epsabs=0.0, epsrel=1e-13, limit=200)[0]
        for a, b in ((1.0, zr), (zr, zm))
    )
    s = math.sqrt(T)

    def cells(c):
        return np.diff(ndtr((edges - c - MU * T) / s))

    w = math.exp(-2.0 * MU * PB)
    return cells(PB) - w * cells(-PB), ndtr((PB + MU * T) / s) - w * ndtr((-PB + MU * T) / s)


def scenes():
    clock = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=_clock_B2, B1=lambda p, z: MU * _clock_B2(p, z))
    nonsep = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: PSD.dV_dzeta(z) * (1.0 + 0.2 * p / PB * np.log(z)))
    return {"clock": clock, "non-separable": nonsep, "hardness": pf.ContactProblem.reference(hardness=3.0 * PB)}


def runs(scene, quick):
    """(method, options) of a scene, cheap to dear."""
    tols = (1e-4, 1e-6) if quick else (1e-4, 1e-6, 1e-8, 1e-10)
    out = [("chebyshev", {"tol": t}) for t in tols]
    if scene == "clock":
        out += [("chebyshev", {"tol": t, "march": "magnus"}) for t in ((1e-4,) if quick else (1e-4, 1e-6, 1e-7))]
    if scene == "non-separable":
        out = [("chebyshev", {"tol": t}) for t in ((1e-4,) if quick else (1e-4, 1e-5, 1e-6))]
    ns = (200,) if quick else (200, 400, 800, 1600)
    out += [("fv", {"n_p": n, "n_steps": n}) for n in ns]
    out += [("mol", {"tol": t}) for t in ((1e-3,) if quick else (1e-3, 1e-4))]
    if scene == "hardness":
        out += [("sines", {"tol": t}) for t in ((1e-6,) if quick else (1e-6, 1e-10))]
    return out


def timed(pr, method, opts, repeats):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = pf.solve(pr, method=method, **opts)  # the first call, untimed
        times = []
        for _ in range(repeats if sol.wall_time < 1.0 else 1):
            t0 = time.perf_counter()
            sol = pf.solve(pr, method=method, **opts)
            times.append(time.perf_counter() - t0)
    return float(np.median(times)), sol


def measure(name, pr, method, opts, sol, ref):
    est = sol.error_estimate
    row = {
        "scene": name,
        "method": method,
        "options": str(opts),
        "path": sol.info.get("path", ""),
        "estimate_area": float(np.max(est["contact_area"])),
        "estimate_L1": float(np.max(est["L1"])),
    }
    if name == "hardness":
        c = sol.compare()
        row["error_area"] = float(max(np.max(c.elastic_area_error), np.max(c.plastic_area_error)))
        row["error_L1"] = float(np.max(c.L1))
        row["estimate_area"] = float(max(np.max(est["elastic_area"]), np.max(est["plastic_area"])))
    elif name == "clock":
        edges = np.linspace(0.0, float(np.atleast_2d(sol.p)[-1][-1]), 3001)
        mass, area = clock_exact(edges)
        row["error_area"] = abs(float(sol.contact_area_all[-1, 0]) - area)
        row["error_L1"] = (
            float(np.sum(np.abs(poly_cell_masses(sol, -1, edges) - mass))) if method == "chebyshev" else np.nan
        )
    else:
        row["error_area"] = abs(float(sol.contact_area_all[-1, 0]) - ref)
        row["error_L1"] = np.nan
    if "march" in sol.info:
        row["march_steps"] = sol.info["march"]["steps"]
        row["march_rejected"] = sol.info["march"]["rejected"]
    if method == "chebyshev":
        row["degree"] = sol.info["grid"]["n_p"]
    return row


def main(argv=None):
    p = parser(__doc__.splitlines()[0])
    args = p.parse_args(argv)
    repeats = args.repeats or (1 if args.quick else 3)
    rows = []
    for name, pr in scenes().items():
        ref = None
        if name == "non-separable":  # the stated reference: chebyshev at a much tighter tol
            with warnings.catch_warnings():  # (the reference only: more time than a user call's default budget)
                warnings.simplefilter("ignore")
                fine = pf.solve(pr, method="chebyshev", tol=1e-5 if args.quick else 1e-7, max_time=600)
            ref = float(fine.contact_area_all[-1, 0])
        for method, opts in runs(name, args.quick):
            try:
                t, sol = timed(pr, method, opts, repeats)
            except (ValueError, pf.SolverError) as err:
                rows.append({"scene": name, "method": method, "options": str(opts), "status": str(err)[:120]})
                continue
            row = {**measure(name, pr, method, opts, sol, ref), "seconds": t, "status": "ok"}
            rows.append(row)
            print(
                f"{name:14s} {method:9s} {str(opts):40s} {t * 1e3:9.1f} ms  area err {row['error_area']:.2e} "
                f"est {row['estimate_area']:.2e}",
                flush=True,
            )
    d = outdir(args)
    write_csv(os.path.join(d, "general_engine_wide.csv"), rows)
    write_md(rows, d, repeats)
    return rows


def write_md(rows, d, repeats):
    lines = [
        "# Beyond the separable form: time against accuracy (benchmarks/general_engine_wide.py)",
        "",
        f"Machine: {machine()}.  Median of {repeats} whole `pf.solve` calls after an untimed one (calls over 1 s: "
        "one); a shared machine, so the times are indicative within a factor ~1.5.",
        "Error: area = worst of |A_el|, |A_pl| against the reference (clock: the image solution in the clock; "
        "hardness: pf.exact; non-separable: chebyshev at tol 1e-7 (its own estimate ~1e-7), *not* an exact "
        "solution); L1 where measured.",
        "",
        "| scene | method | options | path | time | error (area) | estimate (area) | error (L1) | estimate (L1) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r.get("status") != "ok":
            lines.append(f"| {r['scene']} | {r['method']} | `{r['options']}` | refused: {r['status']} | | | | | |")
            continue
        eL1 = "-" if not np.isfinite(r["error_L1"]) else f"{r['error_L1']:.2g}"
        lines.append(
            f"| {r['scene']} | {r['method']} | `{r['options']}` | {r['path']} | {r['seconds'] * 1e3:.3g} ms | "
            f"{r['error_area']:.2g} | {r['estimate_area']:.2g} | {eL1} | {r['estimate_L1']:.2g} |"
        )
    with open(os.path.join(d, "general_engine_wide.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
