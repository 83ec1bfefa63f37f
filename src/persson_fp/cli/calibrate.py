"""``persson-fp calibrate``: fit a fudge model's parameters to measured or simulated A*(p_bar) / mean separation.

Wires :func:`persson_fp.calibrate` to the command line; bad arguments and bad data raise ``ValueError`` (printed
as one line by :func:`persson_fp.cli.app.main`, exit code 2).
"""

from __future__ import annotations

import argparse
import csv
import json
import os

from persson_fp.cli._io import add_units_arg, choice, col, resolve_units, unit

HELP = "fit a fudge model's parameters (gamma) to your A*(p_bar) and/or mean-separation data, with uncertainty"

EPILOG = """\
DATA.csv has a header row with p_bar (pressure) and contact_area (A*, in (0, 1]) and/or mean_separation
(length), optionally contact_area_err / mean_separation_err (1 standard deviation).  Each --psd file is an
isotropic spectrum with columns q,C (Persson's C, <h^2> = 2 pi int q C dq).  With several --psd files, DATA
needs a column 'surface' naming each row's spectrum file (its name without .csv); the surfaces share the
parameters.  The fit minimises squared relative errors; the uncertainty is s^2 (J^T J)^-1.  Several --model
values are each fitted and ranked (--criterion).  A calibration holds for surfaces like those fitted.

examples:
  persson-fp calibrate bem.csv --psd surface.csv
  persson-fp calibrate runs.csv --psd s1.csv s2.csv s3.csv --model YP08 WM17 Xu24 --plot fit.png
  persson-fp calibrate gaps.csv --psd s.csv --quantities mean_separation --weighting corrected-area --json fit.json
"""


def add_parser(sub) -> argparse.ArgumentParser:
    """Register the ``calibrate`` sub-command on ``sub`` (the parser's sub-parsers)."""
    ca = sub.add_parser(
        "calibrate", help=HELP, description=HELP, epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ca.add_argument("data", help="CSV with p_bar and contact_area and/or mean_separation (see below)")
    ca.add_argument("--psd", nargs="+", required=True, help="spectrum CSV file(s), columns q,C (one per surface)")
    ca.add_argument("--q-column", default="q", help="wavenumber column of the spectra (default q)")
    ca.add_argument("--C-column", dest="C_column", default="C", help="PSD column of the spectra (default C)")
    ca.add_argument(
        "--model",
        "--fudge",
        dest="model",
        nargs="+",
        type=choice(["YP08", "WM17", "Xu24"]),
        default=["YP08"],
        help="fudge model(s): YP08 (default), WM17, Xu24 (any case); several: fitted and ranked",
    )
    ca.add_argument("--params", nargs="+", default=["gamma"], help="free parameters (default gamma)")
    ca.add_argument(
        "--quantities", nargs="+", default=None, help="contact_area and/or mean_separation (default: those in DATA)"
    )
    ca.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E/(1-nu^2), pressure (default 1)")
    ca.add_argument(
        "--weighting",
        default="yang-persson",
        type=str.lower,
        help="energy weighting of the mean separation (default yang-persson)",
    )
    ca.add_argument(
        "--criterion",
        default="held-out",
        type=str.lower,
        help="ranking of several models: held-out (default), aic, bic",
    )
    ca.add_argument("--bootstrap", type=int, default=0, help="bootstrap resamples of the data points (default 0)")
    ca.add_argument("--seed", type=int, default=None, help="random seed of the bootstrap")
    ca.add_argument("--output", default=None, help="write the residual table (data, fit, relative error) as CSV")
    ca.add_argument("--json", default=None, help="write the fitted values, uncertainties and intervals as JSON")
    ca.add_argument("--plot", default=None, help="write a PNG of data, fit and 95 %% band")
    ca.add_argument("--force", action="store_true", help="replace existing --output / --json / --plot files")
    add_units_arg(ca)
    ca.set_defaults(func=cmd_calibrate)
    return ca


def _fit_record(cal) -> dict:
    ci = cal.interval(0.95)
    return {
        "model": cal.family.name,
        "params": cal.params,
        "std": cal.uncertainty,
        "interval_95": {k: list(v) for k, v in ci.items()},
        "bootstrap_std": None if cal.bootstrap_std is None else dict(zip(cal.names, map(float, cal.bootstrap_std))),
        "n_points": cal.n_points,
        "quantities": list(cal.quantities),
        "rms_rel_error": cal.rms_rel_error,
        "mean_abs_rel_error": cal.mean_abs_rel_error,
        "aic": cal.aic,
        "bic": cal.bic,
    }


def cmd_calibrate(args) -> int:
    from persson_fp.calibration import ModelSelection, calibrate
    from persson_fp.cli._io import CLIError, _atomic_open, _check_new_file, _make_parent, _save_figure
    from persson_fp.surfaces.tabulated import TabulatedPSD

    units = resolve_units(args)
    for opt in ("output", "json", "plot"):
        _check_new_file(getattr(args, opt), args.force, f"--{opt}")
    for path in [args.data, *args.psd]:
        if not os.path.isfile(path):
            raise CLIError(f"{'is a directory' if os.path.isdir(path) else 'no such file'}: {path!r}")
    names = [os.path.splitext(os.path.basename(p))[0] for p in args.psd]
    if len(set(names)) != len(names):
        raise CLIError(
            f"--psd: two spectra with the same file name ({names}); the 'surface' column needs distinct ones"
        )
    psds = {n: TabulatedPSD.from_csv(p, args.q_column, args.C_column) for n, p in zip(names, args.psd)}
    model = args.model[0] if len(args.model) == 1 else list(args.model)
    res = calibrate(
        psds if len(psds) > 1 else psds[names[0]], args.data, model, tuple(args.params), args.quantities,
        E_star=args.E_star, weighting=args.weighting, bootstrap=args.bootstrap, rng=args.seed,
        criterion=args.criterion,
    )  # fmt: skip
    if isinstance(res, ModelSelection):
        print(res.summary())
        print()
        cal = res.best
        print("best: " + cal.summary())
        if args.bootstrap:
            print("(--bootstrap applies to a single --model)")
    else:
        cal = res
        print(cal.summary())
    if args.output:
        _make_parent(args.output, "--output")
        table = cal.residual_table()
        kinds = {"contact_area": "-", "mean_separation": "length"}
        table = {  # units in the headers; data and fit in the unit of each row's quantity (the unit column)
            "surface": table["surface"],
            "quantity": table["quantity"],
            "unit": [unit(kinds.get(str(q), "-"), units) for q in table["quantity"]],
            col("p_bar", "pressure", units): table["p_bar"],
            "data [unit]": table["data"],
            "fit [unit]": table["fit"],
            col("rel_error", "-", units): table["rel_error"],
            col("residual", "-", units): table["residual"],
        }
        with _atomic_open(args.output, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(list(table))
            for row in zip(*table.values()):
                w.writerow([v if isinstance(v, str) else f"{v:.12g}" for v in row])
        print(f"written {args.output}")
    if args.json:
        _make_parent(args.json, "--json")
        record = _fit_record(cal)
        if isinstance(res, ModelSelection):
            record = {
                "criterion": res.criterion, "held_out_scheme": res.held_out_scheme, "ranking": res.ranking,
                "held_out_mean_abs_rel_error": res.held_out, "fits": [_fit_record(res.fits[n]) for n in res.ranking],
            }  # fmt: skip
        with _atomic_open(args.json, "w") as fh:
            json.dump(record, fh, indent=2)
        print(f"written {args.json}")
    if args.plot:
        _make_parent(args.plot, "--plot")
        _save_figure(cal.plot(), args.plot, dpi=110)
        print(f"written {args.plot}")
    return 0
