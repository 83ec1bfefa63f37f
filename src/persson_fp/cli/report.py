"""``persson-fp report`` (the default): the exact table of every fudge model, persson-fp's solvers checked against
the exact solution, PNG figures."""

from __future__ import annotations

import csv
import os

import numpy as np

from persson_fp._version import __version__
from persson_fp.analysis.energy import elastic_energy
from persson_fp.analysis.exact import exact
from persson_fp.cli._io import _atomic_open, _check_new_files, _save_figure, unit
from persson_fp.cli._problem import (
    FUDGES,
    _add_problem_args,
    _outdir,
    _problem,
    _progress,
)


def cmd_report(args) -> int:
    from persson_fp import plotting
    from persson_fp.solvers import available_methods, solve

    out = _outdir(args.output)
    methods = [m for m in available_methods() if m not in ("py-pde", "fipy") or args.all_methods]
    if args.no_solvers:
        methods = []
    names = ["pdf_exact.png"] + (["solvers.csv", "error_vs_time.png"] + [f"pdf_{m}.png" for m in methods])
    _check_new_files(out, names, args.force)
    base = _problem(args)
    psd = base.psd
    V = float(base.V())
    print(f"persson-fp {__version__} -- report")
    print(f"surface: {psd!r}")
    P, L = unit("pressure", args.units), unit("length", args.units)
    print(
        f"E* = {base.E_star:.6g} {P}, zeta_max = {base.zeta_max:.6g}, V(zeta_max) = {V:.6e} {P}^2, "
        f"sqrt(V) = {np.sqrt(V):.6e} {P}"
    )
    print(f"rms slope = {psd.rms_slope:.6g}, rms height = {psd.rms_height:.6g} {L}")
    print()
    pu = f"p_bar [{unit('pressure', args.units)}]"
    header = f"{'fudge':<6} {pu:>11} {'p_bar/sqrtV':>11} {'A*':>12} {'Var(p)':>12} {'U_el/A_n':>12} {'tau/V':>9}"
    print("Exact solution at zeta_max (eq:Area_Persson, eq:variance_p_form1, eq:Uel_original):")
    print(header)
    print("-" * len(header))
    for name in FUDGES:
        pr = _problem(args, fudge=name)
        ex = exact(pr)
        U = np.atleast_1d(elastic_energy(pr))
        for j, pb in enumerate(pr.p_bar):
            A = np.atleast_1d(ex.contact_area)[j]
            var = np.atleast_1d(ex.variance)[j]
            tau = np.atleast_1d(ex.tau)[j]
            print(f"{name:<6} {pb:11.4e} {pb / np.sqrt(V):11.4g} {A:12.8f} {var:12.5e} {U[j]:12.5e} {tau / V:9.5f}")
    print()

    zetas = [1.5, 4.0, 16.0, base.zeta_max]
    zetas = sorted({z for z in zetas if z <= base.zeta_max})
    fig = plotting.plot_exact_pdfs(base, zetas)
    _save_figure(fig, os.path.join(out, "pdf_exact.png"), dpi=120)

    rows = []
    if methods:
        print(f"Numerical solvers on this problem (fudge = {base.fudge.name}), checked against the exact solution:")
        print(
            f"{'method':<20} {'n_p':>6} {'steps':>8} {'wall [ms]':>10} {'first [ms]':>11} {'L1':>10} {'|dA*|':>10} "
            f"{'load drift':>10}"
        )
        sols = []
        for i, m in enumerate(methods):
            _progress(i, len(methods), f"solving ({m})")
            try:
                sol = solve(base, method=m, zeta_out=np.array(zetas[1:]))
                first, warm = (
                    sol.wall_time,
                    _warm_times(lambda m=m: solve(base, method=m, zeta_out=np.array(zetas[1:]))),
                )
            except Exception as err:  # report, keep going
                print(f"\r{m:<20} failed: {err}")
                continue
            c = sol.compare().final()
            rows.append({"method": m, "time": float(np.median(warm)), "first": first, "n_warm": len(warm), **c})
            sols.append(sol)
        _progress(len(methods), len(methods), "solving")
        for r, sol in zip(rows, sols):
            print(
                f"{r['method']:<20} {sol.p.size:6d} {str(sol.info.get('steps', '-')):>8} {r['time'] * 1e3:10.3g} "
                f"{r['first'] * 1e3:11.3g} {r['L1']:10.2e} {r['area_error']:10.2e} {r['load_drift']:10.2e}"
            )
        if rows:
            n = sorted({r["n_warm"] for r in rows})
            n_txt = f"{n[0]}" if len(n) == 1 else f"{n[0]} to {n[-1]}"
            print(f"wall: median of {n_txt} warm calls; first: the first call (imports, compilation, caches) apart")
        with _atomic_open(os.path.join(out, "solvers.csv"), "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(list(_CSV_COLUMNS))
            for r in rows:
                w.writerow([r["method"]] + [f"{r[k] * s:.6g}" for k, s in list(_CSV_COLUMNS.values())[1:]])
        for sol in sols:
            _save_figure(sol.plot(), os.path.join(out, f"pdf_{sol.method}.png"), dpi=110)
        if rows:
            _save_figure(plotting.plot_error_vs_time(rows), os.path.join(out, "error_vs_time.png"), dpi=110)
    print(f"\nfigures and tables written to {os.path.abspath(out)}/")
    return 0


_CSV_COLUMNS = {
    "method": ("method", 1),
    "wall [ms]": ("time", 1e3),
    "first call [ms]": ("first", 1e3),
    "warm calls": ("n_warm", 1),
    "L1 [-]": ("L1", 1),
    "area_error [-]": ("area_error", 1),
    "area_error_rel [-]": ("area_error_rel", 1),
    "load_drift [-]": ("load_drift", 1),
}
"""solvers.csv: header -> (row key, factor); times in ms as on the screen."""

WARM_CALLS = 5
"""Warm calls timed per solver (fewer when they take long: about WARM_BUDGET_S in all)."""

WARM_BUDGET_S = 0.5


def _warm_times(call) -> list:
    """The solver's own wall time of up to WARM_CALLS warm calls (at least one; stopped after ~WARM_BUDGET_S)."""
    times, spent = [], 0.0
    while len(times) < WARM_CALLS and (not times or spent < WARM_BUDGET_S):
        t = call().wall_time
        times.append(t)
        spent += t
    return times


def add_parser(sub) -> None:
    """Register the ``report`` subcommand on the subparsers ``sub``."""
    rep = sub.add_parser("report", help="exact table + solver check + figures (the default)")
    _add_problem_args(rep)
    rep.add_argument("--output", default="persson-fp-output", help="folder for PNG/CSV (default persson-fp-output)")
    rep.add_argument("--force", action="store_true", help="replace existing figures and solvers.csv in --output")
    rep.add_argument("--no-solvers", action="store_true", help="only the exact solution")
    rep.add_argument("--all-methods", action="store_true", help="also run py-pde and FiPy when installed (slow)")
    rep.set_defaults(func=cmd_report)
