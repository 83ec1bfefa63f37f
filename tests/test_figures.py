"""What the figures show: every load of a solution with its own error, the gap panel's atoms apart and named, the
units given on the axes and in the legends (the drawn numbers against closed forms written here)."""

import re
import warnings

import numpy as np
import pytest
from scipy.special import erf

import persson_fp as pf
from persson_fp.plotting import plot_gap_pdf, plot_leak_rate, plot_psd

E = 1.0
SLOPE = 0.1
PSD = pf.SelfAffinePSD.from_rms_slope(SLOPE, 0.8, 2 * np.pi, 8 * np.pi, 128 * np.pi)
SQRT_V = E * SLOPE / 2  # V(zeta_max) = E*^2 <|grad h|^2> / 4 (Persson 2001), the full band's rms slope
RATIOS = (0.2, 0.6, 2.0)


@pytest.fixture(scope="module")
def three_loads():
    pr = pf.ContactProblem(PSD, E, [r * SQRT_V for r in RATIOS])
    return pr, pf.solve(pr, "fv", n_p=200)


def _labels(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_solution_plot_draws_every_load_with_its_own_error(three_loads):
    pr, sol = three_loads
    fig = sol.plot(pressure_unit="Pa")  # as `solve --plot` calls it, plus the unit the caller knows
    ax = fig.axes[0]
    labels = _labels(ax)
    L1 = sol.compare().L1[-1]
    assert len(set(np.round(np.log10(L1), 3))) > 1  # the loads' errors differ: one value per load is a real claim
    for j, (pb, r) in enumerate(zip(pr.p_bar, RATIOS)):
        entry = [t for t in labels if t.startswith(f"p̄ = {pb:.3g} Pa ")]
        assert len(entry) == 1, labels
        assert f"(p̄/√V = {r:.3g})" in entry[0] and f"L1 = {L1[j]:.2e}" in entry[0]
    # the lines are the exact P0 of each load (eq:P0_solution, here erf-normalised), x in p / sqrt(V)
    lines = [ln for ln in ax.get_lines() if ln.get_linestyle() == "-" and ln.get_label().startswith("p̄")]
    assert len(lines) == 3
    for line, pb in zip(lines, pr.p_bar):
        p = line.get_xdata() * SQRT_V
        ref = pf.exact(pr.with_loads(pb)).pdf(p) * SQRT_V
        # cell averages against point values: O(dp^2 P'') apart, dp = 0.05 sqrt(V) -> < 1 % of the peak
        assert np.max(np.abs(line.get_ydata() - ref)) < 0.01 * np.max(ref)
    # one time, the solution's own: the same number as summary()
    wall = re.search(r"wall=(\d+\.\d+) ms", sol.summary()).group(1)
    assert f"wall time {wall} ms" in ax.get_title()
    assert "worst" not in ax.get_title()


def test_solution_plot_without_a_unit_and_its_refusals(three_loads):
    pr, sol = three_loads
    labels = _labels(sol.plot().axes[0])  # the CLI's call: no unit known
    assert f"p̄ = {pr.p_bar[0]:.3g} (p̄/√V = {RATIOS[0]:.3g})" in labels[0]
    assert not any("[" in t for t in labels)
    one = _labels(sol.plot(loads=[1]).axes[0])
    assert sum(t.startswith("ζ =") for t in one) == sol.zeta.size  # one load: a curve per station
    for bad in ({"pressure_unit": ""}, {"pressure_unit": 3}, {"loads": [3]}, {"stations": [5]}, {"loads": []}):
        with pytest.raises(ValueError, match="unit|loads|stations"):
            sol.plot(**bad)


@pytest.fixture(scope="module")
def gaps():
    pr = pf.ContactProblem(PSD, E, SQRT_V * np.array([0.01, 0.1, 0.5, 2.0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pr, pf.gap_distribution(pr)


def test_gap_panel_names_each_atom_in_the_legend_and_draws_them_apart(gaps):
    pr, gd = gaps
    ax = plot_gap_pdf(gd, length_unit="m", pressure_unit="Pa").axes[0]
    labels = _labels(ax)
    A = erf(pr.p_bar / (np.sqrt(2) * SQRT_V))  # A* without a fudge factor (Persson 2001; eq:Area_Persson)
    for pb, a, t in zip(pr.p_bar, A, labels):
        assert t.startswith(f"p̄ = {pb:.3g} Pa")
        assert float(t.rsplit("A = ", 1)[1]) == pytest.approx(a, rel=2e-3)  # printed to 3 digits
    # one arrow per load, each at its own x left of u = 0; the weights written in a column left of them, each
    # clear of the next (they overlapped when written beside arrows of equal height at one u)
    arrows = [a for a in ax.texts if a.arrow_patch is not None]
    xs = [a.xy[0] for a in arrows]
    assert len(arrows) == 4 and len(set(xs)) == 4 and max(xs) < 0.0
    assert min(np.diff(sorted(xs))) > 0.005 * ax.get_xlim()[1]  # apart by more than a line width
    words = [t for t in ax.texts if t.get_text()]
    assert sorted(t.get_text() for t in words) == sorted(f"{a:.3g}" for a in gd.contact_fraction)
    fig = ax.figure
    fig.canvas.draw()
    boxes = [t.get_window_extent() for t in words]
    assert not any(b1.overlaps(b2) for i, b1 in enumerate(boxes) for b2 in boxes[i + 1 :])
    assert all(t.xy[0] < min(xs) for t in words)
    assert ax.get_xlabel() == "gap u [m]" and ax.get_ylabel() == "P(u) [1/m]"
    bare = plot_gap_pdf(gd).axes[0]
    assert bare.get_xlabel() == "gap u" and bare.get_ylabel() == "P(u)"
    assert not any("[" in t or "Pa" in t for t in _labels(bare))
    with pytest.raises(ValueError, match="unit"):
        plot_gap_pdf(gd, length_unit=" ")


def test_leak_rate_and_spectrum_axes_carry_the_units_given():
    ax = plot_leak_rate([1.0, 2.0], {"a": [1e-9, 0.0]}, length_unit="m", pressure_unit="Pa", time_unit="s").axes[0]
    assert ax.get_xlabel() == r"$\bar p$ [Pa]" and ax.get_ylabel() == "Q [m$^3$/s]"
    ax = plot_leak_rate([1.0, 2.0], {"a": [1e-9, 2e-9]}).axes[0]
    assert ax.get_xlabel() == r"$\bar p$" and ax.get_ylabel() == "Q"
    ax = plot_psd({"s": PSD}, length_unit="µm").axes[0]
    assert ax.get_xlabel() == "wavenumber q [rad/µm]" and ax.get_ylabel() == "$C(q)$ [µm$^4$]"
    assert "[" not in plot_psd({"s": PSD}).axes[0].get_xlabel()
