"""tol= on a named method: a tol below round-off is a ValueError, the budgets bound the refinement, and the methods
without tolerance control say so."""

import re

import pytest

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])


def test_budgets_are_respected_on_the_tol_path():
    gen = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: (1 + p / (2 * PB)) * PSD.dV_dzeta(z))
    with pytest.raises(ValueError, match="max_memory"):
        pf.solve(gen, method="fv", tol=1e-4, max_memory=1e4)
    with pytest.raises((pf.SolverError, ValueError), match="max_time") as err:
        pf.solve(gen, method="mol", tol=1e-7, max_time=0.3)
    # stopped by the budget: either the refinement, naming the caller's budget, or the march that ran into it,
    # naming where it stopped (short of zeta_max)
    msg = str(err.value)
    stop = re.search(r"max_time exceeded at zeta = (\S+) \(of (\S+)\)", msg)
    assert "max_time = 0.3 s" in msg or (stop is not None and float(stop.group(1)) < float(stop.group(2))), msg


@pytest.mark.parametrize("method", ["auto", "fv", "mol"])
@pytest.mark.parametrize("tol", [5e-324, 1e-16])
def test_tol_below_round_off_is_a_value_error(method, tol):
    """pf.solve(..., tol=5e-324) raised OverflowError (a resolution of inf cells); tol is now checked against
    [1e-15, 0.1] before any resolution is derived from it."""
    with pytest.raises(ValueError, match=r"tol must lie in \[1e-15, 0.1\]"):
        pf.solve(pf.ContactProblem.reference(), method, tol=tol)


@pytest.mark.parametrize(("method", "word"), [("monte-carlo", "n_walkers"), ("chapman-kolmogorov", "n_p and")])
def test_methods_without_tolerance_control_say_so(method, word):
    with pytest.raises(ValueError, match=f"no tolerance control.*{word}"):  # was TypeError "unknown option"
        pf.solve(pf.ContactProblem.reference(), method, tol=1e-3)
