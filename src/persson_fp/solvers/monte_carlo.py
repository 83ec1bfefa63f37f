"""Old path of :class:`~persson_fp.solvers.markov.MonteCarloSolver` (moved to :mod:`persson_fp.solvers.markov`).

Kept for one release so that existing imports keep working; import from :mod:`persson_fp.solvers.markov`.
"""

from persson_fp.solvers.markov.monte_carlo import MonteCarloSolver

__all__ = ["MonteCarloSolver"]
