"""Fast paths give the same numbers and the same decisions as the general paths.

``pf.exact(problem)`` at zeta_max reads V and tau from the problem's cache and computes erf lazily
(``math.erf`` for one load at one zeta); ``problem.with_loads`` validates only the new loads.  Each is
checked against the general path (explicit zeta, a freshly built problem) and against the closed form
A* = erf(p_bar / sqrt(2 V)) (Xu et al. tutorial, Eq. 'eq:Area_Persson') with V from scipy's quadrature
of the spectrum.

The shortcuts of a one-load, one-station result keep every check: a positive scalar is validated as the general
path validates it, the invariants of a one-load Solution (Python floats, the extrema of P0 taken once) decide as
those of the same row given as two loads, and the invariant checks' own shortcuts (one element read directly, the
undershoot weighed against the lowest peak first) decide as the full comparison per station and load.

No timing is asserted here (benchmarks/overhead.py measures it).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf
from persson_fp._validate import as_positive_scalar
from persson_fp.results.invariants import check_invariants
from persson_fp.results.solution import Solution

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


def test_exact_tau_at_zeta_max_is_a_writeable_copy():
    pr = _problem("YP08", None, [0.2, 0.9])
    t = pf.exact(pr).tau
    t *= 2.0  # the user's array, not the problem's cache
    np.testing.assert_allclose(pf.exact(pr).tau, t / 2.0, rtol=1e-15)


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf"), -0.0])
def test_positive_scalar_fast_path_refuses_what_the_general_path_refuses(bad):
    with pytest.raises(ValueError, match="k"):
        as_positive_scalar(bad, "k")


def test_positive_scalar_fast_path_zero_only_where_allowed():
    assert as_positive_scalar(0.0, "x", allow_zero=True) == 0.0
    assert as_positive_scalar(2.5, "x") == 2.5
    assert as_positive_scalar(np.float64(2.5), "x") == 2.5  # (not a plain float: the general path)
    with pytest.raises(ValueError):
        as_positive_scalar(-1e-300, "x", allow_zero=True)


def _one(P, load, area=None, check=True):
    """A one-station, one-load Solution on a uniform grid of [0, 1] with the given P0, load and area."""
    pr = pf.ContactProblem.reference()
    p = np.linspace(0.0, 1.0, P.size)
    w = np.full(p.size, p[1])
    A = float(np.sum(P * w)) if area is None else area
    return Solution.build("test", pr, [pr.zeta_max], p, P, w, "point", 0.0, contact_area=A, load=load, check=check)


def test_one_load_breaches_still_raise():
    pr = pf.ContactProblem.reference()
    pb = float(pr.p_bar[0])
    P = np.exp(-0.5 * ((np.linspace(0, 1, 64) - pb) / 0.05) ** 2)
    P /= 2.0 * np.sum(P) / 64
    _one(P, pb)  # balanced: passes
    with pytest.raises(pf.SolverError, match="load_balance"):
        _one(P, 1.5 * pb)  # a 50 % load drift
    with pytest.raises(pf.SolverError, match="area_range"):
        _one(P, pb, area=1.5)
    with pytest.raises(pf.SolverError, match="finite"):
        _one(P, float("nan"))
    for bad in (np.nan, np.inf, -np.inf):
        Q = P.copy()
        Q[10] = bad
        with pytest.raises(pf.InstabilityError, match="NaN or inf"):
            _one(Q, pb)


def test_one_load_overflowing_drift_is_a_breach_not_a_warning():
    """A load near the float limit: the drift overflows to inf (a breach), never an overflow warning."""
    P = np.full(64, 0.5)
    with pytest.warns(RuntimeWarning, match="load_balance"):
        sol = _one(P, 1.7e308, check=False)
    assert math.isinf(sol.info["checks"]["max_load_drift"])


def _two(P, load):
    """The same row as two loads (the general path: arrays, no one-element shortcut)."""
    pr = pf.ContactProblem.reference(p_bar_ratio=[0.5, 0.5])
    p = np.linspace(0.0, 1.0, P.size)
    w = np.full(p.size, p[1])
    z = [pr.zeta_max]
    return Solution.build(
        "test", pr, z, p, np.stack([P, P]), w, "point", 0.0, contact_area=[0.5, 0.5], load=[load, load], check=False
    )


def test_shortcuts_decide_as_the_general_path():
    """Random one-station, one-load results (some dipping, some unbalanced): the checks with the extrema handed over
    by build and the one-load drift in Python floats equal those of the general path (the same row as two loads)."""
    rng = np.random.default_rng(7)
    clean = 0
    for _ in range(200):
        P = rng.normal(0.0, 1.0, 40) + rng.uniform(0.0, 3.0)
        P[rng.random(40) < 0.3] *= rng.choice([1e-12, 1e-3, 1.0])
        load = float(pf.ContactProblem.reference().p_bar[0]) * (1 + rng.choice([0.0, 1e-3, 0.05]))
        with warnings.catch_warnings():  # (check=False: the breaches are warned about, and compared below)
            warnings.simplefilter("ignore", RuntimeWarning)
            one, two = _one(P, load, area=0.5, check=False), _two(P, load)
            again = check_invariants(one, raise_on_breach=False)  # without the extrema: computed here
        for key in ("area_range", "area_increase", "max_load_drift", "min_P0", "breaches", "negative_P0"):
            assert one.info["checks"][key] == two.info["checks"][key] == again[key], key
        assert one.info["checks"]["min_P0"] == float(P.min())
        assert one.info["checks"] == again  # every check of the one-load fast path, as the full path finds it
        clean += not again["breaches"] and again["min_P0"] >= 0.0
    assert clean >= 20  # (the fast path's own cases are among the draws)


def _solution(P, ratio, check=True):
    pr = pf.ContactProblem.reference(p_bar_ratio=ratio)
    p = np.linspace(0.0, 1.0, P.shape[-1])
    w = np.full(p.size, p[1])
    A = np.ones(P.shape[:-1])  # areas and loads given: only the positivity of P is under test
    load = np.broadcast_to(pr.p_bar, A.shape)
    return Solution.build("test", pr, [pr.zeta_max], p, P, w, "point", 0.0, contact_area=A, load=load, check=check)


@pytest.mark.parametrize(
    ("dips", "breach"),
    [
        ((-0.005, -0.0005), False),  # both within 1 % of their own peak
        ((-0.005, -0.002), True),  # the second load dips 2 % of its (small) peak: a breach
        ((0.0, -0.002), True),
        ((-0.02, 0.0), True),
    ],
)
def test_positivity_per_load_against_its_own_peak(dips, breach):
    P = np.zeros((1, 2, 50))
    P[0, 0, 20], P[0, 1, 20] = 1.0, 0.1  # peaks 1 and 0.1
    P[0, 0, 5], P[0, 1, 5] = dips
    with pytest.warns(RuntimeWarning):
        sol = _solution(P, [0.5, 1.0], check=False)
    assert ("positivity" in sol.info["checks"]["breaches"]) == breach
    assert sol.info["checks"]["negative_P0"] == (min(dips) < 0)


def test_one_element_shortcuts_find_a_breach():
    P = np.zeros((1, 1, 50))
    P[0, 0, 20] = 1.0
    sol = _solution(P, 0.5)
    assert sol.info["checks"]["breaches"] == [] and not sol.info["checks"]["negative_P0"]
    P[0, 0, 3] = -0.5
    with pytest.raises(pf.SolverError, match="positivity"):
        _solution(P, 0.5)


def test_round_off_dips_of_one_row_are_bounded_not_weighed():
    """A one-load, one-station sines result dips to ~-2e-15 (round-off of a 4.45 peak): the shortcut reports no
    undershoot and bounds the negative mass from above by -min(P0) x the grid's width (the exact integral is
    computed by the general path, here by hand)."""
    from persson_fp.results.invariants import check_invariants

    sol = pf.solve(pf.ContactProblem.reference(), "sines")
    P = sol.P0_all
    assert P.size == P.shape[-1]
    checks = check_invariants(sol)
    assert checks["negative_P0"] is False and checks["breaches"] == []
    exact_negative_mass = float(np.sum(np.maximum(-P[0, 0], 0.0) * sol.weights))
    assert exact_negative_mass <= checks["negative_mass"] <= -P.min() * float(np.sum(sol.weights)) + 1e-300
