"""Regressions of method "chebyshev" found by fuzzing: a load next to a constant hardness, a fixed degree asked for a
tol it cannot meet, and a drift so large that no far wall holds the PDF (refused naming B1, not B2)."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp import SolverError

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])


@pytest.mark.parametrize("gap", [1e-10, 1e-6, 1e-3])
def test_load_next_to_the_hardness_gives_the_exact_answer(gap):
    # sigma_Y a hair above p_bar: the wall absorbs nearly all of the load before the start V0, and the start's mass
    # check knew nothing of the mass above the wall (it refused, blaming a drift); A_pl now counts that early loss
    pr = pf.ContactProblem(PSD, p_bar=0.03, hardness=0.03 + gap)
    ex = pf.exact(pr)
    sol = pf.solve(pr, method="chebyshev")
    tol = 1e-8  # the default
    for q in ("contact_area", "plastic_area", "elastic_area", "noncontact_area"):
        got, want = float(np.ravel(getattr(sol, q))[-1]), float(np.ravel(getattr(ex, q))[-1])
        assert abs(got - want) <= tol, (q, got, want)


@pytest.mark.filterwarnings("ignore:chebyshev. P0 has negative values")
def test_fixed_degree_that_cannot_meet_the_tol_asked_is_refused():
    # n_p = 20 on the reference problem: estimate ~4e-2 (true error ~3e-3) -- returned silently before
    with pytest.raises(SolverError, match=r"n_p = 20 cannot meet tol = 1e-06"):
        pf.solve(REF, method="chebyshev", n_p=20, tol=1e-6)
    # a fixed degree that meets the tol asked is returned, its estimate within it
    sol = pf.solve(REF, method="chebyshev", n_p=120, tol=1e-6)
    est = sol.info["error_estimate"]
    assert max(float(np.max(est[q])) for q in ("L1", "elastic_area")) <= 1e-6
    assert abs(float(np.ravel(sol.contact_area)[-1]) - float(pf.exact(REF).contact_area)) <= 1e-6
    # without tol, a fixed degree still returns its result and its estimate (no tol was asked)
    sol = pf.solve(REF, method="chebyshev", n_p=20)
    assert float(np.max(sol.info["error_estimate"]["L1"])) > 1e-6


def test_huge_drift_is_blamed_on_b1():
    pr = pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=lambda p, z: np.full(np.shape(p), 1e300))
    with pytest.raises(ValueError, match=r"B1 \(the drift\) is so large") as err:
        pf.solve(pr, method="chebyshev")
    assert "B2 grows" not in str(err.value)
