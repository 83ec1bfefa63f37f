"""Method ``"sines"``: Persson's sine series on a finite strip with an exact delta start.

``SineSeriesSolver`` (``sines.solver``) on the series of ``sines.series`` and the effective-variance map of
``sines.taumap`` (the fudge factor's tau(zeta) from the series' own contact area).
"""

from persson_fp.solvers.sines.series import image_area, modes_needed, series_area, series_pdf
from persson_fp.solvers.sines.solver import SineSeriesSolver

__all__ = ["SineSeriesSolver", "image_area", "modes_needed", "series_area", "series_pdf"]
