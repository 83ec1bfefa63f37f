"""Honesty of method "chebyshev" on the moving yield wall: random problems against fv at fine resolution.

Each problem: a self-affine surface (rms slope 0.05-4, H 0.5-0.95, roll-off q_r/q_l in {1, 2, 4}, zeta_max 4-100),
a load p_bar = r sqrt(V(zeta_max)) (r 0.2-3) and a hardness sigma_1 zeta^n (n 0.05-0.5, sigma_1 = (1 + g) p_bar,
g 0.15-3), no fudge factor.  The reference: fv (front-fixed, second order) at n_p = n_steps = 800, 1600, 3200,
Richardson-extrapolated (:func:`reference`); its uncertainty is added to every bound.  chebyshev runs once with
``tol`` drawn from 1e-3 ... 1e-6 and once at a fixed degree n_p in [12, 48] (``tol=1e-6`` for the march); for each
result and area (A_el, A_pl, A_non) the true error is compared with the reported estimate (+ the reference's
uncertainty) and, for the ``tol=`` runs, with tol.  Also bad inputs, each of
which must be a ValueError.

    python benchmarks/chebyshev_wall_fuzz.py [--quick]  ->  results/chebyshev_wall_fuzz.md
    (--quick: 3 problems, fv 400/800/1600)
"""

from __future__ import annotations

import os
import time
import warnings

import numpy as np
from _common import machine, outdir, parser

import persson_fp as pf
from persson_fp.results.invariants import SolverError

AREAS = ("elastic_area", "plastic_area", "noncontact_area")


def random_problem(rng):
    slope = float(np.exp(rng.uniform(np.log(0.05), np.log(4.0))))
    H = float(rng.uniform(0.5, 0.95))
    q_r = float(rng.choice([1.0, 2.0, 4.0]))
    zmax = float(np.exp(rng.uniform(np.log(max(4.0, 1.5 * q_r)), np.log(100.0))))
    psd = pf.SelfAffinePSD.from_rms_slope(slope, H=H, q_l=1.0, q_r=q_r, q_s=zmax)
    p_bar = float(rng.uniform(0.2, 3.0)) * float(np.sqrt(psd.V(E_star=1.0)))
    n = float(rng.uniform(0.05, 0.5))
    sigma_1 = (1.0 + float(rng.uniform(0.15, 3.0))) * p_bar
    desc = f"slope {slope:.3g}, H {H:.2f}, q_r {q_r:g}, zeta_max {zmax:.3g}, p_bar/sqrt(V) {p_bar / np.sqrt(psd.V(E_star=1.0)):.2f}, sigma_1/p_bar {sigma_1 / p_bar:.2f}, n {n:.2f}"  # noqa: E501
    return pf.ContactProblem(psd, p_bar=p_bar, hardness=pf.hardness.PowerLaw(sigma_1, n)), desc


def reference(pr, base=800):
    """fv at 800, 1600, 3200 cells and steps: the Richardson value of the last two, and as its uncertainty the larger
    of the finest run's own estimate and the change from the Richardson value of the first two (fv is not always
    in its asymptotic range: non-monotone sequences were seen)."""
    sols = [pf.solve(pr, "fv", n_p=k, n_steps=k) for k in (base, 2 * base, 4 * base)]
    ref, unc = {}, {}
    for q in AREAS:
        a, c, f = (float(np.ravel(getattr(s, q))[-1]) for s in sols)
        r1, r2 = c + (c - a) / 3.0, f + (f - c) / 3.0
        ref[q], unc[q] = r2, max(abs(f - c) / 3.0, abs(r2 - r1))
    return ref, unc


def check(sol, ref, unc):
    """(worst true / bound ratio, worst true error) over the areas; bound = estimate + the reference's uncertainty."""
    est = sol.info["error_estimate"]
    ratio, worst = 0.0, 0.0
    for q in AREAS:
        true = abs(float(np.ravel(getattr(sol, q))[-1]) - ref[q])
        ratio = max(ratio, true / (float(np.max(est[q])) + unc[q]))
        worst = max(worst, true - unc[q])
    return ratio, worst


def bad_inputs():
    """Each must raise ValueError: (description, outcome)."""
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)
    hard = pf.hardness.PowerLaw(1.0, 0.2)
    pr = pf.ContactProblem(psd, p_bar=0.3, hardness=hard)
    cases = [
        ("fudge YP08", lambda: pf.solve(pf.ContactProblem(psd, p_bar=0.3, hardness=hard, fudge="YP08"), "chebyshev")),
        ("general coefficients", lambda: pf.solve(pf.FokkerPlanckProblem(psd, p_bar=0.3, hardness=hard), "chebyshev")),
        ("tol = 0.5", lambda: pf.solve(pr, "chebyshev", tol=0.5)),
        ("tol = -1", lambda: pf.solve(pr, "chebyshev", tol=-1.0)),
        ("tol = nan", lambda: pf.solve(pr, "chebyshev", tol=float("nan"))),
        ("n_p = 4", lambda: pf.solve(pr, "chebyshev", n_p=4)),
        ("n_p = 2.5", lambda: pf.solve(pr, "chebyshev", n_p=2.5)),
        ("V0_fraction = 0.5", lambda: pf.solve(pr, "chebyshev", V0_fraction=0.5)),
        ("V0_fraction = 0", lambda: pf.solve(pr, "chebyshev", V0_fraction=0.0)),
        ("march = 'euler'", lambda: pf.solve(pr, "chebyshev", march="euler")),
        ("zeta_out = 20 > zeta_max", lambda: pf.solve(pr, "chebyshev", zeta_out=20.0)),
    ]
    out = []
    for name, fn in cases:
        try:
            fn()
            out.append((name, "no error"))
        except ValueError as err:
            out.append((name, f"ValueError: {str(err)[:90]}"))
        except Exception as err:  # (reported: anything but a ValueError is a finding)
            out.append((name, f"{type(err).__name__}: {str(err)[:90]}"))
    return out


def main(argv=None):
    p = parser(__doc__.splitlines()[0])
    args = p.parse_args(argv)
    n_problems, base = (3, 400) if args.quick else (50, 800)
    rng = np.random.default_rng(20261125)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for i in range(n_problems):
            pr, desc = random_problem(rng)
            tol = float(10.0 ** -rng.integers(3, 7))
            n_p = int(rng.integers(12, 49))
            row = {"i": i, "desc": desc, "tol": tol, "n_p": n_p}
            try:
                ref, unc = reference(pr, base)
            except (ValueError, SolverError) as err:
                row["status"] = f"no fv reference ({type(err).__name__}: {str(err)[:80]})"
                rows.append(row)
                continue
            row["A_pl"], row["ref_unc"] = ref["plastic_area"], max(unc.values())
            for key, opts in (("res_tol", {"tol": tol}), ("res_fixed", {"n_p": n_p, "tol": 1e-6})):
                t0 = time.perf_counter()
                try:
                    sol = pf.solve(pr, "chebyshev", max_time=60.0, **opts)
                    row[key] = check(sol, ref, unc)
                except (ValueError, SolverError) as err:
                    row[key] = f"{type(err).__name__}: {str(err)[:70]}"
                row[key + "_time"] = time.perf_counter() - t0
            rows.append(row)
            print(i, tol, row.get("res_tol"), n_p, row.get("res_fixed"), flush=True)
    bad = bad_inputs()
    write(rows, bad, outdir(args), base)
    return rows


def write(rows, bad, out, base):
    ran = [(r, k) for r in rows for k in ("res_tol", "res_fixed") if isinstance(r.get(k), tuple)]
    over2 = [(r, k) for r, k in ran if r[k][0] > 2.0]
    over1 = [(r, k) for r, k in ran if r[k][0] > 1.0]
    tol_runs = [r for r in rows if isinstance(r.get("res_tol"), tuple)]
    over_tol = [r for r in tol_runs if r["res_tol"][1] > r["tol"]]
    refused = [(r, k) for r in rows for k in ("res_tol", "res_fixed") if isinstance(r.get(k), str)]
    worst = max((r[k][0] for r, k in ran), default=float("nan"))
    lines = [
        "# chebyshev on the moving yield wall: random problems against fv (`benchmarks/chebyshev_wall_fuzz.py`)",
        "",
        f"Machine: {machine()}. {len(rows)} random problems (module docstring), two chebyshev runs each "
        f"(tol= and a fixed degree); reference fv {base}/{2 * base}/{4 * base} Richardson, its uncertainty added to "
        "every bound.",
        "",
        f"- results: {len(ran)} ran, {len(refused)} refused with an error (a SolverError naming the limit)",
        f"- true error > 2 x (estimate + reference uncertainty): {len(over2)}; > 1 x: {len(over1)}; worst ratio "
        f"{worst:.3g}",
        f"- tol= results with a true error over tol (beyond the reference's uncertainty): {len(over_tol)} of "
        f"{len(tol_runs)}",
        f"- bad inputs: {sum(o.startswith('ValueError') for _, o in bad)} of {len(bad)} raised a ValueError",
        "",
        "| # | problem | tol | tol=: ratio / true | time | n_p | fixed: ratio / true | time |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]

    def cell(v):
        return f"{v[0]:.3g} / {v[1]:.2e}" if isinstance(v, tuple) else str(v)

    for r in rows:
        lines.append(
            f"| {r['i']} | {r['desc']} | {r['tol']:g} | {cell(r.get('res_tol', r.get('status')))} | "
            f"{r.get('res_tol_time', float('nan')):.3g} s | {r['n_p']} | {cell(r.get('res_fixed', ''))} | "
            f"{r.get('res_fixed_time', float('nan')):.3g} s |"
        )
    lines += ["", "## Bad inputs", "", "| input | outcome |", "| --- | --- |"]
    lines += [f"| {name} | {outcome} |" for name, outcome in bad]
    with open(os.path.join(out, "chebyshev_wall_fuzz.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines[:9]))


if __name__ == "__main__":
    main()
