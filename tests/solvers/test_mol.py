"""The method-of-lines solver against pf.exact: accuracy, orders, Jacobian, batching, invariants."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.mol import MethodOfLinesSolver, laplacian, laplacian_readable, quadrature_weights


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


def test_laplacian_fast_equals_readable_and_is_exact_for_odd_polynomials(rng):
    for order in (2, 4):
        m, h = 17, 0.3
        P = rng.standard_normal((3, m))
        np.testing.assert_allclose(
            (laplacian(m, h, order) @ P.T).T, laplacian_readable(P, h, order), rtol=1e-13, atol=1e-10
        )
    # odd quintic about p = 0: the 4th-order stencil with odd ghosts is exact next to the wall
    h = 0.1
    p = h * np.arange(1, 9)
    f = p**5 - 3 * p**3 + p
    d2 = laplacian_readable(f[None, :], h, 4)[0]
    np.testing.assert_allclose(d2[:4], 20 * p[:4] ** 3 - 18 * p[:4], atol=1e-9)


def test_gregory_weights_fourth_order():
    errs = []
    n_p = [21, 41, 81]
    for n in n_p:
        p = np.linspace(0.0, 2.0, n)
        errs.append(abs(quadrature_weights(n, p[1], 4) @ np.sin(p) - (1 - np.cos(2.0))))
    assert _fit_order(n_p, errs) > 3.7


@pytest.mark.parametrize(("variable", "fudge"), [("tau", "YP08"), ("zeta", "YP08"), ("zeta", None), ("tau", None)])
def test_jacobian_equals_finite_differences(variable, fudge):
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=[0.3, 1.0])
    sysm = MethodOfLinesSolver(pr, n_p=24, variable=variable).system()
    t = sysm.t0 * 1.3
    y = sysm.y0 * (1.0 + 0.1 * np.sin(np.arange(sysm.y0.size)))
    f0 = sysm.fun_readable(t, y)
    np.testing.assert_allclose(sysm.fun(t, y), f0, rtol=1e-12, atol=1e-12 * np.max(np.abs(f0)))
    J = sysm.jac(t, y) if callable(sysm.jac) else sysm.jac
    J = J.toarray()
    Jfd = np.empty_like(J)
    for k in range(y.size):
        e = np.zeros_like(y)
        e[k] = 1e-6 * np.max(np.abs(y))
        Jfd[:, k] = (sysm.fun_readable(t, y + e) - sysm.fun_readable(t, y - e)) / (2 * e[k])
    np.testing.assert_allclose(J, Jfd, rtol=1e-6, atol=1e-7 * np.max(np.abs(J)))
    if fudge is not None:  # the nonlocal coupling is really there
        n = sysm.n_loads * sysm.m
        block = (
            J[n:, :n] if variable == "tau" else J[: sysm.m, : sysm.m] - np.triu(np.tril(J[: sysm.m, : sysm.m], 2), -2)
        )
        assert np.max(np.abs(block)) > 0


def _single_like_batch(pr_batch, j, sol_batch, **opts):
    """Single-load run on the batch's grid and with the batch's start-up tau0."""
    pb = pr_batch.p_bar[j]
    single = pr_batch.with_loads(pb)
    tau_max = float(single.tau(single.zeta_max)[0])
    k = (sol_batch.p[-1] - pb) / np.sqrt(tau_max)
    tau0 = sol_batch.info["t_span"][0]
    return pf.solve(single, "mol", k_domain=k, tau0_fraction=tau0 / tau_max, **opts)


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_batched_loads_equal_single_loads(fudge):
    ratios = np.geomspace(0.01, 3.0, 4)
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=ratios)
    opts = {"n_p": 81, "rtol": 1e-10, "zeta_out": [20.0, 128.0]}
    batch = pf.solve(pr, "mol", **opts)
    for j in range(pr.n_loads):
        single = _single_like_batch(pr, j, batch, **opts)
        np.testing.assert_allclose(single.p, batch.p, rtol=1e-13)
        np.testing.assert_allclose(batch.P0[:, j], single.P0, rtol=0, atol=1e-7 * single.P0.max())
        np.testing.assert_allclose(batch.contact_area[:, j], single.contact_area, atol=1e-8)


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


def test_options_validated():
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="order"):
        pf.solve(pr, "mol", order=3)
    with pytest.raises(ValueError, match="integrator"):
        pf.solve(pr, "mol", integrator="Euler")
    with pytest.raises(ValueError, match="variable"):
        pf.solve(pr, "mol", variable="V")
    with pytest.raises(TypeError, match="integrator"):
        pf.solve(pr, "mol", integrater="BDF")
    with pytest.warns(UserWarning, match="n_steps"):
        pf.solve(pr, "mol", n_steps=10, n_p=41)


def test_error_keeps_falling_below_1e8():
    """Issue 3: no plateau from the start-up or the far wall -- mol order 4 refined to L1 < 1e-8."""
    pr = pf.ContactProblem.reference()
    errs = [pf.solve(pr, "mol", order=4, n_p=n, rtol=r).compare().final()["L1"] for n, r in ((300, 1e-9), (600, 1e-11))]
    assert errs[1] < errs[0] / 8  # still 4th-order-like between these two resolutions
    assert errs[1] < 1e-8
