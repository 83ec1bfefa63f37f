"""Method "fv" with a constant hardness (the strip between 0 and sigma_Y) against the exact strip series: accuracy
and second order in the steps, the limit A_pl -> p_bar / sigma_Y, and a drained or fully plastic strip that is no
positivity breach."""

import numpy as np
import pytest

import persson_fp as pf

SIGMA = 1.5 * np.sqrt(0.0025)  # 1.5 sqrt(V(zeta_max)) of the reference problem


def _problem(fudge=None):
    return pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0]), hardness=SIGMA, fudge=fudge)


@pytest.mark.parametrize("linalg", ["dst", "banded"])
@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_fv_constant_hardness_against_the_strip_series(fudge, linalg):
    """TR-BDF2 is 2nd order in tau: 400 steps leave ~1.5-3e-7 in A_pl and A_el at zeta_max (measured, both models) and
    ~2.3e-6 at the first station (the graded steps are coarser there, relative to tau); the areas balance to
    round-off (conservative walls) and the load to the scheme's accuracy."""
    sol = pf.solve(_problem(fudge), method="fv", n_p=400, n_steps=400, linalg=linalg, zeta_out=[4.0, 32.0, 128.0])
    c = sol.compare()
    assert np.max(c.plastic_area_error[-1]) < 4e-7 and np.max(c.plastic_area_error) < 4e-6
    assert np.max(c.elastic_area_error[-1]) < 4e-7 and np.max(c.elastic_area_error) < 4e-6
    assert np.max(c.mass_balance) < 1e-12
    # (A_non is 1 - A_el - A_pl by definition; the independent check is the wall-flux balance above)
    assert np.max(np.abs(sol.load - sol.problem.p_bar) / sol.problem.p_bar) < 2e-6


def test_fv_constant_hardness_second_order_in_steps():
    """Halving the step quarters the A_pl error (fit of log error vs log steps within 0.1 of 2)."""
    pr = _problem()
    steps = np.array([100, 200, 400, 800])
    err = [np.max(pf.solve(pr, method="fv", n_p=400, n_steps=n).compare().plastic_area_error) for n in steps]
    slope = -np.polyfit(np.log(steps), np.log(err), 1)[0]
    assert abs(slope - 2.0) < 0.1


def test_fv_plastic_area_tends_to_load_over_hardness():
    """Far beyond sigma^2 the elastic area vanishes and A_pl -> p_bar / sigma (the paradox resolved)."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.5, H=0.8, q_l=1.0, q_r=2.0, q_s=1e4)
    pr = pf.ContactProblem(psd, p_bar=0.02, hardness=0.05)
    sol = pf.solve(pr, method="fv", n_p=200, n_steps=200)
    assert float(sol.elastic_area[-1]) < 1e-6
    assert float(sol.plastic_area[-1]) == pytest.approx(0.02 / 0.05, rel=1e-6)


def test_drained_strip_and_fully_plastic_are_no_positivity_breach():
    """A strip that has drained (peak ~1e-104) may dip below 0 by round-off: no SolverError (it once raised 'P0 dips
    to -2.1e-104 = -1.00x its peak'), and A_pl is the exact strip value.  (mol: mol/test_constant_hardness.py.)"""
    pr = pf.ContactProblem.reference(p_bar_ratio=0.02, hardness=0.005)
    ex = float(pf.exact(pr).plastic_area)
    sol = pf.solve(pr, method="fv")
    assert abs(float(sol.plastic_area_all[-1, 0]) - ex) < 1e-6
    pr = pf.ContactProblem.reference(hardness=0.026)  # sigma_Y just above p_bar: nearly all plastic
    assert abs(float(pf.solve(pr, method="fv").plastic_area_all[-1, 0]) - float(pf.exact(pr).plastic_area)) < 1e-6
