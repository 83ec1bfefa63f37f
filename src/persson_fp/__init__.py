"""persson-fp: Persson's theory of elastic rough-surface contact as a PDE problem.

The contact-pressure PDF obeys ``E:diffusion_equ`` of the Xu et al. tutorial,
dP0/dzeta = 1/2 B2(zeta) d^2P0/dp^2 with an absorbing wall at p = 0; this
package gives its exact solution (:func:`exact`), the spectrum and fudge-factor
physics around it, and numerical solvers behind :func:`solve`.

Importing the package loads numpy, ``scipy.special`` and the light modules only: the calibration and the sweeps
(and through them ``scipy.optimize`` and ``scipy.stats``), the solver families, the plotting and the optional
extras load when first used.  Their public names (:func:`calibrate`, :func:`sweep`, ...) are resolved on first
access by the module-level ``__getattr__`` below, so ``from persson_fp import calibrate`` works as before.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from persson_fp._version import __version__
from persson_fp.analysis.energy import elastic_energy, pressure_spectrum
from persson_fp.analysis.exact import ExactSolution, exact
from persson_fp.analysis.separation import contact_stiffness, mean_separation
from persson_fp.problems.contact import ContactProblem
from persson_fp.problems.fokker_planck import FokkerPlanckProblem
from persson_fp.results.solution import Comparison, InstabilityError, Solution, SolverError
from persson_fp.solvers import METHODS, available_methods, solve
from persson_fp.surfaces.conventions import CONVENTIONS, abel_factor, abel_forward, abel_inverse
from persson_fp.surfaces.psd import PSD, SelfAffinePSD
from persson_fp.surfaces.tabulated import TabulatedPSD
from persson_fp.theory import fudge, hardness
from persson_fp.theory.effective import EffectiveVariance, effective_variance
from persson_fp.theory.image import area_from_tau, image_pdf, variance_closed_form
from persson_fp.theory.separation import WEIGHTINGS, MeanSeparation, separation_from_areas

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
    # what happens in the gaps
    "MagnificationResolved",
    "GapDistribution",
    "gap_distribution",
    "leak_rate",
    "contact_conductance",
    "adhesion",
    "adhesive_contact",
    "AdhesiveContact",
    # calibration
    "calibrate",
    "Calibration",
    "ModelSelection",
    "viscoelastic",
    "rubber_friction",
    "FrictionResult",
    "sliding_contact",
]

# Public names whose modules are heavy (scipy.optimize, scipy.stats) or not needed by a first problem (the interface,
# the height-map import): name -> (defining module, attribute there).
_LAZY: dict[str, tuple[str, str]] = {
    "AdhesiveContact": ("persson_fp.analysis.interface", "AdhesiveContact"),
    "adhesive_contact": ("persson_fp.analysis.interface", "adhesive_contact"),
    "contact_conductance": ("persson_fp.analysis.interface", "contact_conductance"),
    "gap_distribution": ("persson_fp.analysis.interface", "gap_distribution"),
    "leak_rate": ("persson_fp.analysis.interface", "leak_rate"),
    "GapDistribution": ("persson_fp.theory.gaps", "GapDistribution"),
    "MagnificationResolved": ("persson_fp.theory.resolved", "MagnificationResolved"),
    "MeasuredSurface": ("persson_fp.surfaces.heightmap", "MeasuredSurface"),
    "psd_from_heightmap": ("persson_fp.surfaces.heightmap", "psd_from_heightmap"),
    "psd_from_profiles": ("persson_fp.surfaces.heightmap", "psd_from_profiles"),
    "read_heightmap": ("persson_fp.surfaces.readers", "read_heightmap"),
    "read_contact_engineering_csv": ("persson_fp.surfaces.readers", "read_contact_engineering_csv"),
    "from_surface_topography": ("persson_fp.surfaces.readers", "from_surface_topography"),
    "sweep": ("persson_fp.sweeps.run", "sweep"),
    "SweepError": ("persson_fp.sweeps.run", "SweepError"),
    "SweepResult": ("persson_fp.sweeps.table", "SweepResult"),
    "QUANTITIES": ("persson_fp.sweeps.quantities", "QUANTITIES"),
    "register_quantity": ("persson_fp.sweeps.quantities", "register_quantity"),
    "read_sweep_table": ("persson_fp.sweeps.table", "read_table"),
    "calibrate": ("persson_fp.calibration.fit", "calibrate"),
    "Calibration": ("persson_fp.calibration.result", "Calibration"),
    "ModelSelection": ("persson_fp.calibration.select", "ModelSelection"),
    "rubber_friction": ("persson_fp.analysis.friction", "rubber_friction"),
    "FrictionResult": ("persson_fp.analysis.friction", "FrictionResult"),
    "sliding_contact": ("persson_fp.problems.sliding", "sliding_contact"),
}
_LAZY_MODULES: dict[str, str] = {
    "viscoelastic": "persson_fp.theory.viscoelastic",
    "adhesion": "persson_fp.theory.adhesion",
}
# Subpackages that were attributes of the package after ``import persson_fp`` and now load on first access.
_LAZY_SUBMODULES = frozenset({"calibration", "sweeps"})

if TYPE_CHECKING:  # what the static tools see; at run time these load on first access
    from persson_fp import calibration as calibration
    from persson_fp import sweeps as sweeps
    from persson_fp.analysis.friction import FrictionResult, rubber_friction
    from persson_fp.analysis.interface import (
        AdhesiveContact,
        adhesive_contact,
        contact_conductance,
        gap_distribution,
        leak_rate,
    )
    from persson_fp.calibration.fit import calibrate
    from persson_fp.calibration.result import Calibration
    from persson_fp.calibration.select import ModelSelection
    from persson_fp.problems.sliding import sliding_contact
    from persson_fp.surfaces.heightmap import MeasuredSurface, psd_from_heightmap, psd_from_profiles
    from persson_fp.surfaces.readers import from_surface_topography, read_contact_engineering_csv, read_heightmap
    from persson_fp.sweeps.quantities import QUANTITIES, register_quantity
    from persson_fp.sweeps.run import SweepError, sweep
    from persson_fp.sweeps.table import SweepResult
    from persson_fp.sweeps.table import read_table as read_sweep_table
    from persson_fp.theory import adhesion as adhesion
    from persson_fp.theory import viscoelastic as viscoelastic
    from persson_fp.theory.gaps import GapDistribution
    from persson_fp.theory.resolved import MagnificationResolved


def __getattr__(name: str) -> Any:
    """Load a heavy public name (or subpackage) on its first access and keep it in the package's namespace.

    Parameters
    ----------
    name : str
        The attribute asked of the package.

    Returns
    -------
    object
        The object defined under that name in its own module (the same object, not a copy).

    Raises
    ------
    AttributeError
        If the package has no such name.
    """
    if name in _LAZY:
        module, attr = _LAZY[name]
        value = getattr(importlib.import_module(module), attr)
    elif name in _LAZY_MODULES:
        value = importlib.import_module(_LAZY_MODULES[name])
    elif name in _LAZY_SUBMODULES:
        value = importlib.import_module(f"{__name__}.{name}")
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The package's names, those loaded on first access included.

    Returns
    -------
    list of str
        The sorted names of the namespace, the public names and the lazily loaded subpackages.
    """
    return sorted(set(globals()) | set(_LAZY) | set(_LAZY_MODULES) | _LAZY_SUBMODULES)
