"""Finite-volume solver: operator, accuracy, convergence orders, invariants, batches, stability."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.fv import (
    SCHEMES,
    SPACES,
    FiniteVolumeSolver,
    apply_mass,
    apply_operator,
    banded_operator,
    rhs,
)

FUDGES = [None, "YP08", "WM17"]


@pytest.fixture(scope="module")
def problems():
    return {f: pf.ContactProblem.reference(fudge=f) for f in FUDGES}


def errors(problem, **options):
    sol = pf.solve(problem, "fv", **options)
    return sol, sol.compare().final()


def rate(h, err):
    """Observed order: slope of log(err) against log(h)."""
    return np.polyfit(np.log(h), np.log(err), 1)[0]


# -- the operator ---------------------------------------------------------------------------------
def test_banded_matrix_equals_readable_rhs():
    rng = np.random.default_rng(1)
    n, dp = 17, 0.3
    P = rng.standard_normal((3, n))
    ab = banded_operator(n, dp)
    dense = np.diag(ab[1]) + np.diag(ab[0, 1:], 1) + np.diag(ab[2, :-1], -1)
    np.testing.assert_allclose(P @ dense.T, rhs(P, dp), rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(apply_operator(P, 0.5 / dp**2), rhs(P, dp), rtol=1e-13, atol=1e-12)


def test_flux_form_conserves_up_to_wall_fluxes():
    rng = np.random.default_rng(2)
    P = rng.random((2, 30))
    dp = 0.1
    # sum of flux differences = minus the outflow at both walls (P_0 + P_-1) / dp
    np.testing.assert_allclose(rhs(P, dp).sum(axis=-1) * dp, -(P[:, 0] + P[:, -1]) / dp, rtol=1e-12)


def test_compact_mass_matrix_rows():
    P = np.eye(6)
    M = apply_mass(P, "compact4")  # rows of M^T = columns of M (M symmetric)
    np.testing.assert_allclose(M, M.T)
    np.testing.assert_allclose(M[2, 1:4], [1 / 12, 10 / 12, 1 / 12])
    np.testing.assert_allclose(M[0, :2], [9 / 12, 1 / 12])
    np.testing.assert_array_equal(apply_mass(P, "fv2"), P)
    assert set(SPACES) == {"fv2", "compact4"}


def test_scheme_table():
    assert SCHEMES["explicit"].theta == 0.0
    assert SCHEMES["crank-nicolson"].theta == 0.5
    assert SCHEMES["implicit"].theta == 1.0
    assert SCHEMES["tr-bdf2"].l_stable and SCHEMES["tr-bdf2"].order == 2
    assert SCHEMES["implicit"].order == 1


# -- accuracy -------------------------------------------------------------------------------------
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


# -- convergence orders ---------------------------------------------------------------------------
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


# -- invariants -----------------------------------------------------------------------------------
@pytest.mark.parametrize("scheme", ["tr-bdf2", "crank-nicolson", "implicit", "rannacher"])
def test_invariants(problems, scheme):
    zeta_out = np.geomspace(4.0, 128.0, 6)
    sol = pf.solve(problems["YP08"], "fv", scheme=scheme, zeta_out=zeta_out, n_steps=80)
    assert sol.info["checks"]["min_P0"] >= -1e-12 * np.max(sol.P0)
    assert np.all(np.diff(sol.contact_area) <= 1e-14)
    assert sol.info["checks"]["max_load_drift"] < 1e-10
    np.testing.assert_allclose(sol.contact_area, sol.contact_area_flux, atol=1e-12)
    assert sol.compare().max_L1 < (2e-2 if scheme == "implicit" else 3e-3)


def test_stations_share_one_run(problems):
    zeta_out = [10.0, 50.0, 128.0]
    sol = pf.solve(problems[None], "fv", zeta_out=zeta_out)
    assert sol.P0.shape == (3, sol.p.size)
    assert sol.info["zeta0"] < 10.0
    assert sol.compare().max_L1 < 1e-4


# -- batches --------------------------------------------------------------------------------------
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


# -- stability ------------------------------------------------------------------------------------
def test_explicit_past_limit_raises(problems):
    with pytest.raises(ValueError, match=r"r = .* stability limit 0\.5"):
        pf.solve(problems[None], "fv", scheme="explicit", space="fv2", n_p=200, n_steps=200)


def test_explicit_within_limit_runs(problems):
    sol, c = errors(problems[None], scheme="explicit", space="fv2", n_p=50, n_steps=700)
    assert sol.info["r_max"] <= 0.5
    assert c["L1"] < 5e-3


def test_explicit_unstable_blows_up(problems):
    with pytest.raises(pf.InstabilityError, match="raise n_steps"):
        pf.solve(problems[None], "fv", scheme="explicit", space="fv2", n_p=200, n_steps=200, allow_unstable=True)


def test_crank_nicolson_rings_on_delta_tr_bdf2_does_not(problems):
    with pytest.warns(RuntimeWarning, match="negative"):
        cn = pf.solve(problems[None], "fv", scheme="crank-nicolson", initial="delta", n_p=200, n_steps=20)
    assert cn.info["checks"]["negative_P0"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for scheme in ("tr-bdf2", "rannacher"):
            sol = pf.solve(problems[None], "fv", scheme=scheme, initial="delta", n_p=200, n_steps=20)
            assert not sol.info["checks"]["negative_P0"]
            assert sol.info["zeta0"] == 1.0


# -- options --------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "bad",
    [
        {"scheme": "leapfrog"},
        {"stepping": "random"},
        {"coupling": "magic"},
        {"initial": "gauss"},
        {"n_p": 2},
        {"n_steps": 0},
        {"k_domain": -1.0},
        {"space": "fv6"},
    ],
)
def test_bad_options_raise(problems, bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        FiniteVolumeSolver(problems[None], **bad)


def test_misspelt_option(problems):
    with pytest.raises(TypeError, match="scheme"):
        FiniteVolumeSolver(problems[None], schem="implicit")


@pytest.mark.parametrize("stepping", ["geometric", "zeta", "tau"])
def test_steppings(problems, stepping):
    sol, c = errors(problems["WM17"], stepping=stepping)
    assert sol.info["steps"] == 100
    assert c["L1"] < 1e-3


def test_uniform_tau_steps_reuse_factorisation(problems):
    sol = pf.solve(problems[None], "fv", scheme="crank-nicolson", stepping="tau", n_steps=50)
    assert sol.info["factorizations"] <= 2
    assert sol.info["tridiagonal_solves"] == 50
