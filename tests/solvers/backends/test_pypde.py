"""The py-pde backend: agreement with pf.exact, refinement, instability, optional import.

One numba-compiled run (the defaults) is enough; everything else uses backend="numpy" on small
grids so that the file stays fast (numba compilation costs 5-20 s per configuration).
"""

import subprocess
import sys

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.results.solution import InstabilityError
from persson_fp.solvers import get_solver

pde = pytest.importorskip("pde")

ZETA = [4.0, 32.0, 128.0]


def _solve(fudge=None, **opts):
    return pf.solve(pf.ContactProblem.reference(fudge=fudge), method="py-pde", zeta_out=ZETA, **opts)


@pytest.mark.slow
def test_defaults_meet_promise_compiled():
    """Defaults (numba, euler, n_p=800): promised L1 <= 1e-4; measured ~5e-6 (YP08)."""
    sol = _solve("YP08")
    err = sol.compare()
    assert err.max_L1 <= 1e-4, str(err)
    assert err.max_area_error <= 1e-4
    assert sol.info["compile_time"] > 0
    assert sol.wall_time > 0
    # the compiled stepper ran the planned fixed steps, nothing more
    assert sol.info["backend"] == "numba" and sol.info["steps"] == sol.info["steps_requested"]
    assert sol.info["checks"]["area_monotone"] and not sol.info["checks"]["negative_P0"]
    assert sol.info["S"].startswith("YP08")
    assert np.allclose(sol.zeta, ZETA)


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_numpy_backend_agrees_with_exact_and_refines(fudge):
    errs = []
    for n_p in (50, 100):
        sol = _solve(fudge, backend="numpy", n_p=n_p)
        errs.append(sol.compare().max_L1)
        assert sol.info["checks"]["area_monotone"]
        assert sol.info["checks"]["max_load_drift"] < 1e-3
    assert errs[1] <= 2e-3
    assert errs[1] < errs[0] / 3  # 2nd order in dp (r = 1/6 steps)


def test_scipy_solver_and_batch_loads():
    pr = pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=np.array([0.3, 1.0]))
    sol = pf.solve(pr, method="py-pde", solver="scipy", backend="numpy", n_p=100, rtol=1e-6)
    assert sol.P0.shape == (1, 2, 100)
    assert sol.compare().max_L1 <= 2e-3
    assert sol.info["rhs_evaluations"] > 0


def test_explicit_above_limit_is_refused_or_raises():
    with pytest.raises(ValueError, match="explicit stability limit"):
        _solve(backend="numpy", n_p=100, n_steps=20)
    with pytest.raises(InstabilityError):
        _solve(backend="numpy", n_p=100, n_steps=60, allow_unstable=True)


def test_fixed_point_implicit_fails_above_explicit_limit():
    with pytest.raises(InstabilityError, match="fixed-point"):
        _solve(backend="numpy", n_p=60, solver="implicit", cfl=1.5)


def test_bad_options():
    with pytest.raises(ValueError, match="solver must be one of"):
        _solve(solver="rk45")
    with pytest.raises(ValueError, match="backend"):
        _solve(backend="jax")
    with pytest.raises(TypeError, match="unknown option"):
        _solve(n_pp=10)


def test_import_is_lazy_and_missing_extra_is_named(monkeypatch):
    code = "import persson_fp, sys; assert 'pde' not in sys.modules and 'fipy' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)
    monkeypatch.setitem(sys.modules, "pde", None)
    with pytest.raises(ImportError, match=r"persson-fp\[pde\]"):
        get_solver("py-pde")


@pytest.mark.slow  # two compilations by numba (~11 s)
def test_compiled_stepper_is_reused_by_an_identical_call():
    """py-pde freezes grid, time map and S into its stepper; the same call again reuses it (no recompile)."""
    a = _solve("YP08")
    b = _solve("YP08")
    assert b.info["stepper_cached"]
    np.testing.assert_array_equal(a.P0, b.P0)  # the same compiled stepper from the same start: bitwise
    # a new grid is a new stepper (numpy backend: nothing to compile, but the same cache rule)
    c = _solve(None, backend="numpy", n_p=37)
    assert not c.info["stepper_cached"] and _solve(None, backend="numpy", n_p=37).info["stepper_cached"]
    assert c.compare().max_L1 < 1e-2  # 37 cells, r = 1/6: L1 ~ 1e-4 against pf.exact
