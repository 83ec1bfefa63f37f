"""mol with a constant hardness (the strip): against the exact strip series, a plastic area never below 0, and a
drained or fully plastic strip that is no positivity breach."""

import numpy as np
import pytest

import persson_fp as pf

SIGMA = 1.5 * np.sqrt(0.0025)  # 1.5 sqrt(V(zeta_max)) of the reference problem


def _problem(fudge=None):
    return pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0]), hardness=SIGMA, fudge=fudge)


@pytest.mark.parametrize("variable", ["tau", "zeta"])
@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_mol_constant_hardness_against_the_strip_series(fudge, variable):
    """4th-order MOL at its default grid: measured 2.2e-7 .. 5.2e-7 in A_pl (from the load balance) and up to
    2.2e-6 in A_el (the first station, where the automatic grid is sized for L1 ~ 5e-6)."""
    sol = pf.solve(_problem(fudge), method="mol", variable=variable, rtol=1e-8, zeta_out=[4.0, 32.0, 128.0])
    c = sol.compare()
    assert np.max(c.plastic_area_error) < 1e-6 and np.max(c.elastic_area_error) < 5e-6


def test_mol_plastic_area_is_never_negative():
    pr = pf.ContactProblem.reference(hardness=0.3, fudge="YP08")
    sol = pf.solve(pr, method="mol", zeta_out=np.geomspace(1.5, 128.0, 12))
    assert np.min(sol.plastic_area) >= 0.0


def test_drained_strip_and_fully_plastic_are_no_positivity_breach():
    """A strip that has drained (peak ~1e-104) may dip below 0 by round-off: no SolverError (it once raised 'P0 dips
    to -2.1e-104 = -1.00x its peak'), and A_pl is the exact strip value.  (fv: fv/test_constant_hardness.py.)"""
    pr = pf.ContactProblem.reference(p_bar_ratio=0.02, hardness=0.005)
    ex = float(pf.exact(pr).plastic_area)
    sol = pf.solve(pr, method="mol")
    assert abs(float(sol.plastic_area_all[-1, 0]) - ex) < 1e-6
    pr = pf.ContactProblem.reference(hardness=0.026)  # sigma_Y just above p_bar: nearly all plastic
    assert abs(float(pf.solve(pr, method="mol").plastic_area_all[-1, 0]) - float(pf.exact(pr).plastic_area)) < 1e-6
