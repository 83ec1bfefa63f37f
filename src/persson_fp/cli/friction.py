"""``persson-fp friction``: the viscoelastic friction coefficient mu(v, T) and sliding contact area of a rubber.

Persson's theory of rubber friction (Persson, J. Chem. Phys. 115 (2001) 3840; J. Phys.: Condens. Matter 18 (2006)
7789) from a DMA master curve (CSV: frequency, E_storage, E_loss) or a Zener model, a time-temperature shift (WLF or
a table of a_T), and the road's spectrum (a PSD CSV or a height map).  Writes friction.csv (units in the headers)
and friction.png (mu and A/A0 against the speed, one curve per temperature).  The scope (isothermal, hysteretic
friction only) is printed with the results.
"""

from __future__ import annotations

import os

import numpy as np

from persson_fp.cli._io import CLIError, _atomic_open, _make_parent, _save_figure, choice

MAX_POINTS = 100_000
"""Largest number of (velocity, temperature) pairs in one run (~1 kB of work arrays each per q node)."""

EPILOG = """\
examples:
  persson-fp friction --master-curve mc.csv --wlf 8.86 101.6 --T-ref 20 --psd road.csv --p-bar 2e5 \\
      --temperature 0 20 40 --velocity 1e-6 10 --n-velocities 60 --output friction/
  persson-fp friction --zener 3e6 3e9 1e-4 --psd road.csv --p-bar 2e5 --output friction/
  persson-fp friction heights.npy --size 0.01 --master-curve mc.csv --p-bar 2e5 --output friction/

Units: SI throughout here -- lengths (the spectrum, the height map's size) in m, speeds in m/s, moduli and
--p-bar in Pa, temperatures in degrees C, master-curve frequencies in Hz (--frequency-unit rad/s otherwise).
"""


def add_parser(sub):
    fr = sub.add_parser(
        "friction",
        help="rubber friction mu(v, T) and sliding contact area from a master curve and a road spectrum",
        epilog=EPILOG,
        formatter_class=__import__("argparse").RawDescriptionHelpFormatter,
    )
    fr.add_argument("file", nargs="?", default=None, help="height map of the road (.npy or text), with --size")
    fr.add_argument("--size", type=float, nargs="+", default=None, help="physical size Lx [Ly] of the height map, m")
    fr.add_argument("--periodic", action="store_true", help="the height map is periodic (no detrending, no window)")
    fr.add_argument("--trust-units", action="store_true", help="accept a height map's rms slope outside 1e-6..10")
    fr.add_argument("--psd", default=None, help="the road's isotropic spectrum: CSV with header columns q,C (SI)")
    mat = fr.add_mutually_exclusive_group(required=True)
    mat.add_argument("--master-curve", default=None, help="DMA master curve CSV: frequency, E_storage, E_loss")
    mat.add_argument("--zener", type=float, nargs=3, metavar=("E_R", "E_G", "TAU"),
                     help="a Zener rubber: rubbery and glassy moduli (Pa) and relaxation time (s)")  # fmt: skip
    fr.add_argument("--frequency-unit", default="Hz", type=choice(["Hz", "rad/s"]), help="master curve's (default Hz)")
    fr.add_argument("--nu", type=float, default=0.5, help="Poisson ratio in [0, 0.5] (default 0.5)")
    sh = fr.add_mutually_exclusive_group()
    sh.add_argument("--wlf", type=float, nargs=2, metavar=("C1", "C2"), help="WLF shift constants (C2 in K)")
    sh.add_argument("--shift", default=None, help="shift table CSV: T (degrees C), a_T")
    fr.add_argument("--T-ref", type=float, default=None, help="the master curve's temperature, degrees C")
    fr.add_argument("--temperature", type=float, nargs="+", default=None, help="temperature(s), degrees C")
    fr.add_argument("--p-bar", type=float, required=True, help="nominal contact pressure sigma0, Pa")
    fr.add_argument("--velocity", type=float, nargs="+", default=[1e-6, 10.0],
                    help="sliding speeds, m/s: two values are a range (--n-velocities), more are the list")  # fmt: skip
    fr.add_argument("--n-velocities", type=int, default=50, help="speeds in a --velocity range, log-spaced (50)")
    fr.add_argument("--q1", type=float, default=None, help="short-wavelength cut-off q1, 1/m (default the PSD's q_s)")
    fr.add_argument("--fudge", default="YP08", type=choice(["none", "YP08", "WM17", "Xu24"]),
                    help="weight S(P) in the friction integrand (default YP08)")  # fmt: skip
    fr.add_argument("--modulus-in-G", default="reduced", type=choice(["reduced", "plain"]),
                    help="E/(1-nu^2) (default) or E in G(q)")  # fmt: skip
    fr.add_argument("--strain-softening", default=None, help="CSV: strain (fraction), f, g (Payne effect)")
    fr.add_argument("--output", default="persson-fp-friction", help="folder for friction.csv / friction.png")
    fr.add_argument("--force", action="store_true", help="replace existing friction.csv / friction.png")
    fr.set_defaults(func=cmd_friction)
    return fr


def _read_columns(path, option, names):
    """Columns ``names`` of a CSV with a header row; a bad file is a one-line error naming ``option``."""
    from persson_fp._csv import read_columns

    return read_columns(path, names, option)


def _material(args):
    from persson_fp.theory import viscoelastic as ve

    shift = None
    if args.wlf is not None:
        shift = ve.WLF(*args.wlf)
    elif args.shift is not None:
        T, aT = _read_columns(args.shift, "--shift", ["T", "a_T"])
        shift = ve.ShiftTable(T, aT)
    if shift is not None and args.T_ref is None:
        raise CLIError("--T-ref (the master curve's temperature, degrees C) is required with --wlf or --shift")
    kw = dict(nu=args.nu, T_ref=args.T_ref, shift=shift)
    if args.zener is not None:
        return ve.Zener(*args.zener, **kw)
    f, E1, E2 = _read_columns(args.master_curve, "--master-curve", ["frequency", "E_storage", "E_loss"])
    return ve.MasterCurve(f, E1, E2, frequency_unit=args.frequency_unit, **kw)


def _road(args):
    from persson_fp.surfaces.tabulated import TabulatedPSD

    if (args.psd is None) == (args.file is None):
        raise CLIError("give the road as --psd PSD.csv or as a height map FILE (with --size), one of the two")
    if args.psd is not None:
        try:
            return TabulatedPSD.from_csv(args.psd)
        except ValueError as e:
            raise CLIError(f"--psd: {e}") from None
    from persson_fp.cli.surface import _SERIES, _read

    args.series, args.H = _SERIES, None
    surf = _read(args)
    print(surf.describe("m"))  # SI throughout here
    return surf.psd


def cmd_friction(args) -> int:
    from persson_fp.analysis.friction import SCOPE, rubber_friction
    from persson_fp.theory import viscoelastic as ve

    out = os.path.abspath(args.output)
    if os.path.exists(out) and not os.path.isdir(out):
        raise CLIError(f"--output: {args.output} exists and is not a folder")
    names = ("friction.csv", "friction.png")
    existing = [n for n in names if os.path.isfile(os.path.join(out, n))]
    if existing and not args.force:
        raise CLIError(f"--output: {', '.join(existing)} exist in {args.output}; pass --force to replace them")
    if not (np.isfinite(args.p_bar) and args.p_bar > 0):
        raise CLIError(f"--p-bar must be a finite pressure > 0 (Pa), got {args.p_bar:g}")
    v = np.asarray(args.velocity, dtype=float)
    if v.size == 2:
        if not (np.all(np.isfinite(v)) and np.all(v > 0) and v[0] < v[1]):
            raise CLIError("--velocity: a range needs 0 < min < max (m/s), finite")
        if not 2 <= args.n_velocities <= MAX_POINTS:
            raise CLIError(f"--n-velocities must lie in [2, {MAX_POINTS}], got {args.n_velocities}")
        v = np.geomspace(v[0], v[1], args.n_velocities)
    T = None if args.temperature is None else np.asarray(args.temperature, dtype=float)[:, None]
    if T is not None and T.size * v.size > MAX_POINTS:
        raise CLIError(f"{T.size} temperatures x {v.size} speeds: at most {MAX_POINTS} pairs in one run")
    material = _material(args)
    psd = _road(args)
    soft = None
    if args.strain_softening is not None:
        eps, f, g = _read_columns(args.strain_softening, "--strain-softening", ["strain", "f", "g"])
        soft = ve.StrainSoftening(eps, f, g)
    res = rubber_friction(
        psd, material, args.p_bar, v, temperature=T, q1=args.q1, fudge=None if args.fudge == "none" else args.fudge,
        modulus_in_G=args.modulus_in_G, strain_softening=soft,
    )  # fmt: skip
    os.makedirs(out, exist_ok=True)
    csv_path = os.path.join(out, "friction.csv")
    _make_parent(csv_path, "--output")
    Tb = None if res.temperature is None else res.temperature.ravel()
    with _atomic_open(csv_path, newline="") as fh:
        fh.write("# " + SCOPE + "\n")
        fh.write("# " + "; ".join(f"{k} = {val}" for k, val in res.conventions.items()) + "\n")
        cols = (["temperature [degC]"] if Tb is not None else []) + [
            "velocity [m/s]", "mu [-]", "mu_error [-]", "contact_area [-]", "contact_area_error [-]",
        ]  # fmt: skip
        fh.write(",".join(cols) + "\n")
        rows = np.column_stack(
            ([Tb] if Tb is not None else [])
            + [res.velocity.ravel(), res.mu.ravel(), res.mu_error.ravel(), res.contact_area.ravel(),
               res.contact_area_error.ravel()]
        )  # fmt: skip
        np.savetxt(fh, rows, delimiter=",", fmt="%.10g")
    fig = res.plot()
    for ax in fig.axes:
        ax.set_xlabel("sliding speed v [m/s]")
    fig.axes[0].set_title(
        f"sigma0 = {res.sigma0:.4g} Pa, q1 = {res.q1:.3g} 1/m, fudge {res.conventions['fudge']}", fontsize=9
    )
    _save_figure(fig, os.path.join(out, "friction.png"), 120)
    mu = res.mu
    i = np.unravel_index(int(np.argmax(mu)), mu.shape)
    T_txt = "" if res.temperature is None else f" at {float(res.temperature[i]):g} degC"
    print(
        f"mu: {float(mu.min()):.4g} .. {float(mu.max()):.4g} (max at v = {float(res.velocity[i]):.3g} m/s{T_txt}); "
        f"A/A0: {float(res.contact_area.min()):.3g} .. {float(res.contact_area.max()):.3g}; "
        f"largest error estimate {float(res.mu_error.max()):.1g}"
    )
    print(f"note: {SCOPE}")
    print(f"wrote {csv_path} and {os.path.join(out, 'friction.png')}")
    return 0
