"""The two linear-algebra paths of method "fv": the spectral fast path (``linalg="dst"``, ``fv/spectral.py``) gives
the banded path's solution to round-off for every scheme, space, fudge coupling, batch and step placement; "auto"
picks it; the banded path reuses its factorisation on uniform steps."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.schemes import SCHEMES


def both(problem, **options):
    return pf.solve(problem, "fv", linalg="banded", **options), pf.solve(problem, "fv", linalg="dst", **options)


def assert_same(a, b, tol=1e-12):
    scale = np.max(np.abs(a.P0_all))
    np.testing.assert_allclose(b.P0_all, a.P0_all, rtol=0, atol=tol * scale)
    np.testing.assert_allclose(b.contact_area_all, a.contact_area_all, rtol=0, atol=tol)
    np.testing.assert_allclose(b.contact_area_flux_all, a.contact_area_flux_all, rtol=0, atol=tol)
    assert abs(b.info["far_wall_mass"] - a.info["far_wall_mass"]) <= tol
    np.testing.assert_allclose(b.info["tau_numerical"], a.info["tau_numerical"], rtol=1e-13)
    assert b.info["r_max"] == pytest.approx(a.info["r_max"], rel=1e-13)
    assert a.info["linalg"] == "banded" and b.info["linalg"] == "dst"
    assert b.info["tridiagonal_solves"] == 0 and b.info["transforms"] >= 2


@pytest.mark.filterwarnings("ignore:fv. P0 has negative values:RuntimeWarning")  # explicit compact4
@pytest.mark.parametrize("fudge", [None, "YP08"])
@pytest.mark.parametrize("space", ["fv2", "compact4"])
@pytest.mark.parametrize("scheme", list(SCHEMES))
def test_dst_equals_banded(problems, scheme, space, fudge):
    n_steps = 300 if scheme == "explicit" else 30
    a, b = both(problems[fudge], scheme=scheme, space=space, n_p=40, n_steps=n_steps, zeta_out=[6.0, 30.0, 128.0])
    assert_same(a, b)
    # the mass balance (with the far-wall loss, ~1e-11 for implicit on this small grid) is the same
    np.testing.assert_allclose(b.compare().mass_balance, a.compare().mass_balance, rtol=0, atol=1e-13)


@pytest.mark.parametrize(("fudge", "coupling"), [("YP08", "lagged"), ("WM17", "picard"), ("WM17", "predictor")])
def test_dst_equals_banded_couplings(problems, fudge, coupling):
    a, b = both(problems[fudge], coupling=coupling, n_p=60, n_steps=40, zeta_out=[10.0, 128.0])
    assert_same(a, b)
    assert a.info["picard_iterations"] == b.info["picard_iterations"]


@pytest.mark.parametrize("initial", ["exact", "delta"])
@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_dst_equals_banded_batched(problems, fudge, initial):
    base = problems[fudge]
    loads = np.sqrt(float(base.V())) * np.array([0.01, 0.1, 0.5, 1.0, 3.0])
    a, b = both(base.with_loads(loads), n_p=120, n_steps=60, zeta_out=[10.0, 50.0, 128.0], initial=initial)
    assert b.P0_all.shape == (3, 5, 120)
    assert_same(a, b)


@pytest.mark.parametrize("stepping", ["geometric", "zeta"])
def test_dst_equals_banded_steppings(problems, stepping):
    assert_same(*both(problems[None], stepping=stepping, scheme="rannacher", n_p=50, n_steps=40))


def test_auto_is_dst(problems):
    sol = pf.solve(problems["YP08"], "fv", n_p=50, n_steps=20)
    assert sol.info["linalg"] == "dst"
    assert sol.info["options"]["linalg"] == "auto"


@pytest.mark.parametrize("coupling", ["lagged", "predictor"])
def test_fudge_trajectory_is_used_and_converges(problems, coupling):
    """The whole-trajectory coupling (>= 16 steps, one load) converges in a few sweeps and gives the
    step-by-step march's result (the banded path) to 1e-12 of max P0."""
    a, b = both(problems["YP08"], coupling=coupling, n_p=100, n_steps=40, zeta_out=[3.0, 128.0])
    assert 2 <= b.info["trajectory_sweeps"] <= 10 and a.info["trajectory_sweeps"] == 0
    assert_same(a, b)


def test_fudge_trajectory_for_a_small_batch(problems):
    """The several-load branch of the trajectory coupling (up to _fudge_trajectory_max_loads = 3 loads) gives the
    banded path's solution too."""
    base = problems["YP08"]
    pr = base.with_loads(np.sqrt(float(base.V())) * np.array([0.05, 0.5, 3.0]))
    a, b = both(pr, n_p=80, n_steps=40, zeta_out=[5.0, 128.0])
    assert b.info["trajectory_sweeps"] >= 2
    assert_same(a, b)


def test_uniform_tau_steps_reuse_factorisation(problems):
    sol = pf.solve(problems[None], "fv", scheme="crank-nicolson", stepping="tau", n_steps=50, linalg="banded")
    assert sol.info["factorizations"] <= 2
    assert sol.info["tridiagonal_solves"] == 50
