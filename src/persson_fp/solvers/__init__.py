"""Numerical solvers behind :func:`persson_fp.solve`, one module per method.

``METHODS`` maps a method name to ``"module:Class"``; a module is imported
only when its method is chosen, so the optional py-pde and FiPy backends cost
nothing unless used (cf. ``scipy.integrate.solve_ivp``'s ``METHODS``).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from persson_fp.solvers._threads import blas_threads as _limit
from persson_fp.solvers._threads import check_blas_threads
from persson_fp.solvers.base import SHARED_KNOBS, Solver, SolverOutput

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from persson_fp.problems.contact import ContactProblem
    from persson_fp.results.solution import Solution

__all__ = ["METHODS", "EXTRAS", "solve", "get_solver", "available_methods", "Solver", "SolverOutput", "SHARED_KNOBS"]

METHODS = {
    "fv": "persson_fp.solvers.fv:FiniteVolumeSolver",
    "mol": "persson_fp.solvers.mol:MethodOfLinesSolver",
    "sines": "persson_fp.solvers.sines:SineSeriesSolver",
    "py-pde": "persson_fp.solvers.backends.pypde:PyPDESolver",
    "fipy": "persson_fp.solvers.backends.fipy:FiPySolver",
    "chapman-kolmogorov": "persson_fp.solvers.chapman_kolmogorov:ChapmanKolmogorovSolver",
    "monte-carlo": "persson_fp.solvers.monte_carlo:MonteCarloSolver",
    "chebyshev": "persson_fp.solvers.chebyshev:ChebyshevSolver",
}
"""Method name -> "module:Class"."""

EXTRAS = {"py-pde": ("pde", "pde"), "fipy": ("fipy", "fipy")}
"""Method name -> (import name of the third-party package, pip extra of persson-fp)."""


def get_solver(method: str | type[Solver]) -> type[Solver]:
    """The solver class of ``method`` (a name from ``METHODS`` or a :class:`Solver` subclass).

    Parameters
    ----------
    method : str or Solver subclass
        A name from ``METHODS`` or a solver class (returned as it is).

    Returns
    -------
    type
        The solver class; its module is imported now.

    Raises
    ------
    ValueError
        An unknown method name (the message lists the valid ones).
    ImportError
        The method's optional package is missing (the message names the pip extra).
    """
    if isinstance(method, type) and issubclass(method, Solver):
        return method
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be 'auto', one of {sorted(METHODS)} or a Solver subclass, got {method!r}")
    if method in EXTRAS:
        pkg, extra = EXTRAS[method]
        try:
            importlib.import_module(pkg)
        except ImportError as err:
            raise ImportError(
                f"method {method!r} needs the optional package {pkg!r}: pip install 'persson-fp[{extra}]'"
            ) from err
    loaded = _LOADED.get(method)
    if loaded is not None:  # (imported before: a dictionary look-up is all a repeated call costs)
        return loaded
    module, cls = METHODS[method].split(":")
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as err:
        if err.name == module:
            raise NotImplementedError(f"method {method!r} is not built yet") from err
        raise
    _LOADED[method] = getattr(mod, cls)
    return _LOADED[method]


_LOADED: dict = {}
"""Method name -> solver class, for the methods imported so far."""


def available_methods() -> list[str]:
    """Names of the methods that are built and whose optional packages are installed.

    Looks the modules up without importing them, so that asking is cheap (py-pde imports numba).

    Returns
    -------
    list of str
        Method names usable with :func:`solve`, in the order of ``METHODS``.
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


def solve(
    problem: ContactProblem,
    method: str | type[Solver] = "fv",
    zeta_out: ArrayLike | None = None,
    tol: float | None = None,
    *,
    check: bool = True,
    max_memory: float | None = None,
    max_time: float | None = None,
    blas_threads: int | None = 1,
    **options,
) -> Solution:
    """Solve Persson's diffusion problem numerically and return a :class:`~persson_fp.Solution`.

    Parameters
    ----------
    problem : ContactProblem
        Spectrum, modulus, load(s) and fudge factor.
    method : str or Solver subclass
        "auto" (the cheapest way to ``tol``, :mod:`persson_fp.solvers.auto`) or one of ``METHODS``: "fv",
        "mol", "sines", "chebyshev", "py-pde", "fipy", "chapman-kolmogorov", "monte-carlo".
    zeta_out : float or array, optional
        Output stations in (1, zeta_max]; default ``zeta_max``.
    tol : float, optional
        Asked accuracy: the L1 error of P0 and the error of every area at every station.  With "auto" (default
        1e-6 there) and with "fv" / "mol" the resolution is chosen for it, the result checked (against
        :func:`persson_fp.exact`, or the solver's own estimate where no closed form exists) and refined until it
        meets ``tol``; ``info["auto"]`` says what was done.  With "sines" it is the series' truncation tolerance.
    check : bool, default True
        Check the invariants of the result (A* in [0, 1] and non-increasing, load balance, P0 >= 0,
        finite; :func:`persson_fp.results.solution.check_invariants`): a breach raises
        :class:`~persson_fp.SolverError`; ``False`` turns it into a ``RuntimeWarning``.
    max_memory : float, optional
        Memory budget in bytes, in (0, inf] (default ``solvers.base.MEMORY_BUDGET``, 4 GiB; ``inf``: no
        limit): a run estimated to need more is refused with a ``ValueError`` stating the estimate (chebyshev:
        before each degree it tries).
    max_time : float, optional
        Run-time budget in seconds, in (0, inf] (default ``solvers.base.TIME_BUDGET``, 1 hour; ``inf``: no
        limit), checked the same way for the methods with a time model (fv, chapman-kolmogorov,
        monte-carlo); the adaptive loops (``tol=``, auto, chebyshev, mol's march) stop with a ``SolverError``
        naming it when it runs out.
    blas_threads : int or None, default 1
        BLAS threads during the solve (through threadpoolctl, when installed).  One by default: the
        solvers' products are narrow, and a multithreaded BLAS only oversubscribes the cores on them
        (``benchmarks/batch_scaling.py``); ``None`` leaves the BLAS library's own setting.  A solve whose
        (loads x stations) is at most the method's ``SMALL_BATCH`` (sines: 1) leaves the setting alone: its
        products are below OpenBLAS's threading thresholds, and setting the pools costs more than such a solve.
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
        Unknown method, an option out of range, a load outside the method's range of relative accuracy
        (the message names the method that handles it), or a run over the memory budget.
    TypeError
        A misspelt option.
    ImportError
        The method's optional package is missing (names the pip extra).
    InstabilityError
        The discrete evolution went unstable.
    SolverError
        The result breaks an invariant (with ``check=True``).
    """
    n_threads = check_blas_threads(blas_threads)
    if isinstance(method, str) and method == "auto":
        from persson_fp.solvers.auto import solve_auto

        with _limit(n_threads):
            return solve_auto(
                problem, zeta_out, 1e-6 if tol is None else tol, max_memory=max_memory, max_time=max_time, **options
            )
    if tol is not None and isinstance(method, str) and method in ("fv", "mol"):
        from persson_fp.solvers.auto import solve_to_tol
        from persson_fp.solvers.base import check_float

        with _limit(n_threads):
            return solve_to_tol(
                problem,
                method,
                zeta_out,
                check_float(tol, "tol", 1e-15, 1e-1, lo_open=False),  # below 1e-15: round-off
                max_memory=max_memory,
                max_time=max_time,
                **options,
            )
    if tol is not None:
        options["tol"] = tol
    solver = get_solver(method)(
        problem, zeta_out=zeta_out, check=check, max_memory=max_memory, max_time=max_time, **options
    )
    if problem.n_loads * solver.zeta_out.size <= getattr(
        solver, "SMALL_BATCH", 0
    ):  # products too small for a second BLAS
        return solver.run()  # thread: skip threadpoolctl's set/restore (~20 us a call, more than such a solve)
    with _limit(n_threads):
        return solver.run()
