"""Method ``"fv"``: finite volumes in p, theta-schemes and TR-BDF2 in the effective variance.

``FiniteVolumeSolver`` (``fv.solver``); its operators (``fv.operators``: the readable flux differences ``rhs``, the
banded matrix), the exact DST-II path (``fv.dst``, ``fv.spectral``), the step nodes in tau (``fv.stepping``), and its
runs on the front-fixed engine (moving walls, general coefficients).
"""

from persson_fp.solvers.fv.dst import dst_eigenvalues
from persson_fp.solvers.fv.operators import apply_mass, apply_operator, banded_operator, rhs, wall_flux
from persson_fp.solvers.fv.solver import FiniteVolumeSolver

__all__ = [
    "FiniteVolumeSolver",
    "rhs",
    "wall_flux",
    "banded_operator",
    "apply_operator",
    "apply_mass",
    "dst_eigenvalues",
]
