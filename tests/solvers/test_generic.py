"""Properties every registered method must have: each test runs over the registry, ``persson_fp.solvers.METHODS``.

A method whose optional package is missing is skipped (``pytest.importorskip``); every other method runs.  Where
methods need their own options to be cheap (Monte Carlo's walkers, the backends' grids) or their own bounds (a
coarse grid, a statistical error), the tables below hold one entry per method; a method added to METHODS without an
entry fails ``test_every_method_has_an_entry_in_each_table`` (and the tests that need the entry).
"""

import sys
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers import EXTRAS, METHODS, SHARED_KNOBS, get_solver

ALL = list(METHODS)
HEAVY = {"fipy"}
"""Methods whose accuracy and batch checks take seconds here (FiPy's Python loop): in the heavy group (``-m slow``,
which CI runs too); backends/test_fipy.py checks its promise in the default run."""
ALL_HEAVY_SLOW = [pytest.param(m, marks=pytest.mark.slow) if m in HEAVY else m for m in METHODS]

OPTIONS = {  # cheap options of each method ({}: its defaults)
    "fv": {},
    "mol": {},
    "sines": {},
    "py-pde": {"backend": "numpy", "n_p": 100},  # (the default backend compiles with numba: backends/test_pypde.py)
    "fipy": {"n_p": 60, "n_steps": 20},  # (FiPy's defaults, 800 cells: backends/test_fipy.py)
    "chapman-kolmogorov": {},
    "monte-carlo": {"n_walkers": 20_000, "n_steps": 8, "seed": 1},
    "chebyshev": {},
}

SOLVES_FUDGE = {  # whether the method solves problems with a fudge factor S(A*)
    "fv": True,
    "mol": True,
    "sines": True,
    "py-pde": True,
    "fipy": True,
    "chapman-kolmogorov": True,
    "monte-carlo": True,
    "chebyshev": False,  # fudge-free only (B2 = b(p) dV/dzeta): its refusal is in chebyshev/test_refusals.py
}

PROMISED_L1 = {  # (L1 of P0 at zeta_max, L1 at every station) with OPTIONS; None: statistical (z-scores of A*)
    "fv": (1e-5, 1e-3),
    "mol": (1e-5, 1e-3),
    "sines": (1e-5, 1e-3),
    "py-pde": (2e-3, 2e-3),  # 100 cells (measured 2e-4, 4e-4)
    "fipy": (5e-3, 1e-2),  # 60 cells, 20 steps (measured 1.6e-3, 4.4e-3)
    "chapman-kolmogorov": (1e-5, 1e-3),
    "monte-carlo": None,
    "chebyshev": (1e-5, 1e-3),
}

BATCH = {  # (options added to OPTIONS, |batch - single load|, |batch - pf.exact|) of A* at zeta_max
    "fv": ({}, 5e-6, 1e-5),
    "mol": ({}, 5e-6, 1e-5),
    "sines": ({}, 5e-6, 1e-5),
    "py-pde": ({}, 5e-4, 5e-4),  # (the grid of the batch is the largest load's: measured 1.9e-4, 7.3e-5)
    "fipy": ({"n_p": 40, "n_steps": 10}, 1e-2, 1e-2),  # (4 runs with the fudge's sweeps: measured 2.7e-3, 3.6e-3)
    "chapman-kolmogorov": ({}, 5e-6, 1e-5),
    "monte-carlo": ({}, 2e-2, 2e-2),  # 5 standard errors of 20 000 walkers
    # (its default tol 1e-8 is below the round-off floor of a grid clustered at the 0.01 load: refused, naming it)
    "chebyshev": ({"tol": 1e-7}, 5e-6, 1e-5),
}

EARLY_STATION = {  # what each method does with a first station its resolution cannot follow: the refusal it raises
    "fv": (ValueError, r"not resolved by the grid.*raise n_p"),
    "mol": (ValueError, r"needs n_p = .* grid points .*start zeta_out later"),
    "sines": (ValueError, r"needs \d+ modes .*start zeta_out later"),
    "py-pde": (ValueError, r"not resolved by the grid.*raise n_p"),
    "fipy": (ValueError, r"not resolved by the grid.*raise n_p"),
    "chapman-kolmogorov": (ValueError, r"not resolved by the grid.*raise n_p"),
    # (no grid: the walkers refuse the 1e-4 load itself, which too few of them would keep in contact)
    "monte-carlo": (ValueError, r"walkers are expected to stay in contact.*raise n_walkers"),
    # (the mapped grid follows the narrow PDF, but not at its default tol 1e-8: the round-off floor of so clustered
    # a grid is above it)
    "chebyshev": (pf.SolverError, r"best reachable accuracy is about .* loosen tol"),
}

TABLES = {
    "OPTIONS": OPTIONS,
    "SOLVES_FUDGE": SOLVES_FUDGE,
    "PROMISED_L1": PROMISED_L1,
    "BATCH": BATCH,
    "EARLY_STATION": EARLY_STATION,
}

VALID_KNOB = {"n_p": 50, "n_steps": 10, "rtol": 1e-6, "atol": 1e-8, "scheme": "implicit"}
"""A valid value of each shared knob (zeta_out apart), for the methods that ignore it."""


def _entry(table: dict, method: str):
    """The method's entry of ``table``, after skipping a method whose optional package is missing."""
    if method in EXTRAS:
        pytest.importorskip(EXTRAS[method][0])
    assert method in table, f"METHODS has {method!r}, the table of this test has no entry for it: add one"
    return table[method]


def _ignored_knobs(method: str) -> list[str]:
    """The shared knobs the method does not use (it warns that it ignores them)."""
    return [k for k in SHARED_KNOBS if k != "zeta_out" and k not in get_solver(method).OPTIONS]


@pytest.mark.parametrize("table", list(TABLES))
def test_every_method_has_an_entry_in_each_table(table):
    assert set(TABLES[table]) == set(METHODS), f"{table}: add the missing methods, drop the unknown ones"


def test_registry_names_and_unknown_method():
    assert {"fv", "mol", "sines", "py-pde", "fipy", "chapman-kolmogorov", "monte-carlo", "chebyshev"} <= set(METHODS)
    with pytest.raises(ValueError, match="method must be .auto., one of"):
        pf.solve(pf.ContactProblem.reference(), method="finite-volume")


def test_importing_the_package_does_not_import_optional_backends():
    import subprocess

    packages = sorted(pkg for pkg, _ in EXTRAS.values())
    assert packages == ["fipy", "pde"]
    code = "import persson_fp, sys; assert 'pde' not in sys.modules and 'fipy' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize("method,pkg,extra", [(m, *EXTRAS[m]) for m in EXTRAS])
def test_missing_extra_names_the_pip_extra(monkeypatch, method, pkg, extra):
    monkeypatch.setitem(sys.modules, pkg, None)  # makes `import pkg` raise ImportError
    with pytest.raises(ImportError, match=rf"persson-fp\[{extra}\]"):
        get_solver(method)


@pytest.mark.parametrize("method", ALL)
def test_option_validation(method):
    _entry(OPTIONS, method)
    pr = pf.ContactProblem.reference()
    with pytest.raises(TypeError, match="unknown option"):
        pf.solve(pr, method=method, n_pp=10)
    with pytest.raises(ValueError, match="zeta_out"):
        pf.solve(pr, method=method, zeta_out=[200.0])
    with pytest.raises(ValueError, match="zeta_out"):
        pf.solve(pr, method=method, zeta_out=[50.0, 20.0])


@pytest.mark.parametrize("method", ALL_HEAVY_SLOW)
@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_defaults_meet_promised_accuracy(method, fudge):
    """Every method reaches its promised accuracy on the reference problem with its defaults (the backends and Monte
    Carlo: the cheap options of OPTIONS): the own deterministic methods L1 <= 1e-5 at zeta_max and below 1e-3 at
    early stations (where fixed-step defaults spend few steps), Monte Carlo A* within 5 standard errors."""
    options = _entry(OPTIONS, method)
    if fudge is not None and not _entry(SOLVES_FUDGE, method):
        pytest.skip(f"{method} solves fudge-free problems only")
    promised = _entry(PROMISED_L1, method)
    pr = pf.ContactProblem.reference(fudge=fudge)
    sol = pf.solve(pr, method=method, zeta_out=[4.0, 32.0, 128.0], **options)
    err = sol.compare()
    assert err.L1.shape == (3, 1)
    if promised is None:  # statistical: A* within 5 standard errors at every station
        assert np.all(err.area_z_score < 5), str(err)
    else:
        final, early = promised
        assert err.L1[-1, 0] <= final, str(err)
        assert err.area_error[-1, 0] <= final
        assert err.max_L1 <= early, str(err)
    assert sol.info["checks"]["area_monotone"]
    assert sol.wall_time > 0
    assert np.all(np.diff(sol.contact_area) <= 1e-12)


@pytest.mark.parametrize("method", ALL_HEAVY_SLOW)
def test_batched_loads_equal_single_loads(method):
    options = _entry(OPTIONS, method)
    extra, tol_single, tol_exact = _entry(BATCH, method)
    options = {**options, **extra}
    fudge = "WM17" if _entry(SOLVES_FUDGE, method) else None  # (fudge-free methods: the same loads without S)
    ratios = np.array([0.01, 0.5, 3.0])
    batch = pf.solve(pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=ratios), method=method, **options)
    assert batch.P0.shape[:2] == (1, 3)
    for j, r in enumerate(ratios):
        single = pf.solve(pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=r), method=method, **options)
        A_single = single.contact_area[-1]
        # the same answer up to what the (common, larger) grid of the batch changes
        assert batch.contact_area_all[-1, j] == pytest.approx(A_single, abs=tol_single)
        ex = pf.exact(pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=r)).contact_area
        assert batch.contact_area_all[-1, j] == pytest.approx(ex, abs=tol_exact)


@pytest.mark.parametrize("method", ALL)
def test_shared_knob_ignored_warns(method):
    """Each shared knob a method does not use is accepted with a warning that names it (sines: scheme, ...)."""
    options = _entry(OPTIONS, method)
    ignored = _ignored_knobs(method)
    assert ignored, f"{method} uses every shared knob"
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        pf.solve(pf.ContactProblem.reference(), method=method, **{**options, **{k: VALID_KNOB[k] for k in ignored}})
    for knob in ignored:
        assert any(f"ignores the option {knob!r}" in str(x.message) for x in w), knob


@pytest.mark.parametrize("method", ALL)
def test_an_ignored_knob_out_of_range_is_still_an_error(method):
    """`atol=-1` with fv (which ignores atol) only warned; a value outside a knob's range is wrong for every method,
    whether it uses the knob or ignores it."""
    options = _entry(OPTIONS, method)
    ignored = _ignored_knobs(method)
    pr = pf.ContactProblem.reference()
    for knob, bad, match in (
        ("atol", -1, r"atol must lie in \[0, inf\]" if "atol" in ignored else r"atol must lie in"),
        ("rtol", -1, r"rtol must lie in"),
        ("n_steps", 0, r"n_steps must be an integer"),
    ):
        with pytest.raises(ValueError, match=match):
            pf.solve(pr, method=method, **{**options, knob: bad})
    for knob in ("atol", "rtol", "n_steps"):
        if knob in ignored:
            with pytest.warns(UserWarning, match=f"ignores the option '{knob}'"):
                get_solver(method)(pr, **{**options, knob: VALID_KNOB[knob]})


@pytest.mark.parametrize("method", ALL)
def test_unresolved_first_station_is_refused_not_smeared(method):
    """An early station that the method cannot resolve raises (naming the remedy) instead of spoiling later ones."""
    options = _entry(OPTIONS, method)
    error, match = _entry(EARLY_STATION, method)
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([1e-4, 0.5, 3.0]))
    with pytest.raises(error, match=match):
        pf.solve(pr, method=method, zeta_out=[1.002, 128.0], **options)


@pytest.mark.parametrize("method", ALL)
def test_flags_and_domain_are_validated(method):
    _entry(OPTIONS, method)
    pr = pf.ContactProblem.reference()
    if "allow_unstable" in get_solver(method).OPTIONS:
        with pytest.raises(ValueError, match="allow_unstable must be True or False"):
            pf.solve(pr, method=method, allow_unstable="False")
    else:  # (a method without a stability limit has no such flag)
        with pytest.raises(TypeError, match="unknown option 'allow_unstable'"):
            pf.solve(pr, method=method, allow_unstable=False)
    with pytest.raises(ValueError, match="k_domain must lie in"):
        pf.solve(pr, method=method, k_domain=1e6)
    with pytest.raises(ValueError, match="n_p must be an integer"):
        pf.solve(pr, method=method, n_p=True)


@pytest.mark.parametrize("method", ALL)
def test_methods_without_the_general_path_refuse(method):
    """A method that does not declare general coefficients (``SUPPORTS``) refuses them, naming the ones that solve
    them; one that declares them accepts the problem.  pf.exact has no closed form for it either way."""
    _entry(OPTIONS, method)
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=64.0)
    fp = pf.FokkerPlanckProblem(psd, p_bar=0.02, B1=lambda p, z: 0.0 * p)
    if "general" in get_solver(method).SUPPORTS:
        assert get_solver(method)(fp).problem is fp  # (built, not run)
    else:
        with pytest.raises(ValueError, match="does not solve general Fokker-Planck"):
            pf.solve(fp, method=method)
    with pytest.raises(ValueError, match="no closed form"):
        pf.exact(fp)
