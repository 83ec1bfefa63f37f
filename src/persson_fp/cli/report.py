"""``persson-fp report`` (the default): the exact table of every fudge model, persson-fp's solvers checked against
the exact solution, PNG figures."""

from __future__ import annotations

import csv
import os

import numpy as np

from persson_fp._version import __version__
from persson_fp.analysis.energy import elastic_energy
from persson_fp.analysis.exact import exact
from persson_fp.cli._io import (
    _atomic_open,
    _note_replaced,
    _save_figure,
)
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
    base = _problem(args)
    psd = base.psd
    V = float(base.V())
    print(f"persson-fp {__version__} -- report")
    print(f"surface: {psd!r}")
    print(f"E* = {base.E_star:.6g}, zeta_max = {base.zeta_max:.6g}, V(zeta_max) = {V:.6e}, sqrt(V) = {np.sqrt(V):.6e}")
    print(f"rms slope = {psd.rms_slope:.6g}, rms height = {psd.rms_height:.6g}")
    print()
    header = f"{'fudge':<6} {'p_bar':>11} {'p_bar/sqrtV':>11} {'A*':>12} {'Var(p)':>12} {'U_el/A_n':>12} {'tau/V':>9}"
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
    _note_replaced(out, ["pdf_exact.png", "solvers.csv", "error_vs_time.png"])
    fig = plotting.plot_exact_pdfs(base, zetas)
    _save_figure(fig, os.path.join(out, "pdf_exact.png"), dpi=120)

    methods = [m for m in available_methods() if m not in ("py-pde", "fipy") or args.all_methods]
    rows = []
    if methods and not args.no_solvers:
        print(f"Numerical solvers on this problem (fudge = {base.fudge.name}), checked against the exact solution:")
        print(f"{'method':<20} {'n_p':>6} {'steps':>8} {'wall [ms]':>10} {'L1':>10} {'|dA*|':>10} {'load drift':>10}")
        sols = []
        for i, m in enumerate(methods):
            _progress(i, len(methods), f"solving ({m})")
            try:
                sol = solve(base, method=m, zeta_out=np.array(zetas[1:]))
            except Exception as err:  # report, keep going
                print(f"\r{m:<20} failed: {err}")
                continue
            c = sol.compare().final()
            rows.append({"method": m, "time": sol.wall_time, **c})
            sols.append(sol)
        _progress(len(methods), len(methods), "solving")
        for r, sol in zip(rows, sols):
            print(
                f"{r['method']:<20} {sol.p.size:6d} {str(sol.info.get('steps', '-')):>8} {r['time'] * 1e3:10.2f} "
                f"{r['L1']:10.2e} {r['area_error']:10.2e} {r['load_drift']:10.2e}"
            )
        with _atomic_open(os.path.join(out, "solvers.csv"), "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]) if rows else ["method"])
            w.writeheader()
            w.writerows(rows)
        for sol in sols:
            _save_figure(sol.plot(), os.path.join(out, f"pdf_{sol.method}.png"), dpi=110)
        if rows:
            _save_figure(plotting.plot_error_vs_time(rows), os.path.join(out, "error_vs_time.png"), dpi=110)
    print(f"\nfigures and tables written to {os.path.abspath(out)}/")
    return 0


# -- solve --------------------------------------------------------------------------------------------


def add_parser(sub) -> None:
    """Register the ``report`` subcommand on the subparsers ``sub``."""
    rep = sub.add_parser("report", help="exact table + solver check + figures (the default)")
    _add_problem_args(rep)
    rep.add_argument("--output", default="persson-fp-output", help="folder for PNG/CSV (default persson-fp-output)")
    rep.add_argument("--no-solvers", action="store_true", help="only the exact solution")
    rep.add_argument("--all-methods", action="store_true", help="also run py-pde and FiPy when installed (slow)")
    rep.set_defaults(func=cmd_report)
