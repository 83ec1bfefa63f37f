"""The fast path of a ``pf.solve(..., "sines")`` call gives what the general path gives and keeps every check: the
series evaluated on its quadrature grid equals the readable series, options passed are validated (those left at
their defaults are the class defaults, not re-validated), and the whole call records its checks and its true
error."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.sines import series_area, series_pdf


def test_fast_path_equals_readable_series_and_areas():
    pr = pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=[0.3, 1.0])
    sol = pf.solve(pr, "sines", zeta_out=[2.0, 128.0])
    L, N = sol.info["p_max"], sol.info["n_modes"]
    for i in range(2):
        for j, pb in enumerate(pr.p_bar):
            tau = sol.info["tau"][i, j]
            ref = series_pdf(sol.p, L, pb, tau, N)
            np.testing.assert_allclose(sol.P0[i, j], ref, rtol=0, atol=1e-11 * ref.max())
            # area from the series = quadrature of P0 on the Gauss-Legendre grid
            assert abs(series_area(L, pb, tau, N) - sol.contact_area[i, j]) < 1e-13
            assert abs(sol.weights @ sol.P0[i, j] - sol.contact_area[i, j]) < 1e-12


@pytest.mark.parametrize(
    ("option", "value"),
    [("tol", 0.5), ("tol", -1.0), ("tol", float("nan")), ("rtol", 1.0), ("k_domain", 2.0), ("k_domain", True)],
)
def test_sines_options_passed_are_still_validated(option, value):
    with pytest.raises(ValueError, match=option):
        pf.solve(pf.ContactProblem.reference(), "sines", **{option: value})


def test_sines_options_at_their_defaults_are_the_class_defaults():
    from persson_fp.solvers.sines import SineSeriesSolver

    sv = SineSeriesSolver(pf.ContactProblem.reference(), tol=1e-10)
    assert sv.given == {"tol"}
    assert sv.opts["tol"] == 1e-10 and sv.opts["rtol"] == SineSeriesSolver.OPTIONS["rtol"]


def test_whole_sines_call_checks_and_estimates():
    """The one-load call still records its checks and has the true error at hand (sol.error_estimate)."""
    sol = pf.solve(pf.ContactProblem.reference(), "sines")
    assert sol.info["checks"]["breaches"] == []
    est = sol.error_estimate
    assert est["kind"].startswith("true error") and float(np.max(est["L1"])) < 1e-12
