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


def _unit(unit: str | None) -> str:
    """`` [unit]`` for an axis label, or nothing when the unit is not known."""
    if unit is None:
        return ""
    if not isinstance(unit, str) or not unit.strip():
        raise ValueError(f"a unit must be a non-empty string or None, got {unit!r}")
    return f" [{unit.strip()}]"


def _load_label(p_bar: float, scale: float | None = None, pressure_unit: str | None = None) -> str:
    r"""Legend text of one load: :math:`\bar p` with its unit when known, and :math:`\bar p/\sqrt{V}` when ``scale``
    (:math:`\sqrt{V}`, pressure) is given.

    Parameters
    ----------
    p_bar : float, pressure
        The nominal pressure.
    scale : float, optional, pressure
        :math:`\sqrt{V(\zeta_{max})}`; adds the relative load.
    pressure_unit : str, optional
        The unit of ``p_bar`` (e.g. ``"Pa"``); None: the number alone.

    Returns
    -------
    str
        E.g. ``"p̄ = 1e+05 Pa (p̄/√V = 0.5)"`` or ``"p̄ = 0.01 (p̄/√V = 0.5)"``.

    Raises
    ------
    ValueError
        ``pressure_unit`` not None or a non-empty string.
    """
    unit = _unit(pressure_unit)[2:-1]
    text = f"p̄ = {float(p_bar):.3g}" + (f" {unit}" if unit else "")
    if scale is not None and scale > 0:
        text += f" (p̄/√V = {float(p_bar) / scale:.3g})"
    return text


def plot_solution(
    sol: Solution,
    ax: Axes | None = None,
    stations: Sequence[int] | None = None,
    loads: Sequence[int] | None = None,
    pressure_unit: str | None = None,
) -> Figure:
    r"""Numerical P0 (markers) against the exact solution (lines) at the stations of ``sol``, every load.

    One load: one curve per station, the title gives its error.  Several loads: one colour per load, at the last
    station (or at ``stations``, told apart by line style), each legend entry giving :math:`\bar p` (with
    ``pressure_unit``), :math:`\bar p/\sqrt{V}` and that load's L1 error at the last station drawn.  p is in units of
    :math:`\sqrt{V(\zeta_{max})}`, the same for all loads.  Without a closed form (a moving yield wall, general
    coefficients) the numerical P0 is drawn alone (lines with markers) and the errors are the solver's estimates
    (marked ≈).  The time in the title is ``sol.wall_time``, as :meth:`~persson_fp.Solution.summary` states it.

    Parameters
    ----------
    sol : Solution
        A numerical solution from :func:`persson_fp.solve`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; default a new figure.
    stations : sequence of int, optional
        Indices of the output stations to draw; default all with one load, the last with several.
    loads : sequence of int, optional
        Indices of the loads to draw; default all.
    pressure_unit : str, optional
        Unit of the problem's pressures for the legend (e.g. ``"Pa"``); None: numbers alone.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.

    Raises
    ------
    ValueError
        An index in ``stations`` or ``loads`` out of range, or ``pressure_unit`` not a non-empty string.
    """
    from matplotlib.lines import Line2D

    _unit(pressure_unit)
    n_z, n_l = sol.zeta.size, sol.problem.n_loads
    jdx = list(range(n_l)) if loads is None else [int(j) for j in loads]
    several = len(jdx) > 1
    idx = (list(range(n_z)) if not several else [n_z - 1]) if stations is None else [int(i) for i in stations]
    for name, ii, n in (("stations", idx, n_z), ("loads", jdx, n_l)):
        if not ii or any(not -n <= i < n for i in ii):
            raise ValueError(f"{name} must be indices in [0, {n - 1}], got {ii!r}")
    idx, jdx = [i % n_z for i in idx], [j % n_l for j in jdx]
    fig, ax = _axes(ax)
    scale = float(np.sqrt(sol.problem.V()))
    closed = sol.problem.has_closed_form
    ref = sol.exact_on_grid() if closed else None
    if closed:
        err = sol.compare()
        L1, dA, approx = err.L1, err.area_error, "= "
    elif sol.info.get("error_estimate") is not None:
        est = sol.error_estimate
        L1, dA, approx = np.reshape(est["L1"], (n_z, n_l)), np.reshape(est["contact_area"], (n_z, n_l)), "≈ "
    else:
        L1 = dA = None
        approx = "= "
    L1 = None if L1 is None else np.reshape(L1, (n_z, n_l))
    dA = None if dA is None else np.reshape(dA, (n_z, n_l))
    p_all = np.asarray(sol.p)
    styles = ["-", "--", ":", "-."]
    last = idx[-1]
    for c, j in enumerate(jdx):
        color = f"C{c % 10}"
        for s, i in enumerate(idx):
            p = p_all if p_all.ndim == 1 else p_all[i]  # a moving yield wall: a grid per station
            step = max(1, p.size // 60)
            if several:
                label = _load_label(sol.problem.p_bar[j], scale, pressure_unit) if i == last else None
                if label is not None and L1 is not None:
                    label += f": L1 {approx}{L1[i, j]:.2e}"
                ls = styles[(len(idx) - 1 - s) % len(styles)]
            else:
                label, color, ls = f"ζ = {sol.zeta[i]:.4g}", None, "-"
            curve = ref[i, j] if closed else sol.P0_all[i, j]
            (line,) = ax.plot(p / scale, curve * scale, lw=1.2 if closed else 0.8, ls=ls, color=color, label=label)
            ax.plot(p[::step] / scale, sol.P0_all[i, j, ::step] * scale, "o", ms=3, color=line.get_color(), mfc="none")
    handles, _ = ax.get_legend_handles_labels()
    key = [Line2D([], [], color="0.3", marker="o", ls="none", mfc="none", ms=4, label=f"{sol.method} (markers)")]
    if closed:
        key.append(Line2D([], [], color="0.3", lw=1.2, label="exact (lines)"))
    if several and len(idx) > 1:
        key += [
            Line2D([], [], color="0.3", ls=styles[(len(idx) - 1 - s) % len(styles)], label=f"ζ = {sol.zeta[i]:.4g}")
            for s, i in enumerate(idx)
        ]
    wall = f"wall time {sol.wall_time * 1e3:.2f} ms"
    if L1 is None:
        title = f"{sol.method}: {wall}\nno closed form, no error estimate"
    elif several:
        what = "L1 error" if closed else "L1 error estimate (no closed form)"
        title = f"{sol.method}: {wall}\n{len(jdx)} loads at ζ = {sol.zeta[last]:.4g}, {what} per load in the legend"
    else:
        j = jdx[0]
        title = (
            f"{sol.method}: L1 {approx}{L1[last, j]:.2e}, |ΔA*| {approx}{dA[last, j]:.2e} at ζ = {sol.zeta[last]:.4g}"
            f", {wall}"
        )
        if not closed:
            title += "\nno closed form: the errors are the solver's estimates"
        if n_l > 1 or pressure_unit is not None:
            title += "\n" + _load_label(sol.problem.p_bar[j], scale, pressure_unit)
    # the axis ends where every curve has fallen below 1e-3 of its own peak (the far grid is empty)
    reach = [
        float(np.max(x[y > 1e-3 * np.max(y)], initial=0.0))
        for x, y in ((np.asarray(ln.get_xdata()), np.asarray(ln.get_ydata())) for ln in ax.get_lines())
    ]
    right = float(np.max([np.max(line.get_xdata()) for line in ax.get_lines()]))
    ax.set_xlim(left=min(0.0, ax.get_xlim()[0]), right=min(right, 1.05 * max(reach)) or None)
    ax.set_title(title, fontsize=9)
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


def plot_psd(
    psds: Mapping,
    ax: Axes | None = None,
    n_q: int = 400,
    mark_cutoffs: bool = True,
    length_unit: str | None = None,
) -> Figure:
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
    length_unit : str, optional
        Unit of length of the spectra (e.g. ``"m"``: q in rad/m, C in m^4) for the axis labels; None: no unit.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn on.
    """
    lu = _unit(length_unit)
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
    unit = length_unit.strip() if lu else None
    ax.set_xlabel("wavenumber q" + (f" [rad/{unit}]" if unit else ""))
    ax.set_ylabel(r"$C(q)$" + (f" [{unit}$^4$]" if unit else ""))
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


def plot_gap_pdf(
    gaps,
    loads: Sequence[int] | None = None,
    ax: Axes | None = None,
    n_u: int = 400,
    length_unit: str | None = None,
    pressure_unit: str | None = None,
) -> Figure:
    r"""The gap distribution P(u) (Almqvist et al., JMPS 59 (2011) 2355) at a few loads, the contact atom
    :math:`A(\zeta_{max})\delta(u)` at u = 0 drawn as an arrow whose length is its weight times the largest P(u).

    The atoms all sit at u = 0: their arrows are drawn side by side just left of it (in the legend's order), their
    weights written in a column further left at the arrows' heights (pushed apart where they would overlap) and
    in the legend entry of their load.

    Parameters
    ----------
    gaps : GapDistribution
        From :func:`persson_fp.gap_distribution`.
    loads : sequence of int, optional
        Indices of the loads to draw (default: up to four, spread over the loads).
    ax : matplotlib.axes.Axes, optional
    n_u : int
        Points in u, from 0 to the largest mean gap plus four standard deviations.
    length_unit, pressure_unit : str, optional
        Units of the gaps and of the loads (e.g. ``"m"``, ``"Pa"``) for the axis labels and the legend; None:
        no unit written.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        A unit not None or a non-empty string.
    """
    lu = _unit(length_unit)
    _unit(pressure_unit)
    fig, ax = _axes(ax)
    n = gaps.n_loads
    idx = list(loads) if loads is not None else sorted({int(round(k)) for k in np.linspace(0, n - 1, min(n, 4))})
    mean, std = np.atleast_1d(gaps.mean), np.atleast_1d(gaps.std)
    u = np.linspace(0.0, float(np.max(mean[idx] + 4.0 * std[idx])) or 1.0, n_u)
    pdf = np.asarray(gaps.pdf(u)).reshape(n, n_u)
    atom = np.atleast_1d(gaps.contact_fraction)
    p_bar = np.atleast_1d(gaps.p_bar)
    peak = float(np.max(pdf[idx])) or 1.0
    for c, k in enumerate(idx):
        label = _load_label(p_bar[k], None, pressure_unit) + f": contact atom A = {atom[k]:.3g}"
        ax.plot(u, pdf[k], color=f"C{c % 10}", label=label)
    # the atoms all sit at u = 0: arrows side by side just left of it (legend order), their weights written in a
    # column further left, each at its arrow's height or pushed up to clear the one below (they smeared when
    # written beside arrows of equal height)
    gap = 0.012 * float(u[-1])
    drawn = [(c, k) for c, k in enumerate(idx) if atom[k] > 0]
    tops = {k: max(atom[k], 0.05) * peak for _, k in drawn}
    y_text, below = {}, -np.inf
    for _, k in sorted(drawn, key=lambda ck: tops[ck[1]]):
        y_text[k] = below = max(tops[k], below + 0.075 * peak)
    x_col = -gap * (len(idx) + 1.5)
    for c, k in drawn:
        x = -gap * (len(idx) - c)
        plot_atom(ax, atom[k], tops[k], x=x, color=f"C{c % 10}", text=False)
        ax.annotate(f"{atom[k]:.3g}", (x_col, y_text[k]), ha="right", va="center", fontsize=7, color=f"C{c % 10}")
    if drawn:
        ax.set_xlim(left=x_col - 0.13 * float(u[-1]))
    ax.axvline(0.0, color="0.6", lw=0.6, ls=":")
    ax.set(xlabel="gap u" + lu, ylabel="P(u)" + (f" [1/{length_unit.strip()}]" if lu else ""))
    ax.set_title("gap distribution P(u); arrows: contact atom A at u = 0\n(side by side, length ∝ A)", fontsize=9)
    ax.legend(fontsize=7)
    return fig


def plot_leak_rate(
    p_bar: ArrayLike,
    curves: Mapping,
    ax: Axes | None = None,
    length_unit: str | None = None,
    pressure_unit: str | None = None,
    time_unit: str | None = None,
) -> Figure:
    """Leak rate Q against the nominal pressure (Lorenz & Persson 2009, 2010), log-log; loads where a curve is 0
    (the seal closed) are marked on the bottom axis.

    Parameters
    ----------
    p_bar : array_like, pressure
        Loads.
    curves : mapping
        Label -> flow rates Q (length^3/time) at ``p_bar``.
    ax : matplotlib.axes.Axes, optional
    length_unit, pressure_unit, time_unit : str, optional
        Units for the axis labels (e.g. ``"m"``, ``"Pa"``, ``"s"``: Q in m^3/s for a viscosity in Pa s); None: no
        unit written (Q's unit is written when ``length_unit`` is given, per ``time_unit`` or per "time").

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        A unit not None or a non-empty string.
    """
    lu, pu, tu = _unit(length_unit), _unit(pressure_unit), _unit(time_unit)
    fig, ax = _axes(ax)
    p = np.asarray(p_bar, dtype=float)
    for c, (label, Q) in enumerate(curves.items()):
        Q = np.asarray(Q, dtype=float)
        open_ = Q > 0
        ax.loglog(p[open_], Q[open_], color=f"C{c}", label=label)
        if np.any(~open_):
            ax.plot(p[~open_], np.zeros(np.sum(~open_)), "|", color=f"C{c}", ms=8, transform=ax.get_xaxis_transform())
    q_unit = f" [{length_unit.strip()}$^3$/{time_unit.strip() if tu else 'time'}]" if lu else ""
    ax.set(xlabel=r"$\bar p$" + pu, ylabel="Q" + q_unit, title="leak rate (ticks: sealed)")
    ax.legend(fontsize=7)
    return fig
