"""``Solution.from_output``: a Solution from one ``SolverOutput``, against the image solution of Persson's equation.

Oracle (``eq:P0_solution``, ``eq:Area_Persson``, written here, not taken from ``pf.exact``): the absorbed Gaussian
P0(p) = [phi((p - p_bar)/s) - phi((p + p_bar)/s)] / s, s = sqrt(V); its cell averages on [0, p_bar + 12 s] are
differences of its closed-form integral, so the Solution's contact area must be erf(p_bar / (s sqrt 2)) up to the
tail beyond the grid (< 1e-30 here) and round-off, and its load the first moment p_bar up to the midpoint rule's
error (about h^2 / (12 s) for cells of width h; allowed h^2 / (2 s)).  Bad output (NaN, negative P0) raises.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.special import erf, ndtr

import persson_fp as pf
from persson_fp.results.output import SolverOutput


def _image_cells(p_bar, s, n):
    edges = np.linspace(0.0, p_bar + 12.0 * s, n + 1)
    F = ndtr((edges - p_bar) / s) - ndtr((edges + p_bar) / s)  # an integral of P0 (the image subtracted)
    F = F - F[0]
    return edges, np.diff(F) / np.diff(edges)


@settings(max_examples=60, deadline=None)
@given(st.floats(0.05, 3.0), st.integers(200, 2000))
def test_areas_and_load_of_the_image_solution(ratio, n):
    pr = pf.ContactProblem.reference(p_bar_ratio=ratio)
    s, p_bar = float(np.sqrt(pr.V_max)), float(pr.p_bar[0])
    edges, P = _image_cells(p_bar, s, n)
    out = SolverOutput(p=0.5 * (edges[1:] + edges[:-1]), P0=P[None, None, :], weights=np.diff(edges), kind="cell")
    sol = pf.Solution.from_output(pr, out, method="oracle", zeta=pr.zeta_max, wall_time=0.0)
    A = erf(p_bar / (s * np.sqrt(2.0)))
    assert float(sol.contact_area[-1]) == pytest.approx(A, rel=1e-12, abs=1e-14)
    h = edges[1] - edges[0]
    assert float(np.ravel(sol.load)[-1]) == pytest.approx(p_bar, abs=h**2 / s * 0.5 + 1e-13)
    assert sol.info["checks"]["breaches"] == []
    assert sol.method == "oracle" and sol.wall_time == 0.0


@pytest.mark.parametrize(("bad", "error"), [(np.nan, pf.InstabilityError), (-1.0, pf.SolverError)])
def test_bad_output_raises(bad, error):
    pr = pf.ContactProblem.reference()
    s, p_bar = float(np.sqrt(pr.V_max)), float(pr.p_bar[0])
    edges, P = _image_cells(p_bar, s, 200)
    P[50] = bad
    out = SolverOutput(p=0.5 * (edges[1:] + edges[:-1]), P0=P[None, None, :], weights=np.diff(edges), kind="cell")
    with pytest.raises(error):
        pf.Solution.from_output(pr, out, method="oracle", zeta=pr.zeta_max, wall_time=0.0)
