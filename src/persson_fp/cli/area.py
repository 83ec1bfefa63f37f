"""``persson-fp area``: the contact-area curves A*(p_bar) of every fudge model (exact), CSV and PNG."""

from __future__ import annotations

import csv
import os
import time

import numpy as np

from persson_fp.analysis.exact import exact
from persson_fp.cli._io import (
    CLIError,
    _atomic_open,
    _check_new_files,
    _count,
    _save_figure,
    col,
)
from persson_fp.cli._problem import (
    FUDGES,
    MAX_LOADS,
    _add_problem_args,
    _outdir,
    _problem,
    _progress,
)
from persson_fp.problems.contact import ContactProblem


def cmd_area(args) -> int:
    from persson_fp import plotting

    if not (0 < args.ratio_min < args.ratio_max) or not np.isfinite(args.ratio_max):
        raise CLIError(
            f"--ratio-min and --ratio-max must satisfy 0 < min < max (finite), got {args.ratio_min:g} and "
            f"{args.ratio_max:g}"
        )
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
    _check_new_files(out, ["contact_area.csv", "contact_area.png"], args.force)
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
    with _atomic_open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        u = args.units
        w.writerow(
            [col("p_bar", "pressure", u), col("p_bar_over_sqrtV", "-", u)] + [col(f"A_{n}", "-", u) for n in FUDGES]
        )
        for j in range(ratio.size):
            w.writerow([f"{p_bar[j]:.12g}", f"{ratio[j]:.12g}"] + [f"{curves[n][j]:.15g}" for n in FUDGES])
    _save_figure(plotting.plot_area_curve(ratio, curves), os.path.join(out, "contact_area.png"), dpi=120)
    print(
        f"{ratio.size} loads x {len(FUDGES)} models in {wall * 1e3:.1f} ms "
        f"({ratio.size * len(FUDGES) / wall:.3g} loads/s)"
    )
    print(f"written {path} and contact_area.png")
    return 0


def add_parser(sub) -> None:
    """Register the ``area`` subcommand on the subparsers ``sub``."""
    ar = sub.add_parser("area", help="A*(p_bar) curves for every fudge model (exact)")
    _add_problem_args(ar)
    ar.add_argument("--n-loads", type=_count, default=1000, help="number of loads (default 1000)")
    ar.add_argument(
        "--p-bar-ratio-min",
        "--ratio-min",
        dest="ratio_min",
        type=float,
        default=1e-3,
        help="smallest p_bar/sqrt(V) (default 1e-3)",
    )
    ar.add_argument(
        "--p-bar-ratio-max",
        "--ratio-max",
        dest="ratio_max",
        type=float,
        default=3.0,
        help="largest p_bar/sqrt(V) (default 3)",
    )
    ar.add_argument("--output", default="persson-fp-output", help="folder for contact_area.csv / .png")
    ar.add_argument("--force", action="store_true", help="replace existing contact_area.csv / contact_area.png")
    ar.set_defaults(func=cmd_area)
