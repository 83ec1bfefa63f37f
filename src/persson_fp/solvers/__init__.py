"""Numerical solvers behind :func:`persson_fp.solve`, one module per method.

``METHODS`` maps a method name to ``"module:Class"``; a module is imported
only when its method is chosen, so the optional py-pde and FiPy backends cost
nothing unless used (cf. ``scipy.integrate.solve_ivp``'s ``METHODS``).
"""

from __future__ import annotations

import importlib

from .base import SHARED_KNOBS, Solver, SolverOutput

__all__ = ["METHODS", "EXTRAS", "solve", "get_solver", "available_methods", "Solver", "SolverOutput", "SHARED_KNOBS"]

METHODS = {
    "fv": "persson_fp.solvers.fv:FiniteVolumeSolver",
    "mol": "persson_fp.solvers.mol:MethodOfLinesSolver",
    "sines": "persson_fp.solvers.sines:SineSeriesSolver",
    "py-pde": "persson_fp.solvers.pypde:PyPDESolver",
    "fipy": "persson_fp.solvers.fipy_backend:FiPySolver",
    "chapman-kolmogorov": "persson_fp.solvers.chapman_kolmogorov:ChapmanKolmogorovSolver",
    "monte-carlo": "persson_fp.solvers.monte_carlo:MonteCarloSolver",
}
"""Method name -> "module:Class"."""

EXTRAS = {"py-pde": ("pde", "pde"), "fipy": ("fipy", "fipy")}
"""Method name -> (import name of the third-party package, pip extra of persson-fp)."""


def get_solver(method) -> type[Solver]:
    """The solver class of ``method`` (a name from ``METHODS`` or a :class:`Solver` subclass)."""
    if isinstance(method, type) and issubclass(method, Solver):
        return method
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)} or a Solver subclass, got {method!r}")
    if method in EXTRAS:
        pkg, extra = EXTRAS[method]
        try:
            importlib.import_module(pkg)
        except ImportError as err:
            raise ImportError(
                f"method {method!r} needs the optional package {pkg!r}: pip install 'persson-fp[{extra}]'"
            ) from err
    module, cls = METHODS[method].split(":")
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as err:
        if err.name == module:
            raise NotImplementedError(f"method {method!r} is not built yet") from err
        raise
    return getattr(mod, cls)


def available_methods() -> list[str]:
    """Names of the methods that are built and whose optional packages are installed.

    Looks the modules up without importing them, so that asking is cheap (py-pde imports numba).
    """
    from importlib.util import find_spec

    out = []
    for name, target in METHODS.items():
        if name in EXTRAS and find_spec(EXTRAS[name][0]) is None:
            continue
        if find_spec(target.split(":")[0]) is None:
            continue
        out.append(name)
    return out


def solve(problem, method="fv", zeta_out=None, blas_threads=1, **options):
    """Solve Persson's diffusion problem numerically and return a :class:`~persson_fp.Solution`.

    Parameters
    ----------
    problem : ContactProblem
        Spectrum, modulus, load(s) and fudge factor.
    method : str or Solver subclass
        One of ``METHODS``: "fv", "mol", "sines", "py-pde", "fipy",
        "chapman-kolmogorov", "monte-carlo".
    zeta_out : float or array, optional
        Output stations in (1, zeta_max]; default ``zeta_max``.
    blas_threads : int or None, default 1
        BLAS threads during the solve (through threadpoolctl, when installed).  One by default: the
        solvers' products are narrow, and a multithreaded BLAS only oversubscribes the cores on them
        (``benchmarks/batch_scaling.py``); ``None`` leaves the BLAS library's own setting.
    **options
        Shared knobs (``n_p``, ``n_steps``, ``rtol``, ``atol``, ``scheme``) and
        the method's own options (``get_solver(method).OPTIONS``).

    Returns
    -------
    Solution
        P0 at the stations, A*, load, variance, wall time, ``info`` and ``compare()``.

    Raises
    ------
    ValueError
        Unknown method or an option out of range.
    TypeError
        A misspelt option.
    ImportError
        The method's optional package is missing (names the pip extra).
    InstabilityError
        The discrete evolution went unstable.
    """
    from ._threads import blas_threads as _limit
    from ._threads import check_blas_threads

    n_threads = check_blas_threads(blas_threads)
    solver = get_solver(method)(problem, zeta_out=zeta_out, **options)
    with _limit(n_threads):
        return solver.run()
