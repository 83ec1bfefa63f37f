"""``persson-fp sweep``: every surface in a folder x fudge models x loads into one table.

Wires :func:`persson_fp.sweep` to the command line; bad arguments raise ``ValueError`` (printed as
one line by :func:`persson_fp.cli.app.main`, exit code 2).  Exit code 1 when some tasks failed (the
table of the others is still written).
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
import warnings

import numpy as np

from persson_fp.cli._io import _check_new_file, _make_parent, check_load_vs_modulus, choice


def _write_table(res, out):
    """Write the table (and a CSV's metadata file) under temporary names, renamed when complete: an interrupted
    sweep leaves no partial table and an existing one untouched."""
    import contextlib

    from persson_fp.cli._io import _atomic_path
    from persson_fp.sweeps.table import metadata_path

    if not out.endswith(".csv"):
        with _atomic_path(out) as tmp:
            res.to_parquet(tmp)
        return
    with _atomic_path(out) as tmp, _atomic_path(metadata_path(out)) as tmp_meta:
        try:
            res.to_csv(tmp)
            os.replace(metadata_path(tmp), tmp_meta)
        finally:
            with contextlib.suppress(OSError):
                os.unlink(metadata_path(tmp))


HELP = "surfaces (CSV spectra, folders of them) x fudge models x loads into one table (CSV or Parquet)"

EPILOG = """\
Each CSV holds an isotropic PSD with header columns q,C (Persson's C, <h^2> = 2 pi int q C dq;
q in 1/length, C in length^4).  Loads are p_bar / sqrt(V(zeta_max)) of each surface unless --p-bar
gives absolute pressures.  The table has one row per surface x model x quantity x load with units;
the metadata (method, versions, failures) is written with it.

examples:
  persson-fp sweep spectra/ --output sweep.csv
  persson-fp sweep spectra/ --models none YP08 --quantities contact_area variance --workers 4 --output s.parquet
  persson-fp sweep a.csv b.csv --p-bar 1e5 1e6 1e7 --E-star 2.1e11
"""


def add_parser(sub) -> argparse.ArgumentParser:
    """Register the ``sweep`` sub-command on ``sub`` (the parser's sub-parsers)."""
    from persson_fp.sweeps.quantities import QUANTITIES
    from persson_fp.theory.fudge import MODELS

    sw = sub.add_parser(
        "sweep", help=HELP, description=HELP, epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    sw.add_argument("surfaces", nargs="+", help="CSV files (columns q,C) or folders of them")
    sw.add_argument("--pattern", default="*.csv", help="which files of a folder to read (glob, default *.csv)")
    sw.add_argument("--q-column", default="q", help="wavenumber column name (default q)")
    sw.add_argument("--C-column", dest="C_column", default="C", help="PSD column name (default C)")
    sw.add_argument("--p-bar", type=float, nargs="+", default=None, help="absolute nominal pressures (pressure)")
    sw.add_argument("--p-bar-ratio", type=float, nargs="+", default=None, help="loads as p_bar/sqrt(V) of each surface")
    sw.add_argument("--n-loads", type=int, default=100, help="relative loads per surface (default 100)")
    sw.add_argument("--p-bar-ratio-min", "--ratio-min", dest="ratio_min", type=float, default=1e-3,
                    help="smallest p_bar/sqrt(V) (default 1e-3)")  # fmt: skip
    sw.add_argument("--p-bar-ratio-max", "--ratio-max", dest="ratio_max", type=float, default=3.0,
                    help="largest p_bar/sqrt(V) (default 3)")  # fmt: skip
    sw.add_argument("--models", "--fudge", dest="models", nargs="+", type=choice(list(MODELS)), default=list(MODELS),
                    help=f"fudge models, any case (default all: {' '.join(MODELS)})")  # fmt: skip
    sw.add_argument(
        "--quantities",
        nargs="+",
        default=["contact_area"],
        help=f"quantities (default contact_area; available: {' '.join(QUANTITIES)})",
    )
    sw.add_argument(
        "--method", default="exact", type=str.lower, help="exact (default) or a solver: fv, mol, sines, ..."
    )
    sw.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E* (default 1)")
    sw.add_argument("--workers", type=int, default=1, help="processes (default 1: serial)")
    sw.add_argument(
        "--output",
        default="sweep.csv",
        help="table path, .csv (metadata in <output>.json) or .parquet (default sweep.csv)",
    )
    sw.add_argument("--force", action="store_true", help="replace an existing --output table")
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")
    sw.set_defaults(func=cmd_sweep)
    return sw


def cmd_sweep(args) -> int:
    from persson_fp.surfaces.tabulated import TabulatedPSD
    from persson_fp.sweeps.run import SweepWarning, sweep

    if args.workers < 1:
        raise ValueError(f"--workers must be >= 1, got {args.workers}")
    if args.p_bar is not None and args.p_bar_ratio is not None:
        raise ValueError("--p-bar and --p-bar-ratio: give the loads one way")
    for flag, x in (("--p-bar", args.p_bar), ("--p-bar-ratio", args.p_bar_ratio)):
        if x is not None and not (np.all(np.isfinite(x)) and np.all(np.array(x) > 0)):
            raise ValueError(f"{flag} must be finite numbers > 0, got {' '.join(f'{v:g}' for v in x)}")
    if args.p_bar is not None:
        loads, relative = np.array(args.p_bar), False
        check_load_vs_modulus(loads, args.E_star)
    elif args.p_bar_ratio is not None:
        loads, relative = np.array(args.p_bar_ratio), True
    else:
        if not (0 < args.ratio_min < args.ratio_max < np.inf):
            raise ValueError("--ratio-min and --ratio-max must satisfy 0 < min < max < inf")
        if args.n_loads < 1:
            raise ValueError(f"--n-loads must be >= 1, got {args.n_loads}")
        loads, relative = np.geomspace(args.ratio_min, args.ratio_max, args.n_loads), True
    out = args.output
    if not out.endswith((".csv", ".parquet", ".pq")):
        raise ValueError(f"--output must end in .csv or .parquet, got {out!r}")
    _check_new_file(out, args.force, "--output")
    _make_parent(out, "--output")
    reader = functools.partial(TabulatedPSD.from_csv, q_column=args.q_column, C_column=args.C_column)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepWarning)  # failures are printed below
        res = sweep(
            args.surfaces,
            loads,
            models=[None if m == "none" else m for m in args.models],
            quantities=args.quantities,
            method=args.method,
            E_star=args.E_star,
            relative_loads=relative,
            executor=args.workers,
            progress=not args.no_progress,
            surface_reader=reader,
            surface_pattern=args.pattern,
        )
    _write_table(res, out)
    n_s, n_m, n_l = res.shape
    wall = res.metadata["wall_time_s"]
    print(
        f"{n_s} surfaces x {n_m} models x {n_l} loads, {len(res.quantities)} quantities, method {args.method}: "
        f"{wall:.3g} s ({n_s * n_m * n_l / wall:.3g} loads/s, {args.workers} worker(s))"
    )
    for f in res.failures:
        print(f"failed: {f}", file=sys.stderr)
    print(f"table written to {out}")
    return 1 if res.failures else 0
