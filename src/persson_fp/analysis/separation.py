r"""Mean interfacial separation and normal contact stiffness at the loads of a contact problem.

The front ends of :class:`~persson_fp.MeanSeparation` (Persson, Phys. Rev. Lett. 99 (2007) 125502; Yang & Persson,
J. Phys.: Condens. Matter 20 (2008) 215214): the problem's spectrum, E*, loads and fudge factor; the formulas are in
:mod:`persson_fp.theory.separation`.  This module imports no solver.
"""

from __future__ import annotations

import numpy as np

from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.separation import MeanSeparation

__all__ = ["mean_separation", "contact_stiffness"]


def _elastic_only(problem) -> None:
    if not isinstance(problem, ContactProblem):
        raise ValueError(f"problem must be a persson_fp ContactProblem, got {type(problem).__name__}")
    problem.require_elastic(
        "the mean separation of Persson (2007)",
        " (use separation_from_areas with a numerical solution's areas)",
    )


def _per_load(problem, weighting: str, quantity: str):
    """``MeanSeparation(...).<quantity>`` at the problem's loads: a float for a scalar load, else an array."""
    _elastic_only(problem)
    ms = MeanSeparation(problem.psd, problem.E_star, problem.fudge, weighting, response=problem.response)
    out = getattr(ms, quantity)(problem.p_bar)
    return float(out[0]) if problem.scalar_load else out


def mean_separation(problem, weighting: str = "yang-persson") -> np.ndarray:
    r"""Mean interfacial separation :math:`\bar u` at the loads of a contact problem.

    Persson's theory (Persson, Phys. Rev. Lett. 99 (2007) 125502; Yang & Persson, J. Phys.: Condens. Matter
    20 (2008) 215214) with the problem's spectrum, E* and fudge factor; see :class:`~persson_fp.MeanSeparation`
    (which to use for many loads or for the energy and stiffness too).

    Parameters
    ----------
    problem : ContactProblem
        The surface, modulus, loads and fudge factor (:class:`~persson_fp.ContactProblem`).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of a fudge model (see :mod:`persson_fp.theory.separation`).

    Returns
    -------
    float or ndarray, length
        :math:`\bar u` at each load: a float for a scalar load, else an array of shape ``(n_loads,)``.

    Raises
    ------
    ValueError
        A problem with a hardness or general coefficients (this is the elastic theory's separation; use
        :func:`~persson_fp.separation_from_areas` with a numerical solution's areas), or a bad ``weighting``.
    """
    return _per_load(problem, weighting, "mean_separation")


def contact_stiffness(problem, weighting: str = "yang-persson") -> np.ndarray:
    r"""Normal contact stiffness per nominal area :math:`K = -d\bar p/d\bar u` at the loads of a contact problem.

    From Persson's mean separation (Persson, Phys. Rev. Lett. 99 (2007) 125502), :math:`K = \bar p/(dU/d\bar p)`;
    see :class:`~persson_fp.MeanSeparation`.

    Parameters
    ----------
    problem : ContactProblem
        The surface, modulus, loads and fudge factor (:class:`~persson_fp.ContactProblem`).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of a fudge model (see :mod:`persson_fp.theory.separation`).

    Returns
    -------
    float or ndarray, pressure / length
        K at each load: a float for a scalar load, else an array of shape ``(n_loads,)``.

    Raises
    ------
    ValueError
        A problem with a hardness or general coefficients (this is the elastic theory's separation; use
        :func:`~persson_fp.separation_from_areas` with a numerical solution's areas), or a bad ``weighting``.
    """
    return _per_load(problem, weighting, "stiffness")
