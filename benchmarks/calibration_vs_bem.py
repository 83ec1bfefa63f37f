"""Calibration against the BEM data: fit on two surfaces, predict the third (every split, both H), fitted vs fixed.

For H = 0.8 and H = 0.3 (three Tamaas surfaces each, data/bem/runs.csv, tag "main", N = 1024, seven loads) every
split fits gamma of YP08, WM17 and Xu24 on two surfaces' A* (``pf.calibrate``, each surface with its realised shell
spectrum) and predicts the third; the error is the mean |A*_theory/A*_BEM - 1| over its seven loads, then averaged
over the three splits.  The fixed models (Persson 2001, YP08 gamma = 0.45, WM17 gamma = 5/9, Xu24 gamma = 0.45)
are scored on the same held-out surfaces.  Cross-H transfer: gamma fitted on all three surfaces of one H predicts
the three of the other.  The mean separation (data/bem/gaps_H0.8.csv, H = 0.8 only) is calibrated the same way,
alone and jointly with A*.  Speed: a one-parameter fit to 3 surfaces x 7 loads, cold (the effective-variance and
separation tables cleared before each repeat), median of repeats.  Coverage: noisy synthetic data sets (3 %
relative Gaussian noise on the package's own curves, nominal spectra) per model; how often the 95 % interval
holds the true gamma = 0.45 (400 draws for Xu24, 50 for YP08).

    python benchmarks/calibration_vs_bem.py [--quick]
        ->  results/calibration_vs_bem.{csv,md}, calibration_speed.csv, calibration_coverage.csv
"""

from __future__ import annotations

import os
import time

import numpy as np
from _common import machine, median_time, outdir, parser, write_csv

import persson_fp as pf

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "bem")
SEEDS = (1, 2, 3)
FIXED = [("Persson 2001", None), ("YP08 γ=0.45", "YP08"), ("WM17 γ=5/9", "WM17"), ("Xu24 γ=0.45", "Xu24")]


def shell_psd(H, seed):
    """The surface's realised spectrum (q = 0 row and the empty shells beyond q_s dropped, as data/bem says)."""
    t = np.genfromtxt(os.path.join(DATA, f"psd_shells_H{H}_seed{seed}.csv"), delimiter=",", names=True)
    keep = (t["n"] >= 1) & (t["n"] <= 64)
    return pf.TabulatedPSD(t["q"][keep], t["C_shell_avg"][keep])


def area_tables(H):
    """{seed: {"p_bar", "contact_area"}} from runs.csv (tag main, N = 1024)."""
    r = np.genfromtxt(os.path.join(DATA, "runs.csv"), delimiter=",", names=True, dtype=None, encoding="utf-8")
    out = {}
    for s in SEEDS:
        m = (r["tag"] == "main") & (r["H"] == H) & (r["seed"] == s)
        order = np.argsort(r["pbar"][m])
        out[s] = {"p_bar": r["pbar"][m][order], "contact_area": r["Astar"][m][order]}
    return out


def gap_tables(areas):
    """{seed: {"p_bar", "mean_separation", "contact_area"}} of H = 0.8: the mean gap of the largest N per surface
    and load (N = 256-1024 agree to 2e-4), the contact area of runs.csv at N = 1024 (``areas``) at the same loads."""
    t = np.genfromtxt(os.path.join(DATA, "gaps_H0.8.csv"), delimiter=",", names=True)
    out = {}
    for s in SEEDS:
        rows = {}
        for row in t[t["seed"] == s]:
            if row["pbar"] not in rows or row["N"] > rows[row["pbar"]]["N"]:
                rows[row["pbar"]] = row
        p = np.array(sorted(rows))
        a = areas[s]
        idx = [int(np.flatnonzero(np.isclose(a["p_bar"], x, rtol=1e-9))[0]) for x in p]
        out[s] = {
            "p_bar": p,
            "mean_separation": np.array([rows[x]["mean_gap"] for x in p]),
            "contact_area": a["contact_area"][idx],
        }
    return out


def held_out_error(psd, table, fudge, quantity, weighting="yang-persson"):
    f = pf.calibration.predict(psd, 1.0, table["p_bar"], pf.fudge.resolve(fudge), quantity, weighting)
    return float(np.mean(np.abs(f / table[quantity] - 1.0)))


def cross_validate(psds, tables, models, quantities, label):
    """Rows: per held-out surface and model (fitted and fixed)."""
    rows = []
    for out in SEEDS:
        train = [s for s in SEEDS if s != out]
        for m in models:
            cal = pf.calibrate([psds[s] for s in train], [tables[s] for s in train], model=m, quantities=quantities)
            err = {q: held_out_error(psds[out], tables[out], cal.model, q) for q in quantities}
            rows.append(
                dict(
                    case=label,
                    held_out=out,
                    model=f"{m} fitted",
                    gamma=cal.params["gamma"],
                    gamma_std=cal.uncertainty["gamma"],
                    **{f"err_{q}": e for q, e in err.items()},
                )
            )
        for name, fz in FIXED:
            err = {q: held_out_error(psds[out], tables[out], fz, q) for q in quantities}
            rows.append(
                dict(
                    case=label,
                    held_out=out,
                    model=name,
                    gamma=np.nan,
                    gamma_std=np.nan,
                    **{f"err_{q}": e for q, e in err.items()},
                )
            )
    return rows


def transfer(psds, tables, models):
    """gamma fitted on all surfaces of one H, error on every surface of the other (A*)."""
    rows = []
    for src, dst in ((0.8, 0.3), (0.3, 0.8)):
        for m in models:
            cal = pf.calibrate([psds[src][s] for s in SEEDS], [tables[src][s] for s in SEEDS], model=m)
            err = np.mean([held_out_error(psds[dst][s], tables[dst][s], cal.model, "contact_area") for s in SEEDS])
            own = np.mean([held_out_error(psds[dst][s], tables[dst][s], m, "contact_area") for s in SEEDS])
            rows.append(
                dict(
                    case=f"fit H={src} -> predict H={dst}",
                    model=m,
                    gamma=cal.params["gamma"],
                    gamma_std=cal.uncertainty["gamma"],
                    err_contact_area=float(err),
                    err_default=float(own),
                )
            )
    return rows


def _clear_caches():
    from persson_fp.theory import effective, separation_weight

    effective._CACHE.clear()
    separation_weight._WEIGHTS.clear()


def speed(psds, tables, repeats):
    out = []
    for m, qs in (("YP08", ("contact_area",)), ("WM17", ("contact_area",)), ("Xu24", ("contact_area",))):

        def run(m=m, qs=qs):
            _clear_caches()
            return pf.calibrate([psds[s] for s in SEEDS], [tables[s] for s in SEEDS], model=m, quantities=qs)

        t, cal = median_time(run, repeats)
        out.append(dict(model=m, quantities="+".join(qs), points=cal.n_points, nfev=cal.nfev, time_s=t))
    return out


def coverage(draws, seed=12345):
    """How often the 95 % (and 1-sigma) interval holds the true gamma = 0.45: Xu24 (A*, 1 surface x 7 loads) and
    YP08 (A* and mean separation, 2 surfaces x 7 loads), 3 % relative noise."""
    q_l = 2 * np.pi
    psds = [pf.SelfAffinePSD.from_rms_slope(0.1, H, q_l, 4 * q_l, 64 * q_l) for H in (0.8, 0.3)]
    p = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]) * 0.1
    out = []
    cases = (("Xu24", psds[:1], ("contact_area",)), ("YP08", psds, ("contact_area", "mean_separation")))
    for (model, surfaces, quantities), n_draws in zip(cases, draws):
        rng = np.random.default_rng(seed)
        truth = pf.fudge.resolve(model)
        clean = [{q: pf.calibration.predict(s, 1.0, p, truth, q) for q in quantities} for s in surfaces]
        hit95 = hit68 = 0
        for _ in range(n_draws):
            data = [
                {"p_bar": p, **{q: v * (1 + 0.03 * rng.standard_normal(p.size)) for q, v in c.items()}} for c in clean
            ]
            cal = pf.calibrate(surfaces, data, model=model)
            lo, hi = cal.interval(0.95)["gamma"]
            hit95 += lo <= 0.45 <= hi
            hit68 += abs(cal.params["gamma"] - 0.45) <= cal.uncertainty["gamma"]
        out.append(
            dict(
                model=model,
                surfaces=len(surfaces),
                quantities="+".join(quantities),
                draws=n_draws,
                in_95=hit95,
                in_1sigma=hit68,
            )
        )
    return out


def _mean(rows, model, key):
    return float(np.mean([r[key] for r in rows if r["model"] == model]))


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    d = outdir(args)
    models = ["YP08"] if args.quick else ["YP08", "WM17", "Xu24"]
    Hs = (0.8,) if args.quick else (0.8, 0.3)
    psds = {H: {s: shell_psd(H, s) for s in SEEDS} for H in (0.8, 0.3)}
    tables = {H: area_tables(H) for H in (0.8, 0.3)}
    t0 = time.perf_counter()
    rows = []
    for H in Hs:
        rows += cross_validate(psds[H], tables[H], models, ("contact_area",), f"A*, H={H}")
    gaps = gap_tables(tables[0.8])
    rows += cross_validate(psds[0.8], gaps, models, ("mean_separation",), "mean separation, H=0.8")
    if not args.quick:
        rows += cross_validate(psds[0.8], gaps, models, ("contact_area", "mean_separation"), "A* + sep., H=0.8")
    trans = [] if args.quick else transfer(psds, tables, models)
    t_cv = time.perf_counter() - t0
    sp = speed(psds[0.8], tables[0.8], args.repeats or (2 if args.quick else 7))
    cov = coverage((5, 5) if args.quick else (400, 50))
    write_csv(os.path.join(d, "calibration_coverage.csv"), cov)
    write_csv(os.path.join(d, "calibration_vs_bem.csv"), rows + trans)
    write_csv(os.path.join(d, "calibration_speed.csv"), sp)

    lines = [
        "# Calibration against BEM: fit on two surfaces, predict the third",
        "",
        "Held-out error: mean |theory/BEM - 1| over the held-out surface's 7 loads, averaged over the 3 splits "
        "(fitted: gamma ± 1 sigma, mean over the splits). Realised spectra; BEM A* at N = 1024 (it reads "
        "1.5-5 % high against the converged value, data/bem/README.md: a fitted gamma absorbs that bias).",
        "",
    ]
    for case in dict.fromkeys(r["case"] for r in rows):
        sel = [r for r in rows if r["case"] == case]
        keys = [k for k in sel[0] if k.startswith("err_")]
        lines += [
            f"## {case}",
            "",
            "| model | gamma (splits) | " + " | ".join(f"held-out {k[4:]}" for k in keys) + " |",
            "|---|---|" + "---|" * len(keys),
        ]
        for m in dict.fromkeys(r["model"] for r in sel):
            g = [r for r in sel if r["model"] == m]
            gam = ", ".join(f"{r['gamma']:.3f}±{r['gamma_std']:.3f}" for r in g) if np.isfinite(g[0]["gamma"]) else "—"
            lines.append(f"| {m} | {gam} | " + " | ".join(f"{_mean(sel, m, k):.1%}" for k in keys) + " |")
        lines.append("")
    if trans:
        lines += [
            "## Cross-H transfer (A*)",
            "",
            "| fit on -> predict | model | gamma | error with fitted gamma | with default gamma |",
            "|---|---|---|---|---|",
        ]
        for r in trans:
            lines.append(
                f"| {r['case']} | {r['model']} | {r['gamma']:.3f}±{r['gamma_std']:.3f} | "
                f"{r['err_contact_area']:.1%} | {r['err_default']:.1%} |"
            )
        lines.append("")
    lines += [
        "## Speed: one-parameter fit, 3 surfaces x 7 loads (A*), cold tables, median of repeats",
        "",
        "| model | points | model evaluations | time |",
        "|---|---|---|---|",
    ]
    for r in sp:
        lines.append(f"| {r['model']} | {r['points']} | {r['nfev']} | {r['time_s'] * 1e3:.0f} ms |")
    lines += [
        "",
        "## Coverage of the stated uncertainty (synthetic data, true gamma = 0.45, 3 % noise)",
        "",
        "| model | surfaces x 7 loads | quantities | 95 % interval holds gamma | ± 1 sigma holds gamma |",
        "|---|---|---|---|---|",
    ]
    for r in cov:
        lines.append(
            f"| {r['model']} | {r['surfaces']} | {r['quantities']} | {r['in_95']}/{r['draws']} | "
            f"{r['in_1sigma']}/{r['draws']} |"
        )
    lines += ["", f"Cross-validation run: {t_cv:.1f} s. Machine: {machine()}."]
    with open(os.path.join(d, "calibration_vs_bem.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return rows, trans, sp, cov


if __name__ == "__main__":
    main()
