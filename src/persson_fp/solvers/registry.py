"""The registry of methods behind :func:`persson_fp.solve`: ``METHODS``, ``get_solver``, ``available_methods``.

``METHODS`` maps a method name to ``"module:Class"``; a module is imported only when its method is chosen, so the
optional py-pde and FiPy backends cost nothing unless used (cf. ``scipy.integrate.solve_ivp``'s ``METHODS``).
"""

from __future__ import annotations

import importlib

from persson_fp.solvers import base as _base
from persson_fp.solvers.base import Solver

__all__ = ["METHODS", "EXTRAS", "get_solver", "available_methods"]

METHODS = {
    "fv": "persson_fp.solvers.fv:FiniteVolumeSolver",
    "mol": "persson_fp.solvers.mol:MethodOfLinesSolver",
    "sines": "persson_fp.solvers.sines:SineSeriesSolver",
    "py-pde": "persson_fp.solvers.backends.pypde:PyPDESolver",
    "fipy": "persson_fp.solvers.backends.fipy:FiPySolver",
    "chapman-kolmogorov": "persson_fp.solvers.markov:ChapmanKolmogorovSolver",
    "monte-carlo": "persson_fp.solvers.markov:MonteCarloSolver",
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


def supporting(feature: str) -> list[str]:
    """The methods (quoted names) whose ``SUPPORTS`` hold ``feature`` ("hardness", "moving_wall", "general"), in the
    order of ``METHODS``, each with its own condition where it has one (``SUPPORT_NOTES``).  A method of an
    optional package counts once it has been imported (asking does not import py-pde or FiPy)."""
    out = []
    for name in METHODS:
        if name in EXTRAS and name not in _LOADED:
            continue
        try:
            cls = get_solver(name)
        except (ImportError, NotImplementedError):  # (a method not installed or not built: not a hint)
            continue
        if feature in cls.SUPPORTS:
            note = getattr(cls, "SUPPORT_NOTES", {}).get(feature)
            out.append(repr(name) if note is None else f"{name!r} ({note})")
    return out


_base._SUPPORTERS[:] = [supporting]


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
