"""What happens in the gaps: Persson's theory against boundary-element gap fields, leak rates and adhesion.

Reference data (H = 0.8 surfaces of data/bem, L = 1, E* = 1, rms slope 0.1, q_l = 2 pi, q_r = 4 q_l, q_s = 64 q_l;
N = 512, seeds 1-3, p_bar/(E* g) in [0.005, 0.5]), Tamaas 2.9.0 boundary elements:

- ``gap_histograms_H0.8.csv``: the gap over the non-contact area.  Theory: ``pf.gap_distribution`` restricted to
  u > 0, renormalised; the Kolmogorov-Smirnov distance to the BEM histogram's CDF at its 61 bin edges.
- ``leakage_H0.8.csv``: Reynolds flow through each BEM gap field (eta = 1, unit pressure drop, L = 1, mean of x and
  y).  Theory: ``pf.leak_rate`` (critical junction, A_c = 0.42, and effective medium) with the same units.
- ``adhesion_exponential_H0.8_seed1.csv``: exponential attraction w = 1e-5 and 3e-6, rho = 8e-3.  Theory:
  ``pf.adhesive_contact`` (DMT): p_att at the BEM's repulsive pressures, and the pull-off stress.

``--generate`` (needs the optional extra: ``pip install .[bem]``, Tamaas and reynoldsflow) regenerates these three
files from the surfaces' Fourier modes (``_bem_generate.py``: Tamaas contact, gap statistics, Reynolds flow with
``reynoldsflow`` and with the finite-volume solver of ``_reynolds.py``, the adhesion loop of ``_bem_tamaas.py``)
into ``<output>/bem_generated/`` and compares them with the shipped CSVs.  The theory tables then use the generated
files wherever ``<output>/bem_generated/`` holds them, the shipped CSVs otherwise (the .md says which).  Also timed:
a gap distribution on 200 points and a leak rate per load, and 1000 loads at once.

    python benchmarks/interface_vs_bem.py [--quick] [--generate [--N 512]]  ->  results/interface_vs_bem.{csv,md}
"""

from __future__ import annotations

import csv
import os

import numpy as np
from _bem_generate import FILES, compare, generate
from _bem_tamaas import have_tamaas
from _common import median_time, outdir, parser, write_csv

import persson_fp as pf

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "bem")
G_BAR, E_STAR = 0.1, 1.0
Q_L = 2.0 * np.pi
MODELS = [("Persson", None), ("YP08", "YP08"), ("WM17", "WM17")]


SOURCE = {"folder": DATA}  # where the BEM CSVs are read from: data/bem, or the generated ones (set by main)


def _read(name):
    with open(os.path.join(SOURCE["folder"], name), newline="") as fh:
        return list(csv.DictReader(fh))


def nominal():
    return pf.SelfAffinePSD.from_rms_slope(G_BAR, 0.8, Q_L, 4 * Q_L, 64 * Q_L)


def histograms():
    """{(seed, pbar_norm): dict(pbar, A, edges, cdf, mean_gap)} from the BEM gap histograms."""
    out = {}
    for r in _read("gap_histograms_H0.8.csv"):
        key = (int(r["seed"]), float(r["pbar_norm"]))
        h = out.setdefault(
            key,
            dict(
                pbar=float(r["pbar"]),
                A=float(r["contact_fraction"]),
                lo=[],
                hi=[],
                d=[],
                mean_gap=float(r["mean_gap"]),
                hrms=float(r["hrms"]),
            ),
        )
        h["lo"].append(float(r["bin_lo"]))
        h["hi"].append(float(r["bin_hi"]))
        h["d"].append(float(r["density"]))
    for h in out.values():
        lo, hi, d = (np.array(h[k]) for k in ("lo", "hi", "d"))
        h["edges"] = np.concatenate(([lo[0]], hi))
        mass = np.concatenate(([0.0], np.cumsum(d * (hi - lo))))
        h["cdf"] = mass / mass[-1]  # over the non-contact area
    return out


def shell_psd(seed):
    """The realised spectrum of one BEM surface (shells 1..64; the q = 0 row and empty shells dropped)."""
    t = np.genfromtxt(os.path.join(DATA, f"psd_shells_H0.8_seed{seed}.csv"), delimiter=",", names=True)
    keep = (t["n"] >= 1) & (t["n"] <= 64)
    return pf.TabulatedPSD(t["q"][keep], t["C_shell_avg"][keep])


SPECTRA = ("nominal", "realised")


def _psd(spectrum, seed):
    return nominal() if spectrum == "nominal" else shell_psd(seed)


def gap_rows(quick):
    hist = histograms()
    keys = sorted(hist)
    if quick:
        keys = [k for k in keys if k[0] == 1]
    rows = []
    for (label, fudge), spectrum in [(m, sp) for m in MODELS for sp in SPECTRA]:
        loads = sorted({k[1] for k in keys})
        for seed in sorted({k[0] for k in keys}):
            psd = _psd(spectrum, seed)
            pb = np.array([hist[(seed, pn)]["pbar"] for pn in loads])
            gd = pf.gap_distribution(pf.ContactProblem(psd, E_STAR, pb, fudge=fudge))
            for j, pn in enumerate(loads):
                h = hist[(seed, pn)]
                A = gd.contact_fraction[j]
                cdf = (gd.cdf(h["edges"])[j] - A) / max(1.0 - A, 1e-300)
                rows.append(
                    dict(
                        model=label,
                        spectrum=spectrum,
                        seed=seed,
                        pbar_norm=pn,
                        A_bem=h["A"],
                        A_theory=A,
                        ks=float(np.max(np.abs(cdf - h["cdf"]))),
                        mean_gap_bem=h["mean_gap"],
                        mean_gap_theory=float(gd.mean[j]),
                        u_bar_theory=float(gd.mean_separation[j]),
                        truncated_weight=float(gd.truncated_weight[j]),
                    )
                )
    return rows


def leak_rows(quick):
    data = _read("leakage_H0.8.csv")
    if quick:
        data = [r for r in data if r["seed"] == "1"]
    rows = []
    for (label, fudge), spectrum, seed in [
        (m, sp, sd) for m in MODELS for sp in SPECTRA for sd in sorted({int(r["seed"]) for r in data})
    ]:
        sel = [r for r in data if int(r["seed"]) == seed]
        pb = np.array([float(r["pbar"]) for r in sel])
        problem = pf.ContactProblem(_psd(spectrum, seed), E_STAR, pb, fudge=fudge)
        cj = pf.leak_rate(problem, viscosity=1.0, pressure_drop=1.0, method="critical-junction")
        em = pf.leak_rate(problem, viscosity=1.0, pressure_drop=1.0, method="effective-medium")
        for r, q_cj, q_em in zip(sel, cj, em):
            K = float(r["K_mean"])
            rows.append(
                dict(
                    model=label,
                    spectrum=spectrum,
                    seed=int(r["seed"]),
                    pbar_norm=float(r["pbar_norm"]),
                    Q_bem=K,
                    Q_critical_junction=float(q_cj),
                    Q_effective_medium=float(q_em),
                    ratio_cj=float(q_cj / K) if K > 0 else (0.0 if q_cj == 0 else np.inf),
                    ratio_em=float(q_em / K) if K > 0 else (0.0 if q_em == 0 else np.inf),
                )
            )
    return rows


def adhesion_rows():
    psd = nominal()
    data = [r for r in _read("adhesion_exponential_H0.8_seed1.csv") if float(r["w"]) > 0]
    rows, pull = [], []
    for w in sorted({float(r["w"]) for r in data}):
        sel = [r for r in data if float(r["w"]) == w]
        rho = float(sel[0]["rho"])
        p_rep = np.array([float(r["mean_p_rep"]) for r in sel])
        bem_pull = -min(float(r["mean_p"]) for r in sel)
        for label, fudge in MODELS:
            ad = pf.adhesive_contact(
                pf.ContactProblem(psd, E_STAR, p_rep, fudge=fudge), pf.adhesion.Exponential(w=w, rho=rho)
            )
            for r, pa, A, u in zip(sel, ad.p_attractive, ad.contact_area, ad.mean_separation):
                rows.append(
                    dict(
                        model=label,
                        w=w,
                        p_rep=float(r["mean_p_rep"]),
                        p_att_bem=-float(r["mean_p_att"]),
                        p_att_theory=float(pa),
                        A_bem=float(r["A_rep"]),
                        A_theory=float(A),
                        gap_bem=float(r["mean_gap"]),
                        u_bar_theory=float(u),
                    )
                )
            pull.append(
                dict(
                    model=label,
                    w=w,
                    pull_off_bem=bem_pull,
                    pull_off_theory=ad.pull_off,
                    rel_error=ad.pull_off / bem_pull - 1,
                    tabor=ad.tabor,
                    pastewka_robbins=ad.pastewka_robbins["number"],
                    persson_tosatti_w_eff=ad.persson_tosatti["w_eff"],
                )
            )
    return rows, pull


def timings(repeats):
    psd = nominal()
    u = np.linspace(0, 8 * psd.rms_height, 200)
    one = pf.ContactProblem(psd, E_STAR, 0.002, fudge="WM17")
    many = pf.ContactProblem(psd, E_STAR, np.geomspace(1e-4, 0.05, 1000), fudge="WM17")
    t_gd, _ = median_time(lambda: pf.gap_distribution(one).pdf(u), repeats)
    t_cj, _ = median_time(lambda: pf.leak_rate(one, 1.0, 1.0), repeats)
    t_em, _ = median_time(lambda: pf.leak_rate(one, 1.0, 1.0, method="effective-medium"), repeats)
    t_gd_many, _ = median_time(lambda: pf.gap_distribution(many), max(1, repeats // 2))
    t_cj_many, _ = median_time(lambda: pf.leak_rate(many, 1.0, 1.0), max(1, repeats // 2))
    t_em_many, _ = median_time(lambda: pf.leak_rate(many, 1.0, 1.0, method="effective-medium"), 1)
    return dict(
        gap_200_points=t_gd,
        leak_cj=t_cj,
        leak_em=t_em,
        gap_1000_loads=t_gd_many,
        leak_cj_1000=t_cj_many,
        leak_em_1000=t_em_many,
    )


def _fmt_table(rows, key, loads, models, spectrum="nominal"):
    out = []
    for label in models:
        sel = [r for r in rows if r["model"] == label and r["spectrum"] == spectrum]
        vals = [np.mean([r[key] for r in sel if r["pbar_norm"] == p]) for p in loads]
        out.append(f"| {label} | " + " | ".join(f"{v:.3g}" for v in vals) + " |")
    return out


def main(argv=None):
    ap = parser(__doc__.splitlines()[0])
    ap.add_argument("--generate", action="store_true", help="regenerate the BEM data (needs Tamaas, reynoldsflow)")
    ap.add_argument("--N", type=int, default=None, help="BEM grid for --generate (default 512; 256 with --quick)")
    args = ap.parse_args(argv)
    d = outdir(args)
    repeats = args.repeats or (3 if args.quick else 7)
    source, agreement = _source(args, d)
    g = gap_rows(args.quick)
    lk = leak_rows(args.quick)
    ad, pull = adhesion_rows()
    t = timings(repeats)
    write_csv(os.path.join(d, "interface_vs_bem_gaps.csv"), g)
    write_csv(os.path.join(d, "interface_vs_bem_leakage.csv"), lk)
    write_csv(os.path.join(d, "interface_vs_bem_adhesion.csv"), ad + pull)
    models = [m for m, _ in MODELS]
    loads = sorted({r["pbar_norm"] for r in g})
    head = "| model | " + " | ".join(f"{p:g}" for p in loads) + " |"
    sep = "|---" * (len(loads) + 1) + "|"
    lines = [
        f"# What happens in the gaps: theory against BEM (H = 0.8, N = {source['N']})",
        "",
        f"Surfaces: seeds {sorted({r['seed'] for r in g})}; columns p̄/(E*ḡ); values are means over the seeds. "
        f"BEM data: {source['text']} Theory with the nominal spectrum the surfaces "
        "were drawn from, and (marked) with each surface's realised shell spectrum.",
        "",
        *agreement,
        "## Gap distribution over the non-contact area: Kolmogorov-Smirnov distance",
        "",
        head,
        sep,
        *_fmt_table(g, "ks", loads, models),
        "",
        "Realised spectra:",
        "",
        head,
        sep,
        *_fmt_table(g, "ks", loads, models, "realised"),
        "",
        "## Mean gap over the whole area (nominal spectrum): theory mean of P(u) / BEM (the theory's ū(p̄) / BEM below)",
        "",
        head,
        sep,
    ]
    for r in g:
        r["mean_ratio"] = r["mean_gap_theory"] / r["mean_gap_bem"]
        r["ubar_ratio"] = r["u_bar_theory"] / r["mean_gap_bem"]
    lines += _fmt_table(g, "mean_ratio", loads, models) + ["", head, sep] + _fmt_table(g, "ubar_ratio", loads, models)
    lloads = sorted({r["pbar_norm"] for r in lk})
    lhead = "| model | " + " | ".join(f"{p:g}" for p in lloads) + " |"
    lsep = "|---" * (len(lloads) + 1) + "|"
    lines += [
        "",
        "## Leak rate: theory / Reynolds flow on the BEM gap field (0 = both sealed, inf = BEM sealed)",
        "",
        "Critical junction (A_c = 0.42):",
        "",
        lhead,
        lsep,
    ]
    blocks = (
        ("ratio_cj", "nominal", None),
        ("ratio_cj", "realised", "Critical junction, realised spectra:"),
        ("ratio_em", "nominal", "Effective medium (2-D Bruggeman on P(u)):"),
        ("ratio_em", "realised", "Effective medium, realised spectra:"),
    )
    for key, spectrum, title in blocks:
        if title:
            lines += ["", title, "", lhead, lsep]
        for label in models:
            vals = []
            for p in lloads:
                rr = [r for r in lk if r["model"] == label and r["pbar_norm"] == p and r["spectrum"] == spectrum]
                fin = [r[key] for r in rr if np.isfinite(r[key])]
                vals.append(np.mean(fin) if fin else np.inf)
            lines.append(f"| {label} | " + " | ".join(f"{v:.3g}" for v in vals) + " |")
    lines += [
        "",
        "## DMT adhesion (exponential law, rho = 8e-3; seed 1)",
        "",
        "Errors over the BEM rows with p_rep/(E*ḡ) >= 0.005 (max |relative error|):",
        "",
        "| model | w | pull-off theory | pull-off BEM | error | p_att | contact area | mean gap |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for p in pull:
        sel = [r for r in ad if r["model"] == p["model"] and r["w"] == p["w"] and r["p_rep"] >= 5e-4 * (1 - 1e-9)]
        err = [
            max(abs(r[a] / r[b] - 1) for r in sel)
            for a, b in (("p_att_theory", "p_att_bem"), ("A_theory", "A_bem"), ("u_bar_theory", "gap_bem"))
        ]
        lines.append(
            f"| {p['model']} | {p['w']:g} | {p['pull_off_theory']:.4g} | {p['pull_off_bem']:.4g} | "
            f"{p['rel_error']:+.1%} | " + " | ".join(f"{e:.1%}" for e in err) + " |"
        )
    lines += [
        "",
        f"Tabor-like parameter {pull[0]['tabor']:.3g} (DMT regime), Pastewka-Robbins number "
        f"{pull[0]['pastewka_robbins']:.3g} at w = {pull[0]['w']:g} (> 1: not sticky).",
        "",
        "## Speed (median of repeats; WM17)",
        "",
        f"- gap distribution + pdf on 200 points, one load: {t['gap_200_points'] * 1e3:.2f} ms",
        f"- leak rate, one load: critical junction {t['leak_cj'] * 1e3:.2f} ms, effective medium "
        f"{t['leak_em'] * 1e3:.2f} ms",
        f"- 1000 loads: gap distribution {t['gap_1000_loads']:.3f} s, leak rate: critical junction "
        f"{t['leak_cj_1000']:.3f} s, effective medium {t['leak_em_1000']:.3f} s",
    ]
    with open(os.path.join(d, "interface_vs_bem.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return dict(gaps=g, leakage=lk, adhesion=ad, pull_off=pull, timings=t, source=source)


def _source(args, d):
    """Generate the BEM data if asked (and possible); point _read at the generated files if complete, else data/bem."""
    if args.generate:
        if have_tamaas():
            generate(d, n=args.N or (256 if args.quick else 512), quick=args.quick)
        else:  # asked to generate and cannot: an error, not the shipped data under the generated name
            raise SystemExit("interface_vs_bem.py: --generate needs Tamaas and reynoldsflow (pip install '.[bem]')")
    folder = os.path.join(d, "bem_generated")
    agreement = []
    if all(os.path.exists(os.path.join(folder, f)) for f in (*FILES, "generation.csv")):
        SOURCE["folder"] = folder
        with open(os.path.join(folder, "generation.csv"), newline="") as fh:
            meta = next(csv.DictReader(fh))
        rows, worst = compare(folder)
        rel = os.path.relpath(folder, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
        text = (
            f"regenerated in `{rel}/` by `python benchmarks/interface_vs_bem.py --generate --N {meta['N']}"
            f"{' --quick' if args.quick else ''}` ({meta['packages']}; Tamaas contact {meta['tamaas_contact_s']} s, "
            f"Reynolds flow {meta['reynolds_flow_s']} s, adhesion {meta['adhesion_s']} s with "
            f"{meta['adhesion_solves']} Tamaas solves: wall times of that one run on the shared 2-core machine; "
            "agreement with the shipped CSVs in the next table)."
        )
        agreement = [
            "## Regenerated BEM data against the shipped data/bem",
            "",
            "| quantity | compared | worst |",
            "|---|---|---|",
            *(f"| {a} | {b} | {c} |" for a, b, c in rows),
            "",
        ]
        return dict(N=int(meta["N"]), text=text, folder=folder, worst=worst), agreement
    SOURCE["folder"] = DATA
    text = "the shipped CSVs of data/bem (not regenerated: run with --generate and the `bem` extra)."
    return dict(N=512, text=text, folder=DATA, worst=None), agreement


if __name__ == "__main__":
    main()
