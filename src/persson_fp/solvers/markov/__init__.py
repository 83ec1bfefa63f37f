"""Methods on the Markov process behind Persson's equation (``E:Compounded_CK`` of the Xu et al. tutorial).

``"chapman-kolmogorov"``: the compounded transition kernel on cells
(:mod:`~persson_fp.solvers.markov.chapman_kolmogorov`);
``"monte-carlo"``: walkers with Brownian-bridge absorption (:mod:`~persson_fp.solvers.markov.monte_carlo`).
"""

from persson_fp.solvers.markov.chapman_kolmogorov import ChapmanKolmogorovSolver
from persson_fp.solvers.markov.monte_carlo import MonteCarloSolver

__all__ = ["ChapmanKolmogorovSolver", "MonteCarloSolver"]
