"""No silent wrong answers: invariant breaches raise, extreme loads are accurate or refused,
bad input is a ValueError naming the argument, resources are estimated before they are spent.

Every case of a wrong answer once found is one parametrized case here; the references are the closed form
(:func:`persson_fp.exact`, ``eq:Area_Persson``) or the exact cell averages built from it.
"""

import warnings

import numpy as np
import pytest
from scipy.special import ndtr

import persson_fp as pf
from persson_fp.results.solution import Solution, check_invariants
from persson_fp.solvers import available_methods, get_solver

REF = pf.ContactProblem.reference


# -- the invariant check, on manufactured solutions -------------------------------------------------------
def _exact_cells(problem, zeta, n_p=400, k=10.0):
    """Exact cell averages of P0 on [0, p_bar + k sqrt(tau)] (the reference a cell method aims at)."""
    edges = np.linspace(0.0, problem.p_max(k), n_p + 1)
    ex = pf.exact(problem, np.atleast_1d(zeta))
    P = np.diff(np.asarray(ex.cdf_contact(edges)).reshape(np.size(zeta), problem.n_loads, -1), axis=-1)
    return edges, P / np.diff(edges)


def _build(problem, zeta, P, edges, check=True):
    centres = 0.5 * (edges[1:] + edges[:-1])
    return Solution.build("manufactured", problem, zeta, centres, P, np.diff(edges), "cell", 0.0, check=check)


def test_exact_cell_averages_pass_every_invariant():
    pr = REF(fudge="YP08", p_bar_ratio=[1e-6, 0.5, 3.0])
    zeta = np.array([4.0, 32.0, 128.0])
    edges, P = _exact_cells(pr, zeta)
    sol = _build(pr, zeta, P, edges)
    assert sol.info["checks"]["breaches"] == []
    # midpoint quadrature of int p P0 dp on 400 cells: drift O((dp/sqrt(tau))^2 / 24) ~ 1e-5, far below 1 %
    assert sol.info["checks"]["max_load_drift"] < 1e-4


def _scaled(P):
    return 1.05 * P  # 5 % too much mass and load


def _swapped(P):
    return P[::-1].copy()  # A* grows with zeta


def _dip(P):
    Q = P.copy()
    Q[-1, 0, 0] = -0.05 * Q[-1, 0].max()  # a negative undershoot of 5 % of the peak at the wall
    return Q


def _over_one(P):
    return 3.0 * P  # A* ~ 1.1 at the last station of the full-contact load


@pytest.mark.parametrize(
    ("breach", "invariant", "ratio"),
    [(_scaled, "load_balance", 0.5), (_swapped, "area_monotone", 0.5), (_dip, "positivity", 0.5),
     (_over_one, "area_range", 0.5)],
    ids=["load", "monotone", "positivity", "range"],
)  # fmt: skip
def test_a_breach_raises_solver_error_naming_the_invariant(breach, invariant, ratio):
    pr = REF(p_bar_ratio=ratio)
    zeta = np.array([4.0, 128.0])
    edges, P = _exact_cells(pr, zeta)
    with pytest.raises(pf.SolverError, match=invariant) as err:
        _build(pr, zeta, breach(P), edges)
    assert "check=False" in str(err.value)  # the remedy is named
    with pytest.warns(RuntimeWarning, match=invariant):
        sol = _build(pr, zeta, breach(P), edges, check=False)
    assert invariant in sol.info["checks"]["breaches"]


def test_non_finite_field_is_an_instability():
    pr = REF()
    edges, P = _exact_cells(pr, 128.0)
    P[0, 0, 3] = np.nan
    with pytest.raises(pf.InstabilityError):
        _build(pr, 128.0, P, edges, check=False)


def test_monotonicity_is_checked_relative_to_a_tiny_area():
    """A* ~ 8e-9 (p_bar / sqrt(V) = 1e-8): a growth of 1e-12 is 1e-4 relative -- a breach, although tiny."""
    pr = REF(p_bar_ratio=1e-8)
    zeta = np.array([64.0, 128.0])
    edges, P = _exact_cells(pr, zeta)
    P[1] = P[0] * (1.0 + 1e-4)
    with pytest.raises(pf.SolverError, match="area_monotone"):
        _build(pr, zeta, P, edges)
    with pytest.warns(RuntimeWarning):
        sol = _build(pr, zeta, P, edges, check=False)
        checks = check_invariants(sol, {"area": 2e-4}, raise_on_breach=False)  # a looser tolerance admits it
    assert checks["breaches"] == [] and checks["area_increase"] == pytest.approx(1e-4, rel=1e-6)


def test_an_area_drained_to_round_off_is_not_read_as_growth():
    """A drift into the wall leaves A* ~ 1e-160 after A* ~ 0.4: its round-off (a growth of 1e-4 of 1e-160) is judged
    against 1e-13 of the load's largest area, not against itself; the same relative growth of an area that is
    still a tenth of the largest is a breach."""
    pr = REF(p_bar_ratio=0.5)
    zeta = np.array([4.0, 64.0, 128.0])
    edges, P = _exact_cells(pr, zeta)
    for level, breach in ((1e-160, False), (0.1, True)):
        Q = P.copy()
        Q[1] = P[0] * level
        Q[2] = P[0] * level * (1.0 + 1e-4)
        with pytest.warns(RuntimeWarning):
            sol = _build(pr, zeta, Q, edges, check=False)
        checks = check_invariants(sol, {"area": 1e-6}, raise_on_breach=False)
        assert ("area_monotone" in checks["breaches"]) is breach


def test_compare_reports_the_relative_area_error():
    """Cell averages scaled by 1 + 1e-3: |dA*|/A* = 1e-3 for every load (the cells hold A* to ~1e-20, the tail
    beyond k = 10 sigma), while |dA*| itself is ~8e-10 for the tiny load."""
    pr = REF(p_bar_ratio=[1e-6, 0.5])
    edges, P = _exact_cells(pr, 128.0)
    c = _build(pr, 128.0, P * (1.0 + 1e-3), edges).compare()
    np.testing.assert_allclose(c.area_error_rel[-1], 1e-3, rtol=1e-9)
    assert c.area_error[-1, 0] < 1e-9
    assert c.final()["area_error_rel"] == pytest.approx(1e-3, rel=1e-9)
    assert "|dA*|/A*" in str(c)


# -- extreme loads: accurate or refused, naming the method that handles them ------------------------------
@pytest.mark.parametrize(
    ("method", "ratio", "match"),
    [
        ("chapman-kolmogorov", 1e-100, "chapman-kolmogorov.*below 1e-10.*'sines'.*pf.exact"),
        ("fv", 1e-100, "fv.*below 1e-10.*'sines'.*pf.exact"),
        ("fv", 1e-20, "fv.*below 1e-10"),
        ("mol", 1e5, "mol.*needs n_p.*pf.exact"),
        ("mol", 1e6, "mol.*needs n_p.*pf.exact"),
        ("fv", 1e5, "fv.*not resolved.*'sines'"),
        ("sines", 1e5, "sines.*modes.*pf.exact"),
    ],
)
def test_extreme_load_is_refused_naming_a_method_that_handles_it(method, ratio, match):
    with pytest.raises(ValueError, match=match):
        pf.solve(REF(p_bar_ratio=ratio), method)


@pytest.mark.parametrize("ratio", [1e-100, 1e-20, 1e-8, 1e3])
def test_the_named_handler_sines_is_exact_there(ratio):
    """'sines' (named by the refusals) at the loads refused by fv / chapman-kolmogorov: A* to 1e-9 relative
    (measured <= 3e-12 over random problems; the series' own tolerance is 1e-13)."""
    pr = REF(p_bar_ratio=ratio)
    assert pf.solve(pr, "sines").compare().max_area_error_rel < 1e-9


@pytest.mark.parametrize("fudge", [None, "YP08"])
@pytest.mark.parametrize("ratio", [1e-8, 1e-6, 1e-4, 1e3])
def test_mol_keeps_relative_accuracy_at_extreme_loads(ratio, fudge):
    """mol at its defaults (rtol = 1e-5, atol scaled to each load's A*): |dA*|/A* within 10 rtol = 1e-4
    (measured 9.4e-6 at every load from 1e-8 to 1e3; before the scaling: 5.5 % at 1e-8, 3 % at 1e-6)."""
    sol = pf.solve(REF(p_bar_ratio=ratio, fudge=fudge), "mol")
    assert sol.compare().max_area_error_rel < 1e-4


@pytest.mark.parametrize("method", ["fv", "mol", "sines", "chapman-kolmogorov"])
def test_far_wall_too_close_is_refused(method):
    """k_domain = 1 lost 82 % of the load in fv without a word.  (Monte Carlo keeps its k_domain > 0: there it
    bounds only the histogram; walkers above it still count in A* and the load.)"""
    with pytest.raises(ValueError, match="k_domain must lie in"):
        pf.solve(REF(), method, k_domain=1.0)


def test_monte_carlo_refuses_loads_with_too_few_walkers_in_contact():
    with pytest.raises(ValueError, match="n_walkers.*'sines'"):
        pf.solve(REF(p_bar_ratio=[1e-4, 1e-2, 0.5]), "monte-carlo", seed=1)


def test_monte_carlo_load_is_the_walkers_mean_with_its_standard_error():
    """The load balance of a batch is checked on the walkers' mean pressure (unbiased: killed Brownian motion is
    a martingale), not on the histogram (which put the drift of a small load at 173x): within 6 standard errors."""
    pr = REF(p_bar_ratio=[0.05, 0.5])
    sol = pf.solve(pr, "monte-carlo", n_walkers=50_000, n_steps=8, seed=7)
    c = sol.compare()
    assert c.stderr_load is not None
    assert np.all(c.load_drift <= 6.0 * c.stderr_load / pr.p_bar)


# -- bad input: a ValueError naming the argument ---------------------------------------------------------
_PSD = pf.SelfAffinePSD(1e-4, 0.8, 1.0, 2.0, 128.0)
_PR = pf.ContactProblem(_PSD, 1.0, 0.02)
_Q = np.array([1.0, 2.0, 4.0, 8.0])
_C = np.array([1.0, 0.5, 0.1, 0.01])
BAD = {
    "nan": float("nan"),
    "inf": float("inf"),
    "negative": -1.0,
    "zero": 0.0,
    "bool": True,
    "complex": 1 + 1j,
    "string": "abc",
    "empty": [],
    "wrong shape": [[1.0, 2.0]],
}
ARGUMENTS = {
    "C0": lambda v: pf.SelfAffinePSD(v, 0.8, 1, 2, 128),
    "H": lambda v: pf.SelfAffinePSD(1e-4, v, 1, 2, 128),
    "q_l": lambda v: pf.SelfAffinePSD(1e-4, 0.8, v, 2, 128),
    "q_r": lambda v: pf.SelfAffinePSD(1e-4, 0.8, 1, v, 128),
    "q_s": lambda v: pf.SelfAffinePSD(1e-4, 0.8, 1, 2, v),
    "rms_slope": lambda v: pf.SelfAffinePSD.from_rms_slope(v, 0.8, 1, 2, 128),
    "rms_height": lambda v: pf.SelfAffinePSD.from_rms_height(v, 0.8, 1, 2, 128),
    "q": lambda v: pf.TabulatedPSD(np.array([1, 2, v, 8.0]) if isinstance(v, float) else v, _C),
    "C": lambda v: pf.TabulatedPSD(_Q, np.array([1, 0.5, v, 0.01]) if isinstance(v, float) else v),
    "E_star": lambda v: pf.ContactProblem(_PSD, v, 0.02),
    "p_bar": lambda v: pf.ContactProblem(_PSD, 1.0, v),
    "p_bar_ratio": lambda v: pf.ContactProblem.reference(p_bar_ratio=v),
    "zeta": lambda v: pf.exact(_PR, v),
    "fudge": lambda v: pf.ContactProblem(_PSD, 1.0, 0.02, fudge=v),
    "gamma": lambda v: pf.fudge.YangPersson(gamma=v),
    "method": lambda v: pf.solve(_PR, v),
    "zeta_out": lambda v: pf.solve(_PR, "sines", zeta_out=v),
    "n_p": lambda v: pf.solve(_PR, "fv", n_p=v),
    "rtol": lambda v: pf.solve(_PR, "mol", rtol=v),
    "k_domain": lambda v: pf.solve(_PR, "fv", k_domain=v),
    "max_memory": lambda v: pf.solve(_PR, "sines", max_memory=v),
}
# well-defined values of some arguments (H = 0 is a valid Hurst exponent, an empty zeta an empty evaluation,
# max_memory = inf no limit)
VALID = {("H", "zero"), ("zeta", "empty"), ("max_memory", "inf")}


@pytest.mark.parametrize("value", list(BAD), ids=list(BAD))
@pytest.mark.parametrize("argument", list(ARGUMENTS))
def test_bad_input_is_a_value_error_naming_the_argument(argument, value):
    if (argument, value) in VALID:
        pytest.skip("a valid value of this argument")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # never a ComplexWarning (imaginary part dropped) instead of an error
        with pytest.raises(ValueError, match=argument) as err:
            ARGUMENTS[argument](BAD[value])
    assert "np.float64" not in str(err.value)  # plain numbers in messages


@pytest.mark.parametrize("value", [float("inf"), 1e300, True, 2.5, "8", [8], 8 + 0j])
@pytest.mark.parametrize(
    ("method", "option"),
    [(m, o) for m in available_methods() for o, d in get_solver(m).OPTIONS.items()
     if (isinstance(d, int) and not isinstance(d, bool)) or (o in ("n_p", "n_eval") and d is None)],
)  # fmt: skip
def test_every_integer_option_refuses_non_integers_and_overflow(method, option, value):
    """n_p = inf raised OverflowError in 17 options; 1e300 iterations was accepted (a hang)."""
    with pytest.raises(ValueError, match=option):
        get_solver(method)(_PR, **{option: value})


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: pf.ContactProblem(pf.SelfAffinePSD(1e308, 0.8, 1, 2, 128), p_bar=1.0), "floating-point range"),
        (lambda: pf.ContactProblem(pf.SelfAffinePSD(1e-3, 0.8, 1, 2, 128), E_star=1e308, p_bar=1.0), "E_star"),
        (lambda: pf.SelfAffinePSD(1e-3, 0.8, 1e-300, 1e-300, 1).V(), "floating-point range"),
        (lambda: pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1e-300, 2e-300, 1e-298), "q_l, q_r, q_s"),
        (lambda: pf.SelfAffinePSD.from_rms_slope(1e-320, 0.8, 1, 2, 128), "rms_slope"),
        (lambda: pf.ContactProblem(_PSD, 1.0, 0.02, fudge=lambda A: 1.0 / 0.0), "ZeroDivisionError"),
        (lambda: pf.ContactProblem(_PSD, 1.0, 0.02, fudge=lambda A: 1.0 + 1j + 0.0 * A), "complex"),
        (lambda: pf.solve(_PR, ["fv"]), "method must be .auto., one of"),
        (lambda: pf.solve(_PR, "fv", check="yes"), "check must be True or False"),
        (lambda: pf.solve(_PR, "mol", order=np.float64(-1.0)), r"order must be 2 or 4, got -1\.0"),
    ],
    ids=["V=inf", "E_star=1e308", "q=1e-300", "rms from q=1e-300", "rms_slope=1e-320", "fudge raises",
         "complex fudge", "method list", "check string", "order numpy"],
)  # fmt: skip
def test_overflow_and_odd_input_are_value_errors(make, match):
    with pytest.raises(ValueError, match=match):
        make()


# -- resources: estimated before they are spent -----------------------------------------------------------
@pytest.mark.parametrize(
    ("method", "opts", "n_loads", "match"),
    [
        ("fv", {"n_p": 10**6}, 1, "GiB of memory"),
        ("fv", {"n_p": 10**8}, 1, "GiB of memory"),
        ("mol", {"n_p": 10**7}, 1, "GiB of memory"),
        ("mol", {"n_p": 10**5}, 10**3, "GiB of memory"),
        ("monte-carlo", {"n_p": 10**9}, 1, "GiB of memory"),
        ("monte-carlo", {"n_walkers": 10**9}, 1, r"s \(estimate\)"),
    ],
)
def test_runaway_requests_are_refused_with_the_estimate(method, opts, n_loads, match):
    pr = REF(p_bar_ratio=np.geomspace(0.1, 1.0, n_loads) if n_loads > 1 else 0.5)
    with pytest.raises(ValueError, match=match):
        pf.solve(pr, method, **opts)


def test_budgets_are_overridable():
    with pytest.raises(ValueError, match="max_memory"):
        pf.solve(REF(), "fv", max_memory=1e3)
    with pytest.raises(ValueError, match="max_time"):
        pf.solve(REF(), "monte-carlo", max_time=1e-6)
    # the default budget lets the default run through, and a larger one a larger grid
    assert pf.solve(REF(), "fv", n_p=400, max_memory=2**34).compare().max_area_error_rel < 1e-4


@pytest.mark.parametrize("method", ["sines", "fv", "auto"])
def test_an_infinite_budget_is_no_limit(method):
    """max_time = inf was once refused with 'max_time must lie in (0, inf]': inf is no limit, for every method
    and for auto; the result is the one of the default budgets, to the bit."""
    sol = pf.solve(_PR, method, max_time=float("inf"), max_memory=np.inf)
    assert np.array_equal(sol.contact_area, pf.solve(_PR, method).contact_area)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"zeta_out": 1.0}, "zeta_out must lie in"),  # (was an OverflowError in auto's planning)
        ({"zeta_out": []}, "zeta_out must hold"),  # (was numpy's 'zero-size array')
        ({"max_time": float("nan")}, "max_time"),  # (was an UnboundLocalError in auto)
        ({"max_memory": -1.0}, "max_memory"),
    ],
)
def test_auto_checks_stations_and_budgets_first(kwargs, match):
    fp = pf.FokkerPlanckProblem(_PSD, p_bar=0.02, B2=lambda p, z: 2.0 * _PSD.dV_dzeta(z) * np.ones_like(p))
    for problem in (fp, _PR):
        with pytest.raises(ValueError, match=match):
            pf.solve(problem, "auto", **kwargs)


def _cells(pr, z):
    """Exact cell averages of the image solution (normal CDF differences, written here) on 400 cells."""
    edges = np.linspace(0.0, pr.p_max(10.0), 401)
    s = np.sqrt(np.asarray(pr.V(z)))[:, None, None]
    pb = pr.p_bar[None, :, None]
    F = ndtr((edges - pb) / s) - ndtr((edges + pb) / s)
    return edges, np.diff(F, axis=-1) / np.diff(edges)


def test_mass_and_moment_law_breaches_are_named():
    """A* against 1 - absorbed (mass balance) and, for general coefficients, the load against info['load_law']."""
    pr = REF()
    psd, pb = pr.psd, float(pr.p_bar[0])
    z = np.array([8.0, 128.0])
    edges, P = _cells(pr, z)
    A = P.sum(axis=-1) * np.diff(edges)[0]
    mid, w = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    ok = Solution.build("cells", pr, z, mid, P, w, "cell", 0.0, contact_area_flux=A)
    assert ok.info["checks"]["mass_balance"] < 1e-14
    with pytest.raises(pf.SolverError, match="mass_balance"):
        Solution.build("cells", pr, z, mid, P, w, "cell", 0.0, contact_area_flux=A - 1e-3)
    gen = pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, zz: psd.dV_dzeta(zz) + 0 * p)
    law = np.full((2, 1), pb)
    good = Solution.build("cells", gen, z, mid, P, w, "cell", 0.0, info={"load_law": law})
    assert good.info["checks"]["load_law"] == "first-moment law"
    with pytest.raises(pf.SolverError, match="first-moment law"):
        Solution.build("cells", gen, z, mid, P, w, "cell", 0.0, info={"load_law": 1.2 * law})
