"""method="auto" against the best hand-picked method, end to end, at tol = 1e-3, 1e-6, 1e-9.

For every scene and tolerance: the whole ``pf.solve(problem, method="auto", tol=tol)`` call (median of repeats),
and the fastest hand-picked run that meets the same tolerance (a sweep over methods and resolutions; "meets"
means the L1 error of P0 and every area error at every station <= tol: the true error where a closed form exists,
else the solver's own half-resolution estimate).  The hand-picked times do not include the error check that
``auto`` makes (its ``compare()`` or its partner run): the ratio is the price of not knowing the method.

    python benchmarks/auto.py [--quick]  ->  results/auto.{csv,md}
"""

from __future__ import annotations

import os
import time
import warnings

import numpy as np
from _common import machine, median_time, outdir, parser, write_csv

import persson_fp as pf


def scenes():
    ref = pf.ContactProblem.reference()
    dV = lambda z: float(ref.psd.dV_dzeta(z))  # noqa: E731
    psd10 = pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)
    return {
        "A* only": pf.ContactProblem.reference(p_bar_ratio=0.5),
        "fudge YP08": pf.ContactProblem.reference(p_bar_ratio=0.5, fudge="YP08"),
        "constant hardness": pf.ContactProblem.reference(p_bar_ratio=0.5, hardness=0.075),
        "moving hardness": pf.ContactProblem(psd10, p_bar=0.3, hardness=pf.hardness.PowerLaw(1.0, 0.2)),
        "general coefficients": pf.FokkerPlanckProblem(
            ref.psd, p_bar=0.025, B1=lambda p, z: -0.1 * p * dV(z), B2=lambda p, z: (1 + p / 0.05) * dV(z)
        ),
    }


def candidates(pr, quick):
    if pr.has_closed_form:
        out = [("sines", {"tol": t}) for t in (1e-4, 1e-7, 1e-10, 1e-13)]
        fv = [(100, 50), (200, 100), (400, 400), (800, 1600)] if not quick else [(200, 100)]
        out += [("fv", {"n_p": n, "n_steps": k}) for n, k in fv]
        out += [("mol", {"rtol": r}) for r in ((1e-5, 1e-8) if not quick else (1e-5,))]
        return out
    ns = (50, 100, 200, 400, 800) if not quick else (50, 100, 200)
    return [("fv", {"n_p": n, "n_steps": n}) for n in ns] + [("mol", {"rtol": 1e-8, "n_p": n}) for n in ns[:3]]


def errors(sol):
    est = sol.error_estimate
    L1 = float(np.nanmax(est["L1"]))
    areas = [est["contact_area"]] + [est[k] for k in ("elastic_area", "plastic_area") if k in est]
    return L1, float(max(np.max(a) for a in areas))


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    quick = args.quick
    reps = args.repeats or (2 if quick else 5)
    tols = (1e-3, 1e-6) if quick else (1e-3, 1e-6, 1e-9)
    out = outdir(args)
    rows = []
    for name, pr in scenes().items():
        if quick and name == "general coefficients":
            continue
        hand = []
        for method, opts in candidates(pr, quick):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    t, sol = median_time(lambda m=method, o=opts: pf.solve(pr, m, **o), reps if not quick else 1)
                except (ValueError, pf.SolverError) as err:
                    hand.append(
                        {
                            "method": method,
                            "options": opts,
                            "time": np.inf,
                            "L1": np.inf,
                            "area": np.inf,
                            "status": type(err).__name__,
                        }
                    )
                    continue
            L1, area = errors(sol)
            hand.append({"method": method, "options": opts, "time": t, "L1": L1, "area": area, "status": "ok"})
        for tol in tols:
            ok = [h for h in hand if h["L1"] <= tol and h["area"] <= tol]
            best = min(ok, key=lambda h: h["time"]) if ok else None
            row = {"scene": name, "tol": tol}
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    t0 = time.perf_counter()
                    sol = pf.solve(pr, method="auto", tol=tol)
                    first = time.perf_counter() - t0
                    n = reps if first < 2.0 else 1
                    t, sol = median_time(lambda tol=tol: pf.solve(pr, method="auto", tol=tol), n, warmup=0)
                a = sol.info["auto"]
                row.update(
                    auto_method=a["method"],
                    auto_options=repr(a["attempts"][-1]["options"]),
                    auto_attempts=len(a["attempts"]),
                    auto_time=t,
                    auto_L1=a["L1"],
                    auto_area=a["area_error"],
                    auto_kind=a["kind"],
                    auto_status="ok",
                )
            except pf.SolverError as err:
                row.update(auto_status=f"SolverError: {str(err)[:120]}", auto_time=np.nan)
            if best is not None:
                row.update(
                    best_method=best["method"],
                    best_options=repr(best["options"]),
                    best_time=best["time"],
                    ratio=row["auto_time"] / best["time"],
                )
            else:
                row.update(best_method="none reaches tol in the sweep", best_time=np.nan, ratio=np.nan)
            rows.append(row)
            print(
                f"{name:22s} tol {tol:.0e}: auto {row.get('auto_method', '-')} {row['auto_time'] * 1e3:.3g} ms, "
                f"best {row['best_method']} {row['best_time'] * 1e3:.3g} ms, ratio {row['ratio']:.2f}"
            )
    write_csv(os.path.join(out, "auto.csv"), rows)
    lines = [
        "# method='auto' vs the best hand-picked method (`benchmarks/auto.py`)",
        "",
        f"Machine: {machine()}. Whole-call medians; ratio = auto / best hand-picked run meeting tol.",
        "",
        "| scene | tol | auto: method (attempts) | auto time (ms) | best hand-picked | its time (ms) | ratio |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append(
            f"| {r['scene']} | {r['tol']:.0e} | {r.get('auto_method', r['auto_status'])} "
            f"({r.get('auto_attempts', '-')}) | {r['auto_time'] * 1e3:.3g} | {r['best_method']} "
            f"{r.get('best_options', '')} | {r['best_time'] * 1e3:.3g} | {r['ratio']:.2f} |"
        )
    with open(os.path.join(out, "auto.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return rows


if __name__ == "__main__":
    main()
