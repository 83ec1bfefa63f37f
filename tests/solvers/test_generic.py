"""Properties every registered method must have, parametrized over the registry."""

import sys
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers import METHODS, get_solver

OWN = [m for m in ("fv", "mol", "sines", "chapman-kolmogorov") if m in pf.available_methods()]
GENERIC = [m for m in ("py-pde", "fipy") if m in pf.available_methods()]


def test_registry_names_and_unknown_method():
    assert {"fv", "mol", "sines", "py-pde", "fipy", "chapman-kolmogorov", "monte-carlo"} <= set(METHODS)
    with pytest.raises(ValueError, match="method must be .auto., one of"):
        pf.solve(pf.ContactProblem.reference(), method="finite-volume")


def test_importing_the_package_does_not_import_optional_backends():
    import subprocess

    code = "import persson_fp, sys; assert 'pde' not in sys.modules and 'fipy' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize("method,pkg,extra", [("py-pde", "pde", "pde"), ("fipy", "fipy", "fipy")])
def test_missing_extra_names_the_pip_extra(monkeypatch, method, pkg, extra):
    monkeypatch.setitem(sys.modules, pkg, None)  # makes `import pkg` raise ImportError
    with pytest.raises(ImportError, match=rf"persson-fp\[{extra}\]"):
        get_solver(method)


@pytest.mark.parametrize(
    "method", OWN + GENERIC + ["monte-carlo"] if "monte-carlo" in pf.available_methods() else OWN + GENERIC
)
def test_option_validation(method):
    pr = pf.ContactProblem.reference()
    with pytest.raises(TypeError, match="unknown option"):
        pf.solve(pr, method=method, n_pp=10)
    with pytest.raises(ValueError, match="zeta_out"):
        pf.solve(pr, method=method, zeta_out=[200.0])
    with pytest.raises(ValueError, match="zeta_out"):
        pf.solve(pr, method=method, zeta_out=[50.0, 20.0])


@pytest.mark.parametrize("method", OWN)
@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_defaults_meet_promised_accuracy(method, fudge):
    """Every own method's defaults reach L1 <= 1e-5 at zeta_max on the reference problem (issue 3),
    and stay below 1e-3 at early stations (where fixed-step defaults spend few steps)."""
    pr = pf.ContactProblem.reference(fudge=fudge)
    sol = pf.solve(pr, method=method, zeta_out=[4.0, 32.0, 128.0])
    err = sol.compare()
    assert err.L1.shape == (3, 1)
    assert err.L1[-1, 0] <= 1e-5, str(err)
    assert err.area_error[-1, 0] <= 1e-5
    assert err.max_L1 <= 1e-3, str(err)
    assert sol.info["checks"]["area_monotone"]
    assert sol.wall_time > 0
    assert np.all(np.diff(sol.contact_area) <= 1e-12)


@pytest.mark.parametrize("method", OWN)
def test_batched_loads_equal_single_loads(method):
    ratios = np.array([0.01, 0.5, 3.0])
    batch = pf.solve(pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=ratios), method=method)
    assert batch.P0.shape[:2] == (1, 3)
    for j, r in enumerate(ratios):
        single = pf.solve(pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=r), method=method)
        A_single = single.contact_area[-1]
        # the same answer up to what the (common, larger) grid of the batch changes
        assert batch.contact_area_all[-1, j] == pytest.approx(A_single, abs=5e-6)
        ex = pf.exact(pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=r)).contact_area
        assert batch.contact_area_all[-1, j] == pytest.approx(ex, abs=1e-5)


def test_shared_knob_ignored_warns():
    if "sines" not in pf.available_methods():
        pytest.skip("sines not built")
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        pf.solve(pf.ContactProblem.reference(), method="sines", scheme="implicit")
    assert any("ignores the option 'scheme'" in str(x.message) for x in w)


@pytest.mark.parametrize(
    "method", [m for m in ("fv", "chapman-kolmogorov", "py-pde", "fipy") if m in pf.available_methods()]
)
def test_unresolved_first_station_is_refused_not_smeared(method):
    """An early station that the grid cannot resolve raises (naming n_p) instead of spoiling later ones."""
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([1e-4, 0.5, 3.0]))
    with pytest.raises(ValueError, match=r"not resolved by the grid.*raise n_p"):
        pf.solve(pr, method=method, zeta_out=[1.002, 128.0])


def test_early_station_with_enough_cells_is_accurate_everywhere():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([1e-4, 0.5, 3.0]))
    sol = pf.solve(pr, method="fv", zeta_out=[1.05, 128.0], n_p=2000)
    err = sol.compare()
    assert err.L1[-1].max() < 2e-5 and err.load_drift.max() < 1e-10


@pytest.mark.parametrize("method", [m for m in ("fv", "py-pde", "fipy") if m in pf.available_methods()])
def test_flags_and_domain_are_validated(method):
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="allow_unstable must be True or False"):
        pf.solve(pr, method=method, allow_unstable="False")
    with pytest.raises(ValueError, match="k_domain must lie in"):
        pf.solve(pr, method=method, k_domain=1e6)
    with pytest.raises(ValueError, match="n_p must be an integer"):
        pf.solve(pr, method=method, n_p=True)
