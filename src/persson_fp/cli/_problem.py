"""What the report, solve and area subcommands share: the surface and load options, the problem they describe, the
output folder and a progress bar."""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np

from persson_fp.cli._io import CLIError, add_units_arg, check_load_vs_modulus, choice, resolve_units
from persson_fp.problems.contact import ContactProblem
from persson_fp.surfaces.psd import SelfAffinePSD
from persson_fp.surfaces.tabulated import TabulatedPSD
from persson_fp.theory import fudge as _fudge

FUDGES = ["none", "YP08", "WM17", "Xu24"]


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
    g.add_argument(
        "--psd", "--psd-csv", dest="psd_csv", default=None, help="measured isotropic PSD: CSV with header columns q,C"
    )
    m = p.add_argument_group("contact")
    m.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E/(1-nu^2), pressure (default 1)")
    lo = m.add_mutually_exclusive_group()
    lo.add_argument("--p-bar", type=float, nargs="+", default=None, help="nominal pressure(s), pressure units")
    lo.add_argument(
        "--p-bar-ratio", type=float, nargs="+", default=None, help="load(s) as p_bar / sqrt(V(zeta_max)) (default 0.5)"
    )
    m.add_argument(
        "--fudge", default="none", type=choice(FUDGES), help="fudge factor S(A*): none, YP08, WM17, Xu24 (any case)"
    )
    m.add_argument("--gamma", type=float, default=None, help="gamma of the fudge model (default: the model's)")
    add_units_arg(m)


_SURFACE_OPTIONS = ("H", "q_l", "q_r", "zeta_max", "rms_slope", "rms_height", "C0")


def _check_combination(args):
    """Options that would be silently ignored are errors (for the subcommands that take the problem options)."""
    if not hasattr(args, "psd_csv"):  # surface, sweep: their own options, checked by their modules
        return
    if args.psd_csv:
        given = [o for o in _SURFACE_OPTIONS if getattr(args, o) is not None]
        if given:
            flags = ", ".join("--" + o.replace("_", "-") for o in given)
            raise CLIError(f"{flags}: not used with --psd (the measured spectrum fixes the surface)")
    if args.gamma is not None and args.fudge == "none" and args.command == "solve":
        raise CLIError("--gamma: not used with --fudge none (choose YP08, WM17 or Xu24)")


def _problem(args, fudge=None) -> ContactProblem:
    if args.psd_csv:
        if not os.path.isfile(args.psd_csv):
            what = "is a directory" if os.path.isdir(args.psd_csv) else "no such file"
            raise CLIError(f"--psd: {what}: {args.psd_csv!r}")
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
    resolve_units(args)
    if args.p_bar is not None:
        p_bar = np.array(args.p_bar)
        if not (np.all(np.isfinite(p_bar)) and np.all(p_bar > 0)):
            got = " ".join(f"{v:g}" for v in p_bar)
            raise CLIError(f"--p-bar must be finite pressures > 0 (every load), got {got}")
        check_load_vs_modulus(p_bar, args.E_star, args.units)
    else:
        ratio = np.array([0.5] if args.p_bar_ratio is None else args.p_bar_ratio)
        if np.any(~np.isfinite(ratio)) or np.any(ratio <= 0):
            raise CLIError(f"--p-bar-ratio must be > 0 and finite, got {' '.join(f'{v:g}' for v in ratio)}")
        p_bar = ratio * np.sqrt(ContactProblem(psd, args.E_star, 1.0).V_max)  # (checks V's range first)
    return ContactProblem(psd, args.E_star, p_bar[0] if p_bar.size == 1 else p_bar, f)


def _outdir(path) -> str:
    if os.path.exists(path) and not os.path.isdir(path):
        raise CLIError(f"--output: {path} exists and is not a folder")
    os.makedirs(path, exist_ok=True)
    return path


# -- report ------------------------------------------------------------------------------------------
