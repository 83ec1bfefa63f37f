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

from persson_fp.cli._io import _atomic_open, _count, _make_parent, _note_replaced, _save_figure
from persson_fp.cli._problem import FUDGES

_SERIES = "q/π × 2D PSD"

GAP_MODEL = "WM17"
"""The fudge model of the figure's gap panels (with YP08 the closer to boundary-element gap histograms,
benchmarks/results/interface_vs_bem.md)."""

MAX_LOADS = 100_000
"""Largest ``surface --n-loads`` (four models, each load a quadrature of ~400 nodes: ~5 s at the cap)."""


def add_parser(sub):
    s = sub.add_parser("surface", help="measured surface -> A*, mean separation, stiffness (CSV + PNG)")
    s.add_argument("file", help="height map (.npy, or text: whitespace/comma separated) or contact.engineering CSV")
    s.add_argument("--size", type=float, nargs="+", default=None, help="physical size Lx [Ly] of a height map, length")
    s.add_argument("--periodic", action="store_true", help="the height map is periodic (no detrending, no window)")
    s.add_argument(
        "--trust-units",
        action="store_true",
        help="accept an rms slope outside 1e-6..10 (otherwise taken as heights and --size in different units)",
    )
    s.add_argument("--series", default=_SERIES, help=f"contact.engineering series (default {_SERIES!r})")
    s.add_argument("--H", type=float, default=None, help="1-D PSD series: Abel factor of this H (default: numerical)")
    s.add_argument("--E-star", type=float, default=1.0, help="plane-strain modulus E/(1-nu^2), pressure (default 1)")
    s.add_argument("--ratio-min", type=float, default=1e-3, help="smallest p_bar/sqrt(V) (default 1e-3)")
    s.add_argument("--ratio-max", type=float, default=3.0, help="largest p_bar/sqrt(V) (default 3)")
    s.add_argument(
        "--n-loads", type=_count, default=60, help=f"number of loads, log-spaced (default 60, at most {MAX_LOADS})"
    )
    s.add_argument(
        "--weighting",
        default="yang-persson",
        choices=["yang-persson", "corrected-area"],
        help="energy weighting of the fudge models (default yang-persson, the closer to BEM mean gaps)",
    )
    s.add_argument(
        "--viscosity", type=float, default=1.0, help="fluid viscosity for the leak rate, pressure x time (default 1)"
    )
    s.add_argument(
        "--pressure-drop", type=float, default=1.0, help="pressure drop across the seal, pressure (default 1)"
    )
    s.add_argument("--output", default="persson-fp-surface", help="folder for surface.csv / surface.png")
    s.set_defaults(func=cmd_surface)
    return s


def _read(args):
    from persson_fp._validate import as_file_path
    from persson_fp.surfaces.readers import read_contact_engineering_csv, read_heightmap

    path = as_file_path(args.file, "file")
    with open(path, "rb") as fh:
        head = fh.read(4096)
    if not path.endswith(".npy") and b"Data series" in head and b";" in head:
        return read_contact_engineering_csv(path, series=args.series, H=args.H)
    if args.size is None:
        raise ValueError("--size Lx [Ly] (physical size of the height map) is required for a height map")
    if args.H is not None or args.series != _SERIES:
        print("note: --H and --series apply to contact.engineering CSV files only; ignored for a height map")
    size = args.size[0] if len(args.size) == 1 else args.size
    try:
        return _check_units(read_heightmap(path, size, periodic=args.periodic), args)
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


def cmd_surface(args) -> int:
    import warnings

    from persson_fp.analysis.exact import exact
    from persson_fp.problems.contact import ContactProblem
    from persson_fp.theory.separation import MeanSeparation

    if not (0 < args.ratio_min < args.ratio_max) or not np.isfinite(args.ratio_max):
        raise ValueError("--ratio-min and --ratio-max must satisfy 0 < min < max (finite)")
    if not 2 <= args.n_loads <= MAX_LOADS:
        raise ValueError(f"--n-loads must lie in [2, {MAX_LOADS}], got {args.n_loads}")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        surf = _read(args)
    psd = surf.psd
    desc = surf.describe()
    print(desc)
    for w in caught:
        print(f"warning: {w.message}")
    E = args.E_star
    sV = float(np.sqrt(psd.V(E_star=E)))
    ratio = np.geomspace(args.ratio_min, args.ratio_max, args.n_loads)
    p_bar = ratio * sV
    if not (np.all(np.isfinite(p_bar)) and np.all(p_bar > 0)):
        raise ValueError(
            f"--E-star {E:g} with this surface gives sqrt(V) = {sV:.3g} and loads outside the floating-point range "
            "(p_bar = ratio x E* rms slope / 2); rescale the pressure unit (e.g. MPa)"
        )
    t0 = time.perf_counter()
    if not (np.isfinite(args.viscosity) and args.viscosity > 0):
        raise ValueError("--viscosity must be a finite number > 0 (pressure x time)")
    if not (np.isfinite(args.pressure_drop) and args.pressure_drop > 0):
        raise ValueError("--pressure-drop must be a finite number > 0 (pressure)")
    A, u, K, law = {}, {}, {}, {}
    gaps, Q_cj, Q_em, C, gd = {}, {}, {}, {}, {}
    with warnings.catch_warnings(record=True) as caught:  # printed as one line each
        warnings.simplefilter("always")
        for name in FUDGES:
            f = None if name == "none" else name
            A[name] = np.atleast_1d(exact(ContactProblem(psd, E, p_bar, f)).contact_area)
            ms = MeanSeparation(psd, E, f, args.weighting)
            u[name] = ms.mean_separation(p_bar)
            try:
                K[name] = ms.stiffness(p_bar)
            except ValueError as e:
                raise ValueError(f"--ratio-max {args.ratio_max:g} reaches too far into full contact: {e}") from None
            law[name] = ms.small_load_law()
            gd[name], Q_cj[name], Q_em[name] = _interface(psd, E, p_bar, f, args)
            gaps[name] = gd[name].mean
            C[name] = 2.0 * K[name] / E  # Barber: C (rho1 + rho2) = 2K/E*
    for w in {str(w.message): w for w in caught}.values():
        print(f"warning: {w.message}")
    wall = time.perf_counter() - t0
    print(f"E* = {E:.6g}, V(zeta_max) = {sV**2:.6e}, sqrt(V) = {sV:.6e}; energy weighting {args.weighting!r}")
    print(f"{'model':<6} {'u0 [length]':>13} {'beta':>11}   small-load law p_bar = beta E* exp(-u/u0)")
    for name in FUDGES:
        print(f"{name:<6} {law[name][0]:13.6e} {law[name][1]:11.5g}")
    print(f"{args.n_loads} loads x {len(FUDGES)} models in {wall * 1e3:.1f} ms")
    out = args.output
    _make_parent(os.path.join(out, "surface.csv"), "--output")
    _note_replaced(out, ["surface.csv", "surface.json", "surface.png"])
    path = os.path.join(out, "surface.csv")
    meta = {
        "surface": desc.splitlines(),
        "E_star": E,
        "weighting": args.weighting,
        "units": "p_bar in pressure, A dimensionless, u in length, K in pressure/length (the file's length unit)",
        "columns": (
            "A_*, u_*, K_*: contact area, mean separation, stiffness per fudge model; gap_mean: mean of the gap "
            "distribution P(u) (length); Q_cj, Q_em: leak rate of a square seal (critical junction, effective medium; "
            f"length^3/time) for viscosity {args.viscosity!r} and pressure drop {args.pressure_drop!r}; C_rho: "
            "electrical conductance per area times (rho1 + rho2) = 2K/E* (1/length; Barber 2003)"
        ),
    }
    with _atomic_open(os.path.join(out, "surface.json"), "w") as fh:  # metadata beside a plain CSV
        json.dump(meta, fh, indent=1)
        fh.write("\n")
    with _atomic_open(path, "w", newline="") as fh:
        cols = ["p_bar", "p_bar_over_sqrtV"]
        cols += [f"A_{n}" for n in FUDGES] + [f"u_{n}" for n in FUDGES] + [f"K_{n}" for n in FUDGES]
        cols += [f"{c}_{n}" for c in ("gap_mean", "Q_cj", "Q_em", "C_rho") for n in FUDGES]
        fh.write(",".join(cols) + "\n")
        for j in range(ratio.size):
            vals = [p_bar[j], ratio[j]] + [A[n][j] for n in FUDGES] + [u[n][j] for n in FUDGES]
            vals += [K[n][j] for n in FUDGES]
            vals += [d[n][j] for d in (gaps, Q_cj, Q_em, C) for n in FUDGES]
            fh.write(",".join(f"{v:.12g}" for v in vals) + "\n")
    fig = _figure(psd, ratio, p_bar, A, u, K, surf.source, gd[GAP_MODEL], Q_cj[GAP_MODEL], Q_em[GAP_MODEL])
    _save_figure(fig, os.path.join(out, "surface.png"), dpi=110)
    print(f"written {path} (metadata in surface.json) and surface.png")
    return 0


def _interface(psd, E, p_bar, fudge, args):
    """Gap distribution, critical-junction and effective-medium leak rates (:mod:`persson_fp.analysis.interface`)."""
    from persson_fp.analysis.interface import gap_distribution, leak_rate
    from persson_fp.problems.contact import ContactProblem

    problem = ContactProblem(psd, E, p_bar, fudge)
    flow = dict(viscosity=args.viscosity, pressure_drop=args.pressure_drop)
    return (
        gap_distribution(problem, weighting=args.weighting),
        leak_rate(problem, method="critical-junction", weighting=args.weighting, **flow),
        leak_rate(problem, method="effective-medium", weighting=args.weighting, **flow),
    )


def _figure(psd, ratio, p_bar, A, u, K, title, gaps, Q_cj, Q_em):
    import matplotlib.pyplot as plt

    from persson_fp.plotting import plot_gap_pdf, plot_leak_rate

    fig, ax = plt.subplots(2, 3, figsize=(14, 7.5), layout="constrained")
    q = np.geomspace(psd.q_l, psd.q_s, 400)
    ax[0, 0].loglog(q, psd.C(q), "k-")
    ax[0, 0].loglog(psd.q, psd.values, "k.", ms=3)
    ax[0, 0].set(
        xlabel="q  [rad/length]",
        ylabel="C(q)  [length$^4$]",
        title=f"spectrum (rms slope {psd.rms_slope:.3g}, rms height {psd.rms_height:.3g})",
    )
    for n in FUDGES:
        ax[0, 1].loglog(ratio, A[n], label=n)
        ax[1, 0].semilogy(u[n], p_bar, label=n)
        ax[1, 1].loglog(p_bar, K[n], label=n)
    ax[0, 1].set(xlabel=r"$\bar p/\sqrt{V}$", ylabel="A*", title="contact area (eq:Area_Persson)")
    ax[1, 0].set(
        xlabel="mean separation u  [length]", ylabel=r"$\bar p$  [pressure]", title="load-separation (Persson 2007)"
    )
    ax[1, 1].set(xlabel=r"$\bar p$  [pressure]", ylabel="K = -dp/du  [pressure/length]", title="normal stiffness")
    # what happens in the gaps, for one model: P(u) at four loads with the contact atom, and the leak rate
    plot_gap_pdf(gaps, ax=ax[0, 2])
    ax[0, 2].set_title(f"gap distribution P(u), {GAP_MODEL} (arrows: contact atom)", fontsize=9)
    plot_leak_rate(p_bar, {"critical junction": Q_cj, "effective medium": Q_em}, ax=ax[1, 2])
    ax[1, 2].set_title(f"leak rate of a square seal, {GAP_MODEL} (ticks: sealed)", fontsize=9)
    for a in ax.flat:
        a.grid(lw=0.3, which="both")
    ax[0, 1].legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    return fig
