"""Fast paths for repeated questions give the same numbers as the general paths (issue 16).

``pf.exact(problem)`` at zeta_max reads V and tau from the problem's cache and computes erf lazily
(``math.erf`` for one load at one zeta); ``problem.with_loads`` validates only the new loads.  Each is
checked against the general path (explicit zeta, a freshly built problem) and against the closed form
A* = erf(p_bar / sqrt(2 V)) (Xu et al. tutorial, Eq. 'eq:Area_Persson') with V from scipy's quadrature
of the spectrum.  No timing is asserted here (benchmarks/overhead.py measures it).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf

PROPS = (
    "contact_area",
    "atom",
    "tau",
    "elastic_area",
    "plastic_area",
    "noncontact_area",
    "elastic_load",
    "plastic_load",
    "area_asymptote",
    "variance",
    "second_moment",
)


def _problem(fudge, hardness, loads):
    base = pf.ContactProblem.reference()
    sv = np.sqrt(base.V_max)
    hard = None if hardness is None else hardness * sv
    return pf.ContactProblem(base.psd, 1.0, np.asarray(loads) * sv, fudge=fudge, hardness=hard)


@pytest.mark.parametrize("fudge", [None, "YP08"])
@pytest.mark.parametrize("hardness", [None, 2.0])
@pytest.mark.parametrize("loads", [0.5, [0.5], [1e-3, 0.5, 1.5]])
def test_zeta_max_fast_path_equals_the_general_path(fudge, hardness, loads):
    pr = _problem(fudge, hardness, loads)
    fast = pf.exact(pr)
    slow = pf.exact(pr, pr.zeta_max)  # validated zeta, V and tau recomputed
    # 1e-14: the two paths differ only in the rounding of V(zeta_max) (cached vs recomputed) and erf
    # (math.erf vs scipy.special.erf for one number); both are a few ulp
    for name in PROPS:
        a, b = getattr(fast, name), getattr(slow, name)
        assert np.shape(a) == np.shape(b), name
        np.testing.assert_allclose(a, b, rtol=1e-14, atol=1e-300, err_msg=name)
    assert fast.zeta == slow.zeta and fast.V == pytest.approx(slow.V, rel=1e-15)
    np.testing.assert_allclose(fast.pdf(np.array([0.1, 0.3])), slow.pdf(np.array([0.1, 0.3])), rtol=1e-14)


def test_one_load_matches_the_closed_form_with_quadrature_V():
    """A* = erf(p_bar / sqrt(2 V)) without a fudge factor, V = (pi/2) E*^2 int q^3 C dq by quad."""
    pr = pf.ContactProblem.reference()
    psd = pr.psd
    V = (
        np.pi
        / 2
        * (
            quad(lambda q: q**3 * psd.C(q), 1.0, 2.0, epsrel=1e-14)[0]
            + quad(lambda q: q**3 * psd.C(q), 2.0, 128.0, epsrel=1e-14, limit=200)[0]
        )
    )
    for ratio in (1e-3, 0.5, 3.0):
        pb = ratio * np.sqrt(V)
        A = pf.exact(pr.with_loads(pb)).contact_area
        assert isinstance(A, float)
        # quadrature to 1e-14 in V moves A* by < 1e-14 relative (dA/A <= dV/(2V) for erf's argument)
        assert A == pytest.approx(float(erf(pb / np.sqrt(2 * V))), rel=1e-12)


@pytest.mark.parametrize("fudge", [None, "YP08", "Xu24"])
def test_with_loads_equals_a_fresh_problem(fudge):
    pr = _problem(fudge, None, [0.2, 0.9])
    loads = np.array([0.05, 0.7, 2.0]) * np.sqrt(pr.V_max)
    new = pr.with_loads(loads)
    fresh = pf.ContactProblem(pr.psd, pr.E_star, loads, fudge=fudge)
    assert new.n_loads == 3 and not new.scalar_load
    np.testing.assert_array_equal(new.p_bar, fresh.p_bar)
    np.testing.assert_allclose(new.tau_max, fresh.tau_max, rtol=1e-15)
    np.testing.assert_allclose(pf.exact(new, 40.0).contact_area, pf.exact(fresh, 40.0).contact_area, rtol=1e-15)
    # the original keeps its loads and caches
    assert pr.n_loads == 2 and pr.tau_max.shape == (2,)
    # still an immutable value
    with pytest.raises(ValueError):
        new.p_bar[0] = 1.0
    with pytest.raises(AttributeError):
        new.p_bar = loads


def test_with_loads_validates_the_new_loads():
    pr = _problem(None, 2.0, 0.5)
    for bad in (0.0, -1.0, np.nan, [[0.1]], []):
        with pytest.raises(ValueError, match="p_bar"):
            pr.with_loads(bad)
    with pytest.raises(ValueError, match="hardness|sigma"):  # a load above the yield stress
        pr.with_loads(3.0 * np.sqrt(pr.V_max))


def test_solve_runs_with_one_blas_thread_and_restores_the_pool():
    threadpoolctl = pytest.importorskip("threadpoolctl")
    from persson_fp.solvers.sines import SineSeriesSolver

    seen = []

    class Recording(SineSeriesSolver):
        def _solve(self):
            seen.append(max(i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"))
            return super()._solve()

    def blas():
        return [i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"]

    before = blas()
    pr = _problem("YP08", None, [0.2, 0.9])
    a = pf.solve(pr, Recording).contact_area
    b = pf.solve(pr, Recording, blas_threads=None).contact_area
    assert seen[0] == 1 and seen[1] == max(before, default=1)
    assert blas() == before
    # the thread count changes only the summation order: the same areas to round-off
    np.testing.assert_allclose(a, b, rtol=1e-13)
    # and both the exact ones (sines' default: modes for 1e-13)
    np.testing.assert_allclose(a[-1], pf.exact(pr).contact_area, rtol=1e-9)


@pytest.mark.parametrize("bad", [0, -1, 1.5, "1", True])
def test_blas_threads_is_validated(bad):
    with pytest.raises(ValueError, match="blas_threads"):
        pf.solve(_problem(None, None, 0.5), "sines", blas_threads=bad)


def test_exact_tau_at_zeta_max_is_a_writeable_copy():
    pr = _problem("YP08", None, [0.2, 0.9])
    t = pf.exact(pr).tau
    t *= 2.0  # the user's array, not the problem's cache
    np.testing.assert_allclose(pf.exact(pr).tau, t / 2.0, rtol=1e-15)
