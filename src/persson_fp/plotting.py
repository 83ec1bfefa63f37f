"""Matplotlib figures used by the CLI, the notebooks and the benchmarks.

Only the CLI, benchmarks, notebooks and ``Solution.plot`` import this module;
the physics and the solvers never do.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem

if TYPE_CHECKING:  # matplotlib is imported only when a figure is drawn
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from persson_fp.results.solution import Solution

__all__ = ["plot_exact_pdfs", "plot_solution", "plot_area_curve", "plot_error_vs_time"]


def _axes(ax, figsize=(6.4, 4.2)):
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax.figure, ax


def plot_exact_pdfs(problem: ContactProblem, zetas: ArrayLike, ax: Axes | None = None, n_p: int = 400) -> Figure:
    """P0(p, zeta) of the image solution (``eq:P0_solution``) at several zeta, p in units of sqrt(V(zeta_max)).

    Parameters
    ----------
    problem : ContactProblem
        The problem; its first load is drawn.
    zetas : array_like, dimensionless
        Magnifications in [1, zeta_max].
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    n_p : int
        Number of pressure points per curve.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    fig, ax = _axes(ax)
    zetas = np.atleast_1d(np.asarray(zetas, float))
    scale = float(np.sqrt(problem.V()))
    p = np.linspace(0.0, problem.p_bar[0] + 5.0 * scale, n_p)
    ex = exact(problem.with_loads(problem.p_bar[0]), zetas)
    P = np.atleast_2d(ex.pdf(p))
    A = np.atleast_1d(ex.contact_area)
    for z, Pz, Az in zip(zetas, P, A):
        ax.plot(p / scale, Pz * scale, label=f"ζ = {z:.4g}  (A* = {Az:.3f})")
    ax.axvline(problem.p_bar[0] / scale, color="0.6", lw=0.8, ls=":")
    top = float(np.max(P) * scale)
    for k, Az in enumerate(A):  # the atom 1 - A* at p = 0, drawn as an arrow whose length is its weight
        if 1.0 - Az > 1e-3:
            ax.annotate(
                "",
                xy=(0.0, (1.0 - Az) * top),
                xytext=(0.0, 0.0),
                arrowprops=dict(arrowstyle="-|>", color=f"C{k}", lw=1.5),
            )
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
    ax.set_ylabel(r"$P_0\,\sqrt{V(\zeta_{max})}$")
    ax.set_title(f"Exact P0 (fudge {problem.fudge.name}); arrows at p = 0: atom 1 − A* (length ∝ weight)", fontsize=10)
    ax.legend(fontsize=8)
    return fig


def plot_solution(sol: Solution, ax: Axes | None = None, stations: Sequence[int] | None = None) -> Figure:
    """Numerical P0 (markers) against the exact solution (lines) at the stations of ``sol``.

    Without a closed form (a moving yield wall, general coefficients) the numerical P0 is drawn alone (lines with
    markers) and the title gives the solver's error estimate instead of the error.

    Parameters
    ----------
    sol : Solution
        A numerical solution from :func:`persson_fp.solve`; its first load is drawn.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    stations : sequence of int, optional
        Indices of the output stations to draw; default all.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    from matplotlib.lines import Line2D

    fig, ax = _axes(ax)
    scale = float(np.sqrt(sol.problem.V()))
    closed = sol.problem.has_closed_form
    ref = sol.exact_on_grid() if closed else None
    idx = range(sol.zeta.size) if stations is None else stations
    p = np.asarray(sol.p) if np.ndim(sol.p) == 1 else np.asarray(sol.p)[0]  # a grid per load: the first one's
    step = max(1, p.size // 60)
    for i in idx:
        label = f"ζ = {sol.zeta[i]:.4g}"
        if closed:
            (line,) = ax.plot(p / scale, ref[i, 0] * scale, lw=1.2, label=label)
            ax.plot(p[::step] / scale, sol.P0_all[i, 0, ::step] * scale, "o", ms=3, color=line.get_color(), mfc="none")
        else:
            (line,) = ax.plot(p / scale, sol.P0_all[i, 0] * scale, lw=0.8, label=label)
            ax.plot(p[::step] / scale, sol.P0_all[i, 0, ::step] * scale, "o", ms=3, color=line.get_color(), mfc="none")
    handles, _ = ax.get_legend_handles_labels()
    key = [Line2D([], [], color="0.3", marker="o", ls="none", mfc="none", ms=4, label=f"{sol.method} (markers)")]
    if closed:
        key.append(Line2D([], [], color="0.3", lw=1.2, label="exact (lines)"))
        err = sol.compare().final()
        title = f"{sol.method}: L1 = {err['L1']:.2e}, |ΔA*| = {err['area_error']:.2e}, {sol.wall_time * 1e3:.1f} ms"
    elif sol.info.get("error_estimate") is not None:
        e = sol.error_estimate
        title = (
            f"{sol.method} (no closed form): L1 ≈ {float(np.max(e['L1'][-1])):.2e}, |ΔA*| ≈ "
            f"{float(np.max(e['contact_area'][-1])):.2e} (estimates), {sol.wall_time * 1e3:.1f} ms"
        )
    else:
        title = f"{sol.method} (no closed form, no error estimate), {sol.wall_time * 1e3:.1f} ms"
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
    ax.set_ylabel(r"$P_0\,\sqrt{V(\zeta_{max})}$")
    ax.legend(handles=handles + key, fontsize=8)
    return fig


def plot_area_curve(ratio: ArrayLike, curves: Mapping, ax: Axes | None = None, asymptote: bool = True) -> Figure:
    """A*(p_bar / sqrt(V)) for several models (Xu et al. tutorial, Fig. 5(b)).

    Parameters
    ----------
    ratio : array_like, dimensionless
        Loads p_bar / sqrt(V).
    curves : mapping
        Legend label -> A* at ``ratio``.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    asymptote : bool
        Also draw the small-load asymptote sqrt(2/pi) p_bar/sqrt(V) (``eq:Asymptote_1``), where it is below 1.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    fig, ax = _axes(ax)
    for label, A in curves.items():
        ax.plot(ratio, A, label=label)
    if asymptote:
        label = r"small-load asymptote $\sqrt{2/\pi}\,\bar p/\sqrt{V}$"
        small = np.sqrt(2 / np.pi) * np.asarray(ratio, dtype=float)
        # drawn only where it is below 1 (a straight line ending at A* = 1), not clipped onto a plateau at 1
        ax.plot(ratio, np.where(small <= 1.0, small, np.nan), "k:", lw=0.8, label=label)
    ax.set_xscale("log")
    ax.set_xlabel(r"$\bar p/\sqrt{V}$")
    ax.set_ylabel(r"$A^*$")
    ax.legend(fontsize=8)
    return fig


def plot_error_vs_time(rows: Sequence[Mapping], ax: Axes | None = None, error_key: str = "L1") -> Figure:
    """Error (log) against wall time (log), one line per method.

    Parameters
    ----------
    rows : sequence of mapping
        Runs, each with keys ``"method"``, ``"time"`` (s) and ``error_key``.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    error_key : str
        Key of the error to draw.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    fig, ax = _axes(ax)
    methods = sorted({r["method"] for r in rows})
    for m in methods:
        rr = sorted((r for r in rows if r["method"] == m), key=lambda r: r["time"])
        ax.loglog([r["time"] for r in rr], [r[error_key] for r in rr], "o-", ms=4, label=m)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel(f"{error_key} error of P0 at ζ_max")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", lw=0.3)
    return fig


# -- helpers for the notebooks ----------------------------------------------------------------------------------------
__all__ += ["plot_psd", "plot_pdf_histogram"]


def plot_psd(psds: Mapping, ax: Axes | None = None, n_q: int = 400, mark_cutoffs: bool = True) -> Figure:
    """C(q) on log-log axes (Xu et al. tutorial, Fig. A.1).

    A tabulated spectrum is drawn at its table points (markers) plus its log-log interpolant; the cut-offs
    q_l, q_s (and q_r where the PSD has one) of the first spectrum are marked by vertical lines.

    Parameters
    ----------
    psds : mapping
        Legend label -> spectrum (:class:`~persson_fp.SelfAffinePSD` or :class:`~persson_fp.TabulatedPSD`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    n_q : int
        Number of wavenumbers per curve.
    mark_cutoffs : bool
        Mark the cut-offs of the first spectrum.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    fig, ax = _axes(ax)
    for k, (label, psd) in enumerate(psds.items()):
        q = np.geomspace(psd.q_l, psd.q_s, n_q)
        (line,) = ax.loglog(q, psd.C(q), lw=1.2, label=label, color=f"C{k}")
        table_q = getattr(psd, "q", None)
        if table_q is not None:
            inside = (table_q >= psd.q_l) & (table_q <= psd.q_s)
            ax.loglog(table_q[inside], psd.values[inside], "o", ms=2.5, color=line.get_color())
    if mark_cutoffs and psds:
        first = next(iter(psds.values()))
        for name in ("q_l", "q_r", "q_s"):
            val = getattr(first, name, None)
            if val is not None:
                ax.axvline(val, color="0.6", lw=0.8, ls=":")
                ax.annotate(
                    name,
                    (val, 1.0),
                    xycoords=("data", "axes fraction"),
                    xytext=(2, -12),
                    textcoords="offset points",
                    fontsize=8,
                    color="0.4",
                )
    ax.set_xlabel("q [1/length]")
    ax.set_ylabel(r"$C(q)$ [length$^4$]")
    ax.legend(fontsize=8)
    return fig


def plot_pdf_histogram(
    bin_lo: ArrayLike,
    bin_hi: ArrayLike,
    density: ArrayLike,
    ax: Axes | None = None,
    scale: float = 1.0,
    label: str | None = None,
    **kwargs,
) -> Figure:
    """A pressure histogram (e.g. a boundary-element one) as a step line, p in units of ``scale``.

    Parameters
    ----------
    bin_lo, bin_hi : array_like, pressure
        Lower and upper edges of the bins (contiguous).
    density : array_like, 1/pressure
        Probability density per unit pressure, so that ``sum(density * (bin_hi - bin_lo))`` is the
        contact area; drawn as ``density * scale`` against ``p / scale``.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    scale : float, pressure
        Pressure unit of the drawing.
    label : str, optional
        Legend label.
    **kwargs
        Passed on to ``Axes.stairs``.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    fig, ax = _axes(ax)
    lo = np.asarray(bin_lo, float) / scale
    hi = np.asarray(bin_hi, float) / scale
    d = np.asarray(density, float) * scale
    edges = np.append(lo, hi[-1])
    ax.stairs(d, edges, label=label, **kwargs)
    return fig


# -- helpers for notebooks 01, 05, 07 ---------------------------------------------------------------------------------
__all__ += ["plot_atom", "plot_pdf_waterfall"]


def plot_atom(
    ax: Axes,
    weight: float,
    height: float,
    x: float = 0.0,
    color: str | None = None,
    label: str | None = None,
    text: bool = True,
    fontsize: int = 8,
) -> Figure:
    """A delta atom of probability ``weight`` at ``x`` drawn as an arrow of length ``height``, its weight written on it.

    The axes' data limits are extended to include the arrow.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes to draw on.
    weight : float, dimensionless
        Probability of the atom (e.g. 1 - A* at p = 0).
    height : float
        Arrow length in the axes' data units; choose it proportional to ``weight`` to make lengths
        comparable, e.g. ``weight * P0_peak``.
    x : float
        Position of the atom on the horizontal axis.
    color : str, optional
        Matplotlib colour; default "C0".
    label : str, optional
        Legend entry for the arrow.
    text : bool
        Write the weight next to the arrow head.
    fontsize : int
        Font size of that text.

    Returns
    -------
    matplotlib.figure.Figure
        The figure of ``ax``.
    """
    ax.annotate("", xy=(x, height), xytext=(x, 0.0), arrowprops=dict(arrowstyle="-|>", color=color or "C0", lw=1.6))
    if label is not None:  # a legend entry for the arrow
        ax.plot([], [], color=color or "C0", lw=1.6, marker="^", label=label)
    if text:
        ax.annotate(
            f"{weight:.3g}",
            (x, height),
            xytext=(3, 2),
            textcoords="offset points",
            fontsize=fontsize,
            color=color or "C0",
        )
    ax.update_datalim([(x, 0.0), (x, height)])
    ax.autoscale_view()
    return ax.figure


def plot_pdf_waterfall(
    problem: ContactProblem, zetas: ArrayLike, ax: Axes | None = None, n_p: int = 300, k: float = 4.0
) -> Figure:
    """The exact P0(p, zeta) as a 3-D waterfall over log10(zeta) (Xu et al. tutorial, Fig. 2(b)).

    p is drawn in units of sqrt(V(zeta_max)). The atom 1 - A* at p = 0 (``eq:PDF_piecewise_explicit``) is
    a vertical stem whose length is its weight times the largest P0 drawn; the delta(p - p_bar) of
    zeta = 1 (weight 1) is drawn the same way when ``zetas`` contains 1.

    Parameters
    ----------
    problem : ContactProblem
        The problem; its first load is drawn.
    zetas : array_like, dimensionless
        Magnifications in [1, zeta_max].
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D, optional
        3-D axes to draw on; default a new figure.
    n_p : int
        Number of pressure points per curve.
    k : float
        The pressure axis reaches p_bar + k sqrt(V(zeta_max)).

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        fig = plt.figure(figsize=(7.5, 5.0), layout="constrained")
        ax = fig.add_subplot(projection="3d")
    zetas = np.atleast_1d(np.asarray(zetas, float))
    pb = float(problem.p_bar[0])
    scale = float(np.sqrt(problem.V()))
    p = np.linspace(0.0, pb + k * scale, n_p)
    smooth = zetas[zetas > 1.0]
    ex = exact(problem.with_loads(pb), smooth)
    P = np.atleast_2d(ex.pdf(p)) * scale
    A = np.atleast_1d(ex.contact_area)
    top = float(np.max(P)) if P.size else 1.0
    for z, Pz, Az in zip(smooth, P, A):
        y = np.full_like(p, np.log10(z))
        ax.plot(p / scale, y, Pz, color="C3", lw=1.0)
        ax.plot([0.0, 0.0], [y[0], y[0]], [0.0, (1.0 - Az) * top], color="C0", lw=2.0)
        ax.scatter([0.0], [y[0]], [(1.0 - Az) * top], color="C0", marker="^", s=12)
    if np.any(zetas <= 1.0):
        ax.plot([pb / scale] * 2, [0.0, 0.0], [0.0, top], color="C3", lw=2.0)
        ax.scatter([pb / scale], [0.0], [top], color="C3", marker="^", s=12)
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
    ax.set_ylabel(r"$\log_{10}\zeta$")
    ax.set_zlabel(r"$P_0\,\sqrt{V(\zeta_{max})}$")
    ax.set_title("P0(p, ζ) (red) and the atom 1 − A* at p = 0 (blue, length = weight × max P0)", fontsize=9)
    return ax.figure


# -- what happens in the gaps -----------------------------------------------------------------------------------------
__all__ += ["plot_gap_pdf", "plot_leak_rate"]


def plot_gap_pdf(gaps, loads: Sequence[int] | None = None, ax: Axes | None = None, n_u: int = 400) -> Figure:
    r"""The gap distribution P(u) (Almqvist et al., JMPS 59 (2011) 2355) at a few loads, the contact atom
    :math:`A(\zeta_{max})\delta(u)` at u = 0 drawn as an arrow carrying its weight.

    Parameters
    ----------
    gaps : GapDistribution
        From :func:`persson_fp.gap_distribution`.
    loads : sequence of int, optional
        Indices of the loads to draw (default: up to four, spread over the loads).
    ax : matplotlib.axes.Axes, optional
    n_u : int
        Points in u, from 0 to the largest mean gap plus four standard deviations.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _axes(ax)
    n = gaps.n_loads
    idx = list(loads) if loads is not None else sorted({int(round(k)) for k in np.linspace(0, n - 1, min(n, 4))})
    mean, std = np.atleast_1d(gaps.mean), np.atleast_1d(gaps.std)
    u = np.linspace(0.0, float(np.max(mean[idx] + 4.0 * std[idx])) or 1.0, n_u)
    pdf = np.asarray(gaps.pdf(u)).reshape(n, n_u)
    atom = np.atleast_1d(gaps.contact_fraction)
    peak = float(np.max(pdf[idx])) or 1.0
    for c, k in enumerate(idx):
        col = f"C{c}"
        ax.plot(u, pdf[k], color=col, label=rf"$\bar p$ = {gaps.p_bar[k]:.3g}")
        if atom[k] > 0:
            plot_atom(ax, atom[k], max(atom[k], 0.05) * peak, color=col, text=True, fontsize=7)
    ax.set(xlabel="gap u  [length]", ylabel="P(u)  [1/length]", title="gap distribution (arrows: contact atom A)")
    ax.legend(fontsize=7)
    return fig


def plot_leak_rate(p_bar: ArrayLike, curves: Mapping, ax: Axes | None = None) -> Figure:
    """Leak rate Q against the nominal pressure (Lorenz & Persson 2009, 2010), log-log; loads where a curve is 0
    (the seal closed) are marked on the bottom axis.

    Parameters
    ----------
    p_bar : array_like, pressure
        Loads.
    curves : mapping
        Label -> flow rates Q (length^3/time) at ``p_bar``.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _axes(ax)
    p = np.asarray(p_bar, dtype=float)
    for c, (label, Q) in enumerate(curves.items()):
        Q = np.asarray(Q, dtype=float)
        open_ = Q > 0
        ax.loglog(p[open_], Q[open_], color=f"C{c}", label=label)
        if np.any(~open_):
            ax.plot(p[~open_], np.zeros(np.sum(~open_)), "|", color=f"C{c}", ms=8, transform=ax.get_xaxis_transform())
    ax.set(xlabel=r"$\bar p$  [pressure]", ylabel="Q  [length$^3$/time]", title="leak rate (ticks: sealed)")
    ax.legend(fontsize=7)
    return fig
