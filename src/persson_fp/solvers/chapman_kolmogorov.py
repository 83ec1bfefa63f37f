"""Old path of :class:`~persson_fp.solvers.markov.ChapmanKolmogorovSolver` (moved to :mod:`persson_fp.solvers.markov`).

Kept for one release so that existing imports keep working; import from :mod:`persson_fp.solvers.markov`.
"""

from persson_fp.solvers.markov.chapman_kolmogorov import ChapmanKolmogorovSolver

__all__ = ["ChapmanKolmogorovSolver"]
