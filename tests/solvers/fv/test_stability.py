"""Stability of method "fv": the explicit scheme's limit refused a priori, the blow-up past it named as an
instability, and the limit where the amplification factor of the top mode reaches 1."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.fv import dst_eigenvalues
from persson_fp.solvers.fv.dst import _amplification, _growth


def errors(problem, **options):
    sol = pf.solve(problem, "fv", **options)
    return sol, sol.compare().final()


def test_explicit_past_limit_raises(problems):
    with pytest.raises(ValueError, match=r"r = .* stability limit 0\.5"):
        pf.solve(problems[None], "fv", scheme="explicit", space="fv2", n_p=200, n_steps=200)


def test_explicit_within_limit_runs(problems):
    sol, c = errors(problems[None], scheme="explicit", space="fv2", n_p=50, n_steps=700)
    assert sol.info["r_max"] <= 0.5
    assert c["L1"] < 5e-3


@pytest.mark.parametrize("linalg", ["dst", "banded"])
@pytest.mark.parametrize("space", ["fv2", "compact4"])
def test_explicit_unstable_blows_up(problems, linalg, space):
    with pytest.raises(pf.InstabilityError, match="raise n_steps"):
        pf.solve(
            problems[None],
            "fv",
            scheme="explicit",
            space=space,
            n_p=200,
            n_steps=200,
            allow_unstable=True,
            linalg=linalg,
        )


@pytest.mark.parametrize("linalg", ["dst", "banded"])
def test_explicit_unstable_blows_up_with_fudge(problems, linalg):
    with pytest.raises(pf.InstabilityError, match="raise n_steps"):
        pf.solve(problems["YP08"], "fv", scheme="explicit", n_p=200, n_steps=200, allow_unstable=True, linalg=linalg)


@pytest.mark.parametrize("space", ["fv2", "compact4"])
def test_explicit_limit_is_where_the_top_mode_amplifies(space):
    """The a-priori limit r = 1/2 (fv2), 1/3 (compact4) is |R| = 1 of the explicit step at j = n_p."""
    n, dp = 50, 0.1
    mu, m = dst_eigenvalues(n, dp, space)
    limit = 0.5 if space == "fv2" else 1.0 / 3.0
    for r, unstable in ((0.99 * limit, False), (1.01 * limit, True)):
        R, _ = _amplification("theta", 0.0, 2.0 * r * dp**2 * mu / m)
        assert (np.max(np.abs(R)) > 1.0) == unstable


@pytest.mark.parametrize(("kind", "theta"), [("tr-bdf2", 0.5), ("be-halves", 1.0), ("theta", 0.0), ("theta", 0.5)])
def test_growth_is_the_amplification_factor(kind, theta):
    """The R-only factor of the trajectory sweeps against _amplification's R (same formula written once
    more, without the wall-flux weight): equal to round-off over x = dtau lambda in [-1e4, 0]."""
    x = -np.geomspace(1e-6, 1e4, 200)
    R, _ = _amplification(kind, theta, x.copy())
    np.testing.assert_allclose(_growth(kind, theta, x), R, rtol=1e-13, atol=1e-16)
