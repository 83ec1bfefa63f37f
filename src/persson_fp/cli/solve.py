"""``persson-fp solve``: one problem with a chosen method; P0 as CSV/JSON, a PNG against the exact solution."""

from __future__ import annotations

import csv
import json
import time

import numpy as np

from persson_fp.analysis.exact import exact
from persson_fp.cli._io import (
    CLIError,
    _atomic_open,
    _check_new_file,
    _count,
    _make_parent,
    _save_figure,
    col,
    unit,
)
from persson_fp.cli._problem import (
    MIN_TOL,
    _add_problem_args,
    _problem,
)
from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.hardness import PowerLaw


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
    pu = f"p_bar [{unit('pressure', args.units)}]"
    if not pr.has_closed_form:  # a moving yield wall: the solver's own error estimate instead of the exact one
        est = sol.error_estimate
        print(f"{sol.method}: steps = {sol.info.get('steps')}, {_times(sol, wall)} ({est['kind']})")
        print(f"{pu:>14} {'A_el':>12} {'A_pl':>12} {'A_non':>12} {'error est.':>10} {'load/p_bar-1':>13}")
        for j, pb in enumerate(pr.p_bar):
            print(
                f"{pb:14.5e} {sol.elastic_area_all[-1, j]:12.8f} {sol.plastic_area_all[-1, j]:12.8f} "
                f"{1 - sol.contact_area_all[-1, j]:12.8f} {est['contact_area'][-1, j]:10.2e} "
                f"{sol.load_all[-1, j] / pb - 1:13.2e}"
            )
        return _write_solution(args, sol, pr)
    cmp_ = sol.compare()
    if pr.hardness is not None:
        print("elastoplastic: A_pl (num) " + " ".join(f"{v:.8f}" for v in sol.plastic_area_all[-1]))
    ex = exact(pr)
    print(f"{sol.method}: n_p = {sol.p.size}, steps = {sol.info.get('steps')}, {_times(sol, wall)}")
    print(f"{pu:>14} {'A* (num)':>12} {'A* (exact)':>12} {'|dA*|':>10} {'Var(p)':>12} {'load/p_bar-1':>13} {'L1':>10}")
    A_ex = np.atleast_1d(ex.contact_area)
    for j, pb in enumerate(pr.p_bar):
        print(
            f"{pb:14.5e} {sol.contact_area_all[-1, j]:12.8f} {A_ex[j]:12.8f} {cmp_.area_error[-1, j]:10.2e} "
            f"{np.reshape(sol.variance, (sol.zeta.size, -1))[-1, j]:12.5e} "
            f"{sol.load_all[-1, j] / pb - 1:13.2e} {cmp_.L1[-1, j]:10.2e}"
        )
    return _write_solution(args, sol, pr)


def _times(sol, wall) -> str:
    """The solver's wall time (``sol.wall_time``, what ``sol.plot()`` and the report show) and the whole call's."""
    return f"wall = {sol.wall_time * 1e3:.3g} ms (the whole call, set-up included: {wall * 1e3:.3g} ms)"


def _write_solution(args, sol, pr) -> int:
    """Write ``--output`` (P0 at zeta_max, CSV or JSON) and ``--plot`` (:meth:`Solution.plot`)."""
    if args.output:
        path = args.output
        _make_parent(path, "--output")
        units = args.units
        if path.endswith(".json"):
            data = {
                "units": {k: unit(k, units) for k in ("pressure", "1/pressure")},
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
                up, uP = unit("pressure", units), unit("1/pressure", units)
                if np.ndim(sol.p) == 1:
                    w.writerow([col("p", "pressure", units)] + [f"P0(p_bar={pb:.6g} {up}) [{uP}]" for pb in pr.p_bar])
                    for i, p in enumerate(sol.p):
                        w.writerow([f"{p:.12g}"] + [f"{v:.12g}" for v in sol.P0_all[-1, :, i]])
                else:  # a grid per load (a moving yield wall): p and P0 columns for each load
                    w.writerow(
                        [f"{c}(p_bar={pb:.6g} {up}) [{u}]" for pb in pr.p_bar for c, u in (("p", up), ("P0", uP))]
                    )
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


def add_parser(sub) -> None:
    """Register the ``solve`` subcommand on the subparsers ``sub``."""
    so = sub.add_parser("solve", help="solve one problem with a numerical method")
    _add_problem_args(so)
    so.add_argument(
        "--method",
        default="fv",
        type=str.lower,
        help="auto | fv | mol | sines | chebyshev | py-pde | fipy | chapman-kolmogorov | monte-carlo (any case)",
    )
    so.add_argument("--n-p", dest="n_p", type=_count, default=None, help="grid cells / points / modes")
    so.add_argument("--n-steps", dest="n_steps", type=_count, default=None, help="steps in zeta (fixed-step schemes)")
    so.add_argument("--rtol", type=float, default=None, help="relative tolerance (adaptive methods)")
    so.add_argument("--atol", type=float, default=None, help="absolute tolerance (adaptive methods)")
    so.add_argument(
        "--scheme", default=None, type=str.lower, help="fv time scheme (explicit, crank-nicolson, implicit, tr-bdf2)"
    )
    so.add_argument("--output", default=None, help="write P0 at zeta_max: .csv or .json")
    so.add_argument("--plot", default=None, help="write a PNG of P0 against the exact solution")
    so.add_argument("--force", action="store_true", help="replace existing --output / --plot files")
    so.add_argument("--seed", type=_count, default=None, help="seed of the random walks (--method monte-carlo)")
    so.add_argument("--tol", type=float, default=None, help="asked accuracy: with --method auto, fv, mol or chebyshev")
    so.add_argument("--hardness", type=float, default=None, help="yield stress sigma_Y at zeta = 1 (pressure)")
    so.add_argument(
        "--hardness-exponent", type=float, default=0.0, help="sigma_Y = hardness * zeta^n (default 0: constant)"
    )
    so.set_defaults(func=cmd_solve)
