"""method="chebyshev" with a constant hardness (the strip between 0 and sigma_Y): against the strip series
:func:`persson_fp.exact`, the load balance F_el + sigma_Y A_pl = p_bar (the plastic area comes from the wall flux,
not from that balance), and spectral order in the degree."""

import numpy as np
import pytest

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])


@pytest.mark.parametrize("H", [0.04, 0.075, 0.2])
@pytest.mark.parametrize("tol", [1e-6, 1e-9])
def test_constant_hardness_against_the_strip_series(H, tol):
    pr = pf.ContactProblem.reference(hardness=H)
    sol = pf.solve(pr, method="chebyshev", tol=tol, zeta_out=[8.0, 40.0, PSD.zeta_max])
    c = sol.compare()
    est = sol.error_estimate
    for q in ("elastic_area", "plastic_area", "noncontact_area"):
        true = getattr(c, f"{q}_error")
        assert np.all(true <= np.maximum(est[q], 1e-12)), (q, true, est[q])
        assert np.all(est[q] <= tol)
    assert np.all(c.L1 <= np.maximum(est["L1"], 1e-12))
    # the areas balance, and A_pl from the wall flux meets the load balance F_el + sigma_Y A_pl = p_bar
    total = sol.elastic_area_all + sol.plastic_area_all + (1.0 - sol.contact_area_all)
    assert np.allclose(total, 1.0, rtol=0, atol=1e-15)
    balance = np.abs(sol.load_all - PB) / PB  # int p P0 dp + sigma_Y A_pl
    assert np.all(balance <= 10 * tol + 1e-11), balance
    assert sol.info["mass_balance_residual"] <= tol


@pytest.mark.filterwarnings("ignore:chebyshev. P0 has negative values")
def test_hardness_observed_order_is_spectral():
    pr = pf.ContactProblem.reference(hardness=0.075)
    ns = np.array([16, 20, 24, 28, 32])
    errs = [float(pf.solve(pr, method="chebyshev", n_p=int(n), V0_fraction=1e-2).compare().L1[0, 0]) for n in ns]
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert errs[-1] < 1e-5 and slope >= 4.0, (errs, slope)
