"""``persson-fp surface FILE``: from a measured surface to contact area, mean separation and stiffness.

Reads a height map (``.npy``, or a text table of heights) or a contact.engineering power-spectrum CSV,
prints the spectrum's convention, rms height and slope (checked against the height data), and writes for a
range of loads, for every fudge model: the contact area A* (Xu et al. tutorial, ``eq:Area_Persson``), the
mean separation u and the normal stiffness K = -dp/du (Persson, Phys. Rev. Lett. 99 (2007) 125502; Yang & Persson,
J. Phys.: Condens. Matter 20 (2008) 215214) as a CSV with units and a PNG; and what happens in the gaps: the mean of
the gap distribution, the leak rate of a square seal (``--viscosity``, ``--pressure-drop``; Lorenz & Persson, Eur.
Phys. J. E 31 (2010) 159) and Barber's conductance (Proc. R. Soc. Lond. A 459 (2003) 53); the PNG's gap panels
show P(u) with its contact atom at four loads and the leak rate against the load, for the WM17 model.
"""

from __future__ import annotations

import json
import os
import time

import numpy as np

from persson_fp.cli._io import (
    CLIError,
    _atomic_open,
    _check_new_files,
    _count,
    _make_parent,
    _save_figure,
    add_units_arg,
    check_load_vs_modulus,
    choice,
    col,
    resolve_units,
    unit,
    warn,
)
from persson_fp.cli._problem import FUDGES

_SERIES = "q/π × 2D PSD"

GAP_MODEL = "WM17"
"""The fudge model of the figure's gap panels (with YP08 the closer to boundary-element gap histograms,
benchmarks/results/interface_vs_bem.md)."""

MAX_LOADS = 100_000
"""Largest ``surface --n-loads`` (four models, each load a quadrature of ~400 nodes: ~5 s at the cap)."""


def add_parser(sub):
    s = sub.add_parser(
        "surface",
        help="measured surface -> A*, mean separation, stiffness, gaps and leak rate (CSV + PNG)",
        description="A measured surface (height map or contact.engineering CSV) -> spectrum, contact area A*, mean "
        "separation u, stiffness K, gap distribution and leak rate, for every fudge model (CSV + PNG).",
        epilog=EPILOG,
        formatter_class=__import__("argparse").RawDescriptionHelpFormatter,
    )
    s.add_argument("file", help="height map (.npy, or text: whitespace/comma separated) or contact.engineering CSV")
    s.add_argument("--size", type=float, nargs="+", default=None, help="physical size Lx [Ly] of a height map (m)")
    s.add_argument("--periodic", action="store_true", help="the height map is periodic (no detrending, no window)")
    s.add_argument(
        "--trust-units",
        action="store_true",
        help="accept an rms slope outside 1e-6..10 (otherwise taken as heights and --size in different units)",
    )
    s.add_argument("--series", default=_SERIES, help=f"contact.engineering series (default {_SERIES!r})")
    s.add_argument("--H", type=float, default=None, help="1-D PSD series: Abel factor of this H (default: numerical)")
    s.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E/(1-nu^2), pressure (default 1)")
    add_units_arg(s)
    lo = s.add_argument_group("loads (one of; default --p-bar-ratio-min 1e-3 --p-bar-ratio-max 3)")
    lo.add_argument("--p-bar", type=float, nargs="+", default=None, help="nominal pressure(s), pressure units (Pa)")
    lo.add_argument("--p-bar-min", type=float, default=None, help="smallest nominal pressure of a log-spaced range")
    lo.add_argument("--p-bar-max", type=float, default=None, help="largest nominal pressure of a log-spaced range")
    lo.add_argument("--p-bar-ratio", type=float, nargs="+", default=None, help="load(s) as p_bar / sqrt(V(zeta_max))")
    lo.add_argument("--p-bar-ratio-min", "--ratio-min", dest="ratio_min", type=float, default=None,
                    help="smallest p_bar/sqrt(V) of a log-spaced range (default 1e-3)")  # fmt: skip
    lo.add_argument("--p-bar-ratio-max", "--ratio-max", dest="ratio_max", type=float, default=None,
                    help="largest p_bar/sqrt(V) of a log-spaced range (default 3)")  # fmt: skip
    lo.add_argument(
        "--n-loads", type=_count, default=60, help=f"loads of a range, log-spaced (default 60, at most {MAX_LOADS})"
    )
    s.add_argument(
        "--weighting",
        default="yang-persson",
        type=choice(["yang-persson", "corrected-area"]),
        help="energy weighting of the fudge models (default yang-persson, the closer to BEM mean gaps)",
    )
    s.add_argument(
        "--viscosity", type=float, default=None, help="fluid viscosity for the leak rate, pressure x time (Pa s)"
    )
    s.add_argument("--pressure-drop", type=float, default=None, help="pressure drop across the seal, pressure (Pa)")
    s.add_argument("--output", default="persson-fp-surface", help="folder for surface.csv / .json / .png")
    s.add_argument("--force", action="store_true", help="replace existing surface.csv / surface.json / surface.png")
    s.set_defaults(func=cmd_surface)
    return s


EPILOG = """\
Units: SI by default (--size in m, --E-star and --p-bar in Pa, --viscosity in Pa s; said once on stdout); the
CSV headers carry their units in brackets (p_bar [Pa], u_YP08 [m], K_YP08 [Pa/m], Q_cj_WM17 [m^3/s]).  With
--units none the input is any consistent set and the headers name the dimension ([length], [pressure]).
The leak-rate columns Q_cj_*, Q_em_* are written only when --viscosity and --pressure-drop are both given.

examples:
  persson-fp surface heights.npy --size 1e-3 --E-star 2.1e11 --p-bar 1e5 --viscosity 1e-3 --pressure-drop 1e5
  persson-fp surface heights.npy --size 1e-3 --E-star 2.1e11 --p-bar-min 1e4 --p-bar-max 1e8 --n-loads 40
  persson-fp surface psd.csv --E-star 1e7 --p-bar-ratio 0.1 0.5 --output rubber/
"""


def _read(args):
    import warnings

    from persson_fp._validate import as_file_path
    from persson_fp.surfaces.heightmap import ImplausibleSlopeWarning
    from persson_fp.surfaces.readers import read_contact_engineering_csv, read_heightmap

    path = as_file_path(args.file, "file")
    with open(path, "rb") as fh:
        head = fh.read(4096)
    if not path.endswith(".npy") and b"Data series" in head and b";" in head:
        return _warn_slope(read_contact_engineering_csv(path, series=args.series, H=args.H), args)
    if args.size is None:
        raise ValueError("--size Lx [Ly] (physical size of the height map) is required for a height map")
    if args.H is not None or args.series != _SERIES:
        print("note: --H and --series apply to contact.engineering CSV files only; ignored for a height map")
    size = args.size[0] if len(args.size) == 1 else args.size
    try:
        with warnings.catch_warnings():  # the command's own check below says it once, naming --size
            warnings.filterwarnings("ignore", category=ImplausibleSlopeWarning)
            surf = read_heightmap(path, size, periodic=args.periodic)
        return _warn_slope(_check_units(surf, args), args)
    except (ArithmeticError, ValueError) as e:  # ArithmeticError: overflow, or numpy's FloatingPointError
        if isinstance(e, ArithmeticError) or "floating-point range" in str(e) or str(e).startswith("C must be finite"):
            raise ValueError(
                f"--size {' '.join(f'{v:g}' for v in args.size)} with these heights gives a spectrum outside the "
                f"floating-point range ({e}); rescale the length unit"
            ) from None
        raise


SLOPE_RANGE = (1e-6, 10.0)
"""rms slopes a measured height map can have: outside, the heights and ``--size`` are in different units (heights in
micrometres with a size in metres give slopes 1e6 too steep; the reverse 1e6 too flat).  Machined, polished and
rough surfaces measure 1e-4 to ~3; ``--trust-units`` accepts any value."""


SLOPE_WARN = (1e-4, 5.0)
"""rms slopes inside SLOPE_RANGE that are still unusual for a measured surface: a one-line warning naming the likely
unit mix-up (the run goes on)."""


def _warn_slope(surf, args):
    """Warn (one line) when the rms slope is plausible enough to run but unusual: steeper than 5 or flatter than
    1e-4 (machined, polished and rough surfaces measure 1e-4 to ~3)."""
    slope = surf.rms_slope_data if surf.rms_slope_data is not None else float(surf.psd.rms_slope)
    lo, hi = SLOPE_WARN
    if lo <= slope <= hi or getattr(args, "trust_units", False):
        return surf
    where = f"the height map with --size {' '.join(f'{v:g}' for v in args.size)}" if args.size else "the spectrum"
    if slope > hi:
        why = "the heights in a larger unit than --size (heights in um with --size in mm: slopes 1e3 too steep)"
    else:
        why = "the heights in a smaller unit than --size (heights in nm with --size in um: slopes 1e3 too flat)"
    if not args.size:
        why = "q and C in different length units (e.g. q in 1/um with C in m^4)"
    warn(
        f"{where} has an rms slope of {slope:.3g}, unusual for a measured surface (1e-4 to ~3): check the units, "
        f"likely {why}"
    )
    return surf


def _check_units(surf, args):
    """Refuse a height map whose rms slope says that its heights and ``--size`` are in different units."""
    slope = surf.rms_slope_data if surf.rms_slope_data is not None else float(surf.psd.rms_slope)
    lo, hi = SLOPE_RANGE
    if getattr(args, "trust_units", False) or lo <= slope <= hi:
        return surf
    size = " ".join(f"{v:g}" for v in args.size)
    factor = "too steep" if slope > hi else "too flat"
    raise ValueError(
        f"the height map with --size {size} has an rms slope of {slope:.3g}, {factor} for a measured surface "
        f"(expected {lo:g} to {hi:g}): the heights and --size are probably in different units (heights in "
        "micrometres with a size in metres change the slope by 1e6); give --size in the heights' unit, or pass "
        "--trust-units"
    )


def _loads(args, sV):
    """The nominal pressures (sorted) from the one load option given; a bad value names its option."""
    ways = {
        "--p-bar": args.p_bar is not None,
        "--p-bar-min/--p-bar-max": args.p_bar_min is not None or args.p_bar_max is not None,
        "--p-bar-ratio": args.p_bar_ratio is not None,
        "--p-bar-ratio-min/--p-bar-ratio-max": args.ratio_min is not None or args.ratio_max is not None,
    }
    given = [k for k, v in ways.items() if v]
    if len(given) > 1:
        raise CLIError(f"{' and '.join(given)}: give the loads one way")
    if args.p_bar is not None or args.p_bar_ratio is not None:
        flag = "--p-bar" if args.p_bar is not None else "--p-bar-ratio"
        x = np.sort(np.array(args.p_bar if args.p_bar is not None else args.p_bar_ratio, dtype=float))
        if not (np.all(np.isfinite(x)) and np.all(x > 0)):
            raise CLIError(f"{flag} must be finite numbers > 0, got {' '.join(f'{v:g}' for v in x)}")
        if x.size > MAX_LOADS:
            raise CLIError(f"{flag}: at most {MAX_LOADS} loads, got {x.size}")
        return x if args.p_bar is not None else x * sV
    if not 2 <= args.n_loads <= MAX_LOADS:
        raise ValueError(f"--n-loads must lie in [2, {MAX_LOADS}], got {args.n_loads}")
    if given and given[0] == "--p-bar-min/--p-bar-max":
        lo, hi, flag, scale = args.p_bar_min, args.p_bar_max, "--p-bar-min and --p-bar-max", 1.0
        if lo is None or hi is None:
            raise CLIError("--p-bar-min and --p-bar-max go together (a log-spaced range of --n-loads pressures)")
    else:
        lo = 1e-3 if args.ratio_min is None else args.ratio_min
        hi = 3.0 if args.ratio_max is None else args.ratio_max
        flag, scale = "--p-bar-ratio-min and --p-bar-ratio-max", sV
    if not (0 < lo < hi) or not np.isfinite(hi):
        raise ValueError(f"{flag} must satisfy 0 < min < max (finite), got {lo:g} and {hi:g}")
    return np.geomspace(lo, hi, args.n_loads) * scale


def _largest_load_flag(args) -> str:
    """The option that set the largest load, with its value (for a message)."""
    for flag, v in (("--p-bar", args.p_bar), ("--p-bar-max", args.p_bar_max), ("--p-bar-ratio", args.p_bar_ratio)):
        if v is not None:
            return f"{flag} {np.max(v):g}"
    return f"--p-bar-ratio-max {3.0 if args.ratio_max is None else args.ratio_max:g}"


def cmd_surface(args) -> int:
    from persson_fp.analysis.exact import exact
    from persson_fp.problems.contact import ContactProblem
    from persson_fp.theory.separation import MeanSeparation

    units = resolve_units(args)
    out = args.output
    names = ["surface.csv", "surface.json", "surface.png"]
    if os.path.exists(out) and not os.path.isdir(out):
        raise CLIError(f"--output: {out} exists and is not a folder")
    _check_new_files(out, names, args.force)
    flow = (args.viscosity, args.pressure_drop)
    for flag, v, what in (("--viscosity", flow[0], "viscosity"), ("--pressure-drop", flow[1], "pressure")):
        if v is not None and not (np.isfinite(v) and v > 0):
            raise ValueError(f"{flag} must be a finite number > 0 ({unit(what, units)}), got {v:g}")
    if (flow[0] is None) != (flow[1] is None):
        raise CLIError("--viscosity and --pressure-drop go together (the leak rate needs both; neither: no Q columns)")
    _loads(args, 1.0)  # the load options checked before the surface is read
    leak = flow[0] is not None
    surf = _read(args)
    psd = surf.psd
    desc = surf.describe(unit("length", units))
    print(desc)
    E = args.E_star
    sV = float(np.sqrt(psd.V(E_star=E)))
    with np.errstate(all="ignore"):
        p_bar = _loads(args, sV)
        ratio = p_bar / sV
    if not (np.all(np.isfinite(p_bar)) and np.all(p_bar > 0) and np.all(np.isfinite(ratio)) and np.all(ratio > 0)):
        raise ValueError(
            f"--E-star {E:g} with this surface gives sqrt(V) = {sV:.3g} and loads outside the floating-point range "
            "(p_bar = ratio x E* rms slope / 2); rescale the pressure unit (e.g. MPa)"
        )
    check_load_vs_modulus(p_bar, E, units)
    leak = flow[0] is not None
    scale = flow[1] / flow[0] if leak else 1.0  # Q is linear in pressure_drop / viscosity
    p_req, sel = p_bar, slice(None)
    listed = args.p_bar is not None or args.p_bar_ratio is not None
    if listed and p_bar.size < FIGURE_LOADS:  # a few loads: the figure's curves span the default range, loads marked
        p_bar = np.union1d(p_req, sV * np.geomspace(1e-3, 3.0, FIGURE_LOADS))
        sel = np.searchsorted(p_bar, p_req)
    t0 = time.perf_counter()
    A, u, K, law = {}, {}, {}, {}
    gaps, Q_cj, Q_em, C, gd = {}, {}, {}, {}, {}
    for name in FUDGES:
        f = None if name == "none" else name
        A[name] = np.atleast_1d(exact(ContactProblem(psd, E, p_bar, f)).contact_area)
        ms = MeanSeparation(psd, E, f, args.weighting)
        u[name] = np.atleast_1d(ms.mean_separation(p_bar))
        try:
            K[name] = np.atleast_1d(ms.stiffness(p_bar))
        except ValueError as e:
            raise ValueError(f"{_largest_load_flag(args)} reaches too far into full contact: {e}") from None
        law[name] = ms.small_load_law()
        # the gaps and leak rates (Q per unit pressure drop / viscosity) at the figure's loads for its model only
        on = p_bar if name == GAP_MODEL else p_req
        gd[name], Q_cj[name], Q_em[name] = _interface(psd, E, on, f, args)
        gaps[name] = np.atleast_1d(gd[name].mean)
    wall = time.perf_counter() - t0
    fig_data = (p_bar, A, u, K, gd[GAP_MODEL], Q_cj[GAP_MODEL], Q_em[GAP_MODEL])
    A, u, K = ({n: d[n][sel] for n in FUDGES} for d in (A, u, K))
    gaps, Q_cj, Q_em = ({n: d[n][sel] if n == GAP_MODEL else d[n] for n in FUDGES} for d in (gaps, Q_cj, Q_em))
    C = {n: 2.0 * K[n] / E for n in FUDGES}  # Barber: C (rho1 + rho2) = 2K/E*
    p_bar = p_req
    with np.errstate(over="ignore"):
        finite = all(np.all(np.isfinite(Q[n] * scale)) for Q in (Q_cj, Q_em) for n in FUDGES)
    if leak and not finite:
        raise ValueError(
            f"--viscosity {flow[0]:g} and --pressure-drop {flow[1]:g} give leak rates outside the floating-point "
            "range; rescale the units"
        )
    L, P = unit("length", units), unit("pressure", units)
    print(
        f"E* = {E:.6g} {P}, V(zeta_max) = {sV**2:.6e} {P}^2, sqrt(V) = {sV:.6e} {P}; "
        f"energy weighting {args.weighting!r}"
    )
    print(f"{'model':<6} {'u0 [' + L + ']':>13} {'beta':>11}   small-load law p_bar = beta E* exp(-u/u0)")
    for name in FUDGES:
        print(f"{name:<6} {law[name][0]:13.6e} {law[name][1]:11.5g}")
    if p_bar.size <= MAX_PRINTED:
        _print_table(p_bar, ratio, A, u, K, Q_cj, Q_em, scale if leak else None, units)
    print(f"{p_bar.size} load(s) x {len(FUDGES)} models in {wall * 1e3:.1f} ms")
    _make_parent(os.path.join(out, "surface.csv"), "--output")
    path = os.path.join(out, "surface.csv")
    meta = {
        "surface": desc.splitlines(),
        "E_star": E,
        "units": units,
        "weighting": args.weighting,
        "viscosity": flow[0],
        "pressure_drop": flow[1],
        "columns": (
            "A_*, u_*, K_*: contact area, mean separation, stiffness per fudge model; gap_mean: mean of the gap "
            "distribution P(u); "
            + ("Q_cj, Q_em: leak rate of a square seal (critical junction, effective medium) for the viscosity and "
               "pressure drop given; " if leak else "")
            + "C_rho: electrical conductance per area times (rho1 + rho2) = 2K/E* (Barber 2003); units in brackets"
        ),
    }  # fmt: skip
    with _atomic_open(os.path.join(out, "surface.json"), "w") as fh:  # metadata beside a plain CSV
        json.dump(meta, fh, indent=1)
        fh.write("\n")
    quantities = [("A", A, "-"), ("u", u, "length"), ("K", K, "stiffness"), ("gap_mean", gaps, "length")]
    if leak:
        quantities += [("Q_cj", {n: Q_cj[n] * scale for n in FUDGES}, "flow")]
        quantities += [("Q_em", {n: Q_em[n] * scale for n in FUDGES}, "flow")]
    quantities += [("C_rho", C, "1/length")]
    with _atomic_open(path, "w", newline="") as fh:
        cols = [col("p_bar", "pressure", units), col("p_bar_over_sqrtV", "-", units)]
        cols += [col(f"{c}_{n}", kind, units) for c, _, kind in quantities for n in FUDGES]
        fh.write(",".join(cols) + "\n")
        for j in range(ratio.size):
            vals = [p_bar[j], ratio[j]] + [d[n][j] for _, d, _ in quantities for n in FUDGES]
            fh.write(",".join(f"{v:.12g}" for v in vals) + "\n")
    fig = _figure(psd, sV, fig_data, sel, surf.source, units, (scale, flow) if leak else None)
    _save_figure(fig, os.path.join(out, "surface.png"), dpi=110)
    print(f"written {path} (metadata in surface.json) and surface.png")
    return 0


FIGURE_LOADS = 24
"""Fewer loads than this given as a list (--p-bar, --p-bar-ratio): the figure's curves are drawn over
p_bar/sqrt(V) = 1e-3..3 (and the loads) and the loads asked for marked on them."""

MAX_PRINTED = 12
"""Up to this many loads, the results are also printed as a table."""


def _print_table(p_bar, ratio, A, u, K, Q_cj, Q_em, scale, units):
    """A*, u, K (and the leak rates when a viscosity and pressure drop were given) per load and model, on stdout."""
    L, P, S = unit("length", units), unit("pressure", units), unit("stiffness", units)
    head = f"{'model':<6} {'A* [-]':>12} {'u [' + L + ']':>12} {'K [' + S + ']':>14}"
    if scale is not None:
        F = unit("flow", units)
        head += f" {'Q_cj [' + F + ']':>16} {'Q_em [' + F + ']':>16}"
    for j, pb in enumerate(p_bar):
        print(f"p_bar = {pb:.6g} {P} (p_bar/sqrt(V) = {ratio[j]:.4g}):")
        print(head)
        for n in FUDGES:
            line = f"{n:<6} {A[n][j]:12.6g} {u[n][j]:12.6g} {K[n][j]:14.6g}"
            if scale is not None:
                line += f" {Q_cj[n][j] * scale:16.6g} {Q_em[n][j] * scale:16.6g}"
            print(line)


def _interface(psd, E, p_bar, fudge, args):
    """Gap distribution, critical-junction and effective-medium leak rates (:mod:`persson_fp.analysis.interface`)."""
    from persson_fp.analysis.interface import gap_distribution, leak_rate
    from persson_fp.problems.contact import ContactProblem

    problem = ContactProblem(psd, E, p_bar, fudge)
    flow = dict(viscosity=1.0, pressure_drop=1.0)  # Q per unit pressure drop / viscosity: Q = (dp / eta) x this
    return (
        gap_distribution(problem, weighting=args.weighting),
        leak_rate(problem, method="critical-junction", weighting=args.weighting, **flow),
        leak_rate(problem, method="effective-medium", weighting=args.weighting, **flow),
    )


def _figure(psd, sV, data, sel, title, units="none", leak=None):
    """The six panels: spectrum, A*, load-separation, stiffness, gap distribution and leak rate.

    ``data`` = (p_bar, A, u, K, gaps, Q_cj, Q_em) on the figure's loads (Q per unit pressure drop / viscosity);
    ``sel`` the loads asked for (marked when they are a few: ``sel`` is an index array); ``leak`` = (scale,
    (viscosity, pressure drop)) draws Q itself, None draws Q eta / dp."""
    import matplotlib.pyplot as plt

    from persson_fp.plotting import plot_gap_pdf, plot_leak_rate

    p_bar, A, u, K, gaps, Q_cj, Q_em = data
    marked = not isinstance(sel, slice)
    ratio = p_bar / sV
    L, P, S = unit("length", units), unit("pressure", units), unit("stiffness", units)
    fig, ax = plt.subplots(2, 3, figsize=(14, 7.5), layout="constrained")
    q = np.geomspace(psd.q_l, psd.q_s, 400)
    ax[0, 0].loglog(q, psd.C(q), "k-")
    ax[0, 0].loglog(psd.q, psd.values, "k.", ms=3)
    ax[0, 0].set(
        xlabel=f"q  [{unit('wavenumber', units)}]",
        ylabel=f"C(q)  [{unit('psd', units)}]".replace("^4", "$^4$"),
        title=f"spectrum (rms slope {psd.rms_slope:.3g}, rms height {psd.rms_height:.3g} {L})",
    )
    for c, n in enumerate(FUDGES):
        ax[0, 1].loglog(ratio, A[n], label=n, color=f"C{c}")
        ax[1, 0].semilogy(u[n], p_bar, label=n, color=f"C{c}")
        ax[1, 1].loglog(p_bar, K[n], label=n, color=f"C{c}")
        if marked:  # the loads asked for
            mk = dict(color=f"C{c}", marker="o", ms=5, ls="none")
            ax[0, 1].plot(ratio[sel], A[n][sel], **mk)
            ax[1, 0].plot(u[n][sel], p_bar[sel], **mk)
            ax[1, 1].plot(p_bar[sel], K[n][sel], **mk)
    ax[0, 1].set(xlabel=r"$\bar p/\sqrt{V}$  [-]", ylabel="A*  [-]", title="contact area (eq:Area_Persson)")
    ax[1, 0].set(xlabel=f"mean separation u  [{L}]", ylabel=rf"$\bar p$  [{P}]", title="load-separation (Persson 2007)")
    ax[1, 1].set(xlabel=rf"$\bar p$  [{P}]", ylabel=f"K = -dp/du  [{S}]", title="normal stiffness")
    # what happens in the gaps, for one model: P(u) at up to four loads with the contact atom, and the leak rate
    si = units != "none"  # the plotting functions write a unit only where there is one
    plot_gap_pdf(
        gaps,
        loads=list(sel[:4]) if marked else None,
        ax=ax[0, 2],
        length_unit=L if si else None,
        pressure_unit=P if si else None,
    )
    ax[0, 2].set(xlabel=f"gap u  [{L}]", ylabel=f"P(u)  [1/{L}]")
    ax[0, 2].legend(fontsize=7)
    ax[0, 2].set_title(f"gap distribution P(u), {GAP_MODEL} (arrows: contact atom)", fontsize=9)
    scale = 1.0 if leak is None else leak[0]
    curves = {"critical junction": Q_cj * scale, "effective medium": Q_em * scale}
    plot_leak_rate(p_bar, curves, ax=ax[1, 2])
    if marked:
        for c, Q in enumerate(curves.values()):
            ok = Q[sel] > 0
            ax[1, 2].plot(p_bar[sel][ok], Q[sel][ok], color=f"C{c}", marker="o", ms=5, ls="none")
    if leak is None:
        ylabel = rf"Q $\eta/\Delta p$  [{unit('flow/(dp/eta)', units)}]"
        leak_title = f"leak rate per unit $\\Delta p/\\eta$, {GAP_MODEL} (ticks: sealed)"
    else:
        eta, dp = leak[1]
        ylabel = f"Q  [{unit('flow', units)}]"
        leak_title = rf"leak rate, $\eta$ = {eta:g} {unit('viscosity', units)}, $\Delta p$ = {dp:g} {P}, {GAP_MODEL}"
    ax[1, 2].set(xlabel=rf"$\bar p$  [{P}]", ylabel=ylabel.replace("^3", "$^3$"))
    ax[1, 2].set_title(leak_title, fontsize=9)
    for a in ax.flat:
        a.grid(lw=0.3, which="both")
    ax[0, 1].legend(fontsize=8)
    if marked:
        ax[0, 1].set_title("contact area (eq:Area_Persson; dots: the loads asked for)")
    fig.suptitle(title, fontsize=10)
    return fig
