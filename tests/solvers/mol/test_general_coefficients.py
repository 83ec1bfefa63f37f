"""mol on general coefficients (the front-fixed engine's fluxes, integrated by scipy): a drift in V against Brownian
motion with drift, the march stopping once the PDF has drained, and tiny loads -- refused below fv's range, within
the estimate of the image solution above it."""

import warnings

import numpy as np
import pytest
from scipy.special import erf, log_ndtr, ndtr

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, 0.025
dV = PSD.dV_dzeta


def test_mol_drift_in_V_against_brownian_motion_with_drift():
    """B1 = m dV/dzeta, B2 = dV/dzeta: Brownian motion with drift m in V absorbed at 0, A*(V) =
    Phi((p_bar + m V)/sqrt V) - exp(-2 m p_bar) Phi((-p_bar + m V)/sqrt V).  m = -200 drains the PDF by zeta ~ 20:
    the march stops there (the later stations hold 0, below the closed form's 1e-10 by less than the estimate)."""
    m = -200.0
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=lambda p, z: m * dV(z) + 0.0 * p, B2=lambda p, z: dV(z) + 0.0 * p)
    zeta = np.array([2.0, 3.0, 5.0, 10.0, 30.0, 128.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # (an estimate above 1e-2 at zeta = 3 is warned about)
        sol = pf.solve(fp, method="mol", zeta_out=zeta)
    V = np.asarray(PSD.V(zeta))
    s = np.sqrt(V)
    exact = ndtr((PB + m * V) / s) - np.exp(-2.0 * m * PB + log_ndtr((-PB + m * V) / s))
    A = sol.contact_area_all[:, 0]
    assert np.all(np.abs(A - exact) <= sol.error_estimate["contact_area"][:, 0] + 1e-15)
    assert A[-1] == 0.0 and exact[-1] > 0.0  # drained: the stop was taken
    assert sol.info["nfev"] < 2000  # the march ends at the drain, not at zeta_max (measured 356 right-hand sides)


def _wide(p_bar):
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, B2=lambda p, z: 2.0 * dV(z) * np.ones_like(p))


@pytest.mark.parametrize("p_bar", [1e-12, 1e-300])
def test_mol_refuses_a_load_below_the_range_as_fv_does(p_bar):
    """fv's refusal (base.LOAD_RATIO_RANGE), now mol's too on the engine's path (before: 6e-13 error against an
    estimate of 1.2e-13 at 1e-12, and A* = 0 with an estimate of exactly 0 at 1e-300)."""
    for method in ("fv", "mol"):
        with pytest.raises(ValueError, match=r"is below 1e-10, where this method loses its relative accuracy"):
            pf.solve(_wide(p_bar), method=method)


@pytest.mark.parametrize("p_bar", [1e-9, 1e-6])
def test_mol_small_load_within_its_estimate_of_the_image_solution(p_bar):
    """B2 = 2 dV/dzeta: the image solution A* = erf(p_bar / sqrt(2 * 2 V_max)).  Before: 1.8e-10 error against an
    estimate of 1.3e-10 at p_bar = 1e-9 (atol absolute, 1e-8); now atol is relative to the load's mass."""
    sol = pf.solve(_wide(p_bar), method="mol")
    exact = erf(p_bar / np.sqrt(4.0 * REF.V_max))
    err = abs(float(sol.contact_area_all[-1, 0]) - exact)
    est = float(sol.error_estimate["contact_area"][-1, 0])
    assert err <= est
    assert est < 1e-2 * exact  # and the estimate is relative to the load, not to 1
