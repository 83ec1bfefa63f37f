"""Method ``"mol"``: the method of lines, 2nd/4th-order differences in p and ``scipy.integrate`` in zeta or tau.

``MethodOfLinesSolver`` (``mol.solver``) on the grids of ``mol.grid``, marched by ``mol.ivp_march`` (scipy's
``OdeSolver`` classes with shared block factorisations), and on the front-fixed engine's fluxes by ``mol.lines``.
"""

from persson_fp.solvers.mol.grid import laplacian, laplacian_readable, quadrature_weights
from persson_fp.solvers.mol.solver import MethodOfLinesSolver

__all__ = ["MethodOfLinesSolver", "laplacian", "laplacian_readable", "quadrature_weights"]
