"""The front-fixed finite-volume engine: moving yield walls and general Fokker--Planck coefficients.

Conservative fluxes and walls on a cell grid and their time steps (:mod:`~persson_fp.solvers.front_fixed.fluxes`), the
grid x = p / sigma_Y(zeta) that keeps a moving yield wall at x = 1 (:mod:`~persson_fp.solvers.front_fixed.moving_wall`),
the coefficients' domain (:mod:`~persson_fp.solvers.front_fixed.domain`), the start-up of general coefficients
(:mod:`~persson_fp.solvers.front_fixed.start`) and the paired-run error estimate
(:mod:`~persson_fp.solvers.front_fixed.estimate`).  The methods ``"fv"`` and ``"mol"`` march it; it builds no solver and
no result.
"""
