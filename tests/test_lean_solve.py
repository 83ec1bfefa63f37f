"""The lean path of a one-load ``pf.solve(..., "sines")`` call (issue 21) keeps every check: options passed are
validated (those left at their defaults are not re-validated), the invariants still raise on a breach, NaN or inf
in P0 is still an InstabilityError, and the shortcuts (Python floats for one station and one load, the extrema of
P0 taken once) decide exactly as the general path."""

import math
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp._validate import as_positive_scalar
from persson_fp.results.invariants import check_invariants
from persson_fp.results.solution import Solution


@pytest.mark.parametrize(
    ("option", "value"),
    [("tol", 0.5), ("tol", -1.0), ("tol", float("nan")), ("rtol", 1.0), ("k_domain", 2.0), ("k_domain", True)],
)
def test_sines_options_passed_are_still_validated(option, value):
    with pytest.raises(ValueError, match=option):
        pf.solve(pf.ContactProblem.reference(), "sines", **{option: value})


def test_sines_options_at_their_defaults_are_the_class_defaults():
    from persson_fp.solvers.sines import SineSeriesSolver

    sv = SineSeriesSolver(pf.ContactProblem.reference(), tol=1e-10)
    assert sv.given == {"tol"}
    assert sv.opts["tol"] == 1e-10 and sv.opts["rtol"] == SineSeriesSolver.OPTIONS["rtol"]


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


def test_whole_sines_call_checks_and_estimates():
    """The lean call still records its checks and has the true error at hand (sol.error_estimate)."""
    sol = pf.solve(pf.ContactProblem.reference(), "sines")
    assert sol.info["checks"]["breaches"] == []
    est = sol.error_estimate
    assert est["kind"].startswith("true error") and float(np.max(est["L1"])) < 1e-12
