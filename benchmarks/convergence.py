"""Observed orders of convergence in p and in the step of every scheme.

On the reference problem (no fudge factor; p_bar = 0.5 sqrt(V)), L1 of P0 at zeta_max against
``pf.exact``:

* **in p** -- error against the grid spacing dp with the time error made negligible: fv with
  TR-BDF2 and many steps (``fv2`` -> 2, ``compact4`` -> 4), mol at rtol 1e-11 (order 2 / 4),
  Chapman--Kolmogorov (exact kernel in time, 4th order with its variance correction), FiPy when
  installed; the explicit schemes refine "diagonally" (dtau proportional to dp^2 at fixed
  r = dtau/(2 dp^2)): fv explicit fv2 and py-pde's euler at r = 1/6, where the leading space and
  time errors of forward Euler cancel (4th order), and at r = 0.4 (2nd order);
* **in the step** -- error against dtau at fine dp (fv compact4, n_p = 800): implicit (backward
  Euler) -> 1, Crank--Nicolson, Rannacher and TR-BDF2 -> 2; steps are uniform in the effective
  variance tau (fv's default "tau" stepping), so the x axis is dtau / tau_max = 0.95 / n_steps;
  mol's error against ``rtol`` (a tolerance exponent, ~1 for a tolerance-proportional integrator);
  Chapman--Kolmogorov against its number of steps (~0: the compounded kernel is exact in time);
* **sines** -- spectral: log L1 against the number of modes is a straight line; its slope per mode
  is reported as the "order".

Outputs: convergence.csv (every run), convergence_orders.csv (fitted slope over the three finest
points above 1e-13, against the theoretical one), convergence.png.

    python benchmarks/convergence.py [--quick] [--output DIR]
"""

from __future__ import annotations

import math
import os
import sys
import time
import warnings

import numpy as np

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import errors_of, fit_order, machine, markdown_table, outdir, parser, progress, write_csv  # noqa: E402


def explicit_steps(problem, n_p, r, k_domain=8.0, tau0_fraction=0.05):
    dp = problem.p_max(k_domain) / n_p
    return int(math.ceil((1.0 - tau0_fraction) * float(np.max(problem.tau())) / (2.0 * r * dp**2)))


def studies(pr, quick: bool) -> list[dict]:
    """Each study: label, direction ("p", "step", "rtol", "modes"), method, expected slope, runs."""
    q = quick
    fine_steps = 1000 if q else 4000
    n4 = (20, 40, 80) if q else (20, 40, 80, 160)
    n2 = (25, 50, 100) if q else (25, 50, 100, 200, 400)
    steps = (10, 20, 40) if q else (10, 20, 40, 80, 160, 320)
    out = [
        dict(
            label="fv compact4 (tr-bdf2)",
            direction="p",
            method="fv",
            expected=4,
            runs=[dict(space="compact4", stepping="tau", scheme="tr-bdf2", n_p=n, n_steps=fine_steps) for n in n4],
        ),
        dict(
            label="fv fv2 (tr-bdf2)",
            direction="p",
            method="fv",
            expected=2,
            runs=[dict(space="fv2", stepping="tau", scheme="tr-bdf2", n_p=n, n_steps=fine_steps) for n in n2],
        ),
        dict(
            label="mol order 4",
            direction="p",
            method="mol",
            expected=4,
            runs=[dict(order=4, n_p=n, rtol=1e-11) for n in n4],
        ),
        dict(
            label="mol order 2",
            direction="p",
            method="mol",
            expected=2,
            runs=[dict(order=2, n_p=n, rtol=1e-11) for n in n2],
        ),
        dict(
            label="fv explicit fv2, r=1/6 (diagonal)",
            direction="p",
            method="fv",
            expected=4,
            runs=[
                dict(space="fv2", stepping="tau", scheme="explicit", n_p=n, n_steps=explicit_steps(pr, n, 1 / 6))
                for n in ((25, 50, 100) if q else (25, 50, 100, 200))
            ],
        ),
        dict(
            label="fv explicit fv2, r=0.4 (diagonal)",
            direction="p",
            method="fv",
            expected=2,
            runs=[
                dict(space="fv2", stepping="tau", scheme="explicit", n_p=n, n_steps=explicit_steps(pr, n, 0.4))
                for n in ((25, 50, 100) if q else (25, 50, 100, 200))
            ],
        ),
        dict(
            label="chapman-kolmogorov (5 steps)",
            direction="p",
            method="chapman-kolmogorov",
            expected=4,
            runs=[dict(n_p=n, n_steps=5) for n in ((50, 100, 200) if q else (50, 100, 200, 400))],
        ),
        dict(
            label="sines",
            direction="modes",
            method="sines",
            expected=None,
            runs=[dict(n_p=n) for n in ((6, 8, 10, 12) if q else (6, 8, 10, 12, 14, 16, 18, 20))],
        ),
        dict(
            label="mol order 4, n_p=300",
            direction="rtol",
            method="mol",
            expected=1,
            runs=[
                dict(order=4, n_p=300, rtol=t)
                for t in ((1e-3, 1e-4, 1e-5) if q else (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8))
            ],
        ),
        dict(
            label="chapman-kolmogorov, n_p=400",
            direction="step",
            method="chapman-kolmogorov",
            expected=0,
            runs=[dict(n_p=400, n_steps=s) for s in ((2, 4, 8) if q else (2, 4, 8, 16, 32))],
        ),
    ]
    for scheme, order in (("implicit", 1), ("crank-nicolson", 2), ("rannacher", 2), ("tr-bdf2", 2)):
        out.append(
            dict(
                label=f"fv {scheme}",
                direction="step",
                method="fv",
                expected=order,
                runs=[dict(space="compact4", stepping="tau", scheme=scheme, n_p=800, n_steps=s) for s in steps],
            )
        )
    if not q:
        out += [
            dict(
                label="py-pde euler, r=1/6 (diagonal)",
                direction="p",
                method="py-pde",
                expected=4,
                runs=[dict(solver="euler", cfl=1 / 3, n_p=n) for n in (25, 50, 100, 200)],
            ),
            dict(
                label="py-pde euler, r=0.4 (diagonal)",
                direction="p",
                method="py-pde",
                expected=2,
                runs=[dict(solver="euler", cfl=0.8, n_p=n) for n in (25, 50, 100, 200)],
            ),
            dict(
                label="fipy crank-nicolson",
                direction="p",
                method="fipy",
                expected=2,
                runs=[dict(scheme="crank-nicolson", n_p=n, n_steps=200) for n in (25, 50, 100)],
            ),
            dict(
                label="fipy crank-nicolson",
                direction="step",
                method="fipy",
                expected=2,
                runs=[dict(scheme="crank-nicolson", n_p=400, n_steps=s) for s in (10, 20, 40)],
            ),
            dict(
                label="fipy implicit",
                direction="step",
                method="fipy",
                expected=1,
                runs=[dict(scheme="implicit", n_p=400, n_steps=s) for s in (10, 20, 40)],
            ),
        ]
    return out


BUDGET_S = {"py-pde": 90.0, "fipy": 60.0}


def x_of(direction, opts, sol):
    if direction == "p":
        dp = (sol.info.get("grid") or {}).get("dp") if isinstance(sol.info.get("grid"), dict) else None
        return float(dp) if dp else float(np.median(np.diff(sol.p)))
    if direction == "step":
        return 0.95 / opts["n_steps"] if sol.method != "chapman-kolmogorov" else 1.0 / opts["n_steps"]
    if direction == "rtol":
        return opts["rtol"]
    return float(opts["n_p"])


def plot(rows, orders, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    cmap = plt.get_cmap("tab20")
    panels = {"p": axes[0], "step": axes[1], "rtol": axes[1], "modes": axes[2]}
    labels = list(dict.fromkeys((r["label"], r["direction"]) for r in rows))
    for i, (lab, d) in enumerate(labels):
        ok = [r for r in rows if r["label"] == lab and r["direction"] == d and r["status"] == "ok"]
        if not ok:
            continue
        x = np.array([r["x"] for r in ok])
        e = np.maximum([r["L1"] for r in ok], 1e-17)
        ax = panels[d]
        o = next(o for o in orders if o["label"] == lab and o["direction"] == d)
        name = f"{lab}: {o['observed']:.2f}" + (f" (theory {o['expected']})" if o["expected"] is not None else "")
        if d == "rtol":
            name = f"{lab} vs rtol: {o['observed']:.2f}"
        style = "s--" if d == "rtol" else "o-"
        if d == "modes":
            ax.semilogy(x, e, style, color=cmap(i % 20), label=f"{lab}: log10 L1 per mode {o['observed']:.2f}")
            continue
        ax.loglog(x, e, style, color=cmap(i % 20), ms=4, label=name)
        if o["expected"]:  # theoretical slope through the finest point
            j = int(np.argmin(x))
            xx = np.array([x.min(), x.max()])
            ax.loglog(xx, e[j] * (xx / x[j]) ** o["expected"], ":", color=cmap(i % 20), lw=1)
    axes[0].set_xlabel("dp (pressure units)")
    axes[0].set_title("error vs dp (time error negligible; dotted: theoretical slope)")
    axes[1].set_xlabel("dtau / tau_max (fv, n_p = 800)  |  rtol (mol)  |  1/n_steps (CK)")
    axes[1].set_title("error vs step (fine dp)")
    axes[2].set_xlabel("number of sine modes")
    axes[2].set_title("sine series: spectral convergence")
    for ax in axes:
        ax.set_ylabel("L1 error of P0 at zeta_max")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    pr = pf.ContactProblem.reference()
    pf.exact(pr)
    print(machine())
    avail = pf.available_methods()
    rows, orders = [], []
    for st in studies(pr, args.quick):
        if st["method"] not in avail:
            print(f"  skip {st['label']}: method {st['method']!r} not available")
            continue
        spent, budget = 0.0, BUDGET_S.get(st["method"], np.inf)
        for i, opts in enumerate(st["runs"]):
            row = {"label": st["label"], "direction": st["direction"], "method": st["method"], "options": repr(opts)}
            if spent > budget:
                rows.append({**row, "status": "skipped (budget)"})
                continue
            t0 = time.perf_counter()
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    sol = pf.solve(pr, st["method"], **opts)
                row.update(
                    status="ok",
                    x=x_of(st["direction"], opts, sol),
                    n_p=sol.p.size,
                    wall_time=sol.wall_time,
                    **errors_of(sol),
                )
            except Exception as err:  # noqa: BLE001
                row.update(status=f"{type(err).__name__}: {err}")
            spent += time.perf_counter() - t0
            rows.append(row)
            progress(i + 1, len(st["runs"]), st["label"])
        ok = [
            r for r in rows if r["label"] == st["label"] and r["direction"] == st["direction"] and r["status"] == "ok"
        ]
        if st["direction"] == "modes":
            x = np.array([r["x"] for r in ok])
            e = np.array([r["L1"] for r in ok])
            keep = e > 1e-13
            slope = float(np.polyfit(x[keep], np.log10(e[keep]), 1)[0]) if keep.sum() >= 2 else np.nan
        else:
            slope = fit_order([r["x"] for r in ok], [r["L1"] for r in ok])
        orders.append(
            {
                "label": st["label"],
                "direction": st["direction"],
                "method": st["method"],
                "expected": st["expected"],
                "observed": slope,
                "points": len(ok),
            }
        )
    write_csv(os.path.join(out, "convergence.csv"), rows)
    write_csv(os.path.join(out, "convergence_orders.csv"), orders)
    body = [
        [
            o["label"],
            o["direction"],
            "spectral" if o["expected"] is None else o["expected"],
            f"{o['observed']:.2f}" + (" (log10 L1 per mode)" if o["direction"] == "modes" else ""),
            o["points"],
        ]
        for o in orders
    ]
    text = markdown_table(["scheme", "refined in", "theory", "observed", "points"], body)
    with open(os.path.join(out, "convergence.md"), "w") as fh:
        fh.write(f"# Observed orders (reference problem, no fudge)\n\nMachine: {machine()}\n\n{text}\n")
    print(text)
    plot(rows, orders, os.path.join(out, "convergence.png"))
    return rows, orders


if __name__ == "__main__":
    main()
