"""Calibration: fit a fudge model's free parameters to a user's simulations or measurements, with uncertainty.

:func:`persson_fp.calibrate` (module ``fit``) returns a :class:`persson_fp.Calibration` (module ``result``), or for a
list of models a :class:`persson_fp.ModelSelection` (module ``select``); data are read and checked by
:mod:`persson_fp.calibration.data`, the parametric models built by :mod:`persson_fp.calibration.models`, the
residuals and the covariance computed by :mod:`persson_fp.calibration.objective`.  This package uses the closed
forms (problems, results, theory) and imports no solver.
"""

from persson_fp.calibration.data import QUANTITIES, Dataset, pair_surfaces, read_table
from persson_fp.calibration.fit import calibrate
from persson_fp.calibration.models import Family, family
from persson_fp.calibration.objective import predict
from persson_fp.calibration.result import Calibration
from persson_fp.calibration.select import CRITERIA, ModelSelection

__all__ = [
    "calibrate",
    "predict",
    "Calibration",
    "ModelSelection",
    "CRITERIA",
    "QUANTITIES",
    "Dataset",
    "read_table",
    "pair_surfaces",
    "Family",
    "family",
]
