"""Matplotlib figures used by the CLI, the notebooks and the benchmarks.

Only the CLI, benchmarks, notebooks and ``Solution.plot`` import this module;
the physics and the solvers never do.
"""

from __future__ import annotations

import numpy as np

from .exact import exact
from .problem import ContactProblem

__all__ = ["plot_exact_pdfs", "plot_solution", "plot_area_curve", "plot_error_vs_time"]


def _axes(ax, figsize=(6.4, 4.2)):
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax.figure, ax


def plot_exact_pdfs(problem: ContactProblem, zetas, ax=None, n_p: int = 400):
    """P0(p, zeta) of the image solution (``eq:P0_solution``) at several zeta, p in units of sqrt(V(zeta_max))."""
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


def plot_solution(sol, ax=None, stations=None):
    """Numerical P0 (markers) against the exact solution (lines) at the stations of ``sol``."""
    fig, ax = _axes(ax)
    scale = float(np.sqrt(sol.problem.V()))
    ref = sol.exact_on_grid()
    idx = range(sol.zeta.size) if stations is None else stations
    step = max(1, sol.p.size // 60)
    for i in idx:
        (line,) = ax.plot(sol.p / scale, ref[i, 0] * scale, lw=1.2, label=f"exact, ζ = {sol.zeta[i]:.4g}")
        ax.plot(sol.p[::step] / scale, sol.P0_all[i, 0, ::step] * scale, "o", ms=3, color=line.get_color(), mfc="none")
    err = sol.compare().final()
    ax.set_title(f"{sol.method}: L1 = {err['L1']:.2e}, |ΔA*| = {err['area_error']:.2e}, {sol.wall_time * 1e3:.1f} ms")
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
    ax.set_ylabel(r"$P_0\,\sqrt{V(\zeta_{max})}$")
    ax.legend(fontsize=8)
    return fig


def plot_area_curve(ratio, curves: dict, ax=None, asymptote=True):
    """A*(p_bar / sqrt(V)) for several models (seed Fig. 5(b)); ``curves`` maps a label to A* values."""
    fig, ax = _axes(ax)
    for label, A in curves.items():
        ax.plot(ratio, A, label=label)
    if asymptote:
        ax.plot(ratio, np.minimum(np.sqrt(2 / np.pi) * ratio, 1.0), "k:", lw=0.8, label="eq:Asymptote_1")
    ax.set_xscale("log")
    ax.set_xlabel(r"$\bar p/\sqrt{V}$")
    ax.set_ylabel(r"$A^*$")
    ax.legend(fontsize=8)
    return fig


def plot_error_vs_time(rows, ax=None, error_key="L1"):
    """Error (log) against wall time (log), one line per method; ``rows`` are dicts with method, time, error."""
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
