"""Monte Carlo solver: unbiased to the standard error with the bridge, biased without; its options, seeds included."""

import numpy as np
import pytest

import persson_fp as pf

MC = "monte-carlo"
SEED = 20240607  # fixed seed: the assertions are 5-standard-error bounds, checked for this stream


@pytest.fixture(scope="module")
def problem():
    return pf.ContactProblem.reference()


def z_scores(sol):
    """|error| / standard error of A*, load and second moment at every station (exact references)."""
    ex = pf.exact(sol.problem, sol.zeta)
    m = sol.info["moments"]
    z_A = sol.compare().area_z_score[:, 0]
    z_load = np.abs(m["load"][:, 0] - sol.problem.p_bar[0]) / m["stderr_load"][:, 0]
    z_m2 = np.abs(m["second_moment"][:, 0] - ex.second_moment) / m["stderr_second_moment"][:, 0]
    return z_A, z_load, z_m2


def test_area_and_moments_within_five_standard_errors(problem):
    sol = pf.solve(problem, MC, zeta_out=[4.0, 128.0], n_walkers=200_000, n_steps=8, seed=SEED)
    for z in z_scores(sol):
        assert np.all(z < 5), z
    se = sol.stderr_area_all[-1, 0]
    A = sol.contact_area[-1]
    assert se == pytest.approx(np.sqrt(A * (1 - A) / 200_000))
    # histogram: a density with its statistical error, consistent with the exact cell averages
    err = np.abs(sol.P0[-1] - sol.exact_on_grid()[-1, 0])
    se_P0 = sol.info["stderr_P0"][-1, 0]
    assert np.mean(err[se_P0 > 0] / se_P0[se_P0 > 0]) < 1.5  # ~ sqrt(2/pi) for pure noise
    assert sol.info["above_p_max"][-1, 0] == 0


def test_bridge_removes_the_discrete_monitoring_bias(problem):
    """Plain absorption misses excursions below 0 inside a step: A* biased high ~ sqrt(dzeta)."""
    N = 100_000
    bias = {}
    for steps in (4, 16):
        with pytest.raises(pf.SolverError, match="load_balance"):  # the bias breaks the load balance
            pf.solve(problem, MC, n_walkers=N, n_steps=steps, bridge=False, seed=SEED)
        with pytest.warns(RuntimeWarning, match="load_balance"):
            plain = pf.solve(problem, MC, n_walkers=N, n_steps=steps, bridge=False, seed=SEED, check=False)
        bridged = pf.solve(problem, MC, n_walkers=N, n_steps=steps, bridge=True, seed=SEED)
        ex = pf.exact(problem).contact_area
        assert plain.contact_area[-1] - ex > 20 * plain.stderr_area_all[-1, 0]  # biased high, many SE
        assert bridged.compare().area_z_score[-1, 0] < 5
        bias[steps] = plain.contact_area[-1] - ex
    # O(sqrt(dtau)): four times the steps halves the bias (within the statistical error)
    assert bias[4] / bias[16] == pytest.approx(2.0, rel=0.25)
    # with the bridge the walk is exact killed Brownian motion: even one step is unbiased
    one = pf.solve(problem, MC, n_walkers=N, n_steps=1, seed=SEED)
    assert one.compare().area_z_score[-1, 0] < 5


@pytest.mark.parametrize("fudge", ["YP08", "WM17"])
def test_fudge_factor_within_five_standard_errors(fudge):
    pr = pf.ContactProblem.reference(fudge=fudge)
    sol = pf.solve(pr, MC, zeta_out=[8.0, 128.0], n_walkers=100_000, n_steps=8, seed=SEED, chunk_size=30_000)
    assert sol.info["chunks"] == 4  # lock-step over chunks: S from the whole population
    # coarse steps are fine: within a step A* is the expected survival given the walkers (no step error)
    for z in z_scores(sol):
        assert np.all(z < 5), z
    ex = pf.exact(pr, sol.zeta)
    np.testing.assert_allclose(sol.info["tau"][:, 0], ex.tau, rtol=5e-3)


def test_reproducible_and_batched(problem):
    a = pf.solve(problem, MC, n_walkers=20_000, n_steps=4, seed=7)
    b = pf.solve(problem, MC, n_walkers=20_000, n_steps=4, seed=np.random.SeedSequence(7))
    np.testing.assert_array_equal(a.P0, b.P0)
    c = pf.solve(problem, MC, n_walkers=20_000, n_steps=4, seed=8)
    assert not np.array_equal(a.P0, c.P0)
    assert "seed_entropy" in a.info
    loads = problem.p_bar[0] * np.array([0.5, 1.0, 2.0])
    pr = pf.ContactProblem(problem.psd, p_bar=loads, fudge="YP08")
    sol = pf.solve(pr, MC, n_walkers=50_000, n_steps=16, seed=SEED, chunk_size=40_000)
    assert sol.P0.shape == (1, 3, 200)
    assert np.all(sol.compare().area_z_score < 5)


def test_bad_options(problem):
    for bad, name in (
        ({"n_walkers": 0}, "n_walkers"),
        ({"n_walkers": 2.5}, "n_walkers"),
        ({"n_steps": 0}, "n_steps"),
        ({"n_p": 0}, "n_p"),
        ({"chunk_size": 0}, "chunk_size"),
        ({"k_domain": -1.0}, "k_domain"),
        ({"seed": -3}, "seed"),
        ({"seed": "abc"}, "seed"),
        ({"bridge": "yes"}, "bridge"),
    ):
        with pytest.raises(ValueError, match=name):
            pf.solve(problem, MC, **bad)
    with pytest.raises(TypeError, match="n_walkers"):
        pf.solve(problem, MC, n_walker=10)


@pytest.mark.parametrize("seed", [float("inf"), True, np.bool_(True), -1, 2.5, "3"])
def test_monte_carlo_refuses_odd_seeds(seed):
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="seed must be"):  # inf was OverflowError, True was accepted
        pf.solve(pr, "monte-carlo", seed=seed, n_walkers=100)
