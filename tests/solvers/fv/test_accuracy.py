"""Method "fv" against pf.exact: accuracy of the defaults and the best scheme, convergence orders in p and tau, the
fudge couplings, stations and batches, step placements."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf

FUDGES = [None, "YP08", "WM17"]


def errors(problem, **options):
    sol = pf.solve(problem, "fv", **options)
    return sol, sol.compare().final()


def rate(h, err):
    """Observed order: slope of log(err) against log(h)."""
    return np.polyfit(np.log(h), np.log(err), 1)[0]


def test_defaults_reach_1e_5(problems):
    sol, c = errors(problems[None])
    assert c["L1"] <= 1.5e-5
    info = sol.info
    for key in ("grid", "steps", "zeta0", "scheme", "stepping", "coupling", "edges", "tridiagonal_solves"):
        assert key in info
    assert info["grid"]["n_p"] == sol.p.size
    assert 1.0 < info["zeta0"] < problems[None].zeta_max
    assert info["far_wall_mass"] < 1e-12 and info["tail_mass_exact"] < 1e-12
    assert sol.compare().reference == "cell averages"


@pytest.mark.parametrize("fudge", FUDGES)
def test_best_scheme_accuracy(problems, fudge):
    sol, c = errors(problems[fudge], scheme="tr-bdf2", n_p=200, n_steps=700)
    assert c["L1"] <= 1e-6
    assert c["area_error"] <= 1e-7
    assert sol.compare().mass_balance.max() < 1e-12
    assert sol.info["coupling"] == ("exact (S = 1)" if fudge is None else "predictor")


def test_error_keeps_falling_to_1e_8(problems):
    L1 = [errors(problems[None], n_p=n, n_steps=s)[1]["L1"] for n, s in ((100, 200), (200, 800), (400, 3200))]
    assert L1[0] > L1[1] > L1[2]
    assert L1[2] <= 1e-8


@pytest.mark.parametrize(("space", "order", "n_p"), [("fv2", 2, (50, 100, 200)), ("compact4", 4, (30, 45, 60))])
def test_order_in_p(problems, space, order, n_p):
    err = [errors(problems[None], space=space, n_p=n, n_steps=800)[1]["L1"] for n in n_p]
    assert abs(rate(1.0 / np.array(n_p), err) - order) < 0.3


@pytest.mark.parametrize(
    ("scheme", "fudge", "order"),
    [("crank-nicolson", None, 2), ("tr-bdf2", None, 2), ("tr-bdf2", "YP08", 2), ("implicit", None, 1)],
)
def test_order_in_tau(problems, scheme, fudge, order):
    steps = np.array([20, 40, 80])
    err = [errors(problems[fudge], scheme=scheme, n_p=300, n_steps=s)[1]["L1"] for s in steps]
    assert abs(rate(1.0 / steps, err) - order) < 0.25


def test_lagged_coupling_is_first_order(problems):
    steps = np.array([20, 40, 80])
    err = [errors(problems["YP08"], coupling="lagged", n_p=300, n_steps=s)[1]["L1"] for s in steps]
    assert abs(rate(1.0 / steps, err) - 1) < 0.25


def test_picard_coupling_converges(problems):
    sol, c = errors(problems["WM17"], coupling="picard", n_steps=60)
    assert sol.info["picard_iterations"] >= 60
    assert c["L1"] < 1e-4


def test_stations_share_one_run(problems):
    zeta_out = [10.0, 50.0, 128.0]
    sol = pf.solve(problems[None], "fv", zeta_out=zeta_out)
    assert sol.P0.shape == (3, sol.p.size)
    assert sol.info["zeta0"] < 10.0
    assert sol.compare().max_L1 < 1e-4


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_batch_equals_single_loads(problems, fudge):
    base = problems[fudge]
    sqrtV = float(np.sqrt(base.V()))
    loads = sqrtV * np.array([0.01, 0.1, 0.5, 1.0, 3.0])
    batch = pf.solve(base.with_loads(loads), "fv", n_p=300, n_steps=150)
    assert batch.P0.shape == (1, loads.size, 300)
    cb = batch.compare()
    assert np.max(cb.L1) < 1e-5
    for j in (0, 2, 4):
        single = pf.solve(base.with_loads(loads[j]), "fv", n_p=300, n_steps=150)
        assert abs(single.contact_area[-1] - batch.contact_area[-1, j]) < 2e-6
        assert single.compare().final()["L1"] < 1e-5


@pytest.mark.parametrize("stepping", ["geometric", "zeta", "tau", "graded"])
def test_steppings(problems, stepping):
    sol, c = errors(problems["WM17"], stepping=stepping)
    assert sol.info["steps"] == 100
    assert c["L1"] < 1e-3


def test_early_station_with_enough_cells_is_accurate_everywhere():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([1e-4, 0.5, 3.0]))
    sol = pf.solve(pr, method="fv", zeta_out=[1.05, 128.0], n_p=2000)
    err = sol.compare()
    assert err.L1[-1].max() < 2e-5 and err.load_drift.max() < 1e-10
