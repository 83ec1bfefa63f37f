"""The BEM benchmark's own tools (benchmarks/_reynolds.py, _bem_stats.py, _bem_tamaas.compliance) against closed forms.

Reynolds flow div(g^3/(12 eta) grad p) = 0 between two reservoirs, periodic across (Lorenz & Persson, EPJE 31 (2010)
159): a uniform gap gives Q = g^3 dp / (12 eta) per unit width; strips along the flow add their conductances
(arithmetic mean), strips across it add their resistances (harmonic mean) — both exact for the harmonic-mean
finite-volume faces, so the tolerances are round-off.  None of these needs Tamaas or reynoldsflow.
"""

from __future__ import annotations

import csv
import os
import sys

import numpy as np
import pytest

BENCH = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "benchmarks")
if BENCH not in sys.path:
    sys.path.insert(0, BENCH)

from _bem_stats import gap_histogram, gap_statistics, histogram_cdf, ks_histograms  # noqa: E402
from _bem_tamaas import compliance, surface_from_modes  # noqa: E402
from _reynolds import flow, percolating_cells  # noqa: E402

DATA = os.path.join(os.path.dirname(BENCH), "data", "bem")
RTOL = 1e-11  # a direct sparse solve of a well-posed system: round-off times the condition number, far below this


@pytest.mark.parametrize("shape", [(8, 8), (16, 5), (3, 40)])
def test_uniform_gap_is_plane_poiseuille(shape):
    g0, eta, dp, L = 2.5e-3, 1.7, 3.0, 1.0
    out = flow(np.full(shape, g0), viscosity=eta, pressure_drop=dp, length=L)
    exact = g0**3 * dp / (12 * eta)  # per unit width, times width L over length L
    assert out["percolates"]
    assert out["Q"] == pytest.approx(exact, rel=RTOL)
    assert out["inflow"] == pytest.approx(out["outflow"], rel=RTOL)
    # the pressure falls linearly from dp at the inlet face to 0 at the outlet face
    x = (np.arange(shape[0]) + 0.5) / shape[0]
    np.testing.assert_allclose(out["pressure"], np.repeat((dp * (1 - x))[:, None], shape[1], 1), rtol=1e-10)


def test_strips_along_the_flow_add_conductances():
    n, k = 20, 7  # columns j < k have gap g1, the rest g2; the flow runs along axis 0
    g1, g2 = 1.0, 0.4
    g = np.full((n, n), g2)
    g[:, :k] = g1
    exact = (k / n * g1**3 + (1 - k / n) * g2**3) / 12  # arithmetic mean of the conductances
    assert flow(g)["Q"] == pytest.approx(exact, rel=RTOL)
    # the same strips across the flow direction when the flow runs along axis 1 of the transposed field
    assert flow(g.T, axis=1)["Q"] == pytest.approx(exact, rel=RTOL)


def test_strips_across_the_flow_add_resistances():
    n, k = 24, 9  # rows i < k have gap g1: two resistors in series
    g1, g2 = 1.0, 0.3
    g = np.full((n, n), g2)
    g[:k, :] = g1
    f = k / n
    exact = 1.0 / (12 * (f / g1**3 + (1 - f) / g2**3))  # harmonic mean of the conductances
    out = flow(g)
    assert out["Q"] == pytest.approx(exact, rel=RTOL)
    assert out["inflow"] == pytest.approx(out["outflow"], rel=RTOL)


def test_a_blocked_line_across_the_flow_seals():
    g = np.ones((16, 16))
    g[5, :] = 0.0  # contact all across: no path between the reservoirs
    out = flow(g)
    assert out["Q"] == 0.0 and not out["percolates"]
    assert not percolating_cells(g).any()
    g[5, 3] = 1e-3  # one open cell reopens a path, with a finite flow far below the open channel's
    out = flow(g)
    assert out["percolates"] and 0 < out["Q"] < 1e-3 / 12
    # ... which is the series resistance through that throat: not checked in closed form, but along y it is open
    assert flow(g, axis=1)["percolates"]


def test_isolated_pockets_change_nothing():
    rng = np.random.default_rng(3)
    g = rng.uniform(0.5, 1.5, (30, 30))
    g[10:20, 10:20] = 0.0
    g[13:17, 13:17] = rng.uniform(0.5, 1.5, (4, 4))  # a pocket fully enclosed by contact
    closed = g.copy()
    closed[13:17, 13:17] = 0.0
    a, b = flow(g), flow(closed)
    assert a["Q"] == pytest.approx(b["Q"], rel=RTOL)
    live = percolating_cells(g)
    assert not live[13:17, 13:17].any() and live[0].all()


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_fields_conserve_mass_and_scale(seed):
    rng = np.random.default_rng(seed)
    g = rng.lognormal(0.0, 0.5, (40, 40))  # conductances over ~3 decades: a direct solve keeps ~1e-13
    g[rng.random(g.shape) < 0.35] = 0.0
    out = flow(g, viscosity=2.0, pressure_drop=5.0)
    if not out["percolates"]:
        pytest.skip("this draw does not percolate")
    assert abs(out["inflow"] - out["outflow"]) <= 1e-11 * out["Q"]
    # Q is linear in dp / eta and cubic in the gap
    base = flow(g)["Q"]
    assert out["Q"] == pytest.approx(base * 5.0 / 2.0, rel=1e-11)
    assert flow(2 * g)["Q"] == pytest.approx(8 * base, rel=1e-11)
    # axis 1 of a field is axis 0 of its transpose
    assert flow(g, axis=1)["Q"] == pytest.approx(flow(g.T)["Q"], rel=1e-12)
    # each interior cell conserves mass: the discrete divergence of the face fluxes vanishes
    p = np.where(np.isnan(out["pressure"]), 0.0, out["pressure"])
    c = np.where(percolating_cells(g), g, 0.0) ** 3 / 24.0
    kx = np.where((c[1:] > 0) & (c[:-1] > 0), 2 * c[1:] * c[:-1] / np.maximum(c[1:] + c[:-1], 1e-300), 0)
    cy = np.roll(c, -1, 1)
    ky = np.where((c > 0) & (cy > 0), 2 * c * cy / np.maximum(c + cy, 1e-300), 0)
    fx = -kx * (p[1:] - p[:-1])
    fy = -ky * (np.roll(p, -1, 1) - p)
    div = fx[1:] - fx[:-1] + fy[1:-1] - np.roll(fy, 1, 1)[1:-1]
    assert np.max(np.abs(div)) <= 1e-11 * out["Q"]


def test_reynoldsflow_agrees_when_installed():
    pytest.importorskip("reynoldsflow")
    from _reynolds import flow_reynoldsflow

    rng = np.random.default_rng(5)
    g = rng.uniform(0, 1, (32, 32))
    g[g < 0.3] = 0
    for axis in (0, 1):
        assert flow_reynoldsflow(g, axis=axis)["Q"] == pytest.approx(flow(g, axis=axis)["Q"], rel=1e-9)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(gap=np.ones(5)),
        dict(gap=np.full((4, 4), np.nan)),
        dict(gap=np.ones((4, 4)), viscosity=0.0),
        dict(gap=np.ones((4, 4)), viscosity=np.inf),
        dict(gap=np.ones((4, 4)), pressure_drop=np.nan),
        dict(gap=np.ones((4, 4)), axis=2),
        dict(gap=np.ones((4, 4)), length=-1.0),
    ],
)
def test_flow_refuses_bad_input(kwargs):
    with pytest.raises(ValueError, match="gap|viscosity|pressure_drop|axis|length"):
        flow(**kwargs)


def test_gap_histogram_of_a_known_field():
    hrms, n = 0.2, 120
    edges = np.linspace(0, 8 * hrms, 61)
    centres = 0.5 * (edges[1:] + edges[:-1])
    g = np.zeros(n * n)
    g[: 60 * 200] = np.repeat(centres, 200)  # 200 cells per bin, the other 2400 cells in contact
    st = gap_statistics(g.reshape(n, n), hrms)
    A = 2400 / n**2
    assert st["contact_fraction"] == pytest.approx(A, rel=1e-15)
    np.testing.assert_allclose(st["density"], 200 / (n**2 * np.diff(edges)), rtol=1e-12)
    assert np.sum(st["density"] * np.diff(edges)) == pytest.approx(1 - A, rel=1e-12)
    assert st["mean_gap"] == pytest.approx(4 * hrms * (1 - A), rel=1e-12)  # uniform on [0, 8 hrms] over 1 - A
    with pytest.raises(ValueError, match="gap"):
        gap_histogram(-g.reshape(n, n) - 1, hrms)
    with pytest.raises(ValueError, match="hrms"):
        gap_histogram(g, 0.0)


def test_ks_of_uniform_against_triangular_is_a_quarter():
    edges = np.linspace(0, 1, 41)
    uniform = np.ones(40)
    triangular = (edges[1:] ** 2 - edges[:-1] ** 2) / np.diff(edges)  # density 2x, exact bin averages
    # sup |x - x^2| = 1/4 at x = 1/2, an edge
    assert ks_histograms(edges, uniform, triangular) == pytest.approx(0.25, rel=1e-13)
    np.testing.assert_allclose(histogram_cdf(edges, 3 * triangular), edges**2, atol=1e-15)
    with pytest.raises(ValueError, match="edges"):
        histogram_cdf(edges[:-1], uniform)
    with pytest.raises(ValueError, match="mass"):
        histogram_cdf(edges, 0 * uniform)


def test_half_space_compliance_of_one_mode():
    n, k, e_star = 64, 3, 2.0
    x = np.arange(n) / n
    p = np.cos(2 * np.pi * k * x)[:, None] * np.ones(n)[None, :]
    u = compliance(p, e_star=e_star)
    np.testing.assert_allclose(u, 2 * p / (e_star * 2 * np.pi * k), atol=1e-14)  # u_q = 2 p_q / (E* q)


def test_surface_from_modes_is_band_limited_and_has_the_shipped_rms():
    path = os.path.join(DATA, "surfaces", "surface_H0.8_seed1_modes.npz")
    h256, h512 = surface_from_modes(path, 256), surface_from_modes(path, 512)
    np.testing.assert_allclose(h512[::2, ::2], h256, atol=1e-15)
    with open(os.path.join(DATA, "leakage_H0.8.csv"), newline="") as fh:
        hrms = float(next(r for r in csv.DictReader(fh) if r["seed"] == "1")["hrms"])
    assert h512.std() == pytest.approx(hrms, rel=1e-12)
    with pytest.raises(ValueError, match="N must be"):
        surface_from_modes(path, 100)


# -- the committed regenerated BEM data and what the "Performance and accuracy" page quotes from them ----------------
RESULTS = os.path.join(BENCH, "results")
GENERATED = os.path.join(RESULTS, "bem_generated")


def _page():
    with open(os.path.join(os.path.dirname(BENCH), "docs", "performance.md"), encoding="utf8") as fh:
        return " ".join(fh.read().split())


def _results(name):
    with open(os.path.join(RESULTS, name), newline="") as fh:
        return list(csv.DictReader(fh))


def _sig(x, n=3):
    return f"{float(f'{x:.{n}g}'):g}"


@pytest.mark.skipif(not os.path.isdir(GENERATED), reason="no regenerated BEM data committed")
def test_regenerated_bem_data_reproduce_the_shipped_data_and_the_page_says_so():
    import re

    from _bem_generate import compare

    _, worst = compare(GENERATED)
    # the same solver on the same surfaces: the contact fields are identical; the flows and the adhesion loop agree
    # to their solvers' tolerances (direct sparse solves; the loop stops at max |d sigma| < 1e-9 w/rho)
    assert worst["contact_fraction"] == worst["mean_gap"] == worst["ks"] == 0.0
    assert worst["sealed_same"] and worst["leak"] < 1e-6 and worst["pull_off"] < 1e-8
    assert worst["mean_p_adhesion"] < 1e-8 and worst["fv_vs_reynoldsflow"] < 1e-6
    m = re.search(
        r"exactly in contact fraction, mean gap and gap histograms, to ([\d.e+-]+) in leak rate and to ([\d.e+-]+) "
        r"in pull-off; the two Reynolds solvers agree to ([\d.e+-]+)",
        _page(),
    )
    assert m, "the sentence on the regenerated BEM data is gone from docs/performance.md (update this test with it)"
    assert m.group(1) == f"{worst['leak']:.1e}" and m.group(3) == f"{worst['fv_vs_reynoldsflow']:.1e}"
    assert m.group(2) == f"{worst['pull_off']:.0e}"


def test_page_table_of_the_theory_against_bem_is_the_results_file():
    """The page's per-load table (WM17, nominal spectrum) is interface_vs_bem_{gaps,leakage}.csv, means over seeds."""
    import re

    gaps = [r for r in _results("interface_vs_bem_gaps.csv") if r["model"] == "WM17" and r["spectrum"] == "nominal"]
    leak = [r for r in _results("interface_vs_bem_leakage.csv") if r["model"] == "WM17" and r["spectrum"] == "nominal"]
    loads = sorted({float(r["pbar_norm"]) for r in gaps})

    def per_load(rows, f):
        out = []
        for p in loads:
            v = [f(r) for r in rows if float(r["pbar_norm"]) == p]
            v = [x for x in v if np.isfinite(x)]
            out.append(_sig(np.mean(v)))
        return out

    expect = {
        "gap distribution over the non-contact area: Kolmogorov–Smirnov distance": per_load(
            gaps, lambda r: float(r["ks"])
        ),
        "mean separation ū / BEM mean gap": per_load(
            gaps, lambda r: float(r["u_bar_theory"]) / float(r["mean_gap_bem"])
        ),
        "leak rate, effective medium / Reynolds flow on the BEM gaps": per_load(leak, lambda r: float(r["ratio_em"])),
        "leak rate, critical junction / Reynolds flow on the BEM gaps": per_load(leak, lambda r: float(r["ratio_cj"])),
    }
    text = _page()
    assert "| p̄/(E*ḡ) | " + " | ".join(f"{p:g}" for p in loads) + " |" in text
    for label, values in expect.items():
        m = re.search(re.escape(f"| {label} |") + r"((?: [^|]+ \|){" + str(len(loads)) + "})", text)
        assert m, f"table row {label!r} is gone from docs/performance.md"
        quoted = [_sig(float(v)) for v in m.group(1).strip(" |").split(" | ")]
        assert quoted == values, f"{label}: page {quoted}, results {values}"
