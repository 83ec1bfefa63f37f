"""The FiPy backend: agreement with pf.exact, refinement, sweeps, instability, optional import."""

import subprocess
import sys

import pytest

import persson_fp as pf
from persson_fp.results.solution import InstabilityError
from persson_fp.solvers import get_solver

fipy = pytest.importorskip("fipy")

ZETA = [4.0, 32.0, 128.0]


def _solve(fudge=None, **opts):
    return pf.solve(pf.ContactProblem.reference(fudge=fudge), method="fipy", zeta_out=ZETA, **opts)


@pytest.mark.parametrize("fudge", [None, pytest.param("YP08", marks=pytest.mark.slow)])
def test_defaults_meet_promise(fudge):
    """Defaults (CN, n_p=800, 200 steps): promised L1 <= 1e-3; measured ~3e-5 / 6e-5."""
    sol = _solve(fudge)
    err = sol.compare()
    assert err.max_L1 <= 1e-3, str(err)
    assert err.max_area_error <= 1e-3
    assert sol.info["checks"]["area_monotone"] and not sol.info["checks"]["negative_P0"]
    if fudge is not None:
        assert sol.info["sweeps"] >= sol.info["steps"] and sol.info["sweeps_capped"] == 0


@pytest.mark.slow
def test_refinement_and_linear_solvers():
    coarse = _solve("YP08", n_p=100, n_steps=25).compare().max_L1
    fine = _solve("YP08", n_p=200, n_steps=50).compare().max_L1
    assert fine < coarse / 3
    pcg = _solve("YP08", n_p=200, n_steps=50, linear_solver="pcg").compare().max_L1
    assert pcg == pytest.approx(fine, rel=1e-4)


def test_explicit_scheme_stable_and_unstable():
    sol = _solve(None, scheme="explicit", n_p=40)
    assert sol.compare().max_L1 <= 5e-3
    with pytest.raises(ValueError, match="explicit stability limit"):
        _solve(None, scheme="explicit", n_p=40, n_steps=10)
    with pytest.raises(InstabilityError):
        # a one-cell delta holds every mode, so the unstable sawtooth shows within a few steps
        _solve(None, scheme="explicit", n_p=40, n_steps=20, initial="delta", allow_unstable=True)


def test_implicit_is_first_order_but_correct():
    sol = _solve("YP08", scheme="implicit", n_p=100, n_steps=60)
    assert sol.compare().max_L1 <= 3e-2  # 1st order: ~2.5e-2 here, CN gets ~1e-3 with these steps
    assert sol.info["checks"]["area_monotone"]


def test_bad_options():
    with pytest.raises(ValueError, match="scheme must be one of"):
        _solve(scheme="tr-bdf2")
    with pytest.raises(ValueError, match="linear_solver"):
        _solve(linear_solver="gmres")
    with pytest.raises(ValueError, match="sweep_tol"):
        _solve(sweep_tol=-1.0)


def test_import_is_lazy_and_missing_extra_is_named(monkeypatch):
    code = "import persson_fp, sys; assert 'pde' not in sys.modules and 'fipy' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)
    monkeypatch.setitem(sys.modules, "fipy", None)
    with pytest.raises(ImportError, match=r"persson-fp\[fipy\]"):
        get_solver("fipy")
