"""What a method hands back: :class:`SolverOutput`, the one object a :class:`~persson_fp.Solution` is built from."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["SolverOutput"]


@dataclass
class SolverOutput:
    """What a method's ``_solve`` hands back to :meth:`persson_fp.solvers.Solver.run`, which builds the
    :class:`~persson_fp.Solution` from it (:meth:`~persson_fp.Solution.from_output`).

    P0 has shape ``(n_zeta_out, n_loads, n_p)``.  ``kind`` is "cell" for cell averages or "point" for point values.
    """

    p: np.ndarray
    """Grid (pressure), ``(n_p,)``, or ``(n_zeta_out, n_p)`` for a moving yield wall."""
    P0: np.ndarray
    """P0 at the stations (1/pressure), reshapeable to ``(n_zeta_out, n_loads, n_p)``."""
    weights: np.ndarray
    """Quadrature weights of the grid (pressure), the shape of ``p``."""
    kind: str
    """"cell" (cell averages) or "point" (point values)."""
    info: dict = field(default_factory=dict)
    """What the method did (grid, steps, calls, error estimate ...)."""
    contact_area: np.ndarray | None = None
    """The method's int P0 dp (the elastic area), ``(n_zeta_out, n_loads)``; default the grid quadrature."""
    contact_area_flux: np.ndarray | None = None
    """A* from the flux absorbed at p = 0 (finite volumes)."""
    stderr_area: np.ndarray | None = None
    """Standard error of A* (stochastic methods)."""
    plastic_area: np.ndarray | None = None
    """A_pl at the stations, (n_zeta_out, n_loads), for a problem with a hardness wall."""
    load: np.ndarray | None = None
    """The method's own estimate of int p P0 dp where the grid quadrature is not the best one (pressure)."""
    stderr_load: np.ndarray | None = None
    """Standard error of ``load`` (pressure)."""
