"""The solver classes stay importable from the module paths they had before the solvers got one folder per family
(for one release), and ``METHODS`` names each class where it lives now."""

from __future__ import annotations

import importlib

import pytest

from persson_fp.solvers import METHODS, get_solver

OLD_PATHS = {
    "fv": ("persson_fp.solvers.fv", "FiniteVolumeSolver"),
    "mol": ("persson_fp.solvers.mol", "MethodOfLinesSolver"),
    "sines": ("persson_fp.solvers.sines", "SineSeriesSolver"),
    "chebyshev": ("persson_fp.solvers.chebyshev", "ChebyshevSolver"),
    "chapman-kolmogorov": ("persson_fp.solvers.chapman_kolmogorov", "ChapmanKolmogorovSolver"),
    "monte-carlo": ("persson_fp.solvers.monte_carlo", "MonteCarloSolver"),
    "py-pde": ("persson_fp.solvers.backends.pypde", "PyPDESolver"),
    "fipy": ("persson_fp.solvers.backends.fipy", "FiPySolver"),
}


def test_every_method_has_an_old_path():
    assert set(OLD_PATHS) == set(METHODS)


@pytest.mark.parametrize("method", sorted(OLD_PATHS))
def test_old_path_gives_the_registered_class(method):
    module, name = OLD_PATHS[method]
    if method in ("py-pde", "fipy"):
        pytest.importorskip({"py-pde": "pde", "fipy": "fipy"}[method])
    assert getattr(importlib.import_module(module), name) is get_solver(method)
    new_module, new_name = METHODS[method].split(":")
    assert getattr(importlib.import_module(new_module), new_name) is get_solver(method)


def test_fv_operators_stay_at_the_fv_path():
    """The fv operators the documentation names (``persson_fp.solvers.fv.rhs`` ...) are where it says."""
    fv = importlib.import_module("persson_fp.solvers.fv")
    for name in ("rhs", "banded_operator", "dst_eigenvalues", "apply_operator", "apply_mass", "wall_flux"):
        assert callable(getattr(fv, name)), name
