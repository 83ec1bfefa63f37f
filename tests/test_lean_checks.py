"""The invariant checks' shortcuts (one element read directly, the undershoot weighed against the lowest peak first)
decide exactly as the full comparison per station and load."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.results.solution import Solution


def _solution(P, ratio, check=True):
    pr = pf.ContactProblem.reference(p_bar_ratio=ratio)
    p = np.linspace(0.0, 1.0, P.shape[-1])
    w = np.full(p.size, p[1])
    A = np.ones(P.shape[:-1])  # areas and loads given: only the positivity of P is under test
    load = np.broadcast_to(pr.p_bar, A.shape)
    return Solution.build("test", pr, [pr.zeta_max], p, P, w, "point", 0.0, contact_area=A, load=load, check=check)


@pytest.mark.parametrize(
    ("dips", "breach"),
    [
        ((-0.005, -0.0005), False),  # both within 1 % of their own peak
        ((-0.005, -0.002), True),  # the second load dips 2 % of its (small) peak: a breach
        ((0.0, -0.002), True),
        ((-0.02, 0.0), True),
    ],
)
def test_positivity_per_load_against_its_own_peak(dips, breach):
    P = np.zeros((1, 2, 50))
    P[0, 0, 20], P[0, 1, 20] = 1.0, 0.1  # peaks 1 and 0.1
    P[0, 0, 5], P[0, 1, 5] = dips
    with pytest.warns(RuntimeWarning):
        sol = _solution(P, [0.5, 1.0], check=False)
    assert ("positivity" in sol.info["checks"]["breaches"]) == breach
    assert sol.info["checks"]["negative_P0"] == (min(dips) < 0)


def test_one_element_shortcuts_find_a_breach():
    P = np.zeros((1, 1, 50))
    P[0, 0, 20] = 1.0
    sol = _solution(P, 0.5)
    assert sol.info["checks"]["breaches"] == [] and not sol.info["checks"]["negative_P0"]
    P[0, 0, 3] = -0.5
    with pytest.raises(pf.SolverError, match="positivity"):
        _solution(P, 0.5)


def test_round_off_dips_of_one_row_are_bounded_not_weighed():
    """A one-load, one-station sines result dips to ~-2e-15 (round-off of a 4.45 peak): the shortcut reports no
    undershoot and bounds the negative mass from above by -min(P0) x the grid's width (the exact integral is
    computed by the general path, here by hand)."""
    from persson_fp.results.invariants import check_invariants

    sol = pf.solve(pf.ContactProblem.reference(), "sines")
    P = sol.P0_all
    assert P.size == P.shape[-1]
    checks = check_invariants(sol)
    assert checks["negative_P0"] is False and checks["breaches"] == []
    exact_negative_mass = float(np.sum(np.maximum(-P[0, 0], 0.0) * sol.weights))
    assert exact_negative_mass <= checks["negative_mass"] <= -P.min() * float(np.sum(sol.weights)) + 1e-300
