"""The ``persson-fp`` command: reports, solves and contact-area curves.

It only wires the package together.  Every error -- a bad argument, an unreadable or unwritable
file, a solver that refuses a problem or breaks an invariant -- prints one line on stderr and exits
with code 2; Ctrl-C prints "interrupted" and exits with 130.  Files are written under a temporary
name and renamed when complete, so an interrupted run leaves no half-written file.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import sys
import time

import numpy as np

from persson_fp._version import __version__
from persson_fp.cli._io import (
    CLIError,
    _atomic_open,
    _check_new_file,
    _count,
    _make_parent,
    _note_replaced,
    _save_figure,
)
from persson_fp.problems.contact import ContactProblem
from persson_fp.results.energy import elastic_energy
from persson_fp.results.exact import exact
from persson_fp.results.solution import SolverError
from persson_fp.surfaces.psd import SelfAffinePSD
from persson_fp.surfaces.tabulated import TabulatedPSD
from persson_fp.theory import fudge as _fudge
from persson_fp.theory.hardness import PowerLaw

FUDGES = ["none", "YP08", "WM17", "Xu24"]

DESCRIPTION = """\
persson-fp: Persson's theory of elastic rough-surface contact as a diffusion (Fokker-Planck) problem.

The contact-pressure PDF P0(p, zeta) obeys dP0/dzeta = 1/2 B2 d2P0/dp2 with an absorbing wall at p = 0;
B2 = S(A*) dV/dzeta, S = 1 in Persson's original theory.  The default surface is the reference problem:
self-affine, H = 0.8, q_l = 1, q_r = 2, q_s = 128 (zeta_max = 128), rms slope 0.1, E* = 1,
p_bar = 0.5 sqrt(V(zeta_max)).  Units: any consistent set (the defaults are dimensionless).

commands:
  report   (default) table of V, A*, Var(p), elastic energy for every fudge model, persson-fp's own
           solvers checked against the exact solution (--all-methods adds py-pde and FiPy), PNG figures
  solve    solve one problem (your surface and loads) with a chosen method; CSV/JSON/PNG output
  area     the contact-area curve A*(p_bar) for a range of loads, every fudge model (CSV + PNG)
  surface  a measured surface (height map or contact.engineering CSV) -> spectrum, A*, mean separation,
           stiffness for a range of loads, every fudge model (CSV + PNG)
  sweep    a folder of surfaces (CSV spectra) x fudge models x loads into one table (CSV or Parquet)
  calibrate  fit a fudge model's gamma to your A*(p_bar) / mean-separation data, with uncertainty;
           several models ranked by held-out error

examples:
  persson-fp
  persson-fp report --H 0.3 --zeta-max 1000 --output results/
  persson-fp solve --method fv --p-bar-ratio 0.1 0.5 2 --fudge YP08 --output sol.csv
  persson-fp solve --psd-csv my_psd.csv --E-star 2.1e11 --p-bar 1e6 --method sines
  persson-fp area --n-loads 200 --output area/
  persson-fp surface heights.npy --size 1e-3 --E-star 2.1e11 --output surf/
  persson-fp calibrate data.csv --psd psd.csv --model YP08 WM17 Xu24

Equation labels such as eq:Area_Persson or E:PSD are those of Y. Xu, X. Li, Q. Chen, Y. Zhou, "Persson's
Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic Process Theory".
Fudge factors: Yang & Persson 2008 (YP08), Wang & Muser 2017 (WM17), Xu et al. 2024 (Xu24).
"""


MAX_LOADS = 1_000_000
"""Largest ``area --n-loads`` (the exact curves take ~100 bytes per load and model)."""

SURFACE_DEFAULTS = {"H": 0.8, "q_l": 1.0, "zeta_max": 128.0}
"""Defaults of the self-affine surface options (None in argparse, so that a given one can be told apart)."""


MIN_TOL = 1e-12
"""Smallest ``solve --tol``: below it the grids the methods would need exceed any machine."""


def _progress(i, n, label, stream=sys.stderr):
    """A minimal progress bar on stderr, drawn only when stderr is a terminal."""
    if not getattr(stream, "isatty", lambda: False)():
        return
    width = 24
    done = int(width * i / max(n, 1))
    stream.write(f"\r{label:<28} [{'#' * done}{'.' * (width - done)}] {i}/{n}")
    if i >= n:
        stream.write("\n")
    stream.flush()


def _add_problem_args(p: argparse.ArgumentParser):
    g = p.add_argument_group("surface (self-affine PSD, eq. E:PSD) -- or --psd-csv")
    g.add_argument("--H", type=float, default=None, help="Hurst exponent in [0, 1] (default 0.8)")
    g.add_argument("--q-l", type=float, default=None, help="lower cut-off wavenumber q_l, 1/length (default 1)")
    g.add_argument("--q-r", type=float, default=None, help="roll-off wavenumber q_r (default 2 q_l)")
    g.add_argument("--zeta-max", type=float, default=None, help="magnification q_s/q_l (default 128)")
    amp = g.add_mutually_exclusive_group()
    amp.add_argument("--rms-slope", type=float, default=None, help="rms slope over the band (default 0.1)")
    amp.add_argument("--rms-height", type=float, default=None, help="rms height over the band, length")
    amp.add_argument("--C0", type=float, default=None, help="PSD prefactor C0, length^(2-2H)")
    g.add_argument("--psd-csv", default=None, help="measured isotropic PSD: CSV with header columns q,C")
    m = p.add_argument_group("contact")
    m.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E/(1-nu^2), pressure (default 1)")
    lo = m.add_mutually_exclusive_group()
    lo.add_argument("--p-bar", type=float, nargs="+", default=None, help="nominal pressure(s), pressure units")
    lo.add_argument(
        "--p-bar-ratio", type=float, nargs="+", default=None, help="load(s) as p_bar / sqrt(V(zeta_max)) (default 0.5)"
    )
    m.add_argument("--fudge", default="none", choices=FUDGES, help="fudge factor S(A*) (default none)")
    m.add_argument("--gamma", type=float, default=None, help="gamma of the fudge model (default: the model's)")


_SURFACE_OPTIONS = ("H", "q_l", "q_r", "zeta_max", "rms_slope", "rms_height", "C0")


def _check_combination(args):
    """Options that would be silently ignored are errors (for the subcommands that take the problem options)."""
    if not hasattr(args, "psd_csv"):  # surface, sweep: their own options, checked by their modules
        return
    if args.psd_csv:
        given = [o for o in _SURFACE_OPTIONS if getattr(args, o) is not None]
        if given:
            flags = ", ".join("--" + o.replace("_", "-") for o in given)
            raise CLIError(f"{flags}: not used with --psd-csv (the measured spectrum fixes the surface)")
    if args.gamma is not None and args.fudge == "none" and args.command == "solve":
        raise CLIError("--gamma: not used with --fudge none (choose YP08, WM17 or Xu24)")


def _problem(args, fudge=None) -> ContactProblem:
    if args.psd_csv:
        if not os.path.isfile(args.psd_csv):
            what = "is a directory" if os.path.isdir(args.psd_csv) else "no such file"
            raise CLIError(f"--psd-csv: {what}: {args.psd_csv!r}")
        psd = TabulatedPSD.from_csv(args.psd_csv)
    else:
        H = SURFACE_DEFAULTS["H"] if args.H is None else args.H
        q_l = SURFACE_DEFAULTS["q_l"] if args.q_l is None else args.q_l
        zeta_max = SURFACE_DEFAULTS["zeta_max"] if args.zeta_max is None else args.zeta_max
        q_r = 2.0 * q_l if args.q_r is None else args.q_r
        with np.errstate(over="ignore"):
            q_s = zeta_max * q_l
        if args.C0 is not None:
            psd = SelfAffinePSD(args.C0, H, q_l, q_r, q_s)
        elif args.rms_height is not None:
            psd = SelfAffinePSD.from_rms_height(args.rms_height, H, q_l, q_r, q_s)
        else:
            slope = 0.1 if args.rms_slope is None else args.rms_slope
            psd = SelfAffinePSD.from_rms_slope(slope, H, q_l, q_r, q_s)
    name = args.fudge if fudge is None else fudge
    f = None
    if name != "none":
        cls = _fudge.MODELS[name]
        f = cls() if args.gamma is None else cls(gamma=args.gamma)
    if args.p_bar is not None:
        p_bar = np.array(args.p_bar)
    else:
        ratio = np.array([0.5] if args.p_bar_ratio is None else args.p_bar_ratio)
        if np.any(~np.isfinite(ratio)) or np.any(ratio <= 0):
            raise CLIError("--p-bar-ratio must be > 0 and finite")
        p_bar = ratio * np.sqrt(ContactProblem(psd, args.E_star, 1.0).V_max)  # (checks V's range first)
    return ContactProblem(psd, args.E_star, p_bar[0] if p_bar.size == 1 else p_bar, f)


def _outdir(path) -> str:
    if os.path.exists(path) and not os.path.isdir(path):
        raise CLIError(f"--output: {path} exists and is not a folder")
    os.makedirs(path, exist_ok=True)
    return path


# -- report ------------------------------------------------------------------------------------------
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
def cmd_solve(args) -> int:
    from persson_fp.solvers import solve

    _check_new_file(args.output, args.force, "--output")
    _check_new_file(args.plot, args.force, "--plot")
    if args.seed is not None and args.method != "monte-carlo":
        raise CLIError("--seed: only used with --method monte-carlo")
    for flag, v in (("--tol", args.tol), ("--rtol", args.rtol), ("--atol", args.atol)):
        if v is not None and not (np.isfinite(v) and v > 0):
            raise CLIError(f"{flag} must be a finite number > 0, got {v!r}")
    if args.tol is not None and not MIN_TOL <= args.tol <= 0.1:
        raise CLIError(f"--tol must lie in [{MIN_TOL:g}, 0.1] (accuracy of the contact area), got {args.tol!r}")
    pr = _problem(args)
    if args.hardness is not None:  # elastoplastic contact: a constant or power-law yield stress
        n = args.hardness_exponent
        hard = args.hardness if n == 0 else PowerLaw(args.hardness, n)
        pr = ContactProblem(pr.psd, pr.E_star, pr.p_bar if pr.n_loads > 1 else pr.p_bar[0], pr.fudge, hardness=hard)
    elif args.hardness_exponent != 0:
        raise CLIError("--hardness-exponent needs --hardness")
    opts = {}
    for key in ("n_p", "n_steps", "rtol", "atol", "scheme", "seed"):
        v = getattr(args, key)
        if v is not None:
            opts[key] = v
    t0 = time.perf_counter()
    sol = solve(pr, method=args.method, tol=args.tol, **opts)
    wall = time.perf_counter() - t0
    if not pr.has_closed_form:  # a moving yield wall: the solver's own error estimate instead of the exact one
        est = sol.error_estimate
        print(f"{sol.method}: steps = {sol.info.get('steps')}, wall = {wall * 1e3:.2f} ms ({est['kind']})")
        print(f"{'p_bar':>12} {'A_el':>12} {'A_pl':>12} {'A_non':>12} {'error est.':>10} {'load/p_bar-1':>13}")
        for j, pb in enumerate(pr.p_bar):
            print(
                f"{pb:12.5e} {sol.elastic_area_all[-1, j]:12.8f} {sol.plastic_area_all[-1, j]:12.8f} "
                f"{1 - sol.contact_area_all[-1, j]:12.8f} {est['contact_area'][-1, j]:10.2e} "
                f"{sol.load_all[-1, j] / pb - 1:13.2e}"
            )
        return _write_solution(args, sol, pr)
    cmp_ = sol.compare()
    if pr.hardness is not None:
        print("elastoplastic: A_pl (num) " + " ".join(f"{v:.8f}" for v in sol.plastic_area_all[-1]))
    ex = exact(pr)
    print(f"{sol.method}: n_p = {sol.p.size}, steps = {sol.info.get('steps')}, wall = {wall * 1e3:.2f} ms")
    print(
        f"{'p_bar':>12} {'A* (num)':>12} {'A* (exact)':>12} {'|dA*|':>10} {'Var(p)':>12} "
        f"{'load/p_bar-1':>13} {'L1':>10}"
    )
    A_ex = np.atleast_1d(ex.contact_area)
    for j, pb in enumerate(pr.p_bar):
        print(
            f"{pb:12.5e} {sol.contact_area_all[-1, j]:12.8f} {A_ex[j]:12.8f} {cmp_.area_error[-1, j]:10.2e} "
            f"{np.reshape(sol.variance, (sol.zeta.size, -1))[-1, j]:12.5e} "
            f"{sol.load_all[-1, j] / pb - 1:13.2e} {cmp_.L1[-1, j]:10.2e}"
        )
    return _write_solution(args, sol, pr)


def _write_solution(args, sol, pr) -> int:
    """Write ``--output`` (P0 at zeta_max, CSV or JSON) and ``--plot`` (:meth:`Solution.plot`)."""
    if args.output:
        path = args.output
        _make_parent(path, "--output")
        if path.endswith(".json"):
            data = {
                "method": sol.method,
                "zeta": sol.zeta.tolist(),
                "p": sol.p.tolist(),
                "p_bar": pr.p_bar.tolist(),
                "P0": sol.P0_all[-1].tolist(),
                "contact_area": sol.contact_area_all[-1].tolist(),
                "wall_time": sol.wall_time,
            }
            with _atomic_open(path, "w") as fh:
                json.dump(data, fh)
        else:
            with _atomic_open(path, "w", newline="") as fh:
                w = csv.writer(fh)
                if np.ndim(sol.p) == 1:
                    w.writerow(["p"] + [f"P0(p_bar={pb:.6g})" for pb in pr.p_bar])
                    for i, p in enumerate(sol.p):
                        w.writerow([f"{p:.12g}"] + [f"{v:.12g}" for v in sol.P0_all[-1, :, i]])
                else:  # a grid per load (a moving yield wall): p and P0 columns for each load
                    w.writerow([f"{c}(p_bar={pb:.6g})" for pb in pr.p_bar for c in ("p", "P0")])
                    for i in range(np.shape(sol.p)[-1]):
                        w.writerow(
                            [f"{v:.12g}" for j in range(pr.n_loads) for v in (sol.p[j, i], sol.P0_all[-1, j, i])]
                        )
        print(f"P0 at zeta_max written to {path}")
    if args.plot:
        _make_parent(args.plot, "--plot")
        _save_figure(sol.plot(), args.plot, dpi=120)
        print(f"figure written to {args.plot}")
    return 0


# -- area ----------------------------------------------------------------------------------------------
def cmd_area(args) -> int:
    from persson_fp import plotting

    if not (0 < args.ratio_min < args.ratio_max) or not np.isfinite(args.ratio_max):
        raise CLIError("--ratio-min and --ratio-max must satisfy 0 < min < max")
    if not 2 <= args.n_loads <= MAX_LOADS:
        raise CLIError(f"--n-loads must lie in [2, {MAX_LOADS}], got {args.n_loads}")
    for flag, value in (("--p-bar", args.p_bar), ("--p-bar-ratio", args.p_bar_ratio), ("--gamma", args.gamma)):
        if value is not None:
            raise CLIError(
                f"{flag}: not used by 'area' (loads from --ratio-min/--ratio-max, every model at its default)"
            )
    if args.fudge != "none":
        raise CLIError("--fudge: not used by 'area' (it computes every fudge model)")
    out = _outdir(args.output)
    base = _problem(args)
    ratio = np.geomspace(args.ratio_min, args.ratio_max, args.n_loads)
    p_bar = ratio * np.sqrt(base.V())
    curves = {}
    t0 = time.perf_counter()
    for i, name in enumerate(FUDGES):
        _progress(i, len(FUDGES), "contact-area curves")
        pr = ContactProblem(base.psd, base.E_star, p_bar, None if name == "none" else name)
        curves[name] = np.asarray(exact(pr).contact_area)
    _progress(len(FUDGES), len(FUDGES), "contact-area curves")
    wall = time.perf_counter() - t0
    path = os.path.join(out, "contact_area.csv")
    _note_replaced(out, ["contact_area.csv", "contact_area.png"])
    with _atomic_open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["p_bar", "p_bar_over_sqrtV"] + [f"A_{n}" for n in FUDGES])
        for j in range(ratio.size):
            w.writerow([f"{p_bar[j]:.12g}", f"{ratio[j]:.12g}"] + [f"{curves[n][j]:.15g}" for n in FUDGES])
    _save_figure(plotting.plot_area_curve(ratio, curves), os.path.join(out, "contact_area.png"), dpi=120)
    print(
        f"{ratio.size} loads x {len(FUDGES)} models in {wall * 1e3:.1f} ms "
        f"({ratio.size * len(FUDGES) / wall:.3g} loads/s)"
    )
    print(f"written {path} and contact_area.png")
    return 0


class _Parser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block): "persson-fp solve: error: ... (see --help)"."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="persson-fp", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"persson-fp {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="{report,solve,area,surface,sweep}")

    rep = sub.add_parser("report", help="exact table + solver check + figures (the default)")
    _add_problem_args(rep)
    rep.add_argument("--output", default="persson-fp-output", help="folder for PNG/CSV (default persson-fp-output)")
    rep.add_argument("--no-solvers", action="store_true", help="only the exact solution")
    rep.add_argument("--all-methods", action="store_true", help="also run py-pde and FiPy when installed (slow)")
    rep.set_defaults(func=cmd_report)

    so = sub.add_parser("solve", help="solve one problem with a numerical method")
    _add_problem_args(so)
    so.add_argument(
        "--method", default="fv", help="auto | fv | mol | sines | py-pde | fipy | chapman-kolmogorov | monte-carlo"
    )
    so.add_argument("--n-p", dest="n_p", type=_count, default=None, help="grid cells / points / modes")
    so.add_argument("--n-steps", dest="n_steps", type=_count, default=None, help="steps in zeta (fixed-step schemes)")
    so.add_argument("--rtol", type=float, default=None, help="relative tolerance (adaptive methods)")
    so.add_argument("--atol", type=float, default=None, help="absolute tolerance (adaptive methods)")
    so.add_argument("--scheme", default=None, help="fv time scheme (explicit, crank-nicolson, implicit, tr-bdf2)")
    so.add_argument("--output", default=None, help="write P0 at zeta_max: .csv or .json")
    so.add_argument("--plot", default=None, help="write a PNG of P0 against the exact solution")
    so.add_argument("--force", action="store_true", help="replace existing --output / --plot files")
    so.add_argument("--seed", type=_count, default=None, help="seed of the random walks (--method monte-carlo)")
    so.add_argument("--tol", type=float, default=None, help="asked accuracy: with --method auto, fv or mol")
    so.add_argument("--hardness", type=float, default=None, help="yield stress sigma_Y at zeta = 1 (pressure)")
    so.add_argument(
        "--hardness-exponent", type=float, default=0.0, help="sigma_Y = hardness * zeta^n (default 0: constant)"
    )
    so.set_defaults(func=cmd_solve)

    ar = sub.add_parser("area", help="A*(p_bar) curves for every fudge model (exact)")
    _add_problem_args(ar)
    ar.add_argument("--n-loads", type=_count, default=1000, help="number of loads (default 1000)")
    ar.add_argument("--ratio-min", type=float, default=1e-3, help="smallest p_bar/sqrt(V) (default 1e-3)")
    ar.add_argument("--ratio-max", type=float, default=3.0, help="largest p_bar/sqrt(V) (default 3)")
    ar.add_argument("--output", default="persson-fp-output", help="folder for CSV/PNG")
    ar.set_defaults(func=cmd_area)

    from persson_fp.cli import surface as cli_surface

    cli_surface.add_parser(sub)
    from persson_fp.cli import sweep as cli_sweep

    cli_sweep.add_parser(sub)
    from persson_fp.cli import calibrate as cli_calibrate

    cli_calibrate.add_parser(sub)
    return parser


def main(argv=None) -> int:
    import matplotlib

    matplotlib.use("Agg")
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0].startswith("-") and argv[0] not in ("-h", "--help", "--version"):
        argv = ["report", *argv]
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            args = parser.parse_args(["report"])
        _check_combination(args)
        return args.func(args)
    except KeyboardInterrupt:
        print("persson-fp: interrupted", file=sys.stderr)
        return 130
    except (
        CLIError,
        ValueError,
        TypeError,
        ImportError,
        NotImplementedError,
        SolverError,
        OSError,
        MemoryError,
        EOFError,
        OverflowError,
    ) as err:
        print(f"persson-fp {argv[0] if argv else 'report'}: error: {_one_line(err)}", file=sys.stderr)
        return 2


_USER_ERRORS = (
    CLIError,
    ValueError,
    TypeError,
    ImportError,
    NotImplementedError,
    SolverError,
    OSError,
    MemoryError,
    EOFError,
    OverflowError,
)
"""Errors reported as one line (a solver's refusal, a breached invariant, a file that cannot be read or written)."""


def _one_line(err) -> str:
    """The error as one line (an ``OSError`` as "reason: file")."""
    if isinstance(err, OSError) and err.strerror:
        text = f"{err.strerror}: {err.filename}" if err.filename else err.strerror
    elif isinstance(err, MemoryError):
        text = "out of memory (use a coarser grid or fewer loads)"
    else:
        text = str(err) or type(err).__name__
        for name, flag in _FLAGS.items():  # the solvers' option names, as the command spells them
            text = re.sub(rf"(?<![-\w]){name}(?!\w)", flag, text)
        if any(re.search(rf"(?<![-\w]){name}(?!\w)", text) for name in _API_ONLY):
            text += " (k_domain, zeta_out and n_walkers are options of the Python API, persson_fp.solve)"
    return " ".join(text.split())


_FLAGS = {"n_p": "--n-p", "n_steps": "--n-steps", "E_star": "--E-star", "q_l": "--q-l", "q_r": "--q-r"}
"""Option names in library messages -> the command-line flag that sets them."""

_API_ONLY = ("k_domain", "zeta_out", "n_walkers")
"""Options named in library messages that the command line does not offer."""


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
