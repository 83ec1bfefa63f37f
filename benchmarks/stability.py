"""Stability atlas of the time discretisations.

Reference problem (p_bar = 0.5 sqrt(V)), r = dtau / (2 dp^2) = (1/2) dB2 dzeta / dp^2 per step
(steps uniform in the effective variance tau, so r is the same for every step).

1. **Explicit onset.**  fv ``scheme="explicit"`` with ``space="fv2"`` (theory: stable for r <= 1/2,
   sign-alternating (oscillating) modes for r > 1/4) and ``"compact4"`` (r <= 1/3, oscillating for
   r > 1/6), py-pde's "euler" (same 2nd-order stencil) and FiPy's explicit scheme when installed, for
   r from 0.1 to 2 on several grids, from the exact start (smooth data: only a true instability can
   grow) and from a one-cell delta at zeta = 1 (every mode excited).  persson-fp runs use
   ``allow_unstable=True`` and record the :class:`InstabilityError` they raise.  The growth factor
   per step is *measured* on the implementation: the spectral radius (and most negative eigenvalue)
   of one explicit step built from ``persson_fp.solvers.fv``'s own operators, plus the growth of
   max|P0| the run itself reported before stopping.  Outcome: "blown-up" (the run stopped and the
   step's spectral radius > 1, or it returned a field with |P0| above the start), "oscillating"
   (completed -- or stopped on a non-monotone contact area while the spectral radius is <= 1 -- with
   sign-alternating modes), "stable".
2. **Crank--Nicolson from a discrete delta** (``initial="delta"``): negative P0 and ringing amplitude
   against r, against Rannacher start-up, TR-BDF2 and backward Euler at the same steps.
3. **Backward Euler's smearing**: error and signed A* error against the step, TR-BDF2 alongside.
4. **MOL with an explicit integrator**: RK45 against BDF, rhs calls and time against n_p.
5. **Nonlinear fudge factor** (YP08): fv TR-BDF2 with lagged / predictor / Picard coupling, error
   against steps (the lagged coupling is first order and sets the floor).

Outputs: stability_explicit.csv, stability_ringing.csv, stability_smearing.csv, stability_mol.csv,
stability_coupling.csv, stability.md (measured onsets), stability_map.png (method x r x grid coloured
by outcome), stability.png (panels 2-5).

    python benchmarks/stability.py [--quick] [--output DIR]
"""

from __future__ import annotations

import math
import os
import re
import sys
import time
import warnings

import numpy as np

import persson_fp as pf
from persson_fp.results.solution import InstabilityError

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import errors_of, have, machine, markdown_table, outdir, parser, progress, write_csv  # noqa: E402

THEORY_ONSET = {"fv2": 0.5, "compact4": 1.0 / 3.0}
"""Explicit stability limit in r of fv's spaces (fv.py: r_limit)."""


def step_spectrum(space: str, n_p: int, r: float):
    """(spectral radius, most negative eigenvalue) of one explicit fv step at ``r``, from fv's operators.

    The step is P <- M^-1 (M + dtau L) P with L = ``fv.apply_operator`` and M = ``fv.apply_mass``;
    with dp = 1, dtau = 2 r.
    """
    from persson_fp.solvers import fv

    eye = np.eye(n_p)
    L = fv.apply_operator(eye, 0.5)  # rows act on the last axis: L @ e_j column by column (symmetric)
    M = fv.apply_mass(eye, space)
    A = np.linalg.solve(M, M + 2.0 * r * L)
    lam = np.linalg.eigvals(A).real
    return float(np.max(np.abs(lam))), float(np.min(lam))


def steps_for_r(problem, n_p, r, initial, k_domain=8.0, tau0_fraction=0.05):
    dp = problem.p_max(k_domain) / n_p
    span = float(np.max(problem.tau())) * (1.0 if initial == "delta" else 1.0 - tau0_fraction)
    return max(1, int(math.ceil(span / (2.0 * r * dp**2)))), span, dp


_FACTOR = re.compile(r"factor ([0-9.eE+-]+) by zeta = ([0-9.eE+-]+)")


def run_explicit(pr, method, space, n_p, r, initial):
    """One explicit run; returns the CSV row."""
    n, span, dp = steps_for_r(pr, n_p, r, initial)
    r_act = span / (2.0 * n * dp**2)
    rho, lam_min = step_spectrum("fv2" if method != "fv" else space, n_p, r_act)
    row = {
        "method": method,
        "space": space if method == "fv" else "fv2 stencil",
        "n_p": n_p,
        "initial": initial,
        "r_target": r,
        "r": r_act,
        "n_steps": n,
        "spectral_radius": rho,
        "min_eigenvalue": lam_min,
    }
    if method == "fv":
        opts = dict(
            scheme="explicit",
            stepping="tau",
            space=space,
            n_p=n_p,
            n_steps=n,
            initial=initial,
            allow_unstable=True,
            check_every=1,
        )
    elif method == "py-pde":
        opts = dict(solver="euler", n_p=n_p, cfl=2.0 * r_act, initial=initial, allow_unstable=True)
    else:  # fipy
        opts = dict(scheme="explicit", n_p=n_p, n_steps=n, initial=initial, allow_unstable=True)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = pf.solve(pr, method, check=False, **opts)  # the atlas classifies the result itself
        e = errors_of(sol)
        P = sol.P0_all
        ex = sol.exact_on_grid()
        neg = float(max(-P.min(), 0.0) / np.max(ex))
        grew = float(np.max(np.abs(P)) / np.max(ex))
        r_rep = sol.info.get("r_max")
        if r_rep is not None and method in ("py-pde", "fipy"):
            r_rep = 0.5 * r_rep  # py-pde's and FiPy's r is S dV / dp^2
        outcome = (
            "blown-up"
            if (grew > 10.0 or e["L1"] > 1.0)
            else ("oscillating" if (neg > 1e-10 or lam_min < 0) else "stable")
        )
        row.update(raised="", message="", L1=e["L1"], neg_P0_rel=neg, max_P0_rel=grew, r_reported=r_rep)
    except InstabilityError as err:
        msg = str(err)
        m = _FACTOR.search(msg)
        row.update(raised="InstabilityError", message=msg, L1=np.nan)
        if m:  # apparent growth per step of max|P0| until the check fired
            G, z = float(m.group(1)), float(m.group(2))
            tau_z = float(np.max(pr.tau(z))) - (0.0 if initial == "delta" else 0.05 * float(np.max(pr.tau())))
            k = max(tau_z / (2.0 * r_act * dp**2), 1.0)
            row.update(reported_growth=G, at_zeta=z, growth_per_step_run=G ** (1.0 / k))
        outcome = "blown-up" if rho > 1.0 + 1e-9 else "oscillating"
    except Exception as err:  # noqa: BLE001 - e.g. a generic tool's own error: record it
        row.update(raised=type(err).__name__, message=str(err), L1=np.nan)
        outcome = "blown-up" if rho > 1.0 + 1e-9 else "error"
    row.update(outcome=outcome, wall=time.perf_counter() - t0)
    return row


def explicit_atlas(pr, quick):
    rs = (
        (0.1, 0.3, 0.45, 0.6, 2.0)
        if quick
        else (0.1, 0.2, 0.25, 0.3, 1 / 3, 0.36, 0.45, 0.5, 0.52, 0.6, 0.75, 1.0, 1.5, 2.0)
    )
    grids = (50,) if quick else (50, 100, 200)
    cases = []
    for initial in ("exact", "delta"):
        for space in ("fv2", "compact4"):
            for n_p in grids:
                cases += [("fv", space, n_p, r, initial) for r in rs]
    if not quick:
        if have("py-pde"):
            cases += [("py-pde", "fv2", 100, r, "exact") for r in (0.25, 0.45, 0.5, 0.52, 1.0, 2.0)]
        if have("fipy"):
            cases += [("fipy", "fv2", 50, r, "exact") for r in (0.25, 0.45, 0.5, 0.52, 1.0, 2.0)]
    rows = []
    for i, c in enumerate(cases):
        rows.append(run_explicit(pr, *c))
        progress(i + 1, len(cases), "explicit atlas")
    return rows


def onsets(rows):
    """Per (method, space, initial, n_p): largest r not blown up and smallest r blown up."""
    out = []
    keys = list(dict.fromkeys((r["method"], r["space"], r["initial"], r["n_p"]) for r in rows))
    for k in keys:
        sub = sorted((r for r in rows if (r["method"], r["space"], r["initial"], r["n_p"]) == k), key=lambda r: r["r"])
        ok = [r["r"] for r in sub if r["outcome"] != "blown-up"]
        bad = [r["r"] for r in sub if r["outcome"] == "blown-up"]
        osc = [r["r"] for r in sub if r["outcome"] == "oscillating"]
        first_bad = min(bad) if bad else np.nan
        last_ok = max([x for x in ok if not bad or x < first_bad], default=np.nan)
        theory = THEORY_ONSET.get(k[1], 0.5)
        out.append(
            {
                "method": k[0],
                "space": k[1],
                "initial": k[2],
                "n_p": k[3],
                "stable_up_to": last_ok,
                "blown_up_from": first_bad,
                "first_oscillating": min(osc) if osc else np.nan,
                "theory": theory,
            }
        )
    return out


def ringing(pr, quick):
    steps = (2, 8, 32, 128) if quick else (2, 4, 8, 16, 32, 64, 128, 256, 512, 1024)
    rows = []
    for scheme in ("crank-nicolson", "rannacher", "tr-bdf2", "implicit"):
        for n in steps:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sol = pf.solve(
                    pr,
                    "fv",
                    check=False,  # the ringing is what is measured
                    stepping="tau",
                    scheme=scheme,
                    initial="delta",
                    n_p=200,
                    n_steps=n,
                    zeta_out=[4.0, pr.zeta_max],
                )
            ex = sol.exact_on_grid()
            c = sol.compare()
            for j, z in enumerate(sol.zeta):
                P = sol.P0_all[j, 0]
                peak = float(np.max(ex[j, 0]))
                rows.append(
                    {
                        "scheme": scheme,
                        "n_steps": n,
                        "r": sol.info["r_max"],
                        "zeta": float(z),
                        "neg_P0_rel": float(max(-P.min(), 0.0) / peak),
                        "ringing_rel": float(np.max(np.abs(P - ex[j, 0])) / peak),
                        "L1": float(c.L1[j, 0]),
                        "wall": sol.wall_time,
                    }
                )
        progress(1, 1, f"ringing {scheme}")
    return rows


def smearing(pr, quick):
    steps = (5, 20, 80) if quick else (5, 10, 20, 40, 80, 160, 320)
    rows = []
    for scheme in ("implicit", "tr-bdf2"):
        for n in steps:
            sol = pf.solve(pr, "fv", stepping="tau", scheme=scheme, n_p=400, n_steps=n, check=False)
            ex = pf.exact(pr)
            rows.append(
                {
                    "scheme": scheme,
                    "n_steps": n,
                    **errors_of(sol),
                    "signed_dA": float(sol.contact_area[-1] - ex.contact_area),
                    "signed_dVar_rel": float((sol.variance[-1] - ex.variance) / ex.variance),
                    "wall": sol.wall_time,
                }
            )
    return rows


def mol_explicit(pr, quick):
    grids = (25, 100) if quick else (25, 50, 100, 200, 400, 800)
    rows = []
    for integ in ("BDF", "RK45"):
        for n_p in grids:
            t0 = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sol = pf.solve(pr, "mol", n_p=n_p, integrator=integ, rtol=1e-6, check=False)
            rows.append(
                {
                    "integrator": integ,
                    "n_p": n_p,
                    "nfev": sol.info.get("nfev"),
                    "steps": sol.info.get("steps"),
                    "nlu": sol.info.get("nlu"),
                    "wall": sol.wall_time,
                    "call": time.perf_counter() - t0,
                    **errors_of(sol),
                }
            )
        progress(1, 1, f"mol {integ}")
    return rows


def coupling(quick):
    pr = pf.ContactProblem.reference(fudge="YP08")
    pf.exact(pr)
    steps = (10, 40, 160) if quick else (10, 20, 40, 80, 160, 320, 640)
    rows = []
    for cp in ("lagged", "predictor", "picard"):
        for n in steps:
            sol = pf.solve(pr, "fv", stepping="tau", scheme="tr-bdf2", coupling=cp, n_p=400, n_steps=n, check=False)
            rows.append(
                {
                    "coupling": cp,
                    "n_steps": n,
                    **errors_of(sol),
                    "wall": sol.wall_time,
                    "picard_iterations": sol.info.get("picard_iterations"),
                }
            )
        progress(1, 1, f"coupling {cp}")
    return rows


COLORS = {"stable": "tab:green", "oscillating": "tab:orange", "blown-up": "tab:red", "error": "tab:gray"}


def plot_map(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    keys = list(dict.fromkeys((r["method"], r["space"], r["initial"], r["n_p"]) for r in rows))
    fig, ax = plt.subplots(figsize=(11, 0.38 * len(keys) + 1.8))
    for y, k in enumerate(keys):
        sub = [r for r in rows if (r["method"], r["space"], r["initial"], r["n_p"]) == k]
        for r in sub:
            ax.scatter(r["r"], y, marker="s", s=110, color=COLORS[r["outcome"]], edgecolor="k", lw=0.4)
            if r["outcome"] == "blown-up" and np.isfinite(r.get("spectral_radius", np.nan)):
                ax.annotate(
                    f"{r['spectral_radius']:.2g}",
                    (r["r"], y),
                    textcoords="offset points",
                    xytext=(0, 7),
                    fontsize=5,
                    ha="center",
                )
    ax.set_yticks(range(len(keys)))
    ax.set_yticklabels([f"{m} {s}, {i} start, n_p={n}" for m, s, i, n in keys], fontsize=7)
    ax.set_xscale("log")
    for lim, lab in ((0.5, "1/2 (fv2)"), (1 / 3, "1/3 (compact4)")):
        ax.axvline(lim, color="k", ls=":", lw=1)
        ax.text(lim, len(keys) - 0.3, lab, fontsize=7, ha="center")
    ax.set_xlabel("r = dtau / (2 dp^2) = (1/2) dB2 dzeta / dp^2")
    for name, col in COLORS.items():
        ax.scatter([], [], marker="s", color=col, label=name)
    ax.legend(fontsize=7, loc="lower left", ncol=4)
    ax.set_title("explicit schemes: outcome by step ratio and grid (numbers: spectral radius of the step)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_panels(ring, smear, mol, coup, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    a = ax[0, 0]
    for scheme in dict.fromkeys(r["scheme"] for r in ring):
        sub = [r for r in ring if r["scheme"] == scheme and r["zeta"] == 4.0]
        a.loglog(
            [r["r"] for r in sub], np.maximum([r["neg_P0_rel"] for r in sub], 1e-17), "o-", label=f"{scheme}: -min P0"
        )
    a.set_xlabel("r of the steps")
    a.set_ylabel("-min P0 / max P0_exact at zeta = 4")
    a.set_title("from a one-cell delta at zeta = 1 (n_p = 200)")
    a = ax[0, 1]
    for scheme in dict.fromkeys(r["scheme"] for r in smear):
        sub = [r for r in smear if r["scheme"] == scheme]
        a.loglog([r["n_steps"] for r in sub], [r["L1"] for r in sub], "o-", label=f"{scheme}: L1")
        a.loglog([r["n_steps"] for r in sub], np.abs([r["signed_dA"] for r in sub]), "s--", label=f"{scheme}: |dA*|")
    a.set_xlabel("steps")
    a.set_title("backward Euler smearing (exact start, n_p = 400)")
    a = ax[1, 0]
    for integ in dict.fromkeys(r["integrator"] for r in mol):
        sub = [r for r in mol if r["integrator"] == integ]
        a.loglog([r["n_p"] for r in sub], [r["nfev"] for r in sub], "o-", label=f"{integ}: rhs calls")
        a.loglog(
            [r["n_p"] for r in sub], np.array([r["wall"] for r in sub]) * 1e4, "s--", label=f"{integ}: wall x 1e4 s"
        )
    a.set_xlabel("n_p")
    a.set_title("mol order 4, rtol 1e-6: explicit RK45 vs BDF")
    a = ax[1, 1]
    for cp in dict.fromkeys(r["coupling"] for r in coup):
        sub = [r for r in coup if r["coupling"] == cp]
        a.loglog([r["n_steps"] for r in sub], [r["L1"] for r in sub], "o-", label=f"{cp}: L1")
    a.set_xlabel("steps")
    a.set_title("YP08 fudge factor: coupling of S(A*) (fv tr-bdf2, n_p = 400)")
    for b in ax.ravel():
        b.grid(True, alpha=0.3)
        b.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    pr = pf.ContactProblem.reference()
    pf.exact(pr)
    print(machine())
    ex_rows = explicit_atlas(pr, args.quick)
    ons = onsets(ex_rows)
    ring = ringing(pr, args.quick)
    smear = smearing(pr, args.quick)
    mol = mol_explicit(pr, args.quick)
    coup = coupling(args.quick)
    for name, rows in (
        ("explicit", ex_rows),
        ("onsets", ons),
        ("ringing", ring),
        ("smearing", smear),
        ("mol", mol),
        ("coupling", coup),
    ):
        write_csv(os.path.join(out, f"stability_{name}.csv"), rows)

    md = [
        f"# Stability atlas (reference problem)\n\nMachine: {machine()}\n",
        "## Explicit schemes: measured onset (r = dtau / (2 dp^2))\n",
    ]
    md.append(
        markdown_table(
            [
                "method",
                "space",
                "start",
                "n_p",
                "not blown up up to r",
                "blown up from r",
                "first oscillating r",
                "theory",
            ],
            [
                [
                    o["method"],
                    o["space"],
                    o["initial"],
                    o["n_p"],
                    f"{o['stable_up_to']:.3g}",
                    f"{o['blown_up_from']:.3g}",
                    f"{o['first_oscillating']:.3g}",
                    f"{o['theory']:.3g}",
                ]
                for o in ons
            ],
        )
    )
    flagged = [r for r in ex_rows if r["raised"] and r["outcome"] == "oscillating"]
    if flagged:
        md.append(
            f"\n{len(flagged)} run(s) with spectral radius <= 1 were stopped by the solver's own check "
            f"(e.g. r = {flagged[0]['r']:.3g}, {flagged[0]['space']}, {flagged[0]['initial']} start: "
            f'"{flagged[0]["message"][:160]}"): counted as oscillating, not blown up.'
        )
    md.append("\n## Crank-Nicolson from a one-cell delta (n_p = 200, zeta = 4): -min P0 / max P0_exact\n")
    steps = sorted({r["n_steps"] for r in ring})
    schemes = list(dict.fromkeys(r["scheme"] for r in ring))
    body = []
    for n in steps:
        cells = [
            next(f"{r['neg_P0_rel']:.2e}" for r in ring if r["scheme"] == s and r["n_steps"] == n and r["zeta"] == 4.0)
            for s in schemes
        ]
        rr = next(r["r"] for r in ring if r["n_steps"] == n)
        body.append([n, f"{rr:.3g}"] + cells)
    md.append(markdown_table(["steps", "r"] + schemes, body))
    md.append("\n## Backward Euler smearing (exact start, n_p = 400): L1 and signed A* error\n")
    md.append(
        markdown_table(
            ["scheme", "steps", "L1", "A*_num - A*_exact"],
            [[r["scheme"], r["n_steps"], f"{r['L1']:.2e}", f"{r['signed_dA']:+.2e}"] for r in smear],
        )
    )
    md.append("\n## MOL (order 4, rtol 1e-6): RK45 vs BDF\n")
    md.append(
        markdown_table(
            ["integrator", "n_p", "rhs calls", "steps", "wall", "L1"],
            [
                [r["integrator"], r["n_p"], r["nfev"], r["steps"], f"{r['wall'] * 1e3:.3g} ms", f"{r['L1']:.2e}"]
                for r in mol
            ],
        )
    )
    md.append("\n## YP08 coupling (fv tr-bdf2, n_p = 400)\n")
    md.append(
        markdown_table(
            ["coupling", "steps", "L1", "|dA*|", "wall"],
            [
                [r["coupling"], r["n_steps"], f"{r['L1']:.2e}", f"{r['area_error']:.2e}", f"{r['wall'] * 1e3:.3g} ms"]
                for r in coup
            ],
        )
    )
    text = "\n".join(md) + "\n"
    with open(os.path.join(out, "stability.md"), "w") as fh:
        fh.write(text)
    print(text)
    plot_map(ex_rows, os.path.join(out, "stability_map.png"))
    plot_panels(ring, smear, mol, coup, os.path.join(out, "stability.png"))
    return {"explicit": ex_rows, "onsets": ons, "ringing": ring, "smearing": smear, "mol": mol, "coupling": coup}


if __name__ == "__main__":
    main()
