"""Method ``"chebyshev"``: Chebyshev collocation on a mapped grid for general coefficients.

``ChebyshevSolver`` (``chebyshev.solver``): the coefficients' forms (``chebyshev.coefficients``), the collocation grid
and operators (``chebyshev.collocation``), the Radau IIA march for coefficients that do not separate
(``chebyshev.radau``; exponential steps in ``chebyshev.magnus``) and the front-fixed moving yield wall
(``chebyshev.wall``).
"""

from persson_fp.solvers.chebyshev.solver import ChebyshevSolver

__all__ = ["ChebyshevSolver"]
