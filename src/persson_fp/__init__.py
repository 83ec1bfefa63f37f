"""persson-fp: Persson's theory of elastic rough-surface contact as a PDE problem.

The contact-pressure PDF obeys ``E:diffusion_equ`` of the Xu et al. tutorial,
dP0/dzeta = 1/2 B2(zeta) d^2P0/dp^2 with an absorbing wall at p = 0; this
package gives its exact solution (:func:`exact`), the spectrum and fudge-factor
physics around it, and numerical solvers behind :func:`solve`.
"""

from . import fudge, hardness
from .conventions import CONVENTIONS, abel_factor, abel_forward, abel_inverse
from .effective import EffectiveVariance, effective_variance
from .energy import elastic_energy, pressure_spectrum
from .exact import (
    ExactSolution,
    area_from_tau,
    exact,
    image_pdf,
    variance_closed_form,
)
from .fokker_planck import FokkerPlanckProblem
from .problem import ContactProblem
from .quantities import QUANTITIES, register_quantity
from .separation import WEIGHTINGS, MeanSeparation, contact_stiffness, mean_separation, separation_from_areas
from .solution import Comparison, InstabilityError, Solution, SolverError
from .solvers import METHODS, available_methods, solve
from .spectrum import PSD, SelfAffinePSD, TabulatedPSD
from .surface import MeasuredSurface, psd_from_heightmap, psd_from_profiles
from .surface_io import from_surface_topography, read_contact_engineering_csv, read_heightmap
from .sweep_table import SweepResult
from .sweep_table import read_table as read_sweep_table
from .sweeps import SweepError, sweep

__version__ = "0.1.0"

__all__ = [
    "PSD",
    "SelfAffinePSD",
    "TabulatedPSD",
    "ContactProblem",
    "FokkerPlanckProblem",
    "hardness",
    "fudge",
    "EffectiveVariance",
    "effective_variance",
    "ExactSolution",
    "exact",
    "image_pdf",
    "area_from_tau",
    "variance_closed_form",
    "pressure_spectrum",
    "elastic_energy",
    "Solution",
    "Comparison",
    "SolverError",
    "InstabilityError",
    "METHODS",
    "solve",
    "available_methods",
    "__version__",
    "CONVENTIONS",
    "abel_factor",
    "abel_forward",
    "abel_inverse",
    "WEIGHTINGS",
    "MeanSeparation",
    "mean_separation",
    "contact_stiffness",
    "separation_from_areas",
    "MeasuredSurface",
    "psd_from_heightmap",
    "psd_from_profiles",
    "read_heightmap",
    "read_contact_engineering_csv",
    "from_surface_topography",
    # sweeps
    "sweep",
    "SweepResult",
    "SweepError",
    "QUANTITIES",
    "register_quantity",
    "read_sweep_table",
]
