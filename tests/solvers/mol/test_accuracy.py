"""The method-of-lines solver against pf.exact: accuracy, orders in p, start-up, integrators, invariants."""

import numpy as np
import pytest

import persson_fp as pf


def _fit_order(n_p, errs):
    return -np.polyfit(np.log(np.asarray(n_p) - 1.0), np.log(errs), 1)[0]


def test_default_reaches_1e_5():
    sol = pf.solve(pf.ContactProblem.reference(), "mol")
    c = sol.compare().final()
    assert c["L1"] <= 1.5e-5
    assert sol.info["order"] == 4 and sol.info["integrator"] == "BDF"
    assert 1.0 < sol.info["zeta0"][0] < 3.0
    for key in ("grid", "nfev", "njev", "nlu", "integrator", "order", "zeta0"):
        assert key in sol.info


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_tight_resolution_1e_6(fudge):
    sol = pf.solve(pf.ContactProblem.reference(fudge=fudge), "mol", n_p=301, rtol=1e-8)
    c = sol.compare().final()
    assert c["L1"] <= 1e-6
    assert c["area_error"] <= 1e-7


@pytest.mark.parametrize(("order", "n_p"), [(2, [101, 201, 401]), (4, [61, 91, 121, 161])])
def test_convergence_order_in_p(order, n_p):
    pr = pf.ContactProblem.reference()
    errs = [pf.solve(pr, "mol", order=order, n_p=n, rtol=1e-10, tau0_fraction=0.1).compare().final()["L1"] for n in n_p]
    assert abs(_fit_order(n_p, errs) - order) < 0.3


def test_error_keeps_falling_below_1e8():
    """No plateau from the start-up or the far wall: mol order 4 refined to L1 < 1e-8."""
    pr = pf.ContactProblem.reference()
    errs = [pf.solve(pr, "mol", order=4, n_p=n, rtol=r).compare().final()["L1"] for n, r in ((300, 1e-9), (600, 1e-11))]
    assert errs[1] < errs[0] / 8  # still 4th-order-like between these two resolutions
    assert errs[1] < 1e-8


def test_delta_start_and_stiff_vs_explicit():
    pr = pf.ContactProblem.reference()
    d = pf.solve(pr, "mol", initial="delta", n_p=121)
    assert d.info["zeta0"][0] == 1.0 and d.compare().final()["L1"] < 1e-2
    nfev = {}
    for integ in ("BDF", "RK45"):
        for n in (81, 161):
            nfev[integ, n] = pf.solve(pr, "mol", n_p=n, integrator=integ, tau0_fraction=0.1).info["nfev"]
    assert nfev["RK45", 161] > 3.0 * nfev["RK45", 81]  # explicit cost ~ n_p^2 (stability, not accuracy)
    assert nfev["BDF", 161] < 1.6 * nfev["BDF", 81]
    assert nfev["RK45", 161] > 3.0 * nfev["BDF", 161]


@pytest.mark.parametrize("integrator", ["Radau", "LSODA"])
def test_other_stiff_integrators(integrator):
    sol = pf.solve(pf.ContactProblem.reference(fudge="YP08"), "mol", integrator=integrator)
    assert sol.compare().final()["L1"] < 2e-5


def test_invariants_and_conservation():
    pr = pf.ContactProblem.reference(fudge="WM17")
    z = np.geomspace(2.0, 128.0, 6)
    with pytest.warns(RuntimeWarning, match="negative"):
        sol = pf.solve(pr, "mol", zeta_out=z, n_p=161, rtol=1e-7)
    assert sol.info["checks"]["area_monotone"]
    # 4th-order differences are not positivity preserving: undershoots O(h^4), reported by Solution
    assert sol.info["checks"]["min_P0"] > -1e-6 * np.max(sol.P0)
    assert np.all(np.diff(sol.contact_area) < 0)
    # a uniform grid sized for zeta_max resolves the narrow early P0 less well: L1 ~ (h/sqrt(tau))^4
    L1 = sol.compare().L1[:, 0]
    assert L1[-1] < 3e-6 and np.all(L1[2:] < 2e-5) and L1[0] < 2e-3
    # second order + trapezoid: the first moment is conserved to round-off (absorbing walls)
    sol2 = pf.solve(pf.ContactProblem.reference(), "mol", order=2, n_p=201, zeta_out=z)
    assert sol2.info["checks"]["max_load_drift"] < 1e-10
