"""The sine-series solver (Persson's original form, ``eq:P0_solution``) against pf.exact: accuracy, convergence
faster than any power, the mode count, batches, invariants, options and its refusals."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.sines import SineSeriesSolver, image_area, modes_needed, series_area

ZETA_OUT = [1.5, 10.0, 128.0]


@pytest.mark.parametrize("fudge", [None, "YP08", "WM17", "Xu24"])
def test_reference_accuracy(fudge):
    pr = pf.ContactProblem.reference(fudge=fudge)
    sol = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    cmp = sol.compare()
    assert cmp.max_L1 <= 1e-10
    assert cmp.max_area_error <= 1e-11
    assert np.max(cmp.load_drift) <= 1e-11
    assert sol.info["zeta0"] == 1.0  # the delta is represented exactly
    assert not sol.info["checks"]["negative_P0"]


def test_tau_from_numerical_area_matches_effective_variance():
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=[0.05, 0.5, 2.0])
    sol = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    tau_ex = pr.tau(np.array(ZETA_OUT))
    np.testing.assert_allclose(sol.info["tau"], tau_ex, rtol=1e-11)


def test_faster_than_any_power():
    pr = pf.ContactProblem.reference()
    n = np.array([8, 12, 16, 20])
    with pytest.warns(RuntimeWarning):  # coarse series: Gibbs undershoot, load missed by > 1 %: reported
        err = np.array([pf.solve(pr, "sines", n_p=int(k), n_eval=400, check=False).compare().final()["L1"] for k in n])
    assert np.all(np.diff(err) < 0)
    slopes = np.diff(np.log(err)) / np.diff(np.log(n))  # local algebraic order
    assert np.all(np.diff(slopes) < 0)  # steepens without bound: not a power law
    assert slopes[-1] < -20


def test_auto_modes_and_truncation_bound():
    pr = pf.ContactProblem.reference()
    sol = pf.solve(pr, "sines")
    L = sol.info["p_max"]
    N = sol.info["n_modes"]
    V = float(pr.V())
    k = (N + 1) * np.pi / L
    assert 2 * np.exp(-0.5 * k * k * V) < 1e-13  # the first dropped mode is below the tolerance
    # and the count is not wasteful: within 20 % of the smallest N with that bound (solved by hand here)
    n_min = int(np.ceil(L / np.pi * np.sqrt(2 * np.log(2e13) / V))) - 1
    assert n_min <= N <= 1.2 * n_min + 2
    assert sol.compare().max_L1 < 1e-12


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_batched_loads_equal_single_loads(fudge):
    ratios = np.geomspace(0.01, 3.0, 5)
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=ratios)
    batch = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    assert batch.compare().max_L1 <= 1e-10
    for j, pb in enumerate(pr.p_bar):
        single = pf.solve(pr.with_loads(pb), "sines", zeta_out=ZETA_OUT)
        np.testing.assert_allclose(batch.contact_area[:, j], single.contact_area, rtol=0, atol=1e-12)
        np.testing.assert_allclose(batch.info["tau"][:, j], single.info["tau"][:, 0], rtol=1e-12)


def test_invariants():
    pr = pf.ContactProblem.reference(fudge="YP08")
    z = np.geomspace(1.2, 128.0, 8)
    sol = pf.solve(pr, "sines", zeta_out=z)
    assert np.all(np.diff(sol.contact_area) < 0)  # contact is only lost
    np.testing.assert_allclose(sol.load, pr.p_bar[0], rtol=1e-11)
    # d<p^2>/dtau = A*: Var = int A* dtau (closed form in tau)
    var_ex = pf.variance_closed_form(pr.p_bar[0], sol.info["tau"][:, 0])
    np.testing.assert_allclose(sol.variance, var_ex, rtol=1e-9)


def test_options_validated():
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="n_p"):
        pf.solve(pr, "sines", n_p=0)
    with pytest.raises(TypeError, match="n_eval"):
        pf.solve(pr, "sines", n_evl=10)
    with pytest.warns(UserWarning, match="n_steps"):
        pf.solve(pr, "sines", n_steps=10)
    assert SineSeriesSolver.name == "sines"


def test_image_dual_equals_the_converged_series():
    """Poisson summation: the image sum and the (converged) sine series are the same function."""
    L, pb = 1.0, 0.3
    for tau in (1e-3, 1e-2, 0.05):
        n = int(modes_needed(L, tau, 1e-15))
        assert image_area(L, pb, tau) == pytest.approx(float(series_area(L, pb, tau, n)), abs=1e-14)


def test_far_wall_too_near_is_refused():
    """k_domain = 1 put the far wall where it absorbs much of the load (the closed form has none): refused."""
    with pytest.raises(ValueError, match=r"k_domain must lie in \[5, 1000\]"):
        pf.solve(pf.ContactProblem.reference(), "sines", k_domain=1.0)


@pytest.mark.parametrize(("ratio", "zeta_out"), [(0.5, [1.0 + 1e-9, 128.0]), (1e8, None)])
def test_too_many_modes_is_refused_quickly(ratio, zeta_out):
    """A station whose PDF is far narrower than the domain (a station just after zeta = 1, or a load 1e8 sqrt(V))
    would need millions of modes: a ValueError naming the cause, not a memory error."""
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=ratio)
    with pytest.raises(ValueError, match="needs .* modes"):
        pf.solve(pr, "sines", zeta_out=zeta_out)
