"""Numerical solvers behind :func:`persson_fp.solve`: the front, one folder per method family.

:func:`~persson_fp.solve` validates, picks the method from the registry (:mod:`~persson_fp.solvers.registry`:
``METHODS``, ``get_solver``) and returns the :class:`~persson_fp.Solution` its ``Solver`` built.  Families:
:mod:`~persson_fp.solvers.sines`, :mod:`~persson_fp.solvers.fv`, :mod:`~persson_fp.solvers.mol`,
:mod:`~persson_fp.solvers.chebyshev`, :mod:`~persson_fp.solvers.markov` (Chapman--Kolmogorov, Monte Carlo) and
:mod:`~persson_fp.solvers.backends` (py-pde, FiPy); the front-fixed finite-volume engine that fv and mol march on
general coefficients and moving walls is :mod:`~persson_fp.solvers.front_fixed`.  A family's module is imported only
when its method is chosen.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from persson_fp.solvers._threads import blas_threads as _limit
from persson_fp.solvers._threads import check_blas_threads
from persson_fp.solvers.base import SHARED_KNOBS, Solver, SolverOutput
from persson_fp.solvers.registry import EXTRAS, METHODS, available_methods, get_solver

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from persson_fp.problems.contact import ContactProblem
    from persson_fp.results.solution import Solution

__all__ = ["METHODS", "EXTRAS", "solve", "get_solver", "available_methods", "Solver", "SolverOutput", "SHARED_KNOBS"]


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
